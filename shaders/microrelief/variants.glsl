// variants.glsl: the values of the option macros that choose a variant of the library and
// of relief.frag, by name. This file is where they are written: cmake/generate_contracts.py
// reads every `#define MR_<ENUM>_<NAME> value` below (cmake/Contracts.cmake lists the
// prefixes) and gives C++ the same numbers (core/GlslConstants.h: glsl::kMethodMaxmip ...,
// which src/gl/ReliefShader.cpp holds the C++ enums to, member by member) and JavaScript a
// name -> value table (relief_layout.js: kMethodValues ...), from which the page and
// microrelief-three set the macros. A host writes `#define MICRORELIEF_METHOD 6` (the
// number); a file of the library compares it with a name: `#if MICRORELIEF_METHOD ==
// MR_METHOD_MAXMIP`. The lower-case part after the prefix is the name the programs and
// the pages use (--method maxmip). Values run 0, 1, 2 ... in each enumeration.
//
// use: included by every file that compares one of the macros below with a value.
// options: none. Defines only, and precision.glsl, whose statements are GLSL ES's alone:
// on desktop GL nothing here is a token past the preprocessor, so relief.frag includes it
// above its #extension line (which GLSL ES never takes).
#ifndef MICRORELIEF_VARIANTS_GLSL
#define MICRORELIEF_VARIANTS_GLSL

#include "precision.glsl"

// MICRORELIEF_METHOD (relief.frag): how each pixel's ray is traced (core/scene/Method.h).
#define MR_METHOD_MULTILEVEL 0
#define MR_METHOD_NORMAL 1
#define MR_METHOD_OFFSET 2
#define MR_METHOD_STEEP 3
#define MR_METHOD_POM 4
#define MR_METHOD_RELIEF 5
#define MR_METHOD_MAXMIP 6
#define MR_METHOD_CONE 7
#define MR_METHOD_RCSM 8

// MICRORELIEF_BASE (base_surface.glsl): the base surface (core/base/BaseShape.h: BaseKind).
#define MR_BASE_PLANE 0
#define MR_BASE_CYLINDER 1
#define MR_BASE_ELLIPSOID 2

// MICRORELIEF_INTERPOLATION (relief_patch.glsl): the last level's surface
// (core/heightmap/HeightMap.h: Interpolation).
#define MR_INTERPOLATION_BILINEAR 0
#define MR_INTERPOLATION_BIQUADRATIC 1

// MICRORELIEF_SHADOWS (relief.frag, shadow.glsl): self-shadows (core/scene/Method.h:
// ShadowMode).
#define MR_SHADOWS_OFF 0
#define MR_SHADOWS_HARD 1
#define MR_SHADOWS_SOFT 2

// MICRORELIEF_DEPTH_LAYOUT (relief.frag): what the depth written promises against the
// rasterised proxy's (gl/ReliefShader.h: DepthLayout).
#define MR_DEPTH_LAYOUT_ANY 0
#define MR_DEPTH_LAYOUT_GREATER 1
#define MR_DEPTH_LAYOUT_LESS 2

#endif  // MICRORELIEF_VARIANTS_GLSL
