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
# The page's WebGPU path (web/relief_gpu.js) translates the library's GLSL to WGSL in the
# browser with naga-wasm (docs/webgpu.md), which microrelief-three's `npm ci` puts in its
# node_modules: its browser build staged as web/generated/naga/ (and installed there). Without
# it a stub says so, and the page draws with WebGL 2 (api=webgpu says why in one line).
set(naga_dist ${PROJECT_SOURCE_DIR}/packages/microrelief-three/node_modules/naga-wasm/dist)
set(naga_stage ${PROJECT_BINARY_DIR}/${MICRORELIEF_DATA_SUBDIR}/web/generated/naga)
if(EXISTS ${naga_dist}/index.js)
  foreach(f index.js version.js wasm/naga.js wasm/naga_bg.wasm)
    configure_file(${naga_dist}/${f} ${naga_stage}/${f} COPYONLY)
  endforeach()
  foreach(f LICENSE-MIT LICENSE-APACHE)
    configure_file(${naga_dist}/../${f} ${naga_stage}/${f} COPYONLY)
  endforeach()
  install(DIRECTORY ${naga_stage} DESTINATION ${MICRORELIEF_DATA_SUBDIR}/web/generated)
else()
  message(STATUS "web: no packages/microrelief-three/node_modules/naga-wasm (npm ci there): the page draws with WebGL 2 only")
  file(WRITE ${naga_stage}/index.js
       "// Staged by cmake/RuntimeData.cmake: a build without naga-wasm.\n"
       "export async function init() {\n"
       "    throw new Error('this build has no naga-wasm (npm ci in packages/microrelief-three, then configure again)');\n"
       "}\n")
  install(DIRECTORY ${naga_stage} DESTINATION ${MICRORELIEF_DATA_SUBDIR}/web/generated)
endif()
