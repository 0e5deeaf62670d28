# Shaders and assets are read at run time from <prefix>/share/microrelief. In the build
# tree they are copied there at configure time; configure_file makes CMake re-run when a
# source file changes, so the build tree never serves a stale shader.
function(microrelief_stage_runtime_data subdir)
  file(GLOB_RECURSE files CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/${subdir}
       ${PROJECT_SOURCE_DIR}/${subdir}/*)
  foreach(f IN LISTS files)
    configure_file(${PROJECT_SOURCE_DIR}/${subdir}/${f}
                   ${PROJECT_BINARY_DIR}/${MICRORELIEF_DATA_SUBDIR}/${subdir}/${f} COPYONLY)
  endforeach()
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${subdir} DESTINATION ${MICRORELIEF_DATA_SUBDIR})
endfunction()

microrelief_stage_runtime_data(shaders)
microrelief_stage_runtime_data(assets)
# The WebGL 2 page (web/): it reads ../shaders and ../assets beside it, so it runs from the
# build tree and an install as from the source tree (scripts/web.sh, web/serve.py).
microrelief_stage_runtime_data(web)
