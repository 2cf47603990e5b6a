#include <l2s/high.hpp>

#include "low/low.hpp"

int high() { return low() + 1; }
