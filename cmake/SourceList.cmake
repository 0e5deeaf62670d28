# microrelief_read_source_list(FILE VAR): the C++ files a list names (web/wasm/
# scene_checks_sources.txt: one path a line from the repository's root, '#' lines
# comments), absolute, in VAR. A line with '*' in its file name is the files of its folder
# that match, in name order (packages/microrelief-three/scripts/build.mjs reads it alike).
# The list and the folders globbed are configure dependencies.
function(microrelief_read_source_list file var)
  file(STRINGS ${file} lines REGEX "^[^#]")
  set(sources)
  foreach(line IN LISTS lines)
    if(line MATCHES "\\*")
      file(GLOB matched LIST_DIRECTORIES false CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${line})
      list(SORT matched)
      list(APPEND sources ${matched})
    else()
      list(APPEND sources ${PROJECT_SOURCE_DIR}/${line})
    endif()
  endforeach()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${file})
  set(${var} ${sources} PARENT_SCOPE)
endfunction()
