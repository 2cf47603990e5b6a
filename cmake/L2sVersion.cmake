# l2s/version.hpp, generated from project(VERSION) into the build tree and installed.
set(L2SCALIB_GENERATED_INCLUDE_DIR ${PROJECT_BINARY_DIR}/generated/include)
configure_file(${PROJECT_SOURCE_DIR}/cmake/version.hpp.in
               ${L2SCALIB_GENERATED_INCLUDE_DIR}/l2s/version.hpp @ONLY)
