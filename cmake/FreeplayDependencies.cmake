# Every dependency comes from a Debian 12 package (scripts/setup.sh installs them); nothing is downloaded.

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3.11 REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(CLI11 REQUIRED)
find_package(box2d 2.4 REQUIRED)
if(FREEPLAY_MAIN_JOB_ONLY)
  # The main job uses three OpenCV modules. Debian ships OpenCV's CMake package only in libopencv-dev, which pulls in
  # every module (VTK, the DNN, GUI and contrib modules among them: 111 more packages, 85 MB more to download), so
  # without it the main job finds the three module packages' headers and libraries itself.
  find_package(OpenCV 4.6 QUIET COMPONENTS core imgproc videoio)
  if(NOT OpenCV_FOUND)
    find_path(FREEPLAY_OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
    set(OpenCV_LIBS)
    foreach(module core imgproc videoio)
      find_library(FREEPLAY_OPENCV_${module}_LIBRARY opencv_${module} REQUIRED)
      add_library(opencv_${module} SHARED IMPORTED)
      set_target_properties(opencv_${module} PROPERTIES IMPORTED_LOCATION "${FREEPLAY_OPENCV_${module}_LIBRARY}"
                            INTERFACE_INCLUDE_DIRECTORIES "${FREEPLAY_OPENCV_INCLUDE_DIR}")
      list(APPEND OpenCV_LIBS opencv_${module})
    endforeach()
  endif()
else()
  find_package(OpenCV 4.6 REQUIRED COMPONENTS core imgproc imgcodecs videoio)
endif()
find_package(mujoco 2.2 REQUIRED)
# Debian's mujoco::mujoco names /usr/include/libqhull_r/, which exists only with libqhull-dev (not needed by
# MuJoCo's public headers): drop include folders that do not exist so CMake accepts the target.
get_target_property(FREEPLAY_MUJOCO_INCLUDES mujoco::mujoco INTERFACE_INCLUDE_DIRECTORIES)
set(FREEPLAY_MUJOCO_EXISTING_INCLUDES)
foreach(dir IN LISTS FREEPLAY_MUJOCO_INCLUDES)
  if(EXISTS "${dir}")
    list(APPEND FREEPLAY_MUJOCO_EXISTING_INCLUDES "${dir}")
  endif()
endforeach()
set_target_properties(mujoco::mujoco PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${FREEPLAY_MUJOCO_EXISTING_INCLUDES}")
find_package(ompl 1.5 REQUIRED)
find_package(Boost 1.74 REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
find_package(Threads REQUIRED)
find_package(ZLIB REQUIRED)  # gzip event logs of large runs (runner)
find_package(PNG REQUIRED)  # item pictures (sim), without OpenCV's image codecs and their start-up cost
if(FREEPLAY_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(FREEPLAY_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# yaml-cpp 0.7 on Debian exports the plain target name.
if(TARGET yaml-cpp AND NOT TARGET yaml-cpp::yaml-cpp)
  add_library(yaml-cpp::yaml-cpp ALIAS yaml-cpp)
endif()

# OMPL 1.5's package config exports variables, not a target: wrap them in one.
if(NOT TARGET ompl::ompl)
  find_library(FREEPLAY_OMPL_LIBRARY NAMES ompl HINTS ${OMPL_LIBRARY_DIRS} REQUIRED)
  add_library(ompl::ompl INTERFACE IMPORTED)
  set_target_properties(ompl::ompl PROPERTIES INTERFACE_LINK_LIBRARIES "${FREEPLAY_OMPL_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "/usr/include/ompl-1.5")
endif()

# Debian's ROS 1 bag libraries (librosbag-storage-dev and the message packages): one imported target. Their headers
# need the extra include folders below (engineering-notes.md §1). roslz4 and bz2 are rosbag's decompressors, which
# the bag check (recording/src/bag_check.cpp) calls itself.
if(NOT FREEPLAY_MAIN_JOB_ONLY)  # the main job records nothing
  find_library(FREEPLAY_ROSBAG_STORAGE_LIBRARY NAMES rosbag_storage)
endif()
if(FREEPLAY_MAIN_JOB_ONLY)
  set(FREEPLAY_HAVE_ROSBAG OFF)
elseif(FREEPLAY_ROSBAG_STORAGE_LIBRARY AND EXISTS /usr/include/rosbag/bag.h AND EXISTS /usr/include/visualization_msgs)
  add_library(ros::rosbag_storage INTERFACE IMPORTED)
  set(FREEPLAY_ROS_LIBRARIES)
  foreach(lib rosbag_storage roscpp_serialization rostime cpp_common console_bridge boost_filesystem class_loader
              roslz4 bz2)
    find_library(FREEPLAY_ROS_${lib} NAMES ${lib} REQUIRED)
    list(APPEND FREEPLAY_ROS_LIBRARIES ${FREEPLAY_ROS_${lib}})
  endforeach()
  set_target_properties(ros::rosbag_storage PROPERTIES
    INTERFACE_LINK_LIBRARIES "${FREEPLAY_ROS_LIBRARIES}"
    INTERFACE_INCLUDE_DIRECTORIES "/usr/include/pluginlib;/usr/include/class_loader;/usr/include/rcpputils;/usr/include/rcutils;/usr/include/ament_index_cpp")
  set(FREEPLAY_HAVE_ROSBAG ON)
else()
  message(STATUS "ROS 1 bag libraries not found (scripts/setup.sh installs them): recording is not built")
  set(FREEPLAY_HAVE_ROSBAG OFF)
endif()
