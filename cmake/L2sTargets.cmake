# Helpers shared by every target of the project.

# Warnings for our own code only; third-party headers are SYSTEM includes.
function(l2s_set_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-unused-parameter)
  endif()
endfunction()

# l2s_optimize_as_glue(target): compile `target` at -O1 instead of the build
# type's -O3. For code that orchestrates and reports (the tests, the suite's
# bookkeeping, the command-line tool) while the work runs in the libraries,
# which keep -O3: -O3's inlining of Eigen's, the standard library's and
# GoogleTest's templates is most of such a source's compile time (measured:
# suite_stats.cpp 9.0 -> 6.8 s, the tool's main.cpp 12.6 -> 8.0 s, three test
# sources 27.7 -> 18.8 s), and it runs no slower for it.
function(l2s_optimize_as_glue target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      $<$<OR:$<CONFIG:Release>,$<CONFIG:RelWithDebInfo>>:-O1>)
  endif()
endfunction()

if(L2SCALIB_BUILD_SHARED)
  set(L2S_LIBRARY_TYPE SHARED)
else()
  set(L2S_LIBRARY_TYPE STATIC)
endif()

# l2s_add_library(name ALIAS alias [COMPONENT component] SOURCES ...
#                 [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Declares a library of the SDK with its l2scalib::<alias> name. The core
# library (no COMPONENT) exports into l2scalibTargets, a component into
# l2scalib_<component>Targets, loaded by find_package(l2scalib COMPONENTS ...).
# Symbols are hidden unless a header marks them L2S_EXPORT (l2s/export.hpp);
# on ELF a version script also keeps template instantiations of other
# libraries' types (std::, YAML::, cv::) out of the dynamic symbol table.
function(l2s_add_library name)
  cmake_parse_arguments(ARG "" "ALIAS;COMPONENT" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(exclude "")
  if(ARG_COMPONENT AND NOT L2SCALIB_TOP_LEVEL)
    set(exclude EXCLUDE_FROM_ALL)  # a parent project builds the components it links, no more
  endif()
  add_library(${name} ${L2S_LIBRARY_TYPE} ${exclude} ${ARG_SOURCES})
  add_library(l2scalib::${ARG_ALIAS} ALIAS ${name})
  set_target_properties(${name} PROPERTIES
    EXPORT_NAME ${ARG_ALIAS}
    VERSION ${PROJECT_VERSION}
    SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
    CXX_EXTENSIONS OFF
    POSITION_INDEPENDENT_CODE ON
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  target_include_directories(${name}
    PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
           $<BUILD_INTERFACE:${L2SCALIB_GENERATED_INCLUDE_DIR}>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_features(${name} PUBLIC cxx_std_17)
  if(WIN32)
    if(NOT L2SCALIB_BUILD_SHARED)
      target_compile_definitions(${name} PUBLIC L2S_STATIC)  # export.hpp: no dllimport
    endif()
  else()
    # export.hpp needs no <target>_EXPORTS here; without it a static and a
    # shared build compile with the same command lines (one ccache entry).
    set_target_properties(${name} PROPERTIES DEFINE_SYMBOL "")
  endif()
  if(L2SCALIB_BUILD_SHARED AND CMAKE_SYSTEM_NAME STREQUAL "Linux")
    # A component (sim, pcl, viz) finds the core beside it once installed: a
    # consumer's own RUNPATH covers only the libraries it links directly.
    set_target_properties(${name} PROPERTIES INSTALL_RPATH "$ORIGIN")
    target_link_options(${name} PRIVATE "LINKER:--version-script=${PROJECT_SOURCE_DIR}/cmake/l2scalib.map")
    set_property(TARGET ${name} APPEND PROPERTY LINK_DEPENDS ${PROJECT_SOURCE_DIR}/cmake/l2scalib.map)
  endif()
  l2s_set_warnings(${name})
  if(L2SCALIB_INSTALL)
    if(ARG_COMPONENT)
      set(export_set l2scalib_${ARG_COMPONENT}Targets)
    else()
      set(export_set l2scalibTargets)
    endif()
    install(TARGETS ${name} EXPORT ${export_set}
      LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
      ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
      RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    set_property(GLOBAL APPEND PROPERTY L2SCALIB_EXPORT_SETS ${export_set})
  endif()
endfunction()
