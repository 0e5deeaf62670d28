// maxmip_trace.glsl: the maximum mipmap quadtree traversal, the peer "maxmip" of issue 5
// (A. Tevs, I. Ihrke, H.-P. Seidel, "Maximum Mipmaps for Fast, Accurate, and Scalable
// Dynamic Height Field Rendering", I3D 2008, sec. 4).
//
// Inputs in map space (relief_map.glsl): X, Y in texels, h in map height units, the ray
// origin + t dir (t as in world space); `pyramid` the max pyramid (layout: max_pyramid.glsl),
// `heights` the W x H samples (bilinear_patch.glsl). Output, as mr_traceMultilevel's: the
// exact first point t >= 0 of the ray in the solid, on the top surface, a side wall or
// the bottom face, with the same statistics (iterations = nodes visited).
//
// The pyramid is a quadtree: node (p, q) at level L is the box [p, p+1) 2^L x [q, q+1) 2^L
// x [0, its max]. From the root, each step takes the node the ray is in and clips the ray
// to the node's column. If the ray passes above the box it moves on to the exit boundary,
// into the neighbour at the same level, and goes up one level when that neighbour has a
// different parent. If the ray meets the box it steps onto the box (its top) and goes down
// into the child there. At level 0 the texel spans parts of up to four bilinear patches;
// the ray is solved exactly against those it crosses, in order (mr_baseIntersectLeaf).
#ifndef MICRORELIEF_MAXMIP_TRACE_GLSL
#define MICRORELIEF_MAXMIP_TRACE_GLSL

#include "base_surface.glsl"
#include "leaf_walk.glsl"
#include "relief_patch.glsl"
#include "max_pyramid.glsl"
#include "multilevel_trace.glsl"
#include "relief_hit.glsl"
#include "relief_map.glsl"
#include "relief_query.glsl"
#include "texture_reads.glsl"

// Which way the ray moves over the map, per axis (+1, -1 or 0), and the branch of its line
// on which that holds: on the plane and the cylinder the whole line; on an ellipsoid the
// latitude turns once, at `turn`, and Y's way flips there (the walk stays in its node).
struct mr_MaxMipCourse {
    ivec2 step;
    vec2 branch;
    float turn;  // MR_NEVER where Y never turns
};

mr_MaxMipCourse mr_maxMipCourse(mr_Relief relief, vec3 origin, vec3 dir, float tFar) {
    // The path is the line itself: X and Y go dir's way.
#if MICRORELIEF_BASE_STRAIGHT_PATH
    return mr_MaxMipCourse(ivec2(sign(dir.xy)), vec2(-MR_NEVER, MR_NEVER), MR_NEVER);
#else
    // The branch of the line the segment starts on: before the turn, or after it where the
    // turn lies behind the start (the cones Y = const are crossed once per branch, and a
    // crossing on the other branch, behind the start, must not count).
    float turn = mr_baseTurnY(origin, dir);
    vec2 branch = vec2(-MR_NEVER, MR_NEVER);
    if (turn <= 0.0) {
        branch.x = turn;
        turn = MR_NEVER;
    } else if (turn < tFar) {
        branch.y = turn;
    } else {
        branch.y = min(turn, MR_NEVER);
        turn = MR_NEVER;
    }
    // Y's way before the turn (or on the whole segment): from its value at the start to its
    // value where the branch ends.
    float yStart = mr_baseMapY(relief, origin), yEnd = mr_baseMapY(relief, origin + min(turn, tFar) * dir);
    int stepY = yEnd > yStart ? 1 : yEnd < yStart ? -1 : 0;
    return mr_MaxMipCourse(ivec2(mr_baseXIncreases(origin, dir) ? 1 : -1, stepY), branch, turn);
#endif
}

// Past the turn: Y goes the other way, on the branch after it.
void mr_maxMipTurn(inout mr_MaxMipCourse course) {
    course.step.y = -course.step.y;
    course.branch = vec2(course.turn, MR_NEVER);
    course.turn = MR_NEVER;
}

