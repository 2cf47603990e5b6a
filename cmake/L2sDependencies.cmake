# Third-party dependencies. Eigen is part of the public API; everything else
# stays private to the library (see STYLE.md: PCL and OpenCV live in src/).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs calib3d)
# PCL: the tests cross-check our PCD reader against it. Only the modules we use.
find_package(PCL 1.10 REQUIRED COMPONENTS common io)
find_package(Threads REQUIRED)

# yaml-cpp 0.7 exports a plain `yaml-cpp` target, newer releases `yaml-cpp::yaml-cpp`.
if(TARGET yaml-cpp::yaml-cpp)
  set(L2S_YAML_TARGET yaml-cpp::yaml-cpp)
else()
  set(L2S_YAML_TARGET yaml-cpp)
endif()

# PCL publishes variables rather than one target: attach them privately.
function(l2s_link_pcl target)
  target_include_directories(${target} SYSTEM PRIVATE ${PCL_INCLUDE_DIRS})
  target_link_libraries(${target} PRIVATE ${PCL_LIBRARIES})
  target_compile_definitions(${target} PRIVATE ${PCL_DEFINITIONS})
endfunction()
