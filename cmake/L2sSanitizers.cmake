# Sanitizer builds (scripts/sanitize.sh) and libFuzzer builds (fuzz/). The
# flags go to every target of this directory tree, never to a parent project.
if(L2SCALIB_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "L2SCALIB_BUILD_FUZZERS needs clang (libFuzzer): configure with CXX=clang++ CC=clang")
  endif()
  if(NOT L2SCALIB_SANITIZE)
    set(L2SCALIB_SANITIZE address undefined)
  endif()
  # Coverage for the fuzzer in every library; the fuzz targets link libFuzzer itself.
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(L2SCALIB_SANITIZE)
  string(REPLACE ";" "," l2s_sanitizers "${L2SCALIB_SANITIZE}")
  # Stop at the first report, so a sanitizer finding fails the test that caused it.
  add_compile_options(-fsanitize=${l2s_sanitizers} -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=${l2s_sanitizers})
  message(STATUS "l2scalib: sanitizers ${l2s_sanitizers}")
endif()
