# Shaders and assets are read at run time from <prefix>/share/microrelief. In the build
# tree they are copied there at configure time; configure_file makes CMake re-run when a
# source file changes, so the build tree never serves a stale shader.
# `EXCLUDE folder`: a folder of `subdir` that is built from, not served (web/wasm).
function(microrelief_stage_runtime_data subdir)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "EXCLUDE" "")
  file(GLOB_RECURSE files CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/${subdir}
       ${PROJECT_SOURCE_DIR}/${subdir}/*)
  if(arg_EXCLUDE)
    list(FILTER files EXCLUDE REGEX "^${arg_EXCLUDE}/")
  endif()
  foreach(f IN LISTS files)
    configure_file(${PROJECT_SOURCE_DIR}/${subdir}/${f}
                   ${PROJECT_BINARY_DIR}/${MICRORELIEF_DATA_SUBDIR}/${subdir}/${f} COPYONLY)
  endforeach()
  if(arg_EXCLUDE)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${subdir} DESTINATION ${MICRORELIEF_DATA_SUBDIR}
            PATTERN ${arg_EXCLUDE} EXCLUDE)
  else()
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${subdir} DESTINATION ${MICRORELIEF_DATA_SUBDIR})
  endif()
endfunction()

microrelief_stage_runtime_data(shaders)
microrelief_stage_runtime_data(assets)
# The WebGL 2 page (web/): it reads ../shaders and ../assets beside it, so it runs from the
# build tree and an install as from the source tree (scripts/web.sh, web/serve.py). Its
# WebAssembly (web/wasm/) is built into web/generated/ there (web/wasm/CMakeLists.txt).
microrelief_stage_runtime_data(web EXCLUDE wasm)
