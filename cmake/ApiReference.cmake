# The API reference: Markdown pages generated from the public headers' comments by LLVM's
# clang-doc (Debian: clang-tools-14), cmake/api_reference.py. Not part of `all`:
#   cmake --build build --target api-reference   ->   build/docs/api-reference/index.md
# ctest docs.api_reference (tests/docs) checks what it writes.
find_program(MICRORELIEF_CLANG_DOC NAMES clang-doc clang-doc-14
             DOC "LLVM's clang-doc (Debian: clang-tools-14), for the API reference")
set(MICRORELIEF_API_INCLUDES -I ${PROJECT_BINARY_DIR}/include)
if(TARGET microrelief_glad)
  list(APPEND MICRORELIEF_API_INCLUDES -I ${GLAD_OUT}/include)
endif()
if(MICRORELIEF_CLANG_DOC)
  add_custom_target(api-reference
    COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/cmake/api_reference.py
            --clang-doc ${MICRORELIEF_CLANG_DOC} --source ${PROJECT_SOURCE_DIR}
            --out ${PROJECT_BINARY_DIR}/docs/api-reference ${MICRORELIEF_API_INCLUDES}
    COMMENT "Writing the API reference (clang-doc) into ${PROJECT_BINARY_DIR}/docs/api-reference"
    VERBATIM)
  # The generated headers the public ones include (the contracts, glad's loader).
  add_dependencies(api-reference microrelief_contracts)
  if(TARGET microrelief_glad)
    add_dependencies(api-reference microrelief_glad)
  endif()
endif()
