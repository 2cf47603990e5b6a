#include "low/low.hpp"

#include <l2s/high.hpp>

int low() { return 1; }
int low_calls_high() { return high(); }
