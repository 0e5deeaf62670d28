// relief_patch.glsl: the last level of detail, the surface between the samples, as the
// host chooses it with MICRORELIEF_INTERPOLATION (relief_map.glsl): 0 bilinear
// (bilinear_patch.glsl), 1 biquadratic (biquadratic_patch.glsl). A compile-time choice,
// not a uniform: the two read different samples (4 per cell, 9 per texel square), solve
// different leaves and bound different patches, and a uniform would keep both paths, with
// their registers, in every program.
//
// A patch is the surface over one cell: bilinear cells lie between sample centres, cell
// (i, j) over X in [i + 1/2, i + 3/2]; biquadratic cells are texel squares, X in [i, i + 1].
// MR_PATCH_OFFSET is where cell 0 starts; local coordinates run over [0, 1]^2 across a cell.
// mr_ReliefPatch is the patch's type: the four corner samples, or the 3 x 3 Bezier net.
#ifndef MICRORELIEF_RELIEF_PATCH_GLSL
#define MICRORELIEF_RELIEF_PATCH_GLSL

#include "base_surface.glsl"
#include "bilinear_patch.glsl"
#include "biquadratic_patch.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"
#include "variants.glsl"

#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
#define mr_ReliefPatch mat3
const float MR_PATCH_OFFSET = 0.0;
#else
#define mr_ReliefPatch vec4
const float MR_PATCH_OFFSET = 0.5;
#endif

// A patch's bound (mr_patchTop) is padded by this much of the map's largest height: its own
// float rounding, a few ulp of the net's entries.
const float MR_PATCH_TOP_MARGIN = 1.0 / 1048576.0;

// The cell holding map point xy (ties to the cell on the positive side), its column kept
// in 0..W - 1 on a curved base.
ivec2 mr_patchCellAt(mr_Relief relief, vec2 xy) { return mr_wrapCell(relief, ivec2(floor(xy - MR_PATCH_OFFSET))); }

// Map point xy in the local coordinates of `cell`; on a curved base the seam cell holds
// the points just past X = 0 too (map_addressing.glsl: mr_wrapLocalX).
vec2 mr_patchLocal(mr_Relief relief, ivec2 cell, vec2 xy) {
    vec2 f = xy - (vec2(cell) + MR_PATCH_OFFSET);
#if MICRORELIEF_BASE_WRAPS_U
    f.x = mr_wrapLocalX(relief, f.x);
#endif
    return f;
}

mr_ReliefPatch mr_patchAt(mr_Relief relief, MICRORELIEF_SAMPLER heights, ivec2 cell) {
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
    return mr_biquadraticNet(relief, heights, cell);
#else
    return mr_cellCorners(relief, heights, cell);
#endif
}

// Height and gradient (per texel) of the patch at local coordinates f.
float mr_patchValue(mr_ReliefPatch cellPatch, vec2 f) {
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
    return mr_biquadraticHeight(cellPatch, f);
#else
    return mr_patchHeight(cellPatch, f);
#endif
}

vec2 mr_patchSlope(mr_ReliefPatch cellPatch, vec2 f) {
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
    return mr_biquadraticGradient(cellPatch, f);
#else
    return mr_patchGradient(cellPatch, f);
#endif
}

// The patch's max over the local rectangle [lo, hi], never below it.
float mr_patchTop(mr_ReliefPatch cellPatch, vec2 lo, vec2 hi) {
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BIQUADRATIC
    return mr_biquadraticMaxOver(cellPatch, lo, hi);
#else
    return mr_patchMaxOver(cellPatch, lo, hi);
#endif
}

// h(X, Y): the surface height at a map point.
float mr_reliefHeight(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec2 xy) {
    ivec2 cell = mr_patchCellAt(relief, xy);
    return mr_patchValue(mr_patchAt(relief, heights, cell), clamp(mr_patchLocal(relief, cell, xy), 0.0, 1.0));
}

// The map gradient of the surface at map point xy of `cell`: on the plane the bilinear
// surface's clamped border cells are flat across the edge (the biquadratic surface is
// flat there by itself: its edge control points repeat).
vec2 mr_reliefSlope(mr_Relief relief, mr_ReliefPatch cellPatch, ivec2 cell, vec2 xy) {
    vec2 g = mr_patchSlope(cellPatch, clamp(mr_patchLocal(relief, cell, xy), 0.0, 1.0));
#if MICRORELIEF_INTERPOLATION == MR_INTERPOLATION_BILINEAR
#if !MICRORELIEF_BASE_WRAPS_U
    if (cell.x < 0 || cell.x >= int(relief.map.size.x) - 1) g.x = 0.0;
#endif
    if (cell.y < 0 || cell.y >= int(relief.map.size.y) - 1) g.y = 0.0;
#endif
    return g;
}

#endif
