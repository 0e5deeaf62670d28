// The coarse pass's bound (shaders/microrelief/coarse_start.glsl) on the CPU, against the
// exact reference: a tile's start, found from its four corner rays alone, is never after
// the first hit of any of its pixels. This is the shader's walk transcribed in double
// (same range per slab, same hull of eight points, same in-order subdivision, the same
// stopping rule), with the bound an exact max over the samples the footprint can read
// instead of the pyramid's window. It tests the geometric argument, and the GL test
// (tests/gl/CoarsePassTest.cpp) tests the shader itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "TestSupport.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

constexpr double kMiss = 3.4e38, kKeep = -1.0;

// Map space of the plane (map_space.glsl): X = x N + W / 2, Y = z N + H / 2, h = y / s.
struct MapSpace {
    double n, w, h, s;
    glm::dvec3 point(glm::dvec3 p) const { return {p.x * n + 0.5 * w, p.z * n + 0.5 * h, p.y / s}; }
    glm::dvec3 vector(glm::dvec3 v) const { return {v.x * n, v.z * n, v.y / s}; }
};

// The largest sample any bilinear value over map rectangle [lo, hi] can weigh: the value at
// X is a convex combination of samples floor(X) - 1 to floor(X) + 1 (samples at texel
// centres or corners alike), so those from floor(lo) - 1 to ceil(hi) + 1 (clamped at the
// edges, as the map's reads are).
double maxOver(const HeightMap& map, glm::dvec2 lo, glm::dvec2 hi) {
    const int i0 = std::clamp(int(std::floor(lo.x)) - 1, 0, map.width - 1);
    const int i1 = std::clamp(int(std::ceil(hi.x)) + 1, 0, map.width - 1);
    const int j0 = std::clamp(int(std::floor(lo.y)) - 1, 0, map.height - 1);
    const int j1 = std::clamp(int(std::ceil(hi.y)) + 1, 0, map.height - 1);
    double top = 0.0;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) top = std::max(top, double(map.at(i, j)));
    return top;
}

// The tile's start for rays o + t sum w_i d[i]: mr_coarseStart's walk.
double coarseStart(const HeightMap& map, double top, glm::dvec3 o, const glm::dvec3 (&d)[4]) {
    glm::dvec3 dLo = d[0], dHi = d[0];
    for (const glm::dvec3& v : d) {
        dLo = glm::min(dLo, v);
        dHi = glm::max(dHi, v);
    }
    const glm::dvec3 lo(0.0), hi(map.width, map.height, top);
    double tLow = 0.0, tHigh = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (o[a] < lo[a]) {
            if (dHi[a] <= 0.0) return kMiss;
            tLow = std::max(tLow, (lo[a] - o[a]) / dHi[a]);
        } else if (o[a] > hi[a]) {
            if (dLo[a] >= 0.0) return kMiss;
            tLow = std::max(tLow, (hi[a] - o[a]) / dLo[a]);
        }
        if (dLo[a] > 0.0)
            tHigh = std::min(tHigh, (hi[a] - o[a]) / dLo[a]);
        else if (dHi[a] < 0.0)
            tHigh = std::min(tHigh, (lo[a] - o[a]) / dHi[a]);
    }
    if (!(tLow <= tHigh)) return kMiss;
    const double span = tHigh - tLow;
    int depth = 0;
    std::uint64_t index = 0;
    for (int step = 0; step < 64; ++step) {
        const double ta = tLow + span * double(index) / double(std::uint64_t(1) << depth);
        const double tb = tLow + span * double(index + 1) / double(std::uint64_t(1) << depth);
        glm::dvec3 pLo = o + ta * d[0], pHi = pLo;
        glm::dvec2 cLo = glm::dvec2(o + tb * d[0]), cHi = cLo;
        for (const glm::dvec3& v : d) {
            const glm::dvec3 a = o + ta * v, b = o + tb * v;
            pLo = glm::min(pLo, glm::min(a, b));
            pHi = glm::max(pHi, glm::max(a, b));
            cLo = glm::min(cLo, glm::dvec2(b));
            cHi = glm::max(cHi, glm::dvec2(b));
        }
        if (pLo.z > maxOver(map, glm::dvec2(pLo), glm::dvec2(pHi))) {
            // Skipped: on to the next segment (no climbing: the same segments, more steps).
            index += 1;
            while ((index & 1) == 0 && depth > 0) {
                index >>= 1;
                depth -= 1;
            }
            if (depth == 0 && index == 1) return kMiss;
            continue;
        }
        const glm::dvec2 extent = glm::dvec2(pHi - pLo), cross = cHi - cLo;
        if (std::max(extent.x, extent.y) <= std::max(8.0, 1.25 * std::max(cross.x, cross.y)) ||
            depth >= 20)
            return ta == tLow ? kKeep : ta;
        depth += 1;
        index *= 2;
    }
    const double ta = tLow + span * double(index) / double(std::uint64_t(1) << depth);
    return ta == tLow ? kKeep : ta;
}