// Ray parameter where the ray leaves node `node` at `level` through a side of its column,
// per axis (MR_NEVER along an axis it does not leave by). On a curved base the sides
// are a half-plane of constant X through the axis (the map's seam, X = W, past its last
// column) and a plane or cone of constant Y, met in closed form (base_surface.glsl).
vec2 mr_maxMipNodeExits(mr_Relief relief, ivec2 node, int level, vec3 origin, vec3 dir, float t, mr_MaxMipCourse course) {
    float size = exp2(float(level));
    vec2 exits = vec2(MR_NEVER);
    // The sides are met along the line itself, and X has walls (no seam to go round).
#if MICRORELIEF_BASE_STRAIGHT_PATH && !MICRORELIEF_BASE_WRAPS_U
    for (int axis = 0; axis < 2; ++axis) {
        if (dir[axis] == 0.0) continue;
        float side = (float(node[axis]) + (dir[axis] > 0.0 ? 1.0 : 0.0)) * size;
        exits[axis] = (side - origin[axis]) / dir[axis];
    }
#else
    // A node that spans every column (a map one sample wide, or a level narrower than the
    // map's width rounds to: a map narrower than it is tall) goes all the way round: it
    // has no side in X, and crossing the seam keeps the ray in it. (Its only side would be
    // the seam, which a line crosses once: once crossed, the same crossing, behind the ray,
    // would be its exit again and again.)
    if (((int(relief.map.size.x) - 1) >> level) > 0) {
        float side = course.step.x > 0 ? min(float(node.x + 1) * size, relief.map.size.x) : float(node.x) * size;
        exits.x = mr_baseCrossX(relief, origin, dir, side, t);
    }
    float side = (float(node.y) + (course.step.y > 0 ? 1.0 : 0.0)) * size;
    if (course.step.y != 0 && side > 0.0 && side < relief.map.size.y)
        exits.y = mr_baseCrossY(relief, origin, dir, side, course.branch.x, course.branch.y);
#endif
    return exits;
}

// The child of `node` (at `level` > 0) holding map point p; on the midline, the child the
// ray moves into.
ivec2 mr_maxMipChildAt(ivec2 node, int level, vec2 p, ivec2 step) {
    float halfSize = exp2(float(level - 1));
    ivec2 child = 2 * node;
    for (int axis = 0; axis < 2; ++axis) {
        float mid = (2.0 * float(node[axis]) + 1.0) * halfSize;
        if (p[axis] > mid || (p[axis] == mid && step[axis] > 0)) child[axis] += 1;
    }
    return child;
}

// The node's max height: one texel of the pyramid.
float mr_maxMipNodeHeight(mr_Relief relief, MICRORELIEF_SAMPLER pyramid, ivec2 node, int level) {
    ivec2 levelSize = max(ivec2(1), relief.map.pyramidSize >> level);
    return mr_pyramidTexel(relief, pyramid, clamp(node, ivec2(0), levelSize - 1), level);
}

// Into the neighbour of `node` across the side(s) of its column the ray leaves through
// at tExit; up one level when that neighbour has a different parent. On a curved base the
// nodes wrap in X: past the last column that holds map texels comes column 0.
void mr_maxMipNextNode(mr_Relief relief, inout ivec2 node, inout int level, int topLevel, vec2 exits, float tExit,
                    ivec2 step) {
    ivec2 next = node + ivec2(exits.x <= tExit ? step.x : 0, exits.y <= tExit ? step.y : 0);
#if MICRORELIEF_BASE_WRAPS_U
    int lastColumn = (int(relief.map.size.x) - 1) >> level;
    if (next.x > lastColumn) next.x = 0;
    if (next.x < 0) next.x = lastColumn;
#endif
    bool newParent = any(notEqual(next >> 1, node >> 1));
    node = next;
    if (newParent && level < topLevel) {
        node >>= 1;
        level += 1;
    }
}

