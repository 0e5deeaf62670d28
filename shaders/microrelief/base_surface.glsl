// base_surface.glsl: the base-surface seam of the library, everything the tracers need
// to know about the surface the height map is laid over (paper, section II: "planes,
// ellipsoids, or cylinders"; scene-and-cli.md, "Base surfaces"). The host chooses the base
// with MICRORELIEF_BASE (relief_map.glsl), and this file includes the one file that
// defines it: 0 the plane (base_plane.glsl), 1 a cylinder (base_cylinder.glsl), 2 an
// ellipsoid (base_ellipsoid.glsl). The C++ mirror is include/microrelief/core/base/BaseSurface.h,
// one class per base, each with its row in the table of bases (core/base/BaseType.h). A new
// base is a file of its own here that defines the set below, a line in the choice, and its
// C++ file (docs/bases.md, "Adding a base").
//
// The tracers work in the base's frame, where the ray is a straight line o + t d with the
// world's t (mr_baseFramePoint, mr_baseFrameVector). Every base file defines the same set:
//  * its traits, macros 0 or 1 that the library's files ask instead of the base's number
//    (each file that asks one includes this one, so the base is chosen before any use):
//    MICRORELIEF_BASE_WRAPS_U (the map's columns join across the seam u = 0: cells,
//    texels, pyramid nodes and footprints wrap in X; else X clamps at the edges),
//    MICRORELIEF_BASE_WRAPS_V (the same in v; no base has it yet, and the traversal refuses
//    it below), MICRORELIEF_BASE_STRAIGHT_PATH (the frame is map space, where the ray's path
//    over the map is the straight line itself: a leaf is solved by polynomials along it, a
//    segment's ends are its points, the step-based peers run in it as they are; else the
//    path is a curve, bounded and walked through the functions below);
//  * the frame: mr_baseObjectToFrame, mr_baseObjectToFrameVector, mr_baseFrameToObject,
//    mr_baseObjectNormal (a frame normal in object space);
//  * the map over it: mr_baseMapY, mr_baseMapPoint (X, Y, h) of a frame point,
//    mr_baseMapMargin (how far the X and Y it computes may be from the exact ones, texels),
//    mr_baseRaise (a frame point moved up the height axis), mr_baseSurfacePoint (its
//    inverse), mr_baseTangentFrame;
//  * the traversal's bounds: mr_baseClipToShell (the ray's interval in the bounding shell
//    and the face it enters through), mr_baseEnd and mr_baseFootprintOf (a segment's
//    footprint on the map and its lowest height above the base), mr_baseLowest,
//    mr_baseDescendTo, mr_baseTurnY. Both are bounds, never samples: on a curved base the
//    path in (X, Y, h) is a curve, but the angle about the axis is monotone along a line,
//    the distance from the axis or the centre is convex along it, and the latitude has at
//    most one interior extremum, so each extreme over a segment is at an end or at one
//    interior point found in closed form;
//  * the leaf's walk over cells (leaf_walk.glsl): mr_baseXIncreases, mr_baseCrossX,
//    mr_baseCrossY (where the path crosses a cell boundary, in closed form) and
//    MR_BASE_FINAL_LENGTH;
//  * normals: mr_baseTopNormal (from the map's gradient), mr_baseFaceNormal.
// Built on the set, here: the model transform's part (mr_baseFramePoint,
// mr_baseFrameVector, mr_baseWorldPoint, mr_baseWorldNormal), mr_baseFootprint and
// mr_baseTangentRay.
#ifndef MICRORELIEF_BASE_SURFACE_GLSL
#define MICRORELIEF_BASE_SURFACE_GLSL

#include "base_curved.glsl"
#include "map_space.glsl"
#include "relief_map.glsl"
#include "variants.glsl"

