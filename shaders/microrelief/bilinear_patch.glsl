// bilinear_patch.glsl: the exact surface, h(X, Y), the bilinear interpolation of the
// samples with CLAMP_TO_EDGE (scene-and-cli.md), interpolated in float in the shader
// because hardware filtering weights are low precision on some GPUs.
//
// `heights` is the W x H sample texture (CLAMP_TO_EDGE; its filter is not used). Cell
// (i, j) is the patch between the sample centres (i + 0.5, j + 0.5) and (i + 1.5, j + 1.5);
// cells -1 and W - 1 (H - 1) are the clamped half-texel borders, flat across the edge.
// On a curved base u wraps (MICRORELIEF_BASE_WRAPS_U, base_surface.glsl): the texture's S
// wrap is REPEAT, cell W - 1 joins sample W - 1 to sample 0 across the seam, and cell
// indices are kept in 0..W - 1 (mr_wrapCell).
#ifndef MICRORELIEF_BILINEAR_PATCH_GLSL
#define MICRORELIEF_BILINEAR_PATCH_GLSL

#include "base_surface.glsl"
#include "fetch_count.glsl"
#include "map_addressing.glsl"
#include "relief_map.glsl"
#include "texture_reads.glsl"

// A cell's four samples are one gather or four single reads (texture_reads.glsl:
// MICRORELIEF_TEXTURE_GATHER), counted as 1 or 4 fetches (fetch_count.glsl).

// The four corner samples of a tiled map's cell one by one (mr_sampleTexel).
vec4 mr_tiledCellCorners(mr_Relief relief, MICRORELIEF_SAMPLER heights, ivec2 cell) {
    MICRORELIEF_FETCHED(4);
    return vec4(MICRORELIEF_READ_SAMPLE(heights, mr_sampleTexel(relief, cell)),
                MICRORELIEF_READ_SAMPLE(heights, mr_sampleTexel(relief, cell + ivec2(1, 0))),
                MICRORELIEF_READ_SAMPLE(heights, mr_sampleTexel(relief, cell + ivec2(0, 1))),
                MICRORELIEF_READ_SAMPLE(heights, mr_sampleTexel(relief, cell + 1)));
}

// The four corner samples of cell `cell`: x = h00, y = h10, z = h01, w = h11.
vec4 mr_cellCorners(mr_Relief relief, MICRORELIEF_SAMPLER heights, ivec2 cell) {
#if MICRORELIEF_TILING
#if MICRORELIEF_TEXTURE_GATHER
    // One gather of the REPEATing texture, from the cell's first sample on, reads its four
    // samples, across a seam between tiles too. At the map's own clamped edges the gather
    // reads the edge sample and the next one (or the wrapped one), where the clamped map
    // repeats the edge sample: the selects put that right, without a branch (which a
    // software rasteriser would run on both sides).
    MICRORELIEF_FETCHED(1);
    vec4 g = MICRORELIEF_GATHER_SAMPLES(heights, (vec2(mr_sampleTexel(relief, cell)) + 1.0) / mr_tileSize(relief.map));
    vec4 h = vec4(g.w, g.z, g.x, g.y);
    ivec2 last = ivec2(relief.map.size) - 1;
#if !MICRORELIEF_BASE_WRAPS_U
    h.yw = (cell.x < 0 || cell.x >= last.x) ? h.xz : h.yw;
#endif
    h.zw = (cell.y < 0 || cell.y >= last.y) ? h.xy : h.zw;
    return h;
#else
    return mr_tiledCellCorners(relief, heights, cell);
#endif
#elif MICRORELIEF_TEXTURE_GATHER
    // The bilinear footprint of the point midway between the cell's four samples is
    // exactly those samples, clamped at the edges as CLAMP_TO_EDGE clamps them.
    MICRORELIEF_FETCHED(1);
    vec4 g = MICRORELIEF_GATHER_SAMPLES(heights, (vec2(cell) + 1.0) / relief.map.size);
    return vec4(g.w, g.z, g.x, g.y);  // gather order: (i0, j1), (i1, j1), (i1, j0), (i0, j0)
#else
    ivec2 last = ivec2(relief.map.size) - 1;
    ivec2 c0 = clamp(cell, ivec2(0), last);
    ivec2 c1 = clamp(cell + 1, ivec2(0), last);
#if MICRORELIEF_BASE_WRAPS_U
    c0.x = cell.x;
    c1.x = cell.x + 1 > last.x ? 0 : cell.x + 1;
#endif
    MICRORELIEF_FETCHED(4);
    return vec4(MICRORELIEF_READ_SAMPLE(heights, c0), MICRORELIEF_READ_SAMPLE(heights, ivec2(c1.x, c0.y)),
                MICRORELIEF_READ_SAMPLE(heights, ivec2(c0.x, c1.y)), MICRORELIEF_READ_SAMPLE(heights, c1));
#endif
}

