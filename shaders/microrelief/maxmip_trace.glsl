// maxmip_trace.glsl: the maximum mipmap quadtree traversal, the peer "maxmip" of issue 5
// (A. Tevs, I. Ihrke, H.-P. Seidel, "Maximum Mipmaps for Fast, Accurate, and Scalable
// Dynamic Height Field Rendering", I3D 2008, sec. 4).
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir (t as in world space); `pyramid` the max pyramid (layout: max_pyramid.glsl),
// `heights` the W x H samples (bilinear_patch.glsl). Output, as traceMultilevel's: the
// exact first point t >= 0 of the ray in the solid, on the top surface, a side wall or
// the bottom face, with the same statistics (iterations = nodes visited).
//
// The pyramid is a quadtree: node (p, q) at level L is the box [p, p+1) 2^L x [q, q+1) 2^L
// x [0, its max]. From the root, each step takes the node the ray is in and clips the ray
// to the node's column. If the ray passes above the box it moves on to the exit boundary,
// into the neighbour at the same level, and goes up one level when that neighbour has a
// different parent. If the ray meets the box it steps onto the box (its top) and goes down
// into the child there. At level 0 the texel spans parts of up to four bilinear patches;
// the ray is solved exactly against those it crosses, in order (intersectLeaf).
#ifndef MICRORELIEF_MAXMIP_TRACE_GLSL
#define MICRORELIEF_MAXMIP_TRACE_GLSL

#include "bilinear_patch.glsl"
#include "max_pyramid.glsl"
#include "multilevel_trace.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"

// Ray parameter where the ray leaves node `node` at `level` through a side of its column,
// per axis (1e30 along an axis the ray does not move on).
vec2 maxMipNodeExits(ivec2 node, int level, vec3 origin, vec3 dir) {
    float size = exp2(float(level));
    vec2 exits = vec2(1e30);
    for (int axis = 0; axis < 2; ++axis) {
        if (dir[axis] == 0.0) continue;
        float side = (float(node[axis]) + (dir[axis] > 0.0 ? 1.0 : 0.0)) * size;
        exits[axis] = (side - origin[axis]) / dir[axis];
    }
    return exits;
}

// The child of `node` (at `level` > 0) holding map point p; on the midline, the child the
// ray moves into.
ivec2 maxMipChildAt(ivec2 node, int level, vec2 p, vec3 dir) {
    float halfSize = exp2(float(level - 1));
    ivec2 child = 2 * node;
    for (int axis = 0; axis < 2; ++axis) {
        float mid = (2.0 * float(node[axis]) + 1.0) * halfSize;
        if (p[axis] > mid || (p[axis] == mid && dir[axis] > 0.0)) child[axis] += 1;
    }
    return child;
}

// The node's max height: one texel of the pyramid.
float maxMipNodeHeight(ReliefMap map, sampler2D pyramid, ivec2 node, int level, inout int fetches) {
    ivec2 levelSize = max(ivec2(1), map.pyramidSize >> level);
    return pyramidTexel(map, pyramid, clamp(node, ivec2(0), levelSize - 1), level, fetches);
}

// Into the neighbour of `node` across the side(s) of its column the ray leaves through
// at tExit; up one level when that neighbour has a different parent.
void maxMipNextNode(inout ivec2 node, inout int level, int topLevel, vec2 exits, float tExit, vec3 dir) {
    ivec2 next = node + ivec2(exits.x <= tExit ? int(sign(dir.x)) : 0,
                              exits.y <= tExit ? int(sign(dir.y)) : 0);
    bool newParent = any(notEqual(next >> 1, node >> 1));
    node = next;
    if (newParent && level < topLevel) {
        node >>= 1;
        level += 1;
    }
}

// The quadtree walk over the segment origin + t dir, t in [0, tFar], of a ray that leaves
// the box through its floor when `floorExit`; fills `hit` with local t. The loops have the shape of
// traceMultilevel's (multilevel_trace.glsl): an inner one walks nodes down to a finest
// texel the ray meets, an outer one solves it, so that pixels in SIMD lanes pay for
// their leaves once per outer pass, not on every node.
void walkMaxMip(ReliefMap map, sampler2D pyramid, sampler2D heights, vec3 origin, vec3 dir, float tFar,
                bool floorExit, inout ReliefHit hit) {
    float t = 0.0;  // where the ray is in the current node
    int topLevel = map.levelCount - 1;
    int level = topLevel;
    ivec2 node = ivec2(0);  // the root covers the whole map
    bool finished = false, solved = false;
    float tHit = -1.0;
    vec4 corners;
    ivec2 cell;
    int iteration = 0;
    vec2 exits = vec2(0.0);  // where the ray leaves the current node's column, per axis
    float tExit = 0.0;
    while (!finished) {
        // Down the walk to a finest texel whose box the ray meets, or to the walk's end.
        bool atLeaf = false;
        while (iteration < map.maxIterations) {
            iteration += 1;
            hit.stopLevel = level;
            exits = maxMipNodeExits(node, level, origin, dir);
            tExit = min(max(min(exits.x, exits.y), t), tFar);
            float top = maxMipNodeHeight(map, pyramid, node, level, hit.fetches);
            float hNow = origin.z + t * dir.z, hExit = origin.z + tExit * dir.z;
            if (min(hNow, hExit) <= top) {
                if (level == 0) {
                    atLeaf = true;
                    break;
                }
                // Step onto the box top (only a descending ray can be above it here), then
                // go down into the child that holds that point.
                if (hNow > top) t = clamp((top - origin.z) / dir.z, t, tExit);
                node = maxMipChildAt(node, level, (origin + t * dir).xy, dir);
                level -= 1;
                continue;
            }
            if (tExit >= tFar) {
                finished = true;
                break;
            }
            maxMipNextNode(node, level, topLevel, exits, tExit, dir);
            t = tExit;
        }
        if (!atLeaf) break;  // finished, or out of iterations
        // At level 0 the texel spans parts of up to four bilinear patches; the ray is
        // solved exactly against those it crosses, in order.
        tHit = baseIntersectLeaf(map, heights, origin, dir, t, tExit, hit.fetches, corners, cell);
        if (tHit >= 0.0) {
            finished = solved = true;
        } else if (tExit >= tFar) {
            finished = true;
        } else {
            maxMipNextNode(node, level, topLevel, exits, tExit, dir);
            t = tExit;
        }
    }
    hit.iterations = iteration;
    if (!finished) {
        hit.exhausted = true;
    } else if (solved) {
        setTopHit(hit, map, origin, dir, tHit, corners, cell);
    } else {
        setWalkEndHit(hit, map, heights, origin, dir, tFar, floorExit);  // out of the box
    }
}

ReliefHit traceMaxMip(ReliefMap map, sampler2D pyramid, sampler2D heights, vec3 origin, vec3 dir) {
    ReliefHit hit = reliefMissHit();
    vec3 start;
    float tStart, span;
    bool floorExit;
    if (enterReliefShell(map, heights, origin, dir, hit, start, tStart, span, floorExit)) {
        walkMaxMip(map, pyramid, heights, start, dir, span, floorExit, hit);
        measureFromEye(hit, tStart);
    }
    return hit;
}

#endif