// The one base the host chose. Hosts splice each file once, wherever it is first included,
// before the preprocessor runs (the library's own resolver, the page's, the bundler): what
// two base files share is included above, outside the choice, or the branch that comes
// second would find it spliced into the first.
#if MICRORELIEF_BASE == MR_BASE_CYLINDER
#include "base_cylinder.glsl"
#elif MICRORELIEF_BASE == MR_BASE_ELLIPSOID
#include "base_ellipsoid.glsl"
#else
#include "base_plane.glsl"
#endif

// A base file that leaves out a trait is caught here, before any file asks it (#if takes an
// undefined name for 0 on some compilers). No file handles a map that wraps in v yet.
#if !defined(MICRORELIEF_BASE_WRAPS_U) || !defined(MICRORELIEF_BASE_WRAPS_V) || !defined(MICRORELIEF_BASE_STRAIGHT_PATH)
#error a base file defines MICRORELIEF_BASE_WRAPS_U, _WRAPS_V and _STRAIGHT_PATH (base_surface.glsl)
#endif
#if MICRORELIEF_BASE_WRAPS_V
#error a base whose map wraps in v needs the traversal made to wrap Y first (docs/bases.md)
#endif

// Between the world and the base's frame, in two steps: the model transform
// (mr_ReliefPlacement: the world to the relief's object space, an affine map, so t is
// kept), then the base's own (map space on the plane, the canonical frame on a curved
// base). With the identity for a model both steps are exact in float (a product with
// ones and zeros), so the model costs nothing in accuracy where it is not used.
vec3 mr_baseObjectPoint(mr_Relief relief, vec3 world) {
    return (relief.placement.worldToObject * vec4(world, 1.0)).xyz;
}

vec3 mr_baseFramePoint(mr_Relief relief, vec3 world) {
    return mr_baseObjectToFrame(relief, mr_baseObjectPoint(relief, world));
}

vec3 mr_baseFrameVector(mr_Relief relief, vec3 world) {
    return mr_baseObjectToFrameVector(relief, mat3(relief.placement.worldToObject) * world);
}

vec3 mr_baseWorldPoint(mr_Relief relief, vec3 q) {
    return (relief.placement.objectToWorld * vec4(mr_baseFrameToObject(relief, q), 1.0)).xyz;
}

// A frame normal as a world-space unit vector: the frame's inverse transpose into object
// space, then the model's (the transpose of worldToObject's linear part).
vec3 mr_baseWorldNormal(mr_Relief relief, vec3 n) {
    return normalize(transpose(mat3(relief.placement.worldToObject)) * mr_baseObjectNormal(relief, n));
}

// The footprint of [ta, tb] from its ends, each computed here (a walk that has them passes
// them to mr_baseFootprintOf instead).
mr_BaseFootprint mr_baseFootprint(mr_Relief relief, vec3 origin, vec3 dir, float ta, float tb) {
    return mr_baseFootprintOf(relief, origin, dir, ta, tb, mr_baseEnd(relief, origin + ta * dir), mr_baseEnd(relief, origin + tb * dir));
}

// The ray in the tangent frame where it enters the shell, as engines run parallax methods
// on a curved surface: map space (X, Y, h) taken as flat from that point on, the ray's
// direction expressed in the base's tangent frame there, blind to the curvature beyond.
// False when the ray misses the shell. `tEntry` is where it enters (or 0 inside it).
bool mr_baseTangentRay(mr_Relief relief, vec3 origin, vec3 dir, out vec3 localOrigin, out vec3 localDir,
                    out float tEntry) {
    int entryFace;
    bool floorExit;
    vec2 range = mr_baseClipToShell(relief, origin, dir, entryFace, floorExit);
    tEntry = max(range.x, 0.0);
    localOrigin = mr_baseMapPoint(relief, origin + tEntry * dir);
    localDir = vec3(0.0);
    if (tEntry > range.y) return false;
    vec3 alongX, alongY, alongH;
    mr_baseTangentFrame(relief, localOrigin, alongX, alongY, alongH);
    localDir = vec3(dot(dir, alongX) / dot(alongX, alongX), dot(dir, alongY) / dot(alongY, alongY),
                    dot(dir, alongH) / dot(alongH, alongH));
    return true;
}

#endif