// The corners of the neighbour of `cell` one `step` (+1 or -1) along `axis`, given the
// corners of `cell`; `cell` moves. The two cells share an edge: without gathering, only
// the far edge's two samples are read.
vec4 mr_neighbourCorners(mr_Relief relief, MICRORELIEF_SAMPLER heights, inout ivec2 cell, int axis, int step, vec4 corners) {
    cell[axis] += step;
#if MICRORELIEF_TEXTURE_GATHER || MICRORELIEF_TILING
    return mr_cellCorners(relief, heights, cell);
#else
    ivec2 last = ivec2(relief.map.size) - 1;
    ivec2 c0 = clamp(cell, ivec2(0), last), c1 = clamp(cell + 1, ivec2(0), last);
    MICRORELIEF_FETCHED(2);
    if (axis == 0) {
        int x = step > 0 ? c1.x : c0.x;
        vec2 fresh = vec2(MICRORELIEF_READ_SAMPLE(heights, ivec2(x, c0.y)), MICRORELIEF_READ_SAMPLE(heights, ivec2(x, c1.y)));
        vec2 kept = step > 0 ? corners.yw : corners.xz;
        return step > 0 ? vec4(kept.x, fresh.x, kept.y, fresh.y) : vec4(fresh.x, kept.x, fresh.y, kept.y);
    }
    int y = step > 0 ? c1.y : c0.y;
    vec2 fresh = vec2(MICRORELIEF_READ_SAMPLE(heights, ivec2(c0.x, y)), MICRORELIEF_READ_SAMPLE(heights, ivec2(c1.x, y)));
    vec2 kept = step > 0 ? corners.zw : corners.xy;
    return step > 0 ? vec4(kept, fresh) : vec4(fresh, kept);
#endif
}

// A cell index in 0..W - 1 on a curved base (u wraps); unchanged on the plane.
ivec2 mr_wrapCell(mr_Relief relief, ivec2 cell) {
#if MICRORELIEF_BASE_WRAPS_U
    cell.x = mr_wrapIndex(cell.x, int(relief.map.size.x));
#endif
    return cell;
}

// The cell that holds map point `xy` (ties go to the cell on the positive side).
ivec2 mr_cellAt(vec2 xy) { return ivec2(floor(xy - 0.5)); }

// Map point `xy` in the local coordinates of `cell`, whose sample h00 is at the origin; on
// a curved base the seam cell W - 1 holds the points just past X = 0 too
// (map_addressing.glsl: mr_wrapLocalX).
vec2 mr_cellLocal(mr_Relief relief, ivec2 cell, vec2 xy) {
    vec2 f = xy - (vec2(cell) + 0.5);
#if MICRORELIEF_BASE_WRAPS_U
    f.x = mr_wrapLocalX(relief, f.x);
#endif
    return f;
}

// Height of the patch with corners `h` at local coordinates f in [0, 1]^2.
float mr_patchHeight(vec4 h, vec2 f) {
    return mix(mix(h.x, h.y, f.x), mix(h.z, h.w, f.x), f.y);
}

// Gradient (dh/dX, dh/dY) of the patch at f.
vec2 mr_patchGradient(vec4 h, vec2 f) {
    return vec2(mix(h.y - h.x, h.w - h.z, f.y), mix(h.z - h.x, h.w - h.y, f.x));
}

// h(X, Y): the surface height at a map point.
float mr_surfaceHeight(mr_Relief relief, MICRORELIEF_SAMPLER heights, vec2 xy) {
    ivec2 cell = mr_wrapCell(relief, mr_cellAt(xy));
    return mr_patchHeight(mr_cellCorners(relief, heights, cell), clamp(mr_cellLocal(relief, cell, xy), 0.0, 1.0));
}

// The patch's max over the rectangle [lo, hi] of local coordinates (clamped to the
// patch): bilinear, so linear along each axis, it peaks at a corner of any rectangle.
float mr_patchMaxOver(vec4 h, vec2 lo, vec2 hi) {
    lo = clamp(lo, 0.0, 1.0);
    hi = clamp(hi, 0.0, 1.0);
    return max(max(mr_patchHeight(h, lo), mr_patchHeight(h, vec2(hi.x, lo.y))),
               max(mr_patchHeight(h, vec2(lo.x, hi.y)), mr_patchHeight(h, hi)));
}

// The first root tau in [0, tauMax] of patch(start.xy + tau dir.xy) = start.z + tau dir.z
// for the patch with corners `h` whose origin (sample h00) is at `cellOrigin`, or -1.
// Along a ray the patch height is quadratic in tau (the paper's "exact bilinear
// interpolation at the last level"), so this is a quadratic, solved stably.
float mr_intersectPatch(vec4 h, vec2 cellOrigin, vec3 start, vec3 dir, float tauMax) {
    vec2 f = start.xy - cellOrigin;
    float b = h.y - h.x, c = h.z - h.x, d = h.x - h.y - h.z + h.w;
    // g(tau) = A tau^2 + B tau + C = patch height - ray height: < 0 above the surface,
    // >= 0 inside the solid. The hit is the first tau with g(tau) >= 0.
    float C = h.x + b * f.x + c * f.y + d * f.x * f.y - start.z;
    if (C >= 0.0) return 0.0;  // the piece starts on or below the surface
    float B = b * dir.x + c * dir.y + d * (f.x * dir.y + f.y * dir.x) - dir.z;
    float A = d * dir.x * dir.y;
    float root = -1.0;
    if (abs(A) * tauMax <= 1e-7 * abs(B)) {
        // Linear within float precision over this piece.
        if (B > 0.0) root = -C / B;
    } else {
        float disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            float q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
            float r1 = q / A;
            float r2 = q != 0.0 ? C / q : -1.0;
            float lo = min(r1, r2), hi = max(r1, r2);
            root = lo >= 0.0 ? lo : hi;
        }
    }
    return (root >= 0.0 && root <= tauMax) ? root : -1.0;
}

#endif
