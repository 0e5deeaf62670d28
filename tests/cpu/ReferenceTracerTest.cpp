// The exact CPU reference tracer against hand-computed hits (flat maps, spikes, steps,
// walls, the bottom face, non-square and 1x1 maps) and, for random maps and rays,
// against the definition of a hit: on the ray, on the solid's boundary, and no earlier
// point of the ray inside the solid. HeightMap::surface is the independent evaluation
// of the spec's h(u, v) here; the tracer evaluates its own bilinear patches.
#include "microrelief/core/trace/ReferenceTracer.h"

#include <gtest/gtest.h>

#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/heightmap/PyramidPages.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <tuple>
#include <vector>

namespace microrelief {
namespace {

// Hand-computed hits agree to rounding in double precision: a few ulps of O(1) values.
constexpr double kExact = 1e-12;

struct Extents {
    double a, b;  // footprint side lengths in x and z
};

Extents extentsOf(const HeightMap& map) {
    const double longer = std::max(map.width, map.height);
    return {map.width / longer, map.height / longer};
}

// World (x, z) of the sample-space point (i, j): sample (i, j) sits at integers.
glm::dvec2 worldAtSample(const HeightMap& map, double i, double j) {
    const double longer = std::max(map.width, map.height);
    return {(i + 0.5 - 0.5 * map.width) / longer, (j + 0.5 - 0.5 * map.height) / longer};
}

// y = s h(u, v) of the spec at world (x, z), through HeightMap::surface (texel space).
double surfaceY(const ReliefGeometry& relief, double x, double z) {
    const Extents e = extentsOf(*relief.map);
    const double texelX = (x / e.a + 0.5) * relief.map->width;
    const double texelY = (z / e.b + 0.5) * relief.map->height;
    return relief.heightScale * relief.map->surface(texelX, texelY, false, relief.interpolation);
}

// Inside the solid by more than `margin` in every constraint.
bool deepInside(const ReliefGeometry& relief, const glm::dvec3& p, double margin) {
    const Extents e = extentsOf(*relief.map);
    if (std::abs(p.x) > 0.5 * e.a - margin || std::abs(p.z) > 0.5 * e.b - margin) return false;
    return p.y > margin && p.y < surfaceY(relief, p.x, p.z) - margin;
}

void expectNearVec(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// A ray from `origin` through `target`: t = 1 at the target.
Ray through(const glm::dvec3& origin, const glm::dvec3& target) {
    return {origin, target - origin};
}

// --- Flat maps ------------------------------------------------------------------------

TEST(ReferenceTracerFlat, HitsExactlyAtTheHeightFromEveryAngle) {
    const HeightMap map(5, 4, 0.625f);  // exact in binary
    const ReliefGeometry relief{&map, 0.2};
    const double top = 0.2 * 0.625;
    const glm::dvec3 target(0.13, top, -0.07);
    for (double elevation : {1.0, 5.0, 20.0, 45.0, 70.0, 89.0, 90.0}) {
        for (double azimuth = 0.0; azimuth < 360.0; azimuth += 30.0) {
            const double el = glm::radians(elevation), az = glm::radians(azimuth);
            const glm::dvec3 offset(std::cos(el) * std::cos(az), std::sin(el),
                                    std::cos(el) * std::sin(az));
            SCOPED_TRACE(testing::Message() << "elevation " << elevation << " azimuth " << azimuth);
            const ReferenceHit hit = traceReference(relief, through(target + 2.0 * offset, target));
            ASSERT_EQ(hit.face, HitFace::Top);
            EXPECT_NEAR(hit.t, 1.0, kExact);
            expectNearVec(hit.position, target, kExact);
            expectNearVec(hit.normal, {0.0, 1.0, 0.0}, kExact);
        }
    }
}

TEST(ReferenceTracerFlat, ZeroMapIsHitAtTheBasePlaneFromAbove) {
    const HeightMap map(3, 3, 0.0f);
    const ReliefGeometry relief{&map, 0.1};
    const ReferenceHit hit = traceReference(relief, {{0.1, 1.0, 0.2}, {0.0, -2.0, 0.0}});
    ASSERT_EQ(hit.face, HitFace::Top);
    EXPECT_NEAR(hit.t, 0.5, kExact);
    expectNearVec(hit.position, {0.1, 0.0, 0.2}, kExact);
}

TEST(ReferenceTracerFlat, ZeroRegionsAreHitWhereTheRayMeetsTheBasePlane) {
    // Zeros but for one sample, so the relief's top (0.5) is far above the zero region.
    // There the ray leaves the bounding box through the base plane at the very point it
    // touches the surface: a root that must not round away past the box.
    HeightMap map(5, 12, 0.0f);
    map.at(3, 8) = 0.9f;
    const ReliefGeometry relief{&map, 0.54};
    const ReferenceTracer bounded(relief);
    const Extents e = extentsOf(map);
    int checked = 0;
    for (int p = 0; p < 40; ++p) {
        for (int q = 0; q < 40; ++q) {
            const glm::dvec3 target((p + 0.5) / 40.0 * e.a - 0.5 * e.a, 0.0,
                                    (q + 0.5) / 40.0 * e.b - 0.5 * e.b);
            if (surfaceY(relief, target.x, target.z) > 0.0) continue;
            for (const glm::dvec3& offset :
                 {glm::dvec3(0.0, 0.64, 0.0), glm::dvec3(0.01, 0.7, -0.02)}) {
                const Ray ray = through(target + offset, target);
                for (const ReferenceHit& hit : {traceReference(relief, ray), bounded.trace(ray)}) {
                    SCOPED_TRACE(testing::Message() << "target " << target.x << ", " << target.z);
                    ASSERT_EQ(hit.face, HitFace::Top);
                    EXPECT_NEAR(hit.t, 1.0, kExact);
                    EXPECT_NEAR(hit.position.y, 0.0, kExact);
                    ++checked;
                }
            }
        }
    }
    EXPECT_GT(checked, 2000);
}

// --- Sample centres -------------------------------------------------------------------

TEST(ReferenceTracerSamples, VerticalRayAtASampleCentreHitsTheSample) {
    HeightMap map(7, 5);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (float& h : map.samples) h = value(random);
    const ReliefGeometry relief{&map, 0.3};
    for (int j = 0; j < map.height; ++j) {
        for (int i = 0; i < map.width; ++i) {
            const glm::dvec2 xz = worldAtSample(map, i, j);
            const ReferenceHit hit = traceReference(relief, {{xz.x, 2.0, xz.y}, {0.0, -1.0, 0.0}});
            SCOPED_TRACE(testing::Message() << "sample " << i << ", " << j);
            ASSERT_EQ(hit.face, HitFace::Top);
            EXPECT_NEAR(hit.position.y, 0.3 * map.at(i, j), kExact);
            EXPECT_NEAR(hit.t, 2.0 - 0.3 * map.at(i, j), kExact);
            EXPECT_NEAR(hit.uv.x, (i + 0.5) / map.width, kExact);
            EXPECT_NEAR(hit.uv.y, (j + 0.5) / map.height, kExact);
        }
    }
}

// --- A one-texel spike ----------------------------------------------------------------

// 9 x 9 zeros with 1 at sample (4, 4); heightScale 0.5. In world units a sample step is
// 1/9 and sample (i, j) sits at ((i - 4)/9, (j - 4)/9).
class ReferenceTracerSpike : public testing::Test {
protected:
    ReferenceTracerSpike() : map(9, 9, 0.0f) { map.at(4, 4) = 1.0f; }
    HeightMap map;
    ReliefGeometry relief{&map, 0.5};
};

TEST_F(ReferenceTracerSpike, GrazingRayPassesTheNeighboursAndHitsTheFlank) {
    // Along the row line z_s = 4.25 the surface is 0.5 * 0.75 * (1 - |x_s - 4|): a tent.
    // The ray descends 0.05 per world unit and meets the rising flank at x_s = 3.4, where
    // the surface is 0.5 * 0.75 * 0.4 = 0.15.
    const double xHit = -0.6 / 9.0, zLine = 0.25 / 9.0, yHit = 0.15;
    const glm::dvec3 origin(-1.0, yHit + 0.05 * (1.0 + xHit), zLine);
    const ReferenceHit hit = traceReference(relief, {origin, {1.0, -0.05, 0.0}});
    ASSERT_EQ(hit.face, HitFace::Top);
    expectNearVec(hit.position, {xHit, yHit, zLine}, kExact);
    EXPECT_NEAR(hit.t, 1.0 + xHit, kExact);
    // Cell (3, 4): h = 0.5 (fx - fx fz); at fx = 0.4, fz = 0.25 the gradient per sample is
    // (0.5 * 0.75, -0.5 * 0.4), per world unit nine times that.
    const glm::dvec3 normal = glm::normalize(glm::dvec3(-9.0 * 0.375, 1.0, 9.0 * 0.2));
    expectNearVec(hit.normal, normal, kExact);
}

TEST_F(ReferenceTracerSpike, DiagonalRayMeetsTheQuadraticPartOfThePatch) {
    // Along the diagonal of cell (3, 3), fx = fz = f, the patch is 0.5 f^2: quadratic in t.
    // A level ray at 0.5 / 4 meets it at f = 1/2, the point (3.5, 3.5) in sample space.
    const double y = 0.125, xz = -0.5 / 9.0;
    const ReferenceHit hit = traceReference(relief, {{-1.0, y, -1.0}, {1.0, 0.0, 1.0}});
    ASSERT_EQ(hit.face, HitFace::Top);
    expectNearVec(hit.position, {xz, y, xz}, kExact);
    EXPECT_NEAR(hit.t, 1.0 + xz, kExact);
    const glm::dvec3 normal = glm::normalize(glm::dvec3(-9.0 * 0.25, 1.0, -9.0 * 0.25));
    expectNearVec(hit.normal, normal, kExact);
}

TEST_F(ReferenceTracerSpike, LevelRayJustAboveThePeakMisses) {
    // Along z_s = 4.25 the peak is 0.375; 1e-9 above it the ray clears the spike.
    const double zLine = 0.25 / 9.0;
    EXPECT_FALSE(traceReference(relief, {{-1.0, 0.375 + 1e-9, zLine}, {1.0, 0.0, 0.0}}));
    const ReferenceHit below =
        traceReference(relief, {{-1.0, 0.375 - 1e-9, zLine}, {1.0, 0.0, 0.0}});
    ASSERT_EQ(below.face, HitFace::Top);
    // The flank rises 0.375 per sample: the ray touches it 1e-9 / 0.375 samples early.
    EXPECT_NEAR(below.position.x, -(1e-9 / 0.375) / 9.0, kExact);
}

TEST_F(ReferenceTracerSpike, RayOverTheSpikeTipTouchesItExactly) {
    // Level through the tip along the sample row: the closed solid includes the tip.
    const glm::dvec2 tip = worldAtSample(map, 4, 4);
    const ReferenceHit hit = traceReference(relief, {{-1.0, 0.5, tip.y}, {1.0, 0.0, 0.0}});
    ASSERT_EQ(hit.face, HitFace::Top);
    expectNearVec(hit.position, {tip.x, 0.5, tip.y}, kExact);
}

// --- A step edge ----------------------------------------------------------------------

// 8 x 3, columns 0..3 are 0 and 4..7 are 1, heightScale 0.3: between the sample centres
// x_s = 3 and 4 the surface is the ramp 0.3 (x_s - 3); world x = (x_s - 3.5) / 8.
class ReferenceTracerStep : public testing::Test {
protected:
    ReferenceTracerStep() : map(8, 3, 0.0f) {
        for (int j = 0; j < 3; ++j)
            for (int i = 4; i < 8; ++i) map.at(i, j) = 1.0f;
    }
    HeightMap map;
    ReliefGeometry relief{&map, 0.3};
};

TEST_F(ReferenceTracerStep, LevelRayFromTheLowSideHitsTheRamp) {
    // At y = 0.09 the ramp is at x_s = 3.3, world x = -0.2 / 8.
    const ReferenceHit hit = traceReference(relief, {{-2.0, 0.09, 0.01}, {2.0, 0.0, 0.0}});
    ASSERT_EQ(hit.face, HitFace::Top);
    expectNearVec(hit.position, {-0.025, 0.09, 0.01}, kExact);
    EXPECT_NEAR(hit.t, (2.0 - 0.025) / 2.0, kExact);
    expectNearVec(hit.normal, glm::normalize(glm::dvec3(-0.3 * 8.0, 1.0, 0.0)), kExact);
    EXPECT_NEAR(hit.uv.x, 3.8 / 8.0, kExact);
}

TEST_F(ReferenceTracerStep, SteepRayFromAboveHitsTheRamp) {
    // Descending with dy/dx = -2 through (x_s = 3.5, y = 0.15), the ramp's midpoint:
    // the surface rises 2.4 per world unit, so that point is the first contact.
    const glm::dvec3 mid(0.0, 0.15, -0.05);
    const ReferenceHit hit = traceReference(relief, through(mid + glm::dvec3(-0.1, 0.2, 0.0), mid));
    ASSERT_EQ(hit.face, HitFace::Top);
    EXPECT_NEAR(hit.t, 1.0, kExact);
    expectNearVec(hit.position, mid, kExact);
}

TEST_F(ReferenceTracerStep, LevelRayFromTheHighSideHitsTheWall) {
    const ReferenceHit hit = traceReference(relief, {{2.0, 0.09, 0.01}, {-1.0, 0.0, 0.0}});
    ASSERT_EQ(hit.face, HitFace::WallX);
    expectNearVec(hit.position, {0.5, 0.09, 0.01}, kExact);
    EXPECT_NEAR(hit.t, 1.5, kExact);
    expectNearVec(hit.normal, {1.0, 0.0, 0.0}, 0.0);
    EXPECT_EQ(hit.uv.x, 1.0);
}

// --- Side walls, bottom face, eye in the box, misses --------------------------------------

// 6 x 4 map whose edge samples are all 0.5 and interior samples 1, heightScale 0.4: the
// walls stand 0.2 high, the interior plateau 0.4. a = 1, b = 2/3.
class ReferenceTracerBox : public testing::Test {
protected:
    ReferenceTracerBox() : map(6, 4, 0.5f) {
        for (int j = 1; j < 3; ++j)
            for (int i = 1; i < 5; ++i) map.at(i, j) = 1.0f;
    }
    HeightMap map;
    ReliefGeometry relief{&map, 0.4};
};

TEST_F(ReferenceTracerBox, LowRaysHitTheSideWalls) {
    const ReferenceHit left = traceReference(relief, {{-2.0, 0.1, 0.05}, {1.0, 0.0, 0.0}});
    ASSERT_EQ(left.face, HitFace::WallX);
    EXPECT_NEAR(left.t, 1.5, kExact);
    expectNearVec(left.position, {-0.5, 0.1, 0.05}, kExact);
    expectNearVec(left.normal, {-1.0, 0.0, 0.0}, 0.0);
    EXPECT_EQ(left.uv.x, 0.0);
    EXPECT_NEAR(left.uv.y, 0.05 / (2.0 / 3.0) + 0.5, kExact);

    const ReferenceHit far = traceReference(relief, {{0.2, 0.19, 3.0}, {0.0, 0.0, -2.0}});
    ASSERT_EQ(far.face, HitFace::WallZ);
    EXPECT_NEAR(far.t, (3.0 - 1.0 / 3.0) / 2.0, kExact);
    expectNearVec(far.position, {0.2, 0.19, 1.0 / 3.0}, kExact);
    expectNearVec(far.normal, {0.0, 0.0, 1.0}, 0.0);
    EXPECT_EQ(far.uv.y, 1.0);

    // Descending onto the wall: through (-0.5, 0.05, -0.1) from up and left.
    const glm::dvec3 onWall(-0.5, 0.05, -0.1);
    const ReferenceHit slanted =
        traceReference(relief, through(onWall + glm::dvec3(-0.4, 0.3, -0.2), onWall));
    ASSERT_EQ(slanted.face, HitFace::WallX);
    EXPECT_NEAR(slanted.t, 1.0, kExact);
    expectNearVec(slanted.position, onWall, kExact);
}

TEST_F(ReferenceTracerBox, RayAboveTheWallHitsTheRampBehindIt) {
    // At y = 0.3 the ray clears the 0.2 wall and meets the ramp from sample column 0
    // (0.2) to column 1 (0.4) halfway, at x_s = 0.5: world x = (0.5 - 2.5) / 6.
    const double z = worldAtSample(map, 0, 1.5).y;  // mid-row between interior rows
    const ReferenceHit hit = traceReference(relief, {{-2.0, 0.3, z}, {1.0, 0.0, 0.0}});
    ASSERT_EQ(hit.face, HitFace::Top);
    expectNearVec(hit.position, {-2.0 / 6.0, 0.3, z}, kExact);
}

TEST_F(ReferenceTracerBox, RayFromBelowHitsTheBottomFace) {
    const ReferenceHit up = traceReference(relief, {{0.1, -1.0, 0.2}, {0.0, 1.0, 0.0}});
    ASSERT_EQ(up.face, HitFace::Bottom);
    EXPECT_NEAR(up.t, 1.0, kExact);
    expectNearVec(up.position, {0.1, 0.0, 0.2}, 0.0);
    expectNearVec(up.normal, {0.0, -1.0, 0.0}, 0.0);

    const glm::dvec3 onBottom(-0.45, 0.0, 0.3);
    const ReferenceHit slanted =
        traceReference(relief, through(onBottom + glm::dvec3(-1.0, -0.5, 0.2), onBottom));
    ASSERT_EQ(slanted.face, HitFace::Bottom);
    EXPECT_NEAR(slanted.t, 1.0, kExact);
    expectNearVec(slanted.position, onBottom, kExact);
}

TEST_F(ReferenceTracerBox, RayFromBelowOutsideTheFootprintEntersThroughTheWall) {
    // Rising at 45 degrees from below and left of the footprint, it crosses y = 0 at
    // x = -0.6 and reaches the wall x = -0.5 at y = 0.1.
    const ReferenceHit hit = traceReference(relief, {{-0.8, -0.2, 0.0}, {1.0, 1.0, 0.0}});
    ASSERT_EQ(hit.face, HitFace::WallX);
    expectNearVec(hit.position, {-0.5, 0.1, 0.0}, kExact);
}

TEST_F(ReferenceTracerBox, EyeInsideTheBoxAboveTheSurfaceLooksDown) {
    // The eye is below the plateau's top (0.4) but above the wall rim at the edge.
    const glm::dvec2 edge = worldAtSample(map, 0, 0);
    const ReferenceHit down = traceReference(relief, {{edge.x, 0.3, edge.y}, {0.0, -1.0, 0.0}});
    ASSERT_EQ(down.face, HitFace::Top);
    EXPECT_NEAR(down.t, 0.1, kExact);
    // Looking along the edge row towards the plateau: the ramp from 0.2 to 0.4 between
    // sample rows 0 and 1 is 0.25 at z_s = 0.25.
    const glm::dvec2 mid = worldAtSample(map, 2.5, 0.25);
    const glm::dvec3 eye(mid.x, 0.3, edge.y - 0.05);  // in the border half-cell, above 0.2
    const ReferenceHit slanted = traceReference(relief, through(eye, {mid.x, 0.25, mid.y}));
    ASSERT_EQ(slanted.face, HitFace::Top);
    EXPECT_NEAR(slanted.t, 1.0, kExact);
}

TEST_F(ReferenceTracerBox, RaysThatMiss) {
    EXPECT_FALSE(traceReference(relief, {{0.0, 1.0, 0.0}, {0.3, 1.0, 0.1}}));    // up and away
    EXPECT_FALSE(traceReference(relief, {{0.6, 0.1, -2.0}, {0.0, 0.0, 1.0}}));   // beside, x
    EXPECT_FALSE(traceReference(relief, {{-2.0, 0.1, 0.34}, {1.0, 0.0, 0.0}}));  // beside, z
    EXPECT_FALSE(traceReference(relief, {{-2.0, 0.41, 0.0}, {1.0, 0.0, 0.0}}));  // above it all
    EXPECT_FALSE(traceReference(relief, {{-2.0, 0.1, 0.0}, {-1.0, 0.0, 0.0}}));  // box behind
    EXPECT_FALSE(traceReference(relief, {{0.0, -0.1, 0.0}, {0.0, -1.0, 0.0}}));  // down, below
    EXPECT_FALSE(traceReference(relief, {{0.0, 0.5, 0.0}, {0.0, 1.0, 0.0}}));    // up from above
    EXPECT_FALSE(traceReference(relief, {{0.7, 0.0, 0.0}, {0.0, 0.0, 1.0}}));  // base plane, beside
}

TEST_F(ReferenceTracerBox, GrazingTheEdgesOfTheClosedSolid) {
    // Along the top edge of the wall x = -a/2 (height 0.2 there): the closed solid holds it.
    const ReferenceHit rim = traceReference(relief, {{-0.5, 0.2, -2.0}, {0.0, 0.0, 1.0}});
    ASSERT_TRUE(rim);
    EXPECT_NEAR(rim.position.y, 0.2, kExact);
    EXPECT_NEAR(rim.position.z, -1.0 / 3.0, kExact);
    // Along the bottom edge x = -a/2, y = 0.
    const ReferenceHit floor = traceReference(relief, {{-0.5, 0.0, 2.0}, {0.0, 0.0, -1.0}});
    ASSERT_TRUE(floor);
    expectNearVec(floor.position, {-0.5, 0.0, 1.0 / 3.0}, kExact);
}

TEST_F(ReferenceTracerBox, LevelRayAtTheTopHeightTouchesThePlateauEdge) {
    // At y = 0.4, the box's top, the ray first meets the surface where the ramp from the
    // rim reaches the plateau: sample column 1, x = (1 - 2.5) / 6. With the top known
    // (ReferenceTracer) the ray runs exactly in the bounding box's top face.
    const Ray ray{{-2.0, 0.4, 0.0}, {1.0, 0.0, 0.0}};
    const ReferenceTracer tracer(relief);
    for (const ReferenceHit& hit : {traceReference(relief, ray), tracer.trace(ray)}) {
        ASSERT_EQ(hit.face, HitFace::Top);
        expectNearVec(hit.position, {-0.25, 0.4, 0.0}, kExact);
    }
    const Ray above{{-2.0, 0.4 + 1e-12, 0.0}, {1.0, 0.0, 0.0}};
    EXPECT_FALSE(traceReference(relief, above));
    EXPECT_FALSE(tracer.trace(above));
}

TEST_F(ReferenceTracerBox, BoundedTracerEntersThroughTheTopOfTheBox) {
    // From high above, down onto the plateau: the bounded walk starts at y = 0.4.
    const glm::dvec3 onPlateau(0.05, 0.4, 0.02);
    const Ray ray = through(onPlateau + glm::dvec3(0.3, 1.0, -0.2), onPlateau);
    const ReferenceHit hit = ReferenceTracer(relief).trace(ray);
    ASSERT_EQ(hit.face, HitFace::Top);
    EXPECT_NEAR(hit.t, 1.0, kExact);
    expectNearVec(hit.position, onPlateau, kExact);
    EXPECT_FALSE(ReferenceTracer(relief).trace({{0.0, 1.0, 0.0}, {0.3, 1.0, 0.1}}));
}

// --- Map shapes -----------------------------------------------------------------------

TEST(ReferenceTracerShape, NonSquareMapSpansTheSpecExtents) {
    HeightMap map(300, 77);
    std::mt19937 random(300);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (float& h : map.samples) h = value(random);
    map.at(179, 0) = map.at(180, 0) = 0.5f;  // under the wall hit below
    const ReliefGeometry relief{&map, 0.1};
    const double a = 1.0, b = 77.0 / 300.0, inset = 1e-9;
    // Within half a texel of a corner the surface is the corner sample (clamped).
    for (int sx : {-1, 1}) {
        for (int sz : {-1, 1}) {
            const int i = sx < 0 ? 0 : 299, j = sz < 0 ? 0 : 76;
            const double x = sx * (0.5 * a - inset), z = sz * (0.5 * b - inset);
            const ReferenceHit inside = traceReference(relief, {{x, 1.0, z}, {0.0, -1.0, 0.0}});
            SCOPED_TRACE(testing::Message() << "corner " << sx << ", " << sz);
            ASSERT_EQ(inside.face, HitFace::Top);
            EXPECT_NEAR(inside.position.y, 0.1 * map.at(i, j), kExact);
            EXPECT_FALSE(traceReference(relief, {{x + sx * 2 * inset, 1.0, z}, {0.0, -1.0, 0.0}}));
            EXPECT_FALSE(traceReference(relief, {{x, 1.0, z + sz * 2 * inset}, {0.0, -1.0, 0.0}}));
        }
    }
    // Sample (123, 45): uv at its texel centre.
    const glm::dvec2 xz = worldAtSample(map, 123, 45);
    const ReferenceHit sample = traceReference(relief, {{xz.x, 1.0, xz.y}, {0.0, -1.0, 0.0}});
    ASSERT_EQ(sample.face, HitFace::Top);
    EXPECT_NEAR(sample.position.y, 0.1 * map.at(123, 45), kExact);
    EXPECT_NEAR(sample.uv.x, 123.5 / 300.0, kExact);
    EXPECT_NEAR(sample.uv.y, 45.5 / 77.0, kExact);
    // The wall z = -b/2 from outside, low.
    const ReferenceHit wall = traceReference(relief, {{0.1, 1e-3, -1.0}, {0.0, 0.0, 1.0}});
    ASSERT_EQ(wall.face, HitFace::WallZ);
    EXPECT_NEAR(wall.position.z, -0.5 * b, 0.0);
    EXPECT_NEAR(wall.t, 1.0 - 0.5 * b, kExact);
}

TEST(ReferenceTracerShape, OneByOneMapIsAFlatBox) {
    const HeightMap map(1, 1, 0.8f);
    const ReliefGeometry relief{&map, 0.25};
    const double top = 0.25 * double(0.8f);
    const ReferenceHit down = traceReference(relief, {{0.49, 1.0, -0.49}, {0.0, -1.0, 0.0}});
    ASSERT_EQ(down.face, HitFace::Top);
    EXPECT_NEAR(down.position.y, top, kExact);
    expectNearVec(down.normal, {0.0, 1.0, 0.0}, 0.0);
    const ReferenceHit side = traceReference(relief, {{-1.0, 0.1, 0.3}, {1.0, 0.0, 0.0}});
    ASSERT_EQ(side.face, HitFace::WallX);
    expectNearVec(side.position, {-0.5, 0.1, 0.3}, kExact);
    EXPECT_FALSE(traceReference(relief, {{-1.0, top + 1e-9, 0.3}, {1.0, 0.0, 0.0}}));
    const glm::dvec3 onTop(0.2, top, 0.1);
    const ReferenceHit slanted =
        traceReference(relief, through(onTop + glm::dvec3(0.6, 0.3, 0.5), onTop));
    ASSERT_EQ(slanted.face, HitFace::Top);
    EXPECT_NEAR(slanted.t, 1.0, kExact);
}

// --- The quadratic against bisection --------------------------------------------------

// The first t where the ray is on or below y = s h, by dense sampling then bisection:
// an evaluation that shares nothing with the tracer's quadratic.
double firstContactByBisection(const ReliefGeometry& relief, const Ray& ray, double tMax) {
    const auto below = [&](double t) {
        const glm::dvec3 p = ray.origin + t * ray.direction;
        return p.y - surfaceY(relief, p.x, p.z);
    };
    constexpr int kSteps = 100000;
    double lo = 0.0;
    for (int k = 1; k <= kSteps; ++k) {
        double hi = tMax * k / kSteps;
        if (below(hi) <= 0.0) {
            for (int iteration = 0; iteration < 200 && hi - lo > 0.0; ++iteration) {
                const double midT = 0.5 * (lo + hi);
                if (midT <= lo || midT >= hi) break;
                (below(midT) <= 0.0 ? hi : lo) = midT;
            }
            return hi;
        }
        lo = hi;
    }
    return -1.0;
}

TEST(ReferenceTracerPatch, SlantedRaysAgreeWithBisection) {
    // A 2 x 2 map: one interior bilinear cell with a twist (k != 0), x_s, z_s in [0, 1]
    // at world [-0.25, 0.25]^2. Rays from above the cell through points under it.
    HeightMap map(2, 2);
    map.at(0, 0) = 0.1f;
    map.at(1, 0) = 0.9f;
    map.at(0, 1) = 0.4f;
    map.at(1, 1) = 0.7f;
    const ReliefGeometry relief{&map, 1.0};
    std::mt19937 random(11);
    std::uniform_real_distribution<double> inCell(-0.24, 0.24), unit(-1.0, 1.0);
    for (int n = 0; n < 200; ++n) {
        const glm::dvec3 target(inCell(random), 0.0, inCell(random));
        const glm::dvec3 origin{target.x + 0.2 * unit(random), 1.0, target.z + 0.2 * unit(random)};
        const Ray ray = through(origin, target);
        const ReferenceHit hit = traceReference(relief, ray);
        ASSERT_EQ(hit.face, HitFace::Top);
        // Bisection converges to the last double below the root: ~1e-16, plus the
        // rounding of surface() near the root.
        EXPECT_NEAR(hit.t, firstContactByBisection(relief, ray, 1.0), 1e-12);
    }
}

// For a ray that starts on the footprint's edge above the relief and leaves the
// footprint at tFootprintExit (beyond it surface() clamps and would invent surface).
void expectMatchesBisection(const ReliefGeometry& relief, const Ray& ray, double tFootprintExit) {
    const double expected = firstContactByBisection(relief, ray, tFootprintExit);
    const ReferenceHit hit = traceReference(relief, ray);
    if (expected < 0.0) {
        EXPECT_FALSE(hit) << "hit at t = " << hit.t;
        return;
    }
    ASSERT_EQ(hit.face, HitFace::Top);
    EXPECT_NEAR(hit.t, expected, 1e-12);
}

TEST(ReferenceTracerPatch, RaysAlongCellBoundariesAgreeWithBisection) {
    // Rays in the vertical planes through sample rows and columns: the DDA walks
    // exactly along cell edges there (8 x 5: sample lines are exact in world units).
    HeightMap map(8, 5);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (float& h : map.samples) h = value(random);
    const ReliefGeometry relief{&map, 0.2};
    for (int j = 0; j < map.height; ++j) {
        const double z = worldAtSample(map, 0, j).y;
        for (double dir : {-1.0, 1.0}) {
            // From the wall x = -+a/2, above the relief (max 0.2), to the opposite one.
            expectMatchesBisection(relief, {{-0.5 * dir, 0.25, z}, {dir, -0.3, 0.0}}, 1.0);
        }
    }
    for (int i = 0; i < map.width; ++i) {
        const double x = worldAtSample(map, i, 0).x;
        expectMatchesBisection(relief, {{x, 0.25, -5.0 / 16.0}, {0.0, -0.5, 1.0}}, 5.0 / 8.0);
    }
}

// --- The biquadratic surface -----------------------------------------------------------

// One raised sample is the B-spline itself: 3/4 x 3/4 at its centre, 1/2 x 3/4 on the
// edge of its texel square, 1/8 x 3/4 at the next sample.
TEST(ReferenceTracerBiquadratic, ASpikeIsTheBSpline) {
    const HeightMap map = [] {
        HeightMap m(9, 9, 0.0f);
        m.at(4, 3) = 1.0f;
        return m;
    }();
    const ReliefGeometry relief{&map, 0.5, BaseShape::plane(), Interpolation::Biquadratic};
    const auto down = [&](double i, double j) {
        const glm::dvec2 xz = worldAtSample(map, i, j);
        return traceReference(relief, {{xz.x, 2.0, xz.y}, {0.0, -1.0, 0.0}});
    };
    for (const auto& [i, j, h] : std::vector<std::tuple<double, double, double>>{
             {4.0, 3.0, 0.5625}, {4.5, 3.0, 0.375}, {5.0, 3.0, 0.09375}, {4.0, 3.5, 0.375}}) {
        const ReferenceHit hit = down(i, j);
        ASSERT_EQ(hit.face, HitFace::Top) << i << "," << j;
        EXPECT_NEAR(hit.position.y, 0.5 * h, kExact) << i << "," << j;
    }
    // The peak is smooth: straight up at the centre, tilted evenly either side.
    EXPECT_NEAR(down(4.0, 3.0).normal.y, 1.0, kExact);
    const glm::dvec3 left = down(3.7, 3.0).normal, right = down(4.3, 3.0).normal;
    EXPECT_NEAR(left.x, -right.x, kExact);
    EXPECT_LT(left.x, 0.0);
}

// Slanted rays through the quartic part of a square against dense bisection on the
// surface's own definition (HeightMap::surface).
TEST(ReferenceTracerBiquadratic, SlantedRaysAgreeWithBisection) {
    std::mt19937_64 random(99);
    HeightMap map(7, 5);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (float& h : map.samples) h = value(random);
    const ReliefGeometry relief{&map, 0.4, BaseShape::plane(), Interpolation::Biquadratic};
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int hits = 0;
    for (int k = 0; k < 300; ++k) {
        const glm::dvec3 target{0.45 * unit(random), 0.0, 0.3 * unit(random)};
        const glm::dvec3 eye =
            target + glm::dvec3{unit(random), 0.6 + 0.5 * unit(random), unit(random)};
        const Ray ray = through(eye, {target.x, surfaceY(relief, target.x, target.z), target.z});
        const ReferenceHit hit = traceReference(relief, ray);
        ASSERT_TRUE(hit) << k;  // the target itself is on the surface
        // Bisection for the first point below the surface, from dense samples; none before
        // the target, which is on the surface (and may round to either side of it): t = 1.
        double t0 = 1.0, t1 = 1.0;
        for (int n = 1; n <= 20000; ++n) {
            const double t = n / 20000.0;
            const glm::dvec3 p = ray.origin + t * ray.direction;
            const bool in = std::abs(p.x) <= 0.5 && std::abs(p.z) <= 5.0 / 14.0 &&
                            p.y <= surfaceY(relief, p.x, p.z);
            if (in) {
                t1 = t;
                t0 = (n - 1) / 20000.0;
                break;
            }
        }
        for (int n = 0; n < 60; ++n) {
            const double m = 0.5 * (t0 + t1);
            const glm::dvec3 p = ray.origin + m * ray.direction;
            (p.y <= surfaceY(relief, p.x, p.z) ? t1 : t0) = m;
        }
        if (hit.face != HitFace::Top) continue;
        ++hits;
        EXPECT_NEAR(hit.t, t1, 1e-9) << k;
    }
    EXPECT_GT(hits, 200);
}

// --- Random maps and rays: the definition of a hit ------------------------------------

HeightMap randomMap(std::mt19937_64& random) {
    // Mostly small maps, where edges and border cells are a large share; some larger.
    std::uniform_int_distribution<int> size(1, 12), largeSize(13, 64), style(0, 2);
    const bool large = std::uniform_int_distribution<int>(0, 9)(random) == 0;
    HeightMap map(large ? largeSize(random) : size(random),
                  large ? largeSize(random) : size(random));
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    const int kind = style(random);
    for (float& h : map.samples) {
        const float v = value(random);
        if (kind == 0) h = v;                                 // rough
        if (kind == 1) h = std::floor(v * 4.0f) / 4.0f;       // plateaus and exact ties
        if (kind == 2) h = v < 0.85f ? 0.0f : value(random);  // sparse spikes on zero
    }
    if (map.maxValue() == 0.0f) map.samples[0] = 0.5f;  // a solid with inner points
    return map;
}

// A uniformly random point of the solid (strictly inside by a margin where possible).
glm::dvec3 randomPointInSolid(const ReliefGeometry& relief, std::mt19937_64& random) {
    const Extents e = extentsOf(*relief.map);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (;;) {
        const double x = (unit(random) - 0.5) * e.a * 0.999, z = (unit(random) - 0.5) * e.b * 0.999;
        const double top = surfaceY(relief, x, z);
        if (top > 1e-6) return {x, top * (0.001 + 0.998 * unit(random)), z};
    }
}

// The interval of t for which the ray is inside the bounding box of the solid.
bool boundingInterval(const ReliefGeometry& relief, const Ray& ray, double& t0, double& t1) {
    const Extents e = extentsOf(*relief.map);
    const glm::dvec3 lo(-0.5 * e.a, 0.0, -0.5 * e.b);
    const glm::dvec3 hi(0.5 * e.a, relief.heightScale * relief.map->maxValue(), 0.5 * e.b);
    t0 = 0.0;
    t1 = 1e30;
    for (int axis = 0; axis < 3; ++axis) {
        if (ray.direction[axis] == 0.0) {
            if (ray.origin[axis] < lo[axis] || ray.origin[axis] > hi[axis]) return false;
            continue;
        }
        double a = (lo[axis] - ray.origin[axis]) / ray.direction[axis];
        double b = (hi[axis] - ray.origin[axis]) / ray.direction[axis];
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
    }
    return t0 <= t1;
}

// (a) on the ray, (b) on the face it names, (c) no point of the ray before it deep inside.
void checkHit(const ReliefGeometry& relief, const Ray& ray, const ReferenceHit& hit) {
    constexpr double kOnSurface = 1e-9;
    const Extents e = extentsOf(*relief.map);
    const glm::dvec3 p = hit.position;
    ASSERT_GE(hit.t, 0.0);
    EXPECT_LE(glm::length(ray.origin + hit.t * ray.direction - p), kOnSurface);
    EXPECT_NEAR(glm::length(hit.normal), 1.0, 1e-12);
    EXPECT_NEAR(hit.uv.x, p.x / e.a + 0.5, kOnSurface);
    EXPECT_NEAR(hit.uv.y, p.z / e.b + 0.5, kOnSurface);
    EXPECT_LE(std::abs(p.x), 0.5 * e.a + kOnSurface);
    EXPECT_LE(std::abs(p.z), 0.5 * e.b + kOnSurface);
    EXPECT_GE(p.y, -kOnSurface);
    const double top = surfaceY(relief, std::clamp(p.x, -0.5 * e.a, 0.5 * e.a),
                                std::clamp(p.z, -0.5 * e.b, 0.5 * e.b));
    // A ray entering the solid crosses its boundary inwards (or grazes it).
    const double facing = glm::dot(hit.normal, glm::normalize(ray.direction));
    switch (hit.face) {
        case HitFace::Top:
            EXPECT_NEAR(p.y, top, kOnSurface);
            EXPECT_LE(facing, 1e-6);
            break;
        case HitFace::WallX:
            EXPECT_EQ(std::abs(p.x), 0.5 * e.a);
            EXPECT_LE(p.y, top + kOnSurface);
            EXPECT_LE(facing, 0.0);
            break;
        case HitFace::WallZ:
            EXPECT_EQ(std::abs(p.z), 0.5 * e.b);
            EXPECT_LE(p.y, top + kOnSurface);
            EXPECT_LE(facing, 0.0);
            break;
        case HitFace::Bottom:
            EXPECT_EQ(p.y, 0.0);
            EXPECT_LT(facing, 0.0);
            break;
        case HitFace::None:
        case HitFace::Cap:  // no caps on the plane
            FAIL();
    }
    constexpr int kSamples = 20000;
    const double tEnd = hit.t * (1.0 - 1e-9) - 1e-12;
    for (int k = 0; k < kSamples; ++k) {
        const double t = tEnd * k / kSamples;
        const glm::dvec3 q = ray.origin + t * ray.direction;
        if (deepInside(relief, q, kOnSurface)) {
            ADD_FAILURE() << "the ray is inside the solid at t = " << t
                          << " before the hit at t = " << hit.t;
            return;
        }
    }
}

void checkMiss(const ReliefGeometry& relief, const Ray& ray) {
    double t0, t1;
    if (!boundingInterval(relief, ray, t0, t1)) return;
    constexpr int kSamples = 20000;
    for (int k = 0; k <= kSamples; ++k) {
        const double t = t0 + (t1 - t0) * k / kSamples;
        if (deepInside(relief, ray.origin + t * ray.direction, 1e-9)) {
            ADD_FAILURE() << "a miss, but the ray is inside the solid at t = " << t;
            return;
        }
    }
}

glm::dvec3 randomDirection(std::mt19937_64& random) {
    std::normal_distribution<double> normal;
    for (;;) {
        const glm::dvec3 d(normal(random), normal(random), normal(random));
        if (glm::length(d) > 1e-3) return d;
    }
}

TEST(ReferenceTracerProperty, RandomRaysHitTheSolidFirstWhereTheyEnterIt) {
    std::mt19937_64 random(20240611);
    std::uniform_real_distribution<double> unit(0.0, 1.0), scale(0.05, 1.5);
    std::uniform_int_distribution<int> rayKind(0, 4);
    int hits = 0, misses = 0, faces[5] = {};
    for (int trial = 0; trial < 300; ++trial) {
        const HeightMap map = randomMap(random);
        // Both interpolations, trial by trial.
        const ReliefGeometry relief{
            &map, scale(random), BaseShape::plane(),
            trial % 2 ? Interpolation::Biquadratic : Interpolation::Bilinear};
        const Extents e = extentsOf(map);
        const double boxTop = relief.heightScale * map.maxValue();
        for (int n = 0; n < 12; ++n) {
            // An origin outside the solid: anywhere around it, or in its box above it.
            glm::dvec3 origin;
            const int kind = rayKind(random);
            do {
                if (kind == 4) {
                    origin = {(unit(random) - 0.5) * e.a, 0.0, (unit(random) - 0.5) * e.b};
                    origin.y = surfaceY(relief, origin.x, origin.z) + unit(random) * (boxTop + 0.1);
                } else {
                    origin = {3.0 * unit(random) - 1.5, (boxTop + 1.0) * unit(random) - 0.5,
                              3.0 * unit(random) - 1.5};
                }
            } while (deepInside(relief, origin, 0.0));
            Ray ray{origin, randomDirection(random)};
            const bool mustHit = kind <= 1;
            if (mustHit) ray = through(origin, randomPointInSolid(relief, random));
            if (kind == 2) {
                // Axis-aligned parts and sample lines: zero direction components, origins on
                // cell boundaries.
                const glm::dvec2 line = worldAtSample(map, std::floor(unit(random) * map.width),
                                                      std::floor(unit(random) * map.height));
                if (unit(random) < 0.5) origin.x = line.x;
                if (unit(random) < 0.5) origin.z = line.y;
                for (int axis = 0; axis < 3; ++axis)
                    if (unit(random) < 0.4) ray.direction[axis] = 0.0;
                if (ray.direction == glm::dvec3(0.0)) ray.direction.y = -1.0;
                if (deepInside(relief, origin, 0.0)) continue;
                ray.origin = origin;
            }
            SCOPED_TRACE(testing::Message()
                         << "trial " << trial << " ray " << n << " map " << map.width << "x"
                         << map.height << " s " << relief.heightScale);
            const ReferenceHit hit = traceReference(relief, ray);
            // Knowing the top changes where the walk starts, not the hit.
            const ReferenceHit bounded = ReferenceTracer(relief).trace(ray);
            EXPECT_EQ(bounded.face, hit.face);
            EXPECT_NEAR(bounded.t, hit.t, 1e-12 * std::max(1.0, hit.t));
            if (mustHit) {
                ASSERT_TRUE(hit) << "the ray reaches a point inside the solid at t = 1";
                EXPECT_LE(hit.t, 1.0 + 1e-12);
            }
            if (hit) {
                ++hits;
                ++faces[static_cast<int>(hit.face)];
                checkHit(relief, ray, hit);
            } else {
                ++misses;
                checkMiss(relief, ray);
            }
            if (HasFailure()) return;
        }
    }
    // The rays exercise every face and both outcomes.
    EXPECT_GT(misses, 100);
    EXPECT_GT(faces[static_cast<int>(HitFace::Top)], 500);
    EXPECT_GT(faces[static_cast<int>(HitFace::WallX)], 50);
    EXPECT_GT(faces[static_cast<int>(HitFace::WallZ)], 50);
    EXPECT_GT(faces[static_cast<int>(HitFace::Bottom)], 50);
    std::printf("%d hits (top %d, wall x %d, wall z %d, bottom %d), %d misses\n", hits, faces[1],
                faces[2], faces[3], faces[4], misses);
}

// The reference over a map that is not in memory whole (samples read from pages a block at
// a time, the last 32 kept) is the reference: the same hits, bit for bit, from random eyes
// above, beside and below a map whose sides are not multiples of the blocks, both last
// levels, through a model transform; its cache of 32 blocks read over and over on a map of
// 66 (11 x 6).
TEST(PagedReferenceTracer, GivesTheReferencesHitsOverTheSameSamples) {
    HeightMap map(2600, 1500);
    std::mt19937 random(11);
    std::uniform_real_distribution<float> jitter(0.0f, 0.2f);
    for (int j = 0; j < map.height; ++j)
        for (int i = 0; i < map.width; ++i)
            map.at(i, j) =
                0.5f + 0.3f * std::sin(i * 0.021f) * std::cos(j * 0.017f) + jitter(random);
    const auto pages =
        std::make_shared<PyramidInMemory>(std::make_shared<const HeightMap>(map), false, "test");
    // Turned 30 degrees about y, moved by (0.1, 0, -0.2).
    const ModelTransform turned =
        ModelTransform::fromRows({0.8660254037844387, 0.0, 0.5, 0.1, 0.0, 1.0, 0.0, 0.0, -0.5, 0.0,
                                  0.8660254037844387, -0.2});
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        for (const ModelTransform& model : {ModelTransform{}, turned}) {
            const ReferenceTracer whole(ReliefGeometry{&map, 0.05, {}, interpolation, model});
            const PagedReferenceTracer paged(pages, 0.05, interpolation, model);
            int hits = 0;
            for (int k = 0; k < 400; ++k) {
                // One draw a statement: the order of a call's arguments is the compiler's.
                const double ex = unit(random), ey = 0.02 + 0.3 * (unit(random) + 1.0);
                const double ez = unit(random), tx = 0.45 * unit(random);
                const double tz = 0.25 * unit(random);  // the plane spans z +-0.29
                const glm::dvec3 eye(ex, ey, ez), target(tx, 0.0, tz);
                const Ray ray{eye, target - eye};
                const ReferenceHit expected = whole.trace(ray), got = paged.trace(ray);
                ASSERT_EQ(got.face, expected.face) << k;
                EXPECT_EQ(got.t, expected.t) << k;
                EXPECT_EQ(got.position, expected.position) << k;
                EXPECT_EQ(got.normal, expected.normal) << k;
                hits += expected.face == HitFace::Top;
            }
            EXPECT_GT(hits, 250);
            EXPECT_GT(paged.blocksRead(), 32u) << "the cache was cycled";
        }
    }
}

}  // namespace
}  // namespace microrelief
