# The GL loader is generated at build time by glad2 (Debian's python3-glad) from the
# Khronos XML it ships (--reproducible: no download). --mx makes a per-context function
# table (GladGLContext), so one process can hold EGL, OSMesa and GLFW contexts at once
# without ever calling the gl* symbols that libGL or libOSMesa export. Installed with
# microrelief::gl, its header under include/microrelief/third_party (gl/Gl.h).
find_program(GLAD_EXECUTABLE glad REQUIRED
  DOC "glad2 loader generator (Debian package python3-glad)")

set(GLAD_OUT ${PROJECT_BINARY_DIR}/glad)
set(GLAD_API "gl:core=3.3")
set(GLAD_EXTENSIONS "GL_KHR_debug,GL_ARB_clip_control,GL_ARB_shader_storage_buffer_object,GL_ARB_shader_image_load_store")

add_custom_command(
  OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h
  COMMAND ${GLAD_EXECUTABLE} --quiet --reproducible --out-path ${GLAD_OUT}
          --api ${GLAD_API} --extensions ${GLAD_EXTENSIONS} c --mx
  COMMENT "Generating the GL loader with glad2 (${GLAD_API}, per-context)"
  VERBATIM)

add_library(microrelief_glad STATIC ${GLAD_OUT}/src/gl.c)
add_library(microrelief::glad ALIAS microrelief_glad)
target_include_directories(microrelief_glad SYSTEM PUBLIC
  $<BUILD_INTERFACE:${GLAD_OUT}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/microrelief/third_party>)
set_target_properties(microrelief_glad PROPERTIES POSITION_INDEPENDENT_CODE ON EXPORT_NAME glad)
