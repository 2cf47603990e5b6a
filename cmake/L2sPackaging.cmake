# Installs the headers and a relocatable CMake package: another project writes
# find_package(l2scalib [COMPONENTS sim suite viz pcl recording]) and links
# l2scalib::l2scalib (and l2scalib::sim, ...). Each component has its own
# export file, loaded only when asked for, so that l2scalib::pcl's need for
# PCL reaches only the projects that use it.
include(CMakePackageConfigHelpers)

set(L2SCALIB_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/l2scalib)

# Headers of the components that were built.
set(l2s_header_excludes "")
if(NOT L2SCALIB_BUILD_SIM)
  list(APPEND l2s_header_excludes PATTERN sim EXCLUDE)
endif()
if(NOT L2SCALIB_BUILD_VIZ)
  list(APPEND l2s_header_excludes PATTERN viz EXCLUDE)
endif()
if(NOT L2SCALIB_BUILD_RECORDING)
  list(APPEND l2s_header_excludes PATTERN recording EXCLUDE)
endif()
if(NOT L2SCALIB_WITH_PCL)
  list(APPEND l2s_header_excludes PATTERN adapters EXCLUDE)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/l2s DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} ${l2s_header_excludes})
install(FILES ${L2SCALIB_GENERATED_INCLUDE_DIR}/l2s/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/l2s)

get_property(l2s_export_sets GLOBAL PROPERTY L2SCALIB_EXPORT_SETS)
list(REMOVE_DUPLICATES l2s_export_sets)
set(L2SCALIB_COMPONENTS "")
foreach(export_set ${l2s_export_sets})
  install(EXPORT ${export_set} NAMESPACE l2scalib:: DESTINATION ${L2SCALIB_CMAKE_DIR})
  if(export_set MATCHES "^l2scalib_(.+)Targets$")
    list(APPEND L2SCALIB_COMPONENTS ${CMAKE_MATCH_1})
  endif()
endforeach()

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
