# OpenCV from Debian's per-module -dev packages (libopencv-{core,imgproc,imgcodecs}-dev).
# Their CMake config ships only with the libopencv-dev metapackage, which drags in every module
# (VTK, Qt, ...); we need three, so we import them directly when the config is absent.
find_package(OpenCV QUIET COMPONENTS core imgproc imgcodecs)
if(NOT OpenCV_FOUND)
  find_path(PENA_OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
  foreach(module core imgproc imgcodecs)
    find_library(PENA_OPENCV_${module}_LIBRARY opencv_${module} REQUIRED)
    if(NOT TARGET opencv_${module})
      add_library(opencv_${module} SHARED IMPORTED)
      set_target_properties(opencv_${module} PROPERTIES
        IMPORTED_LOCATION ${PENA_OPENCV_${module}_LIBRARY}
        INTERFACE_INCLUDE_DIRECTORIES ${PENA_OPENCV_INCLUDE_DIR})
    endif()
  endforeach()
  message(STATUS "OpenCV: core, imgproc, imgcodecs from ${PENA_OPENCV_INCLUDE_DIR}")
endif()
