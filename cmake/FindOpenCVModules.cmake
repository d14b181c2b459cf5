# Debian ships OpenCV's CMake package only with the meta package libopencv-dev, which pulls in
# every module (VTK, Qt, ...). We install just the module packages we use and build imported
# targets OpenCV::<module> from their headers and libraries.
find_path(OpenCVModules_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
set(OpenCVModules_FOUND TRUE)
foreach(module IN LISTS OpenCVModules_FIND_COMPONENTS)
  find_library(OpenCVModules_${module}_LIBRARY opencv_${module})
  if(NOT OpenCVModules_${module}_LIBRARY)
    set(OpenCVModules_FOUND FALSE)
    message(FATAL_ERROR "OpenCV module '${module}' not found: run scripts/setup.sh")
  endif()
  if(NOT TARGET OpenCV::${module})
    add_library(OpenCV::${module} UNKNOWN IMPORTED)
    set_target_properties(OpenCV::${module} PROPERTIES
      IMPORTED_LOCATION ${OpenCVModules_${module}_LIBRARY}
      INTERFACE_INCLUDE_DIRECTORIES ${OpenCVModules_INCLUDE_DIR})
  endif()
endforeach()
