// relief_patch.glsl: the last level of detail, the surface between the samples, as the
// host chooses it with MICRORELIEF_INTERPOLATION (relief_map.glsl): 0 bilinear
// (bilinear_patch.glsl), 1 biquadratic (biquadratic_patch.glsl). A compile-time choice,
// not a uniform: the two read different samples (4 per cell, 9 per texel square), solve
// different leaves and bound different patches, and a uniform would keep both paths, with
// their registers, in every program.
//
// A patch is the surface over one cell: bilinear cells lie between sample centres, cell
// (i, j) over X in [i + 1/2, i + 3/2]; biquadratic cells are texel squares, X in [i, i + 1].
// kPatchOffset is where cell 0 starts; local coordinates run over [0, 1]^2 across a cell.
// ReliefPatch is the patch's type: the four corner samples, or the 3 x 3 Bezier net.
#ifndef MICRORELIEF_RELIEF_PATCH_GLSL
#define MICRORELIEF_RELIEF_PATCH_GLSL

#include "bilinear_patch.glsl"
#include "biquadratic_patch.glsl"
#include "relief_map.glsl"

#if MICRORELIEF_INTERPOLATION == 1
#define ReliefPatch mat3
const float kPatchOffset = 0.0;
#else
#define ReliefPatch vec4
const float kPatchOffset = 0.5;
#endif

// The cell holding map point xy (ties to the cell on the positive side), its column kept
// in 0..W - 1 on a curved base.
ivec2 patchCellAt(ReliefMap map, vec2 xy) { return wrapCell(map, ivec2(floor(xy - kPatchOffset))); }

// Map point xy in the local coordinates of `cell`; on a curved base the seam cell holds
// the points just past X = 0 too.
vec2 patchLocal(ReliefMap map, ivec2 cell, vec2 xy) {
    vec2 f = xy - (vec2(cell) + kPatchOffset);
#if MICRORELIEF_BASE != 0
    f.x -= map.size.x * floor(f.x / map.size.x + 0.5);
#endif
    return f;
}

ReliefPatch patchAt(ReliefMap map, sampler2D heights, ivec2 cell, inout int fetches) {
#if MICRORELIEF_INTERPOLATION == 1
    return biquadraticNet(map, heights, cell, fetches);
#else
    return cellCorners(map, heights, cell, fetches);
#endif
}

// Height and gradient (per texel) of the patch at local coordinates f.
float patchValue(ReliefPatch cellPatch, vec2 f) {
#if MICRORELIEF_INTERPOLATION == 1
    return biquadraticHeight(cellPatch, f);
#else
    return patchHeight(cellPatch, f);
#endif
}

vec2 patchSlope(ReliefPatch cellPatch, vec2 f) {
#if MICRORELIEF_INTERPOLATION == 1
    return biquadraticGradient(cellPatch, f);
#else
    return patchGradient(cellPatch, f);
#endif
}

// The patch's max over the local rectangle [lo, hi], never below it.
float patchTop(ReliefPatch cellPatch, vec2 lo, vec2 hi) {
#if MICRORELIEF_INTERPOLATION == 1
    return biquadraticMaxOver(cellPatch, lo, hi);
#else
    return patchMaxOver(cellPatch, lo, hi);
#endif
}

// h(X, Y): the surface height at a map point.
float reliefHeight(ReliefMap map, sampler2D heights, vec2 xy, inout int fetches) {
    ivec2 cell = patchCellAt(map, xy);
    return patchValue(patchAt(map, heights, cell, fetches), clamp(patchLocal(map, cell, xy), 0.0, 1.0));
}

// The map gradient of the surface at map point xy of `cell`: on the plane the bilinear
// surface's clamped border cells are flat across the edge (the biquadratic surface is
// flat there by itself: its edge control points repeat).
vec2 reliefSlope(ReliefMap map, ReliefPatch cellPatch, ivec2 cell, vec2 xy) {
    vec2 g = patchSlope(cellPatch, clamp(patchLocal(map, cell, xy), 0.0, 1.0));
#if MICRORELIEF_INTERPOLATION == 0
#if MICRORELIEF_BASE == 0
    if (cell.x < 0 || cell.x >= int(map.size.x) - 1) g.x = 0.0;
#endif
    if (cell.y < 0 || cell.y >= int(map.size.y) - 1) g.y = 0.0;
#endif
    return g;
}

#endif
