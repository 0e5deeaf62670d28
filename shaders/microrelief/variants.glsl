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

// What each method is: its row, MR_TRAITS_<METHOD>, the MR_TRAIT_* it has, or'ed. The
// programs' checks and lists (core/scene/Method.h: methodHas), the page's menus and
// relief.frag's choices (MICRORELIEF_METHOD_TRAITS) all read these rows. A method is a value
// above, a row here and two lines in relief.frag: its row chosen, and its GLSL entry
// (mr_traceMultilevel, mr_traceMaxMip ...) called in traceInFrame.
// cmake/generate_contracts.py requires a row for every method and bits that are distinct
// powers of two.
#define MR_TRAIT_STEPS 1             // its quality knob is a step count (--steps)
#define MR_TRAIT_SOLID 2             // traces the whole solid, side walls and bottom face
                                     // included: exact, and its hits take self-shadows
#define MR_TRAIT_CURVED 4            // runs on the curved bases
#define MR_TRAIT_TANGENT_FRAME 8     // on a curved base, steps in the base's tangent frame
                                     // where the ray enters the shell, as engines run it
#define MR_TRAIT_TILES 16            // takes a tiled map (--tile)
#define MR_TRAIT_OFF_RAY 32          // its answer is a map point off the ray (a shifted lookup)
#define MR_TRAIT_MAX_PYRAMID 64      // reads the map's own quadtree (aligned max levels)
#define MR_TRAIT_CONE_MAP 128        // reads a conservative cone map (peers/ConeMap.h)
#define MR_TRAIT_RELAXED_CONE_MAP 256  // reads a relaxed cone map

#define MR_TRAITS_MULTILEVEL (MR_TRAIT_SOLID | MR_TRAIT_CURVED | MR_TRAIT_TILES)
#define MR_TRAITS_NORMAL (MR_TRAIT_TILES)
#define MR_TRAITS_OFFSET (MR_TRAIT_TILES | MR_TRAIT_OFF_RAY)
#define MR_TRAITS_STEEP (MR_TRAIT_STEPS | MR_TRAIT_TILES)
#define MR_TRAITS_POM (MR_TRAIT_STEPS | MR_TRAIT_CURVED | MR_TRAIT_TANGENT_FRAME | MR_TRAIT_TILES)
#define MR_TRAITS_RELIEF (MR_TRAIT_STEPS | MR_TRAIT_CURVED | MR_TRAIT_TANGENT_FRAME | MR_TRAIT_TILES)
#define MR_TRAITS_MAXMIP (MR_TRAIT_SOLID | MR_TRAIT_CURVED | MR_TRAIT_MAX_PYRAMID)
#define MR_TRAITS_CONE (MR_TRAIT_SOLID | MR_TRAIT_CONE_MAP)
#define MR_TRAITS_RCSM (MR_TRAIT_STEPS | MR_TRAIT_RELAXED_CONE_MAP)

// MICRORELIEF_BASE (base_surface.glsl): the base surface (core/base/BaseShape.h: BaseKind).
#define MR_BASE_PLANE 0
#define MR_BASE_CYLINDER 1
#define MR_BASE_ELLIPSOID 2

// The named bases, written once: the rows of the table of bases (core/base/BaseType.h:
// baseTypes(), built in core/base/BaseTable.cpp from glsl::kBaseRows; relief_layout.js's
// kBaseRows, from which web/relief_core.js makes the browser's), in the order --help and the
// lists give them. A row, `//@base NAME KIND "summary"`: the name the scene, --base and the
// pages' base= take, its kind (MR_BASE_KIND: the GLSL file and the C++ geometry that draw
// it) and what --help says of it. Each `//@size FIELD "Label" MEMBER = DEFAULTS [example
// NUMBERS]` under it is one of its sizes: the scene's field (base.radius; its flag, --radius,
// and the pages' key, radius, come from it), a slider's label, the core::BaseShape member
// it sets (radii[3]: three numbers), its default (one number, or one a component) and the
// example the viewer offers (the default unless given). One number for a member of three
// sets all three, and such a row names only the shapes whose three are equal (the sphere);
// a row of whole members every shape of its kind that no such row takes, one a kind.
// cmake/generate_contracts.py (read_named) refuses a row it cannot read, naming the line.
// These are comments to GLSL: no shader reads them.
//@base plane PLANE "the plane y = 0, the map's longer side one unit"
//@base cylinder CYLINDER "a column about the y axis with flat caps"
//@size base.radius "Radius" radius = 0.3
//@size base.length "Length" length = 1
//@base ellipsoid ELLIPSOID "the ellipsoid of radii A, B, C about the origin"
//@size base.radii "Radius" radii[3] = 0.5 0.5 0.5 example 0.5 0.35 0.4
//@base sphere ELLIPSOID "the ellipsoid with equal radii"
//@size base.radius "Radius" radii[3] = 0.5

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
