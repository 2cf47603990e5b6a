# Installs the headers and a relocatable CMake package, so that another project
# writes find_package(l2scalib) and links l2scalib::l2scalib (and l2scalib::sim).
include(CMakePackageConfigHelpers)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/l2s DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

set(L2SCALIB_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/l2scalib)
install(EXPORT l2scalibTargets NAMESPACE l2scalib:: DESTINATION ${L2SCALIB_CMAKE_DIR})

configure_package_config_file(
  ${PROJECT_SOURCE_DIR}/cmake/l2scalibConfig.cmake.in
  ${PROJECT_BINARY_DIR}/l2scalibConfig.cmake
  INSTALL_DESTINATION ${L2SCALIB_CMAKE_DIR})
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/l2scalibConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/l2scalibConfig.cmake
  ${PROJECT_BINARY_DIR}/l2scalibConfigVersion.cmake
  DESTINATION ${L2SCALIB_CMAKE_DIR})
