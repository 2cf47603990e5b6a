# The linker of a top-level build. Every program (tests, benchmarks, examples,
# the tool) links the libraries and OpenCV's; GNU ld spends seconds on each, so
# a one-source change costs a minute of linking. mold (else lld) links the
# same objects several times faster. A subproject keeps its parent's linker.
set(L2SCALIB_LINKER AUTO CACHE STRING "Linker: AUTO (mold, else lld, else the compiler's), mold, lld, gold or DEFAULT")
set_property(CACHE L2SCALIB_LINKER PROPERTY STRINGS AUTO mold lld gold DEFAULT)

if(NOT L2SCALIB_TOP_LEVEL OR L2SCALIB_LINKER STREQUAL "DEFAULT" OR CMAKE_VERSION VERSION_LESS 3.18)
  return()
endif()

include(CheckLinkerFlag)
if(L2SCALIB_LINKER STREQUAL "AUTO")
  set(l2s_linker_candidates mold lld)
else()
  set(l2s_linker_candidates ${L2SCALIB_LINKER})
endif()

foreach(linker ${l2s_linker_candidates})
  # Cached per linker and compiler: a second configure does not test again.
  check_linker_flag(CXX "-fuse-ld=${linker}" L2SCALIB_CXX_LINKS_WITH_${linker})
  if(L2SCALIB_CXX_LINKS_WITH_${linker})
    add_link_options("-fuse-ld=${linker}")
    message(STATUS "l2scalib: linking with ${linker}")
    return()
  endif()
endforeach()

if(NOT L2SCALIB_LINKER STREQUAL "AUTO")
  message(FATAL_ERROR "L2SCALIB_LINKER=${L2SCALIB_LINKER}: the compiler cannot link with it (is it installed?)")
endif()
message(STATUS "l2scalib: linking with the compiler's default linker (install mold or lld for faster links)")
