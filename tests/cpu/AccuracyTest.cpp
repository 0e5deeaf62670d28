// The measuring stick itself (trace/Accuracy.h): what a comparison counts, in which unit,
// over which pixels, checked with made-up tracers whose errors are known exactly.
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "render/Camera.h"
#include "synth/SyntheticMaps.h"
#include "trace/Accuracy.h"

using namespace microrelief;

namespace {

// A low view of a raised map, with its near side walls in the picture.
struct Scene {
    HeightMap map = synth::cobbles(64, 64, 3);
    double heightScale = 0.1;
    CameraFrame camera =
        resolveCamera(test::orbitCamera(12.0, 30.0, 1.4, {0.0, 0.03, 0.0}), 48, 48, 2.0);
    ReferencePicture reference = traceReferencePicture(camera, map, heightScale);

    const std::optional<glm::dvec3>& exact(int column, int row) const {
        return reference.hits[std::size_t(row) * camera.width + column];
    }
    bool onTop(int column, int row) const {
        return reference.onTop[std::size_t(row) * camera.width + column];
    }
};

TEST(Accuracy, TopSurfaceScopeTakesInOnlyPixelsWhoseExactHitIsOnTop) {
    const Scene s;
    std::size_t top = 0, wallOrBottom = 0;
    for (int row = 0; row < s.camera.height; ++row) {
        for (int column = 0; column < s.camera.width; ++column) {
            top += s.onTop(column, row);
            wallOrBottom += s.exact(column, row) && !s.onTop(column, row);
        }
    }
    ASSERT_GT(top, 200u);
    ASSERT_GT(wallOrBottom, 20u) << "the view must show side walls";

    // A tracer that knows the top surface only: exact there, and on a wall pixel it
    // answers one texel off (as a step method that stops at its first sample would).
    const auto topOnly = [&](int column, int row, const Ray&) {
        const std::optional<glm::dvec3>& exact = s.exact(column, row);
        if (!exact) return PixelHit{};
        const glm::dvec3 offset =
            s.onTop(column, row) ? glm::dvec3(0.0) : glm::dvec3(0, 1.0 / 64, 0);
        return PixelHit{true, *exact + offset, false};
    };
    const Accuracy all = measureAccuracy(s.camera, s.reference, topOnly);
    const Accuracy onTop =
        measureAccuracy(s.camera, s.reference, topOnly, AccuracyScope::TopSurface);
    EXPECT_EQ(all.pixels, std::size_t(s.camera.width) * s.camera.height);
    EXPECT_EQ(all.offHalfTexel, wallOrBottom);
    EXPECT_EQ(onTop.pixels, top);
    EXPECT_EQ(onTop.referenceHits, top);
    EXPECT_EQ(onTop.offHalfTexel, 0u);
    EXPECT_EQ(onTop.coverageMismatches, 0u);
}

TEST(Accuracy, PixelErrorIsTheDistanceOverAPixelsWidthThere) {
    const Scene s;
    // Every hit moved along its ray by exactly half a pixel's width at the exact hit.
    const double pixelAngle = 2.0 * glm::length(s.camera.up) / s.camera.height;
    const auto halfPixelOff = [&](int column, int row, const Ray& ray) {
        const std::optional<glm::dvec3>& exact = s.exact(column, row);
        if (!exact) return PixelHit{};
        const double width = glm::length(*exact - s.camera.eye) * pixelAngle;
        return PixelHit{true, *exact + 0.5 * width * glm::normalize(ray.direction), false};
    };
    const Accuracy a = measureAccuracy(s.camera, s.reference, halfPixelOff);
    EXPECT_NEAR(a.meanErrorPixels, 0.5, 1e-9);
    EXPECT_NEAR(a.p99ErrorPixels, 0.5, 1e-9);
    EXPECT_EQ(a.coverageMismatches, 0u);
}

}  // namespace
