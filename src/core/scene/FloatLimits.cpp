#include "microrelief/core/scene/FloatLimits.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/base/BaseType.h"

namespace microrelief {

namespace {

// A figure in a message (core/Text.h).
std::string number(double value) { return formatNumber(value, 3); }

// `value` past `limit`, with the digits that tell them apart (1.00000005e+12 beyond 1e+12,
// not 1e+12 beyond 1e+12).
std::string numberBeyond(double value, double limit) {
    int digits = 3;
    while (digits < 17 && formatNumber(value, digits) == formatNumber(limit, digits)) ++digits;
    return formatNumber(value, digits);
}

// The base as the scene's fields give it: "{base} cylinder {base.radius} 0.3 {base.length} 1".
std::string baseFlags(const BaseShape& base) {
    const BaseType& type = baseType(base);
    std::string text = std::string("{base} ") + type.name;
    for (const BaseSize& size : type.sizes) {
        double numbers[3] = {};
        size.read(base, numbers);
        text += std::string(" {") + size.field + "} ";
        for (int i = 0; i < size.count; ++i) text += (i ? "," : "") + number(numbers[i]);
    }
    return text;
}

}  // namespace

void checkFloatLimits(const MapExtent& map, double heightScale, const BaseShape& base,
                      const ModelTransform& model, const Camera& camera, const CameraFrame& frame,
                      const std::string& source) {
    const double maxHeight = map.maxHeight;  // map units, >= 0 (prepareHeights)
    const double top = heightScale * maxHeight;
    const BaseType& type = baseType(base);
    const bool plane = base.kind == BaseKind::Plane;
    // Texels per unit of the base's frame, the most over its axes.
    const double texelsPerUnit = type.texelsPerFrameUnit(map.width, map.height);

    // 1. The relief's box in world units: corners, depth range and AOV are floats. On a
    //    curved base s is a fraction of the radius; the same bound keeps the frame's
    //    radial arithmetic finite.
    if (!(top <= kMaxWorldCoordinate)) {
        throwBadInput(source + ": the relief's top ({heightScale} " + number(heightScale) +
                      " x the largest height " + number(maxHeight) + " = " + number(top) +
                      (plane ? " world units" : " radii") + ") is beyond the " +
                      number(kMaxWorldCoordinate) +
                      " the renderer's float arithmetic holds; lower {heightScale}, or use "
                      "{map.load.normalize} and a {heightScale} of the relief's height");
    }
    //    The box as placed, on any base and through the model, as the shader sees it:
    //    relative to the eye (ReliefRenderer::draw subtracts it in double), its corners
    //    go through the float model and clip transforms to the rasteriser. A cylinder of
    //    --length 1e8 loses 12 % of its hits to the proxy box's clipping in float (every
    //    hit from 1e9), and is right up to 1e7 (measured with the box about the eye):
    //    the bound is the plane's, 1e6, on the corners' distance from the eye.
    //    Absolute positions only meet double: within kMaxWorldPosition, and where
    //    double's step there (2^-52 of the coordinate, once for the eye and once for
    //    the model's translation) is 1/1024 of the relief's shortest texel side in the
    //    world (the object's side, shrunk at most by the model's smallest scale).
    {
        const glm::dvec3 lo = base.boxMin(map.width, map.height, top);
        const glm::dvec3 hi = base.boxMax(map.width, map.height, top);
        double fromEye = 0.0, fromOrigin = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::dvec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                               (corner & 4) ? hi.z : lo.z);
            const glm::dvec3 world = model.pointToWorld(p);
            const glm::dvec3 seen = world - camera.eye;
            fromEye = std::max({fromEye, std::abs(seen.x), std::abs(seen.y), std::abs(seen.z)});
            fromOrigin =
                std::max({fromOrigin, std::abs(world.x), std::abs(world.y), std::abs(world.z)});
        }
        if (!(fromOrigin <= kMaxWorldPosition)) {
            throwBadInput(source + ": the relief's box on " + baseFlags(base) +
                          (model.isIdentity() ? "" : " placed by {model}") + " reaches " +
                          numberBeyond(fromOrigin, kMaxWorldPosition) + " world units from the origin, beyond the " +
                          number(kMaxWorldPosition) + " a world position may lie from it");
        }
        if (!(fromEye <= kMaxWorldCoordinate)) {
            throwBadInput(source + ": the relief's box on " + baseFlags(base) +
                          (model.isIdentity() ? "" : " placed by {model}") + " reaches " +
                          numberBeyond(fromEye, kMaxWorldCoordinate) + " world units from {camera.eye}, beyond the " +
                          number(kMaxWorldCoordinate) +
                          " the renderer's float arithmetic holds (the box's corners and depth "
                          "are floats about the eye); use a smaller base or model scale, or "
                          "come nearer");
        }
        const double eyeReach =
            std::max({std::abs(camera.eye.x), std::abs(camera.eye.y), std::abs(camera.eye.z)});
        const double reach = std::max(fromOrigin, eyeReach);
        const double texelWorld =
            type.shortestTexelSide(base, map.width, map.height) * model.smallestScale();
        const double doubleStepTexels = 2.0 * reach * std::ldexp(1.0, -52) / texelWorld;
        if (!(doubleStepTexels <= std::ldexp(1.0, -10))) {
            throwBadInput(source + (model.isIdentity() ? "" : " placed by {model}") +
                          " and {camera.eye} lie " + number(reach) +
                          " world units from the origin, where double keeps positions to " +
                          numberBeyond(doubleStepTexels, std::ldexp(1.0, -10)) +
                          " of the relief's texel, more than the 1/1024 the renderer allows "
                          "itself; move the scene nearer the origin or scale the relief up");
        }
    }

    // The ray in object space: t is kept, the direction goes through the model's inverse,
    // at most 1 / its smallest scale longer.
    const double longestWorld =
        std::sqrt(1.0 + glm::dot(frame.right, frame.right) + glm::dot(frame.up, frame.up));
    const double longest = longestWorld / model.smallestScale();

    // 2. The patch solve (the plane's; a curved base's leaf interpolates the gap between
    // patch and ray from three values and multiplies no ray coefficients). The ray
    // directions are forward + x right + y up over the picture, x, y in [-1, 1], the
    // three orthogonal: the longest is at a corner. With |b|, |c| <= max h and
    // |d| <= 2 max h (b, c, d: the patch's coefficients) and f in [0, 1]^2,
    // |B| <= 6 max h Dxy + Dh and 4|A C| <= 16 max h^2 Dxy^2 (|C| <= 2 max h inside the
    // box): with max h Dxy <= 2^58 and Dh <= 2^58, B^2 + 4|AC| < 2^126.
    if (plane) {
        const double dxy = longest * texelsPerUnit, dh = longest / heightScale;
        const double solveLimit = std::ldexp(1.0, 58);
        if (maxHeight * dxy > solveLimit || dh > solveLimit) {
            throwBadInput(source + ": heights up to " + number(maxHeight) + " at {heightScale} " +
                          number(heightScale) +
                          " overflow the shader's float patch solve (largest height x " +
                          number(dxy) + " texels per ray unit, and 1 / {heightScale} x " +
                          number(longest) + ", must stay below 2^58); " +
                          (!model.isIdentity()
                               ? "{model} shrinks the relief by " + number(model.smallestScale()) +
                                     ", which lengthens the rays in its object space as much"
                           : dh > solveLimit
                               ? std::string("raise {heightScale} (1 / {heightScale} overflows)")
                               : "use {map.load.normalize} and a {heightScale} of the relief's "
                                 "height"));
        }
    }

    // 3. Normals. The shader takes a frame normal into the world through the inverse
    //    transposes of the frame and the model, and normalises it: its squared length
    //    must stay within float's normal range (2^-126 to 2^128), with a factor 4 to
    //    spare for the sum of three squares and rounding, so its length within 2^+-62.
    //    The model stretches it by 1 / its smallest scale at most and 1 / its largest at
    //    least: a relief shrunk by 1e-20 overflows, one grown by 1e20 underflows (shaded
    //    black or NaN), each without an error of its own.
    {
        const auto [least, most] =
            type.objectNormalRange(base, map.width, map.height, heightScale, map.maxHeight);
        const double longestNormal = most / model.smallestScale();
        const double shortestNormal = least / model.largestScale();
        const double limit = std::ldexp(1.0, 62);
        if (!(longestNormal <= limit && shortestNormal >= 1.0 / limit)) {
            throwBadInput(std::string(model.isIdentity()
                                          ? "{heightScale} " + number(heightScale)
                                          : "{model} (scales " + number(model.smallestScale()) +
                                                " to " + number(model.largestScale()) + ")") +
                          ": the relief's normals on " + source + " reach lengths from " +
                          number(shortestNormal) + " to " + number(longestNormal) +
                          " before they are normalised, beyond the 2^+-62 float squares without "
                          "overflow or underflow; scale the relief by less");
        }
    }

    // 4. The entry point keeps about 2 ulps (2^-23 relative) of |origin| as its error, in
    //    the base's frame (map space on the plane, the canonical frame on a curved base),
    //    where the eye is the model's inverse of --eye.
    //    Plane: in X, Y: (|eye.x or z| T + W or H / 2) 2^-23 <= 2^-5 texel. In h the
    //    error is |eye.y| / s 2^-23 map units, and it moves the hit by that times
    //    |dir.xy| / |dir.h| texels: |eye.y| T 2^-23 times the cotangent of the ray's slope
    //    in world space, the same bound on |eye.y| T (whatever s is: a thin relief seen
    //    from afar is as exact as a thick one, measured with s down to 1e-7).
    //    Curved base: the frame point's error |q| 2^-23 frame units moves the hit by that
    //    many frame units along the surface (radially, times the cotangent as on the
    //    plane), which the texels per frame unit turn into texels: |q| T_frame <= 2^18.
    //    Measured on a cylinder (256 map): p99 0.01 texels at 1.1e5 texels away, 0.088 at
    //    1.1e6, 1.17 at 1.1e7 (the plane's figures below, slightly better).
    const double entryLimit = std::ldexp(1.0, 18);
    const double mapReach = plane ? 0.5 * std::max(map.width, map.height) : texelsPerUnit;
    // The map alone at the limit leaves no eye anywhere: say so, not where the eye is.
    if (mapReach >= entryLimit) {
        throwBadInput(source + ": " + std::to_string(map.width) + " x " +
                      std::to_string(map.height) + " texels (with {tiles}, the tiled whole) on " +
                      baseFlags(base) + " is " + number(mapReach) +
                      " texels across its frame, 2^18 = 262144 or more, beyond which float keeps "
                      "no ray's entry into the relief's box to 1/32 texel; use fewer tiles or a "
                      "smaller map");
    }
    //    On an ellipsoid the frame point's error is also |object coordinate| 2^-23
    //    object units on each axis, whatever the frame's unit is long there, counted in
    //    its shortest texel side (BaseType::frameStretchesPastTexels): radii 4e5, 0.5,
    //    0.5 seen near the tip were 8 silhouette pixels wrong at 48 x 32 before.
    const glm::dvec3 object = model.pointToObject(camera.eye);
    const glm::dvec3 eye = plane ? object : object / base.frameScale();
    const double objectTexels =
        type.frameStretchesPastTexels
            ? std::max({std::abs(object.x), std::abs(object.y), std::abs(object.z)}) /
                  type.shortestTexelSide(base, map.width, map.height)
            : 0.0;
    const double eyeTexels =
        plane ? std::max({std::abs(eye.x) * texelsPerUnit + 0.5 * map.width,
                          std::abs(eye.z) * texelsPerUnit + 0.5 * map.height,
                          std::abs(eye.y) * texelsPerUnit})
              : std::max(std::max({std::abs(eye.x), std::abs(eye.y), std::abs(eye.z)}) *
                             texelsPerUnit,
                         objectTexels);
    if (eyeTexels > entryLimit) {
        throwBadInput("{camera.eye} " + number(camera.eye.x) + "," + number(camera.eye.y) + "," +
                      number(camera.eye.z) + " is too far from " + source +
                      (plane ? "" : " on " + baseFlags(base)) +
                      (model.isIdentity() ? "" : " (placed by {model})") + " for exact hits: " +
                      number(eyeTexels) + " texels away (" +
                      (plane || eyeTexels > objectTexels
                           ? number(texelsPerUnit) + " a " +
                                 (plane ? "world unit" : "unit of the base's frame")
                           : "of the base's shortest texel side, " +
                                 number(type.shortestTexelSide(base, map.width, map.height)) +
                                 " object units") +
                      "), more than the 2^18 = 262144 at which float keeps the ray's entry into "
                      "the relief's box to 1/32 texel");
    }

    // 5. The pixels' rays. Each is forward + x right + y up in float, whose components
    //    (at most 1 in size) carry about 3 ulps of 2^-24 from the rounding of the sum;
    //    neighbouring pixels' rays differ by 2 tan(fovy / 2) / height. At 32 ulps (2^-19)
    //    apart a ray strays 0.09 pixels (p99) from its pixel's centre; measured: p99
    //    0.12 px at 23 ulps, 1.2 px at 2.3 ulps, rows of pixels lost at 0.23 ulps, and all
    //    of them once tan(fovy / 2) underflows (--fovy 1e-37).
    const double pixelStep = 2.0 * glm::length(frame.up) / frame.height;
    const double stepLimit = std::ldexp(1.0, -19);
    if (!(pixelStep >= stepLimit)) {
        const double least =
            2.0 * std::atan(stepLimit * frame.height / 2.0) * 180.0 / std::numbers::pi;
        throwBadInput("{camera.fovyDegrees} " + number(camera.fovyDegrees) + " at a picture " +
                      std::to_string(frame.height) +
                      " pixels high: neighbouring pixels' rays differ by " + number(pixelStep) +
                      ", less than the 2^-19 that float keeps apart; use {camera.fovyDegrees} " +
                      number(least * 1.001) + " or more, or a smaller {size}");
    }
}

}  // namespace microrelief
