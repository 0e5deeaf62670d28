# What C++, JavaScript and GLSL must agree on, written once and generated at build time by
# cmake/generate_contracts.py (Python 3, standard library only); nothing generated is
# committed:
#  * the uniform block MicroreliefParameters, written in shaders/relief_parameters.glsl:
#    the C++ struct (include/microrelief/gl/ReliefParameters.h, with a static_assert on
#    every offset) and an ES module (share/microrelief/web/relief_layout.js: the offsets
#    and a writer) for the page and any JavaScript host;
#  * the GLSL library's constants that the C++ twin shares, listed below as
#    FILE:GLSL_NAME:CppName (include/microrelief/core/GlslConstants.h, namespace
#    microrelief::glsl, and the same module);
#  * the enumerations whose values choose a variant of the shaders (the host's #defines
#    MICRORELIEF_METHOD, _BASE, _INTERPOLATION, _SHADOWS, _DEPTH_LAYOUT) or a uniform's
#    meaning (debugView), written once as `#define MR_METHOD_MAXMIP 6` ... in
#    shaders/microrelief/variants.glsl (and debug_views.glsl), listed below as
#    FILE:PREFIX:CppEnum: a constant a member, a table of names and an X-macro of the
#    members (MICRORELIEF_GLSL_BASE_KIND_MEMBERS(X): BaseShape.h's BaseKind and the kinds'
#    geometry in BaseTable.cpp are spelled from it) in the same header
#    (src/gl/ReliefShader.cpp asserts the other C++ enums' members against them, so a
#    reordered enum stops the build) and a name -> value map in the same module (kMethodValues ...),
#    which the page and microrelief-three set the #defines from;
#  * the methods' rows (MR_TRAITS_MAXMIP ... of MR_TRAIT_* bits, in variants.glsl; the enum
#    spec's :MR_TRAIT:MR_TRAITS): glsl::kMethodTraits[] (core/scene/Method.h: methodHas) and
#    kMethodTraits, each method's trait names (the page's menus);
#  * the named bases (`//@base` rows and their `//@size` lines, in variants.glsl beside
#    MR_BASE_*; the enum spec's :@base): glsl::kBaseRows, which core/base/BaseTable.cpp
#    builds the table of bases from, and kBaseRows, which web/relief_core.js builds the
#    browser's from.
# Adding a member to the block is a line in the GLSL; sharing another constant or
# enumeration, a line here.
find_package(Python3 REQUIRED COMPONENTS Interpreter)

set(MICRORELIEF_SHARED_CONSTANTS
  segment_walk.glsl:MICRORELIEF_MAX_DEPTH:kMaxDepth
  segment_walk.glsl:MICRORELIEF_LEAF_TEXELS:kLeafTexels
  leaf_walk.glsl:MICRORELIEF_CELL_DEPTH:kCellDepth
  leaf_walk.glsl:MR_BIQUADRATIC_FINAL_FOOTPRINT:kBiquadraticFinalFootprint
  base_curved.glsl:MR_CURVED_FINAL_LENGTH:kCurvedFinalLength
  relief_query.glsl:MR_BUDGET_PER_TEXEL:kBudgetPerTexel
  relief_query.glsl:MR_BUDGET_BASE:kBudgetBase)

set(MICRORELIEF_SHARED_ENUMS
  variants.glsl:MR_METHOD:Method:MR_TRAIT:MR_TRAITS
  variants.glsl:MR_BASE:BaseKind:@base
  variants.glsl:MR_INTERPOLATION:Interpolation
  variants.glsl:MR_SHADOWS:ShadowMode
  variants.glsl:MR_DEPTH_LAYOUT:DepthLayout
  debug_views.glsl:MR_DEBUG_VIEW:DebugView)

set(MICRORELIEF_PARAMETERS_HEADER ${PROJECT_BINARY_DIR}/include/microrelief/gl/ReliefParameters.h)
set(MICRORELIEF_CONSTANTS_HEADER ${PROJECT_BINARY_DIR}/include/microrelief/core/GlslConstants.h)
set(MICRORELIEF_LAYOUT_MODULE ${PROJECT_BINARY_DIR}/${MICRORELIEF_DATA_SUBDIR}/web/relief_layout.js)
set(constant_files)
foreach(spec IN LISTS MICRORELIEF_SHARED_CONSTANTS MICRORELIEF_SHARED_ENUMS)
  string(REPLACE ":" ";" parts ${spec})
  list(GET parts 0 file)
  list(APPEND constant_files ${PROJECT_SOURCE_DIR}/shaders/microrelief/${file})
endforeach()
list(REMOVE_DUPLICATES constant_files)
add_custom_command(
  OUTPUT ${MICRORELIEF_PARAMETERS_HEADER} ${MICRORELIEF_CONSTANTS_HEADER} ${MICRORELIEF_LAYOUT_MODULE}
  COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/cmake/generate_contracts.py
          --block ${PROJECT_SOURCE_DIR}/shaders/relief_parameters.glsl
          --shaders ${PROJECT_SOURCE_DIR}/shaders/microrelief
          --constants ${MICRORELIEF_SHARED_CONSTANTS}
          --enums ${MICRORELIEF_SHARED_ENUMS}
          --struct ${MICRORELIEF_PARAMETERS_HEADER}
          --constants-header ${MICRORELIEF_CONSTANTS_HEADER}
          --js ${MICRORELIEF_LAYOUT_MODULE}
  DEPENDS ${PROJECT_SOURCE_DIR}/cmake/generate_contracts.py
          ${PROJECT_SOURCE_DIR}/shaders/relief_parameters.glsl ${constant_files}
  COMMENT "Generating the uniform block's C++ and JavaScript layouts, the shared constants and enumerations"
  VERBATIM)
add_custom_target(microrelief_contracts ALL
  DEPENDS ${MICRORELIEF_PARAMETERS_HEADER} ${MICRORELIEF_CONSTANTS_HEADER} ${MICRORELIEF_LAYOUT_MODULE})
install(FILES ${MICRORELIEF_LAYOUT_MODULE} DESTINATION ${MICRORELIEF_DATA_SUBDIR}/web)
