#include <l2s/version.hpp>

namespace l2s {

// Compiled into the library, so it tells which library a program runs with
// (kVersion tells which headers it was compiled against).
const char* library_version() { return L2SCALIB_VERSION_STRING; }

}  // namespace l2s
