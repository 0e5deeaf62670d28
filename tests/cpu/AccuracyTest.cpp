// The measuring stick itself (core/trace/Accuracy.h): what a comparison counts, in which unit,
// over which pixels, checked with made-up tracers whose errors are known exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/Accuracy.h"
#include "microrelief/core/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

// A low view of a raised map, its near side walls and the sky in the picture; not square,
// so that width and height cannot stand in for each other.
struct Scene {
    HeightMap map = synth::cobbles(64, 64, 3);
    double heightScale = 0.1;
    Camera view = test::orbitCamera(12.0, 30.0, 1.4, {0.0, 0.03, 0.0}, 40.0);
    CameraFrame camera = resolveCamera(view, 64, 40, 2.0);
    ReferencePicture reference = traceReferencePicture(camera, map, heightScale);

    std::size_t at(int column, int row) const { return std::size_t(row) * camera.width + column; }
};

// The picture is traced on several threads, rows handed out as they free up: it must be
// the tracer's own answer for every pixel, in its place.
TEST(Accuracy, TheReferencePictureIsEachPixelsTraceInPlace) {
    const Scene s;
    const ReferenceTracer tracer(ReliefGeometry{&s.map, s.heightScale});
    ASSERT_EQ(s.reference.hits.size(), std::size_t(s.camera.width) * s.camera.height);
    ASSERT_EQ(s.reference.viaTop.size(), s.reference.hits.size());
    std::size_t hits = 0;
    for (int row = 0; row < s.camera.height; ++row) {
        for (int column = 0; column < s.camera.width; ++column) {
            const ReferenceHit exact = tracer.trace(s.camera.pixelRay(column, row));
            const std::optional<glm::dvec3>& got = s.reference.hits[s.at(column, row)];
            ASSERT_EQ(bool(exact), got.has_value()) << column << ", " << row;
            if (exact) {
                ++hits;
                ASSERT_EQ(exact.position, *got) << column << ", " << row;
            }
            ASSERT_EQ(exact.entryFace == HitFace::None, bool(s.reference.viaTop[s.at(column, row)]))
                << column << ", " << row;
        }
    }
    EXPECT_GT(hits, s.reference.hits.size() / 8);  // a picture with the relief in it
}

// The sampled reference (maps read from pyramid files) traces about the pixels asked for,
// spread evenly, each the full reference's answer; every pixel where they are all asked.
TEST(Accuracy, TheSampledReferenceTracesAboutThePixelsAskedForEvenly) {
    const Scene s;
    const ReferenceTracer tracer(ReliefGeometry{&s.map, s.heightScale});
    const auto trace = [&](const Ray& ray) { return tracer.trace(ray); };
    const std::size_t all = std::size_t(s.camera.width) * s.camera.height;  // 64 x 40
    for (const auto& [asked, expected] : std::vector<std::pair<int, std::size_t>>{
             {int(all), all}, {40, 40}, {1, 1}, {2000, 1995}}) {
        const ReferencePicture sampled = traceSampledReferencePicture(
            s.camera, trace, s.reference.texelsPerUnit, s.reference.worldToObject, asked);
        ASSERT_EQ(sampled.traced.size(), all);
        std::size_t traced = 0;
        for (std::size_t pixel = 0; pixel < all; ++pixel) {
            if (!sampled.traced[pixel]) continue;
            ++traced;
            EXPECT_EQ(sampled.hits[pixel], s.reference.hits[pixel]) << pixel;
        }
        // 40 of 2560: cells of 8 x 8, every 8th pixel of every 8th row (5 x 8); 1: one
        // cell, the pixel (32, 20) alone; 2000: cells of 1.13, 57 x 35 (a whole step of 2
        // gave 640, a third: seen before the cells were fractional).
        EXPECT_EQ(traced, expected) << asked << " asked";
    }
}

