// What the shader's float arithmetic holds: the limits on the relief and the camera
// beyond which the picture stops being exact (or finite), checked before a render.
//
// Every number the shader works with is a 32-bit float (24-bit significand, largest
// 3.4e38). World positions never reach it as they are: the renderer traces relative to
// the eye (ReliefRenderer::draw), subtracting the eye from the model's translation, the
// light and the clip transform in double first, so a relief 9e5 units from the world's
// origin is traced as exactly as one at it; what float sees is the scene as seen from the
// eye, and the relief's object space (the model's inverse, taken in double). In map space (map_space.glsl) a ray is origin + t dir with X, Y in texels and
// the height in map units h = y / s (s = --height-scale), so
//   dir.xy = world direction (x, z) * T,  T = max(W, H) texels per world unit,
//   dir.h  = world direction y / s.
// Five things can go wrong, each bounded here with the margins the comments in
// FloatLimits.cpp derive (numbered as there):
//  1. World coordinates: the relief's top s * max h within kMaxWorldCoordinate (it is
//     a size the shader works with); positions (the eye, the target, a point light, the
//     box's corners as placed, any base, through the model) within kMaxWorldPosition, and
//     near enough to the origin that double, in which they are subtracted, keeps them to
//     1/1024 of the relief's texel (a relief 1e-3 wide at 1e12 is not).
//  2. Overflow in the exact patch solve (bilinear_patch.glsl, mr_intersectPatch): B^2 and
//     4AC are products of (height difference * dir.xy) and dir.h terms; they must stay
//     below 2^128. Bounded by max h * Dxy <= 2^58 and Dh <= 2^58, Dxy and Dh the largest
//     |dir.xy|, |dir.h| over the picture's rays (in object space: through the model's
//     inverse).
//  3. Normals whose squared length over- or underflows when the shader normalises them:
//     the object normal's length, stretched by the model's inverse transpose, within
//     2^+-62 (a model that shrinks or grows the relief by 1e20 fails here).
//  4. Precision of the entry point (relief_hit.glsl, mr_enterReliefShell): the ray is moved
//     from the eye to where it enters the box, start = origin + tStart dir, which keeps
//     about 2 ulps of |origin| as its error. Exactness (hits within half a texel; the
//     accuracy sweep measures 0.018 texels at p99) wants the hit moved by less than 1/32
//     texel: the eye within 2^18 texels of the map in X, Y and (h error times the ray's
//     cotangent) |eye.y| T <= 2^18. Measured on a 1024 map: p99 error 0.025 texels at
//     102400 texels away, 0.05 at 256000 (one pixel off by more than half a texel),
//     0.28 at 1024000, 5 % of pixels off at 4096000. All of it in the base's frame: the
//     eye taken into object space by the model's inverse (a relief grown 1e5 times is
//     seen from 1e5 times as far), then into the frame (on a curved base, the canonical
//     frame of radius 1, T_frame texels a frame unit: W / 2 pi around, H / 2 along a
//     cylinder, H / pi in latitude). On an ellipsoid the frame point's error is also
//     |object coordinate| 2^-23 object units on each axis, however long the frame's unit
//     is there (radii 4e5, 0.5, 0.5 seen near the tip keep the eye to 0.05 units, 8
//     times the texel there): the eye's object coordinates, in texels of its shortest
//     texel side (BaseType::frameStretchesPastTexels), within 2^18 as well.
//  5. Rays of neighbouring pixels that float cannot tell apart: 2 tan(fovy / 2) / height
//     at least 2^-19 (32 ulps of a unit direction's components).
#pragma once

#include <string>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/scene/ModelTransform.h"

namespace microrelief {

// The relief's top s * max h, in world units (the relief spans one); also the largest
// component of --up and --light, and of a base's sizes.
inline constexpr double kMaxWorldCoordinate = 1e6;
// Positions (--eye, --target, --light-position, the relief's box as --model places it),
// in world units: differenced in double before the shader sees them (check 1).
inline constexpr double kMaxWorldPosition = 1e12;
// Directions (--up, --light) need a largest component of at least this (smaller ones
// lose their length to underflow when squared in float).
inline constexpr double kMinDirectionComponent = 1e-6;

// What the limits need of a map: its size and its largest height.
struct MapExtent {
    int width = 0, height = 0;  // texels
    double maxHeight = 0.0;     // map units
};

// Throws Error(BadInput) naming `source` (the map) or the flag, with the limit and the
// reason, when rendering a map of `map`'s extent at `heightScale` over `base`, placed by
// `model`, through `camera` (resolved for the picture as `frame`) would leave the range
// above.
void checkFloatLimits(const MapExtent& map, double heightScale, const BaseShape& base,
                      const ModelTransform& model, const Camera& camera, const CameraFrame& frame,
                      const std::string& source);

}  // namespace microrelief
