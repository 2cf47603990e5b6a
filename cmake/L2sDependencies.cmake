# Third-party dependencies. Eigen is part of the public API; everything else
# stays private to the library (see STYLE.md: PCL and OpenCV live in src/).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs calib3d aruco)
find_package(Threads REQUIRED)

# yaml-cpp 0.7 exports a plain `yaml-cpp` target, newer releases `yaml-cpp::yaml-cpp`.
if(TARGET yaml-cpp::yaml-cpp)
  set(L2S_YAML_TARGET yaml-cpp::yaml-cpp)
else()
  set(L2S_YAML_TARGET yaml-cpp)
endif()

# PCL: only the l2scalib::pcl component (and the tests and benchmarks that
# compare our PCD code with PCL's) use it; the core library never does.
string(TOUPPER "${L2SCALIB_BUILD_PCL}" l2s_build_pcl)
if(l2s_build_pcl STREQUAL "ON")
  find_package(PCL 1.10 REQUIRED COMPONENTS common io)
elseif(l2s_build_pcl STREQUAL "AUTO")
  find_package(PCL 1.10 QUIET COMPONENTS common io)
  if(NOT PCL_FOUND)
    message(STATUS "l2scalib: PCL not found, l2scalib::pcl is not built (L2SCALIB_BUILD_PCL=ON to require it)")
  endif()
elseif(NOT l2s_build_pcl STREQUAL "OFF")
  message(FATAL_ERROR "L2SCALIB_BUILD_PCL must be AUTO, ON or OFF, not '${L2SCALIB_BUILD_PCL}'")
endif()
if(PCL_FOUND AND NOT l2s_build_pcl STREQUAL "OFF")
  set(L2SCALIB_WITH_PCL ON)
else()
  set(L2SCALIB_WITH_PCL OFF)
endif()

# For tests and benchmarks that call PCL's own readers: attach PCL privately.
function(l2s_link_pcl target)
  target_link_libraries(${target} PRIVATE pcl_common pcl_io)
endfunction()

# The recording readers (l2scalib::recording) decompress ROS 1 bag chunks with
# bzip2 and lz4. Linked by path, not as imported targets: a static build's
# export then names the libraries themselves.
if(L2SCALIB_BUILD_RECORDING)
  find_package(BZip2 REQUIRED)
  find_path(L2S_LZ4_INCLUDE_DIR lz4frame.h)
  find_library(L2S_LZ4_LIBRARY NAMES lz4)
  if(NOT L2S_LZ4_INCLUDE_DIR OR NOT L2S_LZ4_LIBRARY)
    message(FATAL_ERROR "l2scalib::recording needs lz4 (Debian: liblz4-dev; scripts/setup.sh installs it), "
                        "or -DL2SCALIB_BUILD_RECORDING=OFF")
  endif()
endif()