// Random views of a bumpy 64 x 64 map: from outside at every elevation down to half a
// degree, and from eyes inside the box (some in the solid): 200 views. For each 8 x 8 tile of a 48
// x 40 picture, the start from its corner rays against every pixel's exact first hit.
TEST(CoarseStart, TheTilesStartIsNeverAfterAnyOfItsPixelsFirstHit) {
    const HeightMap map = synth::valueNoise(64, 64, 8.0, 3, 5);
    const double s = 0.1;
    const ReferenceTracer reference(ReliefGeometry{&map, s});
    double top = 0.0;
    for (float v : map.samples) top = std::max(top, double(v));
    const MapSpace space{64.0, 64.0, 64.0, s};
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int width = 48, height = 40, tile = 8;
    std::size_t pixels = 0, hits = 0, moved = 0, missTiles = 0, late = 0;
    for (int view = 0; view < 200; ++view) {
        Camera camera;
        if (view % 4 == 3) {
            // An eye inside the box: under its top, anywhere over the map, looking down
            // a little or level.
            camera.eye = glm::dvec3(unit(random) - 0.5, s * top * unit(random), unit(random) - 0.5);
            const double a = 6.283 * unit(random), e = -0.6 * unit(random);
            camera.target = camera.eye + glm::dvec3(std::cos(e) * std::cos(a), std::sin(e),
                                                    std::cos(e) * std::sin(a));
            camera.fovyDegrees = 50.0;
        } else {
            const double elevation =
                view % 4 == 0 ? 0.5 + 3.0 * unit(random) : 3.0 + 86.0 * unit(random);
            camera = test::orbitCamera(
                elevation, 360.0 * unit(random), 0.4 + 1.6 * unit(random),
                {0.6 * unit(random) - 0.3, s * top * unit(random), 0.6 * unit(random) - 0.3},
                20.0 + 40.0 * unit(random));
        }
        const CameraFrame frame = resolveCamera(camera, width, height, 1.0);
        const glm::dvec3 o = space.point(frame.eye);
        for (int ty = 0; ty < height; ty += tile) {
            for (int tx = 0; tx < width; tx += tile) {
                const int c0 = tx, c1 = std::min(tx + tile, width) - 1;
                const int r0 = ty, r1 = std::min(ty + tile, height) - 1;
                const glm::dvec3 d[4] = {space.vector(frame.pixelRay(c0, r0).direction),
                                         space.vector(frame.pixelRay(c1, r0).direction),
                                         space.vector(frame.pixelRay(c0, r1).direction),
                                         space.vector(frame.pixelRay(c1, r1).direction)};
                const double start = coarseStart(map, top, o, d);
                moved += start >= 0.0 && start < kMiss;
                missTiles += start == kMiss;
                for (int r = r0; r <= r1; ++r) {
                    for (int c = c0; c <= c1; ++c) {
                        const ReferenceHit hit = reference.trace(frame.pixelRay(c, r));
                        ++pixels;
                        if (!hit) continue;
                        ++hits;
                        if (!(start <= hit.t)) {
                            ++late;
                            ADD_FAILURE() << "view " << view << ", pixel " << c << ", " << r
                                          << ": start " << start << " after the hit at " << hit.t;
                            if (late > 5) return;
                        }
                    }
                }
            }
        }
    }
    std::printf("    %zu pixels, %zu hits; tiles moved %zu, missing %zu\n", pixels, hits, moved,
                missTiles);
    EXPECT_EQ(late, 0u);
    // The test means something: the walk moves many tiles, some past all their rays.
    EXPECT_GT(moved, 200u);
    EXPECT_GT(missTiles, 50u);
    EXPECT_GT(hits, pixels / 3);
}

}  // namespace
