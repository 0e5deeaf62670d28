#include "microrelief/render/FloatLimits.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

std::string number(double value) {
    std::ostringstream text;
    text.precision(3);
    text << value;
    return text.str();
}

}  // namespace

void checkFloatLimits(const MapExtent& map, double heightScale, const Camera& camera,
                      const CameraFrame& frame, const std::string& source) {
    const double maxHeight = map.maxHeight;  // map units, >= 0 (prepareHeights)
    const double top = heightScale * maxHeight;
    const double texelsPerUnit = std::max(map.width, map.height);

    // 1. The relief's box in world units: corners, depth range and AOV are floats.
    if (!(top <= kMaxWorldCoordinate)) {
        throwBadInput(source + ": the relief's top (--height-scale " + number(heightScale) +
                      " x the largest height " + number(maxHeight) + " = " + number(top) +
                      " world units) is beyond the " + number(kMaxWorldCoordinate) +
                      " the renderer's float arithmetic holds; lower --height-scale, or use "
                      "--normalize and a --height-scale of the relief's height");
    }

    // 2. The patch solve. The ray directions are forward + x right + y up over the picture,
    // x, y in [-1, 1], the three orthogonal: the longest is at a corner. With
    // |b|, |c| <= max h and |d| <= 2 max h (b, c, d: the patch's coefficients) and f in
    // [0, 1]^2, |B| <= 6 max h Dxy + Dh and 4|A C| <= 16 max h^2 Dxy^2 (|C| <= 2 max h
    // inside the box): with max h Dxy <= 2^58 and Dh <= 2^58, B^2 + 4|AC| < 2^126.
    const double longest =
        std::sqrt(1.0 + glm::dot(frame.right, frame.right) + glm::dot(frame.up, frame.up));
    const double dxy = longest * texelsPerUnit, dh = longest / heightScale;
    const double solveLimit = std::ldexp(1.0, 58);
    if (maxHeight * dxy > solveLimit || dh > solveLimit) {
        throwBadInput(source + ": heights up to " + number(maxHeight) + " at --height-scale " +
                      number(heightScale) +
                      " overflow the shader's float patch solve (largest height x " + number(dxy) +
                      " texels per ray unit, and 1 / --height-scale x " + number(longest) +
                      ", must stay below 2^58); use --normalize and a " +
                      "--height-scale of the relief's height");
    }

    // 3. The entry point keeps about 2 ulps (2^-23 relative) of |origin| as its error.
    //    In X, Y: (|eye.x or z| T + W or H / 2) 2^-23 <= 2^-5 texel. In h the error is
    //    |eye.y| / s 2^-23 map units, and it moves the hit by that times |dir.xy| / |dir.h|
    //    texels: |eye.y| T 2^-23 times the cotangent of the ray's slope in world space,
    //    the same bound on |eye.y| T (whatever s is: a thin relief seen from afar is as
    //    exact as a thick one, measured with s down to 1e-7).
    const double entryLimit = std::ldexp(1.0, 18);
    // Half the map alone at the limit leaves no eye anywhere: say so, not where the eye is.
    if (0.5 * std::max(map.width, map.height) >= entryLimit) {
        throwBadInput(source + ": " + std::to_string(map.width) + " x " +
                      std::to_string(map.height) +
                      " texels (with --tile, the tiled whole) is 2^19 = 524288 or more a side, "
                      "beyond which float keeps no ray's entry into the relief's box to 1/32 "
                      "texel; use fewer tiles or a smaller map");
    }
    const double eyeTexels = std::max({std::abs(camera.eye.x) * texelsPerUnit + 0.5 * map.width,
                                       std::abs(camera.eye.z) * texelsPerUnit + 0.5 * map.height,
                                       std::abs(camera.eye.y) * texelsPerUnit});
    if (eyeTexels > entryLimit) {
        throwBadInput("--eye " + number(camera.eye.x) + "," + number(camera.eye.y) + "," +
                      number(camera.eye.z) + " is too far from " + source + " for exact hits: " +
                      number(eyeTexels) + " texels away (" + number(texelsPerUnit) +
                      " a world unit), more than the 2^18 = 262144 at which float keeps the "
                      "ray's entry into the relief's box to 1/32 texel");
    }
}

}  // namespace microrelief