TEST(Accuracy, TopSurfaceScopeLeavesOutRaysThroughTheWallsAndTheBottom) {
    const Scene s;
    const ReferenceTracer tracer(ReliefGeometry{&s.map, s.heightScale});
    std::size_t inScope = 0, wallHits = 0, wallHitsInScope = 0, missesInScope = 0;
    for (int row = 0; row < s.camera.height; ++row) {
        for (int column = 0; column < s.camera.width; ++column) {
            const ReferenceHit exact = tracer.trace(s.camera.pixelRay(column, row));
            const bool viaTop = s.reference.viaTop[s.at(column, row)];
            inScope += viaTop;
            const bool wall = exact && exact.face != HitFace::Top;
            wallHits += wall;
            wallHitsInScope += wall && viaTop;
            missesInScope += !exact && viaTop;
        }
    }
    ASSERT_GT(wallHits, 20u) << "the view must show side walls";
    ASSERT_GT(missesInScope, 100u) << "the view must show the sky";
    EXPECT_EQ(wallHitsInScope, 0u);

    // A tracer that knows the top surface only: exact where the ray comes in through the
    // top; elsewhere a texel off on a hit and a false hit on a miss (the box's silhouette).
    const auto topOnly = [&](int column, int row, const Ray& ray) {
        const std::optional<glm::dvec3>& exact = s.reference.hits[s.at(column, row)];
        if (s.reference.viaTop[s.at(column, row)])
            return exact ? PixelHit{true, *exact, false} : PixelHit{};
        return PixelHit{true, exact ? *exact + glm::dvec3(0, 1.0 / 64, 0) : ray.origin, false};
    };
    const Accuracy all = measureAccuracy(s.camera, s.reference, topOnly);
    const Accuracy top = measureAccuracy(s.camera, s.reference, topOnly, AccuracyScope::TopSurface);
    EXPECT_EQ(all.pixels, std::size_t(s.camera.width) * s.camera.height);
    EXPECT_GE(all.offHalfTexel, wallHits);
    EXPECT_EQ(top.pixels, inScope);
    EXPECT_EQ(top.offHalfTexel, 0u);
    EXPECT_EQ(top.coverageMismatches, 0u);

    // A false hit where a ray through the top face misses is still counted.
    const auto falseHits = [&](int column, int row, const Ray& ray) {
        const std::optional<glm::dvec3>& exact = s.reference.hits[s.at(column, row)];
        return exact ? PixelHit{true, *exact, false} : PixelHit{true, ray.origin, false};
    };
    EXPECT_EQ(measureAccuracy(s.camera, s.reference, falseHits, AccuracyScope::TopSurface)
                  .coverageMismatches,
              missesInScope);
}

TEST(Accuracy, PixelErrorIsTheDistanceOverAPixelsWidthThere) {
    const Scene s;
    // Every hit moved along its ray by half a pixel's width at the exact hit: the width
    // of the picture's centre pixel, 2 tan(fovy / 2) / height per unit of distance.
    const double perUnit = 2.0 * std::tan(glm::radians(s.view.fovyDegrees) / 2.0) / s.camera.height;
    const auto halfPixelOff = [&](int column, int row, const Ray& ray) {
        const std::optional<glm::dvec3>& exact = s.reference.hits[s.at(column, row)];
        if (!exact) return PixelHit{};
        const double width = glm::length(*exact - s.camera.eye) * perUnit;
        return PixelHit{true, *exact + 0.5 * width * glm::normalize(ray.direction), false};
    };
    const Accuracy a = measureAccuracy(s.camera, s.reference, halfPixelOff);
    EXPECT_GT(a.referenceHits, 500u);
    EXPECT_NEAR(a.meanErrorPixels, 0.5, 1e-9);
    EXPECT_NEAR(a.p99ErrorPixels, 0.5, 1e-9);
    EXPECT_EQ(a.coverageMismatches, 0u);
}

TEST(Accuracy, RefusesAReferenceOfAnotherSize) {
    const Scene s;
    const CameraFrame other = resolveCamera(s.view, 40, 64, 2.0);
    EXPECT_THROW(
        measureAccuracy(other, s.reference, [](int, int, const Ray&) { return PixelHit{}; }),
        Error);
}

}  // namespace
