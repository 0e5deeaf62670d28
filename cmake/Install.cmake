# Installing the library for engines: static archives (position-independent, so they
# link into shared objects too), the public headers, glad2's generated header for
# microrelief::gl, a CMake package with one export set per component, pkg-config files,
# the licence (MIT, LICENSE) under share/doc/microrelief, and (cmake/RuntimeData.cmake) the
# GLSL library under share/microrelief/shaders.
include(CMakePackageConfigHelpers)

# The licence, where a distribution's package keeps it (CMAKE_INSTALL_DOCDIR:
# share/doc/microrelief); the CMake and pkg-config files have no field for it.
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(MICRORELIEF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/microrelief)

# The version header, generated into the build tree's include/ and installed beside the
# others.
configure_file(${PROJECT_SOURCE_DIR}/cmake/Version.h.in
               ${PROJECT_BINARY_DIR}/include/microrelief/Version.h @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/include/microrelief/Version.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/microrelief)
# Each component's headers (its folder) and only those built; the headers generated at
# build time (cmake/Contracts.cmake) into theirs.
foreach(component IN LISTS MICRORELIEF_COMPONENTS)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/microrelief/${component}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/microrelief)
endforeach()
install(FILES ${MICRORELIEF_CONSTANTS_HEADER} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/microrelief/core)
if(MICRORELIEF_WANTS_gl)
  install(FILES ${MICRORELIEF_PARAMETERS_HEADER} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/microrelief/gl)
  install(DIRECTORY ${GLAD_OUT}/include/
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/microrelief/third_party)
endif()

# One export set per component, so that a program asking for core finds no GL, EGL or
# OpenImageIO dependency to resolve. microrelief_glad travels with gl.
foreach(component IN LISTS MICRORELIEF_COMPONENTS)
  set(targets microrelief_${component})
  if(component STREQUAL "gl")
    list(APPEND targets microrelief_glad)
  endif()
  install(TARGETS ${targets} EXPORT microrelief-${component}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT microrelief-${component} NAMESPACE microrelief::
          FILE microrelief-${component}-targets.cmake DESTINATION ${MICRORELIEF_CMAKE_DIR})
endforeach()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/microreliefConfig.cmake.in
  ${PROJECT_BINARY_DIR}/microreliefConfig.cmake
  INSTALL_DESTINATION ${MICRORELIEF_CMAKE_DIR}
  PATH_VARS MICRORELIEF_DATA_SUBDIR CMAKE_INSTALL_INCLUDEDIR)
# 0.x: minor versions may change the API, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/microreliefConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/microreliefConfig.cmake
              ${PROJECT_BINARY_DIR}/microreliefConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/OpenImageIOFix.cmake
        DESTINATION ${MICRORELIEF_CMAKE_DIR})

# pkg-config, one file per component (the archives are static, so each file's Requires
# name what its archive needs at link time). The prefix is found from the file's own
# place (${pcfiledir}), so an install moved elsewhere still works.
file(RELATIVE_PATH MICRORELIEF_PC_TO_PREFIX "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
string(REGEX REPLACE "/$" "" MICRORELIEF_PC_TO_PREFIX "${MICRORELIEF_PC_TO_PREFIX}")
set(MICRORELIEF_IO_GDAL_PC "")
if(MICRORELIEF_IO_GDAL)
  set(MICRORELIEF_IO_GDAL_PC " gdal")
endif()
foreach(component IN LISTS MICRORELIEF_COMPONENTS)
  configure_file(${PROJECT_SOURCE_DIR}/cmake/pkgconfig/microrelief-${component}.pc.in
                 ${PROJECT_BINARY_DIR}/pkgconfig/microrelief-${component}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/pkgconfig/microrelief-${component}.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endforeach()