// The quadtree walk over the segment origin + t dir, t in [0, tFar], of a ray that leaves
// the box through its floor when `floorExit`; fills `hit` with local t. The loops have the shape of
// mr_traceMultilevel's (multilevel_trace.glsl): an inner one walks nodes down to a finest
// texel the ray meets, an outer one solves it, so that pixels in SIMD lanes pay for
// their leaves once per outer pass, not on every node.
void mr_walkMaxMip(mr_Relief relief, mr_RayQuery query, MICRORELIEF_SAMPLER pyramid, MICRORELIEF_SAMPLER heights, vec3 origin,
                   vec3 dir, float tFar, bool floorExit, inout mr_ReliefHit hit) {
    float t = 0.0;  // where the ray is in the current node
    int topLevel = relief.map.levelCount - 1;
    int level = topLevel;
    ivec2 node = ivec2(0);  // the root covers the whole map
    mr_WalkEnd end = mr_walkEnd();
    vec2 exits = vec2(0.0);  // where the ray leaves the current node's column, per axis
    float tExit = 0.0;
    mr_MaxMipCourse course = mr_maxMipCourse(relief, origin, dir, tFar);
    while (!end.finished) {
        // Down the walk to a finest texel whose box the ray meets, or to the walk's end.
        bool atLeaf = false;
        while (end.iterations < query.maxIterations) {
            end.iterations += 1;
            hit.stopLevel = level;
            exits = mr_maxMipNodeExits(relief, node, level, origin, dir, t, course);
            // Where Y turns the node's side ahead in Y changes: a stop of its own.
            float tStop = min(min(exits.x, exits.y), course.turn);
            tExit = min(max(tStop, t), tFar);
            float top = mr_maxMipNodeHeight(relief, pyramid, node, level);
            if (mr_baseLowest(relief, origin, dir, t, tExit) <= top) {
                if (level == 0) {
                    atLeaf = true;
                    break;
                }
                // Step onto the box top (only a ray coming down can be above it here), then
                // go down into the child that holds that point.
                t = mr_baseDescendTo(relief, origin, dir, t, tExit, top);
                node = mr_maxMipChildAt(node, level, mr_baseMapPoint(relief, origin + t * dir).xy, course.step);
                level -= 1;
                continue;
            }
            if (tExit >= tFar) {
                end.finished = true;
                break;
            }
            if (tExit == course.turn) {
                mr_maxMipTurn(course);  // the same node, on the branch after the turn
            } else {
                mr_maxMipNextNode(relief, node, level, topLevel, exits, tExit, course.step);
            }
            t = tExit;
        }
        if (!atLeaf) break;  // finished, or out of iterations
        // At level 0 the texel spans parts of up to four bilinear patches; the ray is
        // solved exactly against those it crosses, in order.
        // Two locals, copied into end after the call (what out means in GLSL anyway): WGSL
        // refuses two pointer arguments into one variable (docs/webgpu.md).
        mr_ReliefPatch leafPatch;
        ivec2 leafCell;
        end.tHit = mr_baseIntersectLeaf(relief, heights, origin, dir, t, tExit, leafPatch, leafCell);
        end.cellPatch = leafPatch;
        end.cell = leafCell;
        if (end.tHit >= 0.0) {
            end.finished = end.solved = true;
        } else if (tExit >= tFar) {
            end.finished = true;
        } else {
            if (tExit == course.turn) {
                mr_maxMipTurn(course);
            } else {
                mr_maxMipNextNode(relief, node, level, topLevel, exits, tExit, course.step);
            }
            t = tExit;
        }
    }
    // tHit >= 0 only where a leaf solved it.
    mr_finishWalk(hit, relief, query, heights, origin, dir, tFar, floorExit, end);
}

// As mr_traceMultilevel, over the aligned pyramid.
mr_ReliefHit mr_traceMaxMip(mr_Relief relief, mr_RayQuery query, MICRORELIEF_SAMPLER pyramid, MICRORELIEF_SAMPLER heights, vec3 origin,
                            vec3 dir) {
    mr_ReliefHit hit = mr_reliefMissHit();
    vec3 start;
    float tStart, span;
    bool floorExit;
    if (mr_enterReliefShell(relief, query, heights, origin, dir, hit, start, tStart, span, floorExit)) {
        mr_walkMaxMip(relief, query, pyramid, heights, start, dir, span, floorExit, hit);
        mr_measureFromEye(hit, tStart);
    }
    return hit;
}

#endif
