# Precompiled headers. Nearly every source of ours includes Eigen through the
# public headers, and every test GoogleTest: parsing them again is a third of
# a translation unit's compile time (measured: 34.3 -> 22.9 s user over five
# library sources). OpenCV stays out: few sources use it, and a precompiled
# header that holds it loads slower than those few sources parse it.
option(L2SCALIB_PRECOMPILE_HEADERS "Precompile Eigen, GoogleTest and the standard library headers" ${L2SCALIB_TOP_LEVEL})

set(L2S_PRECOMPILED_HEADERS
  <algorithm> <array> <cmath> <cstdint> <functional> <limits> <map> <memory>
  <optional> <sstream> <string> <vector>
  <Eigen/Core> <Eigen/Geometry>)

# l2s_precompile_headers(target [GTEST]): compile the heavy headers once for
# `target`'s sources (GTEST: GoogleTest's too).
function(l2s_precompile_headers target)
  cmake_parse_arguments(ARG "GTEST" "" "" ${ARGN})
  if(NOT L2SCALIB_PRECOMPILE_HEADERS)
    return()
  endif()
  set(headers ${L2S_PRECOMPILED_HEADERS})
  if(ARG_GTEST)
    list(APPEND headers <gtest/gtest.h>)
  endif()
  target_precompile_headers(${target} PRIVATE ${headers})
endfunction()

# l2s_reuse_precompiled_headers(target from): `target` compiles with the
# headers `from` precompiled (one precompiled header for many programs). The
# compiler ignores it (and says so, -Winvalid-pch) unless both targets have
# the same definitions and code generation options.
function(l2s_reuse_precompiled_headers target from)
  if(L2SCALIB_PRECOMPILE_HEADERS)
    target_precompile_headers(${target} REUSE_FROM ${from})
  endif()
endfunction()
