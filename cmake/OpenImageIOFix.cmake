# Debian 12's OpenImageIO config lists /usr/include/opencv4 as an include folder even
# when OpenCV is not installed, which CMake rejects; OpenImageIO's public headers never
# need it, so drop folders that do not exist. Used by the project and by the installed
# package (microreliefConfig.cmake) after find_package(OpenImageIO).
if(TARGET OpenImageIO::OpenImageIO)
  foreach(property INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(dirs OpenImageIO::OpenImageIO ${property})
    if(dirs)
      list(FILTER dirs EXCLUDE REGEX "opencv")
      set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${property} "${dirs}")
    endif()
  endforeach()
endif()
