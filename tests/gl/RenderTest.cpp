// Rendering, checked by numbers: the world positions of the AOV against the exact CPU
// reference (core/trace/ReferenceTracer), pixel by pixel. Runs on the backend named by
// --backend=egl|osmesa (one CTest entry each); an absent backend fails the run unless
// MICRORELIEF_ALLOW_MISSING_GL names it, and then every test skips and says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <tuple>

#include "GlTestBackend.h"
#include "SweepCases.h"
#include "TestSupport.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/MultilevelTracer.h"
#include "microrelief/core/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

// Thresholds for every view (issue 3, SweepCases.h): hit/miss may flip only for rays
// that graze a ridge or a silhouette edge; positions may be off by more than half a texel
// only for the same grazing rays, whose hit jumps to a farther surface. Nothing may run
// out of the iteration budget.
using test::kMaxCoverageMismatchPercent;
using test::kMaxOffHalfTexelPercent;

class Render : public ::testing::Test {
protected:
    static GlContext* context() { return &test::glContext(); }

    void SetUp() override {
        if (!isBackendPresent(test::glBackend()))
            GTEST_SKIP() << test::missingBackendMessage(test::glBackend());
    }

    struct Result {
        RenderedFrame frame;
        CameraFrame camera;
        test::Accuracy accuracy;
    };

    // Renders `map` and compares it with the reference; asserts the standard thresholds.
    Result renderAndCompare(const HeightMap& map, const Camera& camera, float heightScale,
                            int size = 64) {
        RenderJob job;
        job.camera = camera;
        job.width = size;
        job.height = size;
        job.heightScale = heightScale;
        Result r;
        HeadlessResult rendered = renderHeadless(*context(), map, "test map", job);
        r.frame = std::move(rendered.frame);
        r.camera = rendered.camera;
        r.accuracy = test::compareWithReference(r.frame, r.camera, map, heightScale);
        r.frame = test::withWorldPositions(std::move(r.frame));  // read below as world positions
        std::printf("    %s\n", r.accuracy.summary().c_str());
        EXPECT_LE(r.accuracy.coverageMismatchPercent(), kMaxCoverageMismatchPercent)
            << r.accuracy.summary();
        EXPECT_LE(r.accuracy.offHalfTexelPercent(), kMaxOffHalfTexelPercent)
            << r.accuracy.summary();
        EXPECT_EQ(r.accuracy.exhausted, 0u) << r.accuracy.summary();
        return r;
    }

    static std::size_t hitCount(const RenderedFrame& frame) {
        std::size_t n = 0;
        for (std::size_t p = 3; p < frame.position.size(); p += 4) n += frame.position[p] > 0.5f;
        return n;
    }
};

TEST_F(Render, FlatMapIsHitAtExactlyTheScaledHeight) {
    const HeightMap map = synth::flat(16, 16, 0.6f);
    for (double elevation : {90.0, 45.0, 10.0}) {
        const Result r = renderAndCompare(map, test::orbitCamera(elevation, 30.0, 1.6), 0.1f);
        std::size_t top = 0;
        for (int row = 0; row < r.frame.height; ++row) {
            for (int column = 0; column < r.frame.width; ++column) {
                const float* p = r.frame.positionAt(column, row);
                if (p[3] < 0.5f || std::abs(p[0]) > 0.499f || std::abs(p[2]) > 0.499f) continue;
                ++top;  // well inside the footprint: must be the top face
                ASSERT_NEAR(p[1], 0.06f, 1e-5f)
                    << "elevation " << elevation << " pixel " << column << "," << row;
            }
        }
        EXPECT_GT(top, 200u) << "elevation " << elevation;
    }
}

TEST_F(Render, MissesShowTheBackgroundAndAZeroAov) {
    const HeightMap map = synth::flat(8, 8, 0.5f);
    const Result r = renderAndCompare(map, test::orbitCamera(60.0, 0.0, 3.0), 0.1f);
    const float* corner = r.frame.positionAt(0, 0);
    EXPECT_EQ(corner[0], 0.0f);
    EXPECT_EQ(corner[3], 0.0f);
    const std::uint8_t* c = &r.frame.color[0];
    const std::uint8_t* centre = &r.frame.color[(32 * 64 + 32) * 4];
    EXPECT_NE(std::make_tuple(c[0], c[1], c[2]), std::make_tuple(centre[0], centre[1], centre[2]));
    EXPECT_GT(hitCount(r.frame), 300u);
    EXPECT_LT(hitCount(r.frame), 64u * 64u);
}

TEST_F(Render, OneTexelSpikeIsHitFromAGrazingAngle) {
    // A spike one texel wide in a 32 x 32 map, seen 4 degrees above the surface: a
    // linear search with fewer than ~32 steps along the ray would step over it.
    const HeightMap map = synth::spike(32, 32, 16, 16);
    const glm::dvec3 spikeTop(0.5 / 32, 0.05, 0.5 / 32);
    const Result r =
        renderAndCompare(map, test::orbitCamera(4.0, 20.0, 0.9, spikeTop, 12.0), 0.1f, 96);
    std::size_t spikePixels = 0;
    for (std::size_t p = 0; p < r.frame.position.size(); p += 4) {
        if (r.frame.position[p + 3] > 0.5f && r.frame.position[p + 1] > 0.02f) ++spikePixels;
    }
    EXPECT_GT(spikePixels, 20u) << "the spike must show: " << r.accuracy.summary();
}

TEST_F(Render, OneTexelWallIsNotSteppedThrough) {
    const HeightMap map = synth::wallColumn(64, 64, 40);
    const Result r =
        renderAndCompare(map, test::orbitCamera(2.0, 180.0, 1.2, {0, 0.02, 0}, 30.0), 0.05f, 96);
    std::size_t wallPixels = 0;
    for (std::size_t p = 0; p < r.frame.position.size(); p += 4) {
        wallPixels += r.frame.position[p + 3] > 0.5f && r.frame.position[p + 1] > 0.01f;
    }
    EXPECT_GT(wallPixels, 100u) << r.accuracy.summary();
}

TEST_F(Render, StepEdgeShowsTheCliff) {
    // Seen from the low side: the bilinear ramp between the last low and the first high
    // sample is a cliff one texel wide.
    const HeightMap map = synth::step(32, 32, 16);
    const Result r = renderAndCompare(map, test::orbitCamera(15.0, 180.0, 1.4), 0.1f, 96);
    std::size_t cliff = 0;
    for (std::size_t p = 0; p < r.frame.position.size(); p += 4) {
        const float* hit = &r.frame.position[p];
        cliff += hit[3] > 0.5f && hit[1] > 0.005f && hit[1] < 0.095f && std::abs(hit[2]) < 0.45f;
    }
    EXPECT_GT(cliff, 50u) << r.accuracy.summary();
}

TEST_F(Render, EyeInsideTheBoxAboveTheSurface) {
    const HeightMap map = synth::valueNoise(64, 64, 16.0, 3, 7);
    const float scale = 0.3f;
    // An eye over the lowest sample, halfway between it and the top of the box.
    std::size_t lowest =
        std::min_element(map.samples.begin(), map.samples.end()) - map.samples.begin();
    const int i = static_cast<int>(lowest % 64), j = static_cast<int>(lowest / 64);
    const glm::dvec3 ground((i + 0.5) / 64 - 0.5, scale * map.at(i, j), (j + 0.5) / 64 - 0.5);
    const double top = scale * map.maxValue();
    Camera camera;
    camera.eye = ground + glm::dvec3(0, 0.5 * (top - ground.y), 0);
    ASSERT_LT(camera.eye.y, top);                                    // inside the box ...
    ASSERT_GT(camera.eye.y, scale * map.surface(i + 0.5, j + 0.5));  // ... above the surface
    camera.target = glm::dvec3(-camera.eye.x * 0.5, ground.y, -camera.eye.z * 0.5);
    camera.fovyDegrees = 90.0;
    const Result r = renderAndCompare(map, camera, scale, 96);
    EXPECT_GT(hitCount(r.frame), 96u * 96u / 2) << r.accuracy.summary();
}

TEST_F(Render, BottomFaceFromBelow) {
    const HeightMap map = synth::valueNoise(32, 32, 8.0, 2, 3);
    Camera camera;
    camera.eye = {0.3, -0.8, 0.2};
    const Result r = renderAndCompare(map, camera, 0.1f);
    std::size_t bottom = 0;
    for (std::size_t p = 0; p < r.frame.position.size(); p += 4) {
        if (r.frame.position[p + 3] < 0.5f) continue;
        ++bottom;
        // Float rounding of eye + t dir in the shader: a few ulps of the eye height.
        EXPECT_NEAR(r.frame.position[p + 1], 0.0f, 1e-6f)
            << "a hit from below is on the bottom face y = 0";
    }
    EXPECT_GT(bottom, 500u);
}

TEST_F(Render, SideWallsFromALowAngle) {
    const HeightMap map = synth::valueNoise(40, 40, 10.0, 3, 9);
    const Result r =
        renderAndCompare(map, test::orbitCamera(3.0, 45.0, 1.5, {0, 0.05, 0}, 35.0), 0.2f, 96);
    std::size_t wall = 0;
    for (std::size_t p = 0; p < r.frame.position.size(); p += 4) {
        const float* hit = &r.frame.position[p];
        wall += hit[3] > 0.5f && (std::abs(std::abs(hit[0]) - 0.5f) < 1e-5f ||
                                  std::abs(std::abs(hit[2]) - 0.5f) < 1e-5f);
    }
    EXPECT_GT(wall, 200u) << r.accuracy.summary();
}

TEST_F(Render, NonSquareNonPowerOfTwoMap) {
    const HeightMap map = synth::valueNoise(300, 77, 20.0, 4, 21);
    const Result r = renderAndCompare(map, test::orbitCamera(35.0, 60.0, 1.3), 0.08f, 96);
    // The footprint is 1 x 77/300 world units: nothing may be hit beyond z = +-b/2.
    for (std::size_t p = 0; p < r.frame.position.size(); p += 4) {
        if (r.frame.position[p + 3] > 0.5f) {
            ASSERT_LE(std::abs(r.frame.position[p + 2]), 0.5f * 77 / 300 + 1e-5f);
        }
    }
}

TEST_F(Render, OneByOneMapIsAFlatBox) {
    const HeightMap map = synth::flat(1, 1, 0.5f);
    const Result r = renderAndCompare(map, test::orbitCamera(30.0, 10.0, 2.0), 0.2f);
    EXPECT_GT(hitCount(r.frame), 300u);
}

TEST_F(Render, AllZeroMapIsASheetSeenFromBothSides) {
    const HeightMap map = synth::flat(8, 8, 0.0f);
    const Result above = renderAndCompare(map, test::orbitCamera(40.0, 0.0, 2.0), 0.1f);
    const Result below = renderAndCompare(map, test::orbitCamera(-40.0, 0.0, 2.0), 0.1f);
    EXPECT_GT(hitCount(above.frame), 300u);
    EXPECT_GT(hitCount(below.frame), 300u);
}

TEST_F(Render, PictureIsShadedNotFlat) {
    // The picture itself, by numbers: hit pixels differ from the background and from each
    // other (lit and unlit slopes), so a black or constant image fails.
    const HeightMap map = synth::cobbles(64, 64, 1);
    const Result r = renderAndCompare(map, test::orbitCamera(40.0, 45.0, 1.5), 0.1f);
    int lo = 255, hi = 0;
    for (std::size_t p = 0; p < r.frame.position.size(); p += 4) {
        if (r.frame.position[p + 3] < 0.5f) continue;
        const int luma = r.frame.color[p] + r.frame.color[p + 1] + r.frame.color[p + 2];
        lo = std::min(lo, luma / 3);
        hi = std::max(hi, luma / 3);
    }
    EXPECT_GT(hi - lo, 80) << "shading range " << lo << ".." << hi;
    EXPECT_GT(hi, 150);
}

// The shader and its CPU twin (core/trace/MultilevelTracer) walk the same segments: per pixel
// the same number of segments and of texel fetches (the instrumented variant), on a
// relief whose joints make rays skim the surface, from 45 degrees and from a grazing 10.
// Float and double may round a comparison differently on a few grazing rays.
// A picture drawn in tiles (the path of pictures larger than the GL's limits) is the
// picture drawn whole, bit for bit: colour, positions and statistics. Tiles of 32 on a
// 150 x 97 picture leave partial tiles at the right and the top.
TEST_F(Render, TiledPictureIsTheWholePictureBitForBit) {
    const HeightMap map = synth::cobbles(96, 80, 5);
    RenderJob job;
    job.camera = test::orbitCamera(35.0, 20.0, 1.4, {0.0, 0.03, 0.0});
    job.width = 150;
    job.height = 97;
    const HeadlessResult whole = renderHeadless(*context(), map, "cobbles", job);
    HeadlessRenderer renderer(*context(), job.method);
    renderer.setHeights(job, map, "cobbles");
    for (int side : {32, 97, 7}) {
        renderer.setMaxTileSide(side);
        const HeadlessResult tiled = renderer.render(job);
        EXPECT_EQ(tiled.frame.color, whole.frame.color) << side;
        EXPECT_EQ(tiled.frame.position, whole.frame.position) << side;
        EXPECT_EQ(tiled.frame.stats, whole.frame.stats) << side;
    }
    EXPECT_GT(hitCount(whole.frame), 150u * 97 / 4) << "the relief fills the picture";
}

TEST_F(Render, ShaderWalksTheSameSegmentsAsTheTwin) {
    const HeightMap map = synth::cobbles(256, 256, 3);
    const float heightScale = 0.1f;
    GlContext& context = test::glContext();
    context.makeCurrent();
    // The twin counts a bilinear patch's four samples as one fetch and a biquadratic one's
    // nine as four, as the GLSL 4.00 variant's textureGather does; under 3.30 they are
    // texelFetch each.
    GLint major = 0;
    context.gl().GetIntegerv(GL_MAJOR_VERSION, &major);
    const bool countsGathers = major >= 4;
    const int size = 64;
    OffscreenTarget target(context.gl(), size, size);
    for (const auto& [interpolation, elevation] :
         {std::pair{Interpolation::Bilinear, 45.0}, std::pair{Interpolation::Bilinear, 10.0},
          std::pair{Interpolation::Biquadratic, 45.0},
          std::pair{Interpolation::Biquadratic, 10.0}}) {
        ReliefRenderer renderer(context.gl(), shaderDirectory());
        renderer.apply(test::relief({}, interpolation, heightScale), &map, "cobbles");
        renderer.setMethod(MethodSettings{}, /*countFetches=*/true);
        const MultilevelTracer twin(map, heightScale, BaseShape::plane(), interpolation);
        const CameraFrame camera = resolveCamera(
            test::orbitCamera(elevation, 40.0, 1.3, {0.0, 0.04, 0.0}), size, size, 2.0);
        target.clear(glm::vec3(0.0f));
        renderer.draw(camera, ShadingOptions{});
        const RenderedFrame frame = target.read(camera.eye);
        std::size_t traced = 0, sameIterations = 0, sameFetches = 0;
        long gpuIterations = 0, gpuFetches = 0, cpuFetches = 0;
        for (int row = 0; row < size; ++row) {
            for (int column = 0; column < size; ++column) {
                const float* gpu = &frame.stats[4 * (std::size_t(row) * size + column)];
                // No statistics: a miss (its fragment is discarded, so hit/miss agreement
                // is for the accuracy tests), or a ray that stops where it enters through
                // a side wall or the bottom face (no walk).
                if (gpu[0] == 0.0f) continue;
                TraversalStats cpu;
                twin.intersect(camera.pixelRay(column, row), &cpu);
                ++traced;
                gpuIterations += static_cast<long>(gpu[0]);
                sameIterations += cpu.iterations == static_cast<int>(gpu[0]);
                gpuFetches += static_cast<long>(gpu[1]);
                cpuFetches += cpu.fetches;
                sameFetches += cpu.fetches == static_cast<int>(gpu[1]);
            }
        }
        std::printf(
            "    %-11s %2.0f deg: %zu rays, %.2f segments and %.2f fetches each (twin: %.2f), "
            "same segments %zu, same fetches %zu\n",
            interpolationName(interpolation), elevation, traced, double(gpuIterations) / traced,
            double(gpuFetches) / traced, double(cpuFetches) / traced, sameIterations, sameFetches);
        ASSERT_GT(traced, std::size_t(size * size / 8));
        EXPECT_GE(sameIterations, traced * 99 / 100)
            << interpolationName(interpolation) << " " << elevation << " degrees";
        if (countsGathers) {
            EXPECT_GE(sameFetches, traced * 99 / 100)
                << interpolationName(interpolation) << " " << elevation << " degrees";
        }
    }
}

// setGlsl330 compiles the 3.30 path in a newer context: the same walk (segments, hits) with
// a cell's samples read one by one, so more fetches than the 4.00 path's gathers.
TEST_F(Render, Glsl330ReadsEachSampleAloneAndWalksTheSameSegments) {
    GlContext& context = test::glContext();
    context.makeCurrent();
    GLint major = 0;
    context.gl().GetIntegerv(GL_MAJOR_VERSION, &major);
    if (major < 4) GTEST_SKIP() << "a GL " << major << " context runs GLSL 3.30 anyway";
    const HeightMap map = synth::cobbles(128, 128, 3);
    const int size = 64;
    OffscreenTarget target(context.gl(), size, size);
    const CameraFrame camera =
        resolveCamera(test::orbitCamera(45.0, 40.0, 1.3, {0.0, 0.04, 0.0}), size, size, 2.0);
    for (Interpolation interpolation : {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        ReliefRenderer renderer(context.gl(), shaderDirectory());
        renderer.apply(test::relief({}, interpolation), &map, "cobbles");
        renderer.setMethod(MethodSettings{}, /*countFetches=*/true);
        RenderedFrame frames[2];
        for (bool glsl330 : {false, true}) {
            renderer.setGlsl330(glsl330);
            EXPECT_EQ(renderer.glsl330(), glsl330);
            target.clear(glm::vec3(0.0f));
            renderer.draw(camera, ShadingOptions{});
            frames[glsl330] = target.read(camera.eye);
        }
        long fetches[2] = {0, 0};
        std::size_t hits = 0;
        for (std::size_t pixel = 0; pixel < std::size_t(size) * size; ++pixel) {
            const float* gather = &frames[0].stats[4 * pixel];
            const float* single = &frames[1].stats[4 * pixel];
            ASSERT_EQ(gather[0], single[0]) << "segments, pixel " << pixel;
            fetches[0] += static_cast<long>(gather[1]);
            fetches[1] += static_cast<long>(single[1]);
            hits += frames[0].position[4 * pixel + 3] > 0.5f;
            ASSERT_EQ(frames[0].position[4 * pixel + 3], frames[1].position[4 * pixel + 3])
                << "hit or miss, pixel " << pixel;
        }
        EXPECT_GT(hits, std::size_t(size * size / 8));
        // A bilinear cell: one gather against four reads; a biquadratic square: four
        // against nine. The traversal's pyramid reads are the same in both.
        EXPECT_GT(fetches[1], fetches[0] + long(hits)) << interpolationName(interpolation);
    }
}

// The same on the curved bases: the twin's seam (base/) and the shader's (base_surface.glsl)
// make the same footprints up to their margins (the shader's float ones are wider: a
// footprint near a texel boundary may reach over it in one and not the other).
TEST_F(Render, ShaderWalksTheSameSegmentsAsTheTwinOnCurvedBases) {
    const HeightMap map = synth::cobbles(128, 64, 3);
    const float heightScale = 0.12f;
    GlContext& context = test::glContext();
    context.makeCurrent();
    GLint major = 0;
    context.gl().GetIntegerv(GL_MAJOR_VERSION, &major);
    const int size = 64;
    OffscreenTarget target(context.gl(), size, size);
    for (const auto& [base, interpolation] :
         {std::pair{BaseShape::cylinder(0.3, 0.8), Interpolation::Bilinear},
          std::pair{BaseShape::sphere(0.4), Interpolation::Bilinear},
          std::pair{BaseShape::cylinder(0.3, 0.8), Interpolation::Biquadratic},
          std::pair{BaseShape::sphere(0.4), Interpolation::Biquadratic}}) {
        ReliefRenderer renderer(context.gl(), shaderDirectory());
        renderer.apply(test::relief(base, interpolation, heightScale), &map, "cobbles");
        renderer.setMethod(MethodSettings{}, /*countFetches=*/true);
        const MultilevelTracer twin(map, heightScale, base, interpolation);
        const std::string name = baseName(base) + " " + interpolationName(interpolation);
        for (double elevation : {35.0, 5.0}) {
            const CameraFrame camera =
                resolveCamera(test::orbitCamera(elevation, -70.0, 1.4), size, size, 2.0);
            target.clear(glm::vec3(0.0f));
            renderer.draw(camera, ShadingOptions{});
            const RenderedFrame frame = target.read(camera.eye);
            std::size_t traced = 0, sameIterations = 0, sameFetches = 0;
            for (int row = 0; row < size; ++row) {
                for (int column = 0; column < size; ++column) {
                    const float* gpu = &frame.stats[4 * (std::size_t(row) * size + column)];
                    if (gpu[0] == 0.0f) continue;
                    TraversalStats cpu;
                    twin.intersect(camera.pixelRay(column, row), &cpu);
                    ++traced;
                    sameIterations += cpu.iterations == static_cast<int>(gpu[0]);
                    sameFetches += cpu.fetches == static_cast<int>(gpu[1]);
                }
            }
            std::printf("    %-20s %2.0f deg: %zu rays, same segments %zu, same fetches %zu\n",
                        name.c_str(), elevation, traced, sameIterations, sameFetches);
            ASSERT_GT(traced, std::size_t(size * size / 8));
            EXPECT_GE(sameIterations, traced * 99 / 100) << name << " " << elevation;
            if (major >= 4) {
                EXPECT_GE(sameFetches, traced * 99 / 100) << name << " " << elevation;
            }
        }
    }
}

// Smoothness (issue 12): on a close-up of a smooth relief, where a texel spans some 40
// pixels, the normal of the biquadratic hit changes little from a pixel to its neighbour
// (the surface is C1 across texel edges: the change is its curvature over one pixel),
// while the bilinear one jumps at every texel edge (each cell is its own facet). Normals
// come from the Normal debug view, n / 2 + 1/2 in 8 bits: a step of 1/255 per component
// (at most 0.011 rad between two pixels' normals). The stated bound, 0.035 rad (2 degrees):
// that quantisation plus the curvature of this relief over a pixel (its second derivative
// times the pixel's footprint, under 0.02 rad here).
TEST_F(Render, BiquadraticNormalsAreSmoothAcrossTexelEdges) {
    constexpr double kBoundRadians = 0.035;
    const HeightMap map = synth::valueNoise(16, 16, 4.0, 2, 21);
    RenderJob job;
    job.width = job.height = 256;
    job.heightScale = 0.15f;
    job.camera.eye = {0.02, 0.35, 0.28};
    job.camera.target = {0.0, 0.05, 0.02};
    job.camera.fovyDegrees = 40.0;
    job.shading.view = DebugView::Normal;
    const double texel = 1.0 / 16.0;
    for (const Interpolation interpolation :
         {Interpolation::Biquadratic, Interpolation::Bilinear}) {
        job.interpolation = interpolation;
        const HeadlessResult r = renderHeadless(*context(), map, "smooth noise", job);
        const auto normalAt = [&](int column, int row) {
            const std::uint8_t* c = &r.frame.color[4 * (std::size_t(row) * job.width + column)];
            return glm::normalize(glm::dvec3(c[0], c[1], c[2]) / 255.0 * 2.0 - 1.0);
        };
        double worst = 0.0;
        std::size_t pairs = 0, jumps = 0;
        for (int row = 8; row < job.height; row += 8) {
            for (int column = 0; column + 1 < job.width; ++column) {
                const float* a = r.frame.positionAt(column, row);
                const float* b = r.frame.positionAt(column + 1, row);
                if (a[3] < 0.5f || b[3] < 0.5f) continue;
                // Neighbours on one stretch of surface (not across an occluding edge).
                if (glm::distance(glm::dvec3(a[0], a[1], a[2]), glm::dvec3(b[0], b[1], b[2])) >
                    0.1 * texel)
                    continue;
                const double angle = std::acos(std::clamp(
                    glm::dot(normalAt(column, row), normalAt(column + 1, row)), -1.0, 1.0));
                worst = std::max(worst, angle);
                jumps += angle > kBoundRadians;
                ++pairs;
            }
        }
        std::printf(
            "    %-11s %zu neighbouring pairs, largest normal change %.4f rad, %zu above %.3f\n",
            interpolationName(interpolation), pairs, worst, jumps, kBoundRadians);
        ASSERT_GT(pairs, std::size_t(5000));
        if (interpolation == Interpolation::Biquadratic) {
            EXPECT_LT(worst, kBoundRadians);
        } else {
            // Facets: rows cross some 5 texel edges each, 31 rows.
            EXPECT_GT(jumps, std::size_t(60)) << "the bilinear normal should jump at texel edges";
        }
    }
}

// The accuracy-controlled level of detail (--pixel-error e) takes the max box of a window
// that projects to at most e pixels for the surface. Its bound: the box holds the solid,
// so a hit is never farther along the ray than the exact one and every exact hit stays a
// hit; and the hit lies inside the window at a height the surface reaches there, so
// within e pixels per axis (at the hit's distance) of a surface point as high. A map with
// 16 texels to a pixel, where the tolerance changes most hits.
TEST_F(Render, PixelErrorBoundsHowFarAHitStrays) {
    const HeightMap map = synth::cobbles(1024, 1024, 3);
    const double heightScale = 0.1, texelsPerUnit = 1024.0;
    const float top = map.maxValue();
    const int size = 64;
    for (float pixelError : {1.0f, 4.0f}) {
        for (double elevation : {45.0, 15.0}) {
            RenderJob job;
            job.camera = test::orbitCamera(elevation, 40.0, 1.3, {0.0, 0.04, 0.0});
            job.width = job.height = size;
            job.heightScale = static_cast<float>(heightScale);
            job.method.pixelError = pixelError;
            const HeadlessResult r = renderHeadless(*context(), map, "cobbles", job);
            const ReferencePicture reference = traceReferencePicture(r.camera, map, heightScale);
            // One pixel's footprint in texels per unit of distance from the eye, as the
            // shader's level-of-detail cone has it (relief.frag).
            const double texelsPerPixelPerUnit = r.camera.pixelWidthPerUnit() * texelsPerUnit;
            std::size_t exactHits = 0, lost = 0, hits = 0, behind = 0, stray = 0, moved = 0;
            double worstStray = 0.0;
            for (int row = 0; row < size; ++row) {
                for (int column = 0; column < size; ++column) {
                    const auto& exact = reference.hits[std::size_t(row) * size + column];
                    const float* p = r.frame.positionAt(column, row);
                    exactHits += exact.has_value();
                    if (p[3] < 0.5f) {
                        lost += exact.has_value();
                        continue;
                    }
                    ++hits;
                    const glm::dvec3 hit = r.frame.worldPositionAt(column, row);
                    const double distance = glm::length(hit - r.camera.eye);
                    if (exact) {
                        const double exactDistance = glm::length(*exact - r.camera.eye);
                        behind += distance > exactDistance + 0.5 / texelsPerUnit;
                        moved += glm::length(hit - *exact) * texelsPerUnit > 0.5;
                    }
                    // A surface point as high within a window's width per axis: the samples
                    // around (one more texel each way covers the patches the square touches).
                    // Hits on the side walls (entered below the surface) are exact.
                    const double x = hit.x * texelsPerUnit + 512.0 - 0.5,
                                 y = hit.z * texelsPerUnit + 512.0 - 0.5;
                    if (std::min({x + 0.5, 1023.5 - x, y + 0.5, 1023.5 - y}) < 1e-3) continue;
                    const double reach = pixelError * texelsPerPixelPerUnit * distance + 1.0;
                    float highest = 0.0f, lowest = top;
                    for (int j = int(std::floor(y - reach)); j <= int(std::ceil(y + reach)); ++j) {
                        for (int i = int(std::floor(x - reach)); i <= int(std::ceil(x + reach));
                             ++i) {
                            highest = std::max(highest, map.clamped(i, j));
                            lowest = std::min(lowest, map.clamped(i, j));
                        }
                    }
                    // The slack: float rounding (1e-4 of the top), and the windows' storage in
                    // half floats, each bound rounded up by at most 2^-10 of itself (issue
                    // 16): a box's top, where such a hit lies, is that much above its max.
                    const double h = hit.y / heightScale,
                                 slack = (1e-4 + std::ldexp(1.0, -10)) * top;
                    const double above = h - highest - slack, below = lowest - h - slack;
                    if (above > 0.0 || below > 0.0) {
                        ++stray;
                        worstStray = std::max({worstStray, above, below});
                    }
                }
            }
            std::printf(
                "    %.0f px, %2.0f deg: %zu exact hits, %zu lost, %zu of %zu hits behind the "
                "exact one, %zu with no surface point as high within reach (worst %.4f), %zu "
                "moved by more than half a texel\n",
                pixelError, elevation, exactHits, lost, behind, hits, stray, worstStray, moved);
            ASSERT_GT(exactHits, std::size_t(size * size / 4));
            EXPECT_LE(lost, exactHits / 1000) << pixelError << " px, " << elevation << " deg";
            EXPECT_LE(behind, hits / 500) << pixelError << " px, " << elevation << " deg";
            EXPECT_EQ(stray, 0u) << pixelError << " px, " << elevation << " deg";
            // Not the exact picture: the tolerance was used.
            EXPECT_GT(moved, exactHits / 4) << pixelError << " px, " << elevation << " deg";
        }
    }
}

}  // namespace

namespace {

// The peers, each as published: maxmip is exact like the multilevel method; the
// step-based methods converge on the top surface as their budget grows and show their
// artifacts with few steps; normal mapping has no parallax at all.
class Peers : public ::testing::Test {
protected:
    void SetUp() override {
        if (!isBackendPresent(test::glBackend()))
            GTEST_SKIP() << test::missingBackendMessage(test::glBackend());
    }

    test::Accuracy measure(Method method, int steps,
                           Interpolation interpolation = Interpolation::Bilinear,
                           AccuracyScope scope = AccuracyScope::AllPixels) {
        const HeightMap map = synth::cobbles(64, 64, 3);
        RenderJob job;
        job.camera = test::orbitCamera(25.0, 40.0, 1.3, {0.0, 0.04, 0.0});
        job.width = job.height = 64;
        job.method.method = method;
        if (steps > 0) {  // 0: a method that takes no steps; the scene keeps its defaults
            job.method.steps = steps;
            job.method.minSteps = std::max(4, steps / 4);
        }
        job.interpolation = interpolation;
        const HeadlessResult r = renderHeadless(test::glContext(), map, "cobbles", job);
        const test::Accuracy a = test::compareWithReference(
            r.frame, r.camera, ReliefGeometry{&map, job.heightScale, {}, interpolation}, scope);
        std::printf("    %-10s %-11s %5d%s: %s\n", methodName(method),
                    interpolationName(interpolation), steps,
                    scope == AccuracyScope::TopSurface ? " (top)" : "", a.summary().c_str());
        return a;
    }

    // maxmip on `base`, 64 x 64 through `camera`, held to the exact methods' thresholds
    // against the reference, with at least `minHits` hit pixels.
    void expectMaxMipExact(const HeightMap& map, const BaseShape& base, Interpolation interpolation,
                           const Camera& camera, const std::string& name, std::size_t minHits) {
        RenderJob job;
        job.camera = camera;
        job.width = job.height = 64;
        job.base = base;
        job.interpolation = interpolation;
        job.method.method = Method::MaxMip;
        const HeadlessResult r = renderHeadless(test::glContext(), map, "cobbles", job);
        const test::Accuracy a = test::compareWithReference(
            r.frame, r.camera, ReliefGeometry{&map, job.heightScale, base, interpolation});
        std::printf("    maxmip on %-40s: %s\n", name.c_str(), a.summary().c_str());
        EXPECT_GT(a.referenceHits, minHits) << name;
        EXPECT_LE(a.coverageMismatchPercent(), 0.1) << name;
        EXPECT_LE(a.offHalfTexelPercent(), 0.2) << name;
        EXPECT_EQ(a.exhausted, 0u) << name;
    }
};

TEST_F(Peers, MaxMipIsExact) {
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        const test::Accuracy a = measure(Method::MaxMip, 0, interpolation);
        EXPECT_LE(a.coverageMismatchPercent(), 0.1) << interpolationName(interpolation);
        EXPECT_LE(a.offHalfTexelPercent(), 0.2) << interpolationName(interpolation);
        EXPECT_EQ(a.exhausted, 0u) << interpolationName(interpolation);
    }
}

// maxmip on the curved bases: the quadtree walk's node sides are half-planes, planes and
// cones met in closed form, the nodes wrap across the seam, Y turns once on an ellipsoid.
TEST_F(Peers, MaxMipIsExactOnCurvedBases) {
    const HeightMap map = synth::cobbles(128, 128, 4);  // square: rows as many as columns
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        for (const BaseShape& base : {BaseShape::cylinder(0.3, 0.8), BaseShape::sphere(0.4),
                                      BaseShape::ellipsoid({0.45, 0.35, 0.3})}) {
            const std::string name = baseName(base) + " " + interpolationName(interpolation);
            // From high above the equator at 45 degrees, at the globe's upper half: segments
            // that begin past the latitude's turn, whose cones Y = const the line's other
            // branch also crosses, behind the start (a walk that took those crossings left
            // its nodes at once and skipped them).
            Camera high;
            high.eye = {0.71, 0.76, 0.97};
            high.target = {0.26, 0.0, 0.36};
            high.up = {-0.416, 0.707, -0.572};
            for (const Camera& camera :
                 {test::orbitCamera(20.0, 40.0, 1.4), test::orbitCamera(5.0, -90.0, 1.2),
                  test::orbitCamera(80.0, 200.0, 1.3), high}) {
                expectMaxMipExact(map, base, interpolation, camera, name, 1000);
            }
        }
    }
}

// Nodes that span every column go all the way round: at the levels where a map narrower
// than it is tall has one column of nodes, and at the root of any map. A walk that took
// the seam for their side in X found the same crossing, behind the ray, as its exit again
// and again, and ran out of budget: seen across the seam on a tall map (17 % of pixels
// hit/miss wrong) and over the pole from afar (every ray near it stays in the root).
TEST_F(Peers, MaxMipNodesThatSpanEveryColumnHaveNoSideInX) {
    const HeightMap tall = synth::cobbles(32, 128, 8), square = synth::cobbles(128, 128, 4);
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        for (const BaseShape& base : {BaseShape::cylinder(0.3, 0.8), BaseShape::sphere(0.4)}) {
            Camera seam;  // behind the object, where u = 0 faces the eye
            seam.eye = {0.2, 0.1, -1.0};
            seam.target = {0.0, 0.0, -0.3};
            const Camera far = test::orbitCamera(25.0, 50.0, 60.0, {0.0, 0.3, 0.0}, 1.0);
            for (const auto& [map, camera, view] :
                 {std::tuple{&tall, seam, "tall map, the seam"},
                  std::tuple{&square, far, "square map, from afar"}}) {
                expectMaxMipExact(
                    *map, base, interpolation, camera,
                    baseName(base) + " " + interpolationName(interpolation) + ", " + view, 300);
            }
        }
    }
}

// pom and relief on a curved base, as engines ship them there: marching in the tangent
// frame where the ray enters the shell, blind to the curvature beyond. Looking straight
// at the globe they come close with enough steps; towards the limb, where the surface
// curves away from the tangent plane within a few texels, their hits sink below it or
// miss it, whatever the budget.
TEST_F(Peers, TangentFrameMethodsAreBlindToTheCurvature) {
    const HeightMap map = synth::cobbles(128, 64, 6);
    const BaseShape base = BaseShape::sphere(0.4);
    const auto render = [&](Method method, const Camera& camera) {
        RenderJob job;
        job.camera = camera;
        job.width = job.height = 64;
        job.base = base;
        job.method.method = method;
        job.method.setSteps(256);
        const HeadlessResult r = renderHeadless(test::glContext(), map, "cobbles", job);
        const test::Accuracy a = test::compareWithReference(r.frame, r.camera, map, job.heightScale,
                                                            base, AccuracyScope::TopSurface);
        std::printf("    %-10s on the sphere: %s\n", methodName(method), a.summary().c_str());
        return a;
    };
    Camera facing = test::orbitCamera(10.0, 60.0, 1.0), limb;
    facing.fovyDegrees = 20.0;
    limb.eye = {0.1, 0.25, 0.9};
    limb.target = {0.38, 0.05, 0.0};
    limb.fovyDegrees = 30.0;
    for (Method method : {Method::Pom, Method::Relief}) {
        EXPECT_LT(render(method, facing).offHalfTexelPercent(), 3.0) << methodName(method);
        // Measured: 1.1 % of pixels hit/miss, 1.7 % of hits off, with 256 steps;
        // the exact method has none of either on the same view.
        const test::Accuracy atLimb = render(method, limb);
        EXPECT_GT(atLimb.coverageMismatchPercent(), 0.5) << methodName(method);
        EXPECT_GT(atLimb.offHalfTexelPercent(), 1.0) << methodName(method);
    }
    const test::Accuracy exact = render(Method::Multilevel, limb);
    EXPECT_LE(exact.offHalfTexelPercent(), 0.2);
    EXPECT_LE(exact.coverageMismatchPercent(), 0.1);
}

TEST_F(Peers, StepMethodsConvergeWithTheirBudget) {
    for (Method method : {Method::Steep, Method::Pom, Method::Relief}) {
        const test::Accuracy few = measure(method, 8, Interpolation::Bilinear,
                                           AccuracyScope::TopSurface),
                             many = measure(method, 512, Interpolation::Bilinear,
                                            AccuracyScope::TopSurface);
        // Scored where the top surface is all a ray can meet (they know no side walls or
        // bottom face). Few steps: visibly wrong (stair steps, sunken or missed
        // features: 2.7 % to 66 % of hits off here). Many steps: held to the budget of the
        // exact methods on this smooth relief (0 off and 0 flipped here).
        EXPECT_GT(few.offHalfTexelPercent(), 1.0) << methodName(method);
        EXPECT_LE(many.offHalfTexelPercent(), kMaxOffHalfTexelPercent) << methodName(method);
        EXPECT_LE(many.coverageMismatchPercent(), kMaxCoverageMismatchPercent)
            << methodName(method);
    }
}

// Parallax offset with offset limiting (Welsh 2004), as published: each hit sits at the
// height h0 the map has where the ray comes in through the top face, moved from there
// away from the eye by the depth (top - s h0) times the horizontal part of the unit view
// vector: off the ray, never farther than the depth, and blind to occlusion, so far from
// the exact hits.
TEST_F(Peers, ParallaxOffsetShiftsByTheDepthAlongTheView) {
    const HeightMap map = synth::cobbles(64, 64, 3);
    RenderJob job;
    job.camera = test::orbitCamera(25.0, 40.0, 1.3, {0.0, 0.04, 0.0});
    job.width = job.height = 64;
    job.method.method = Method::Offset;
    const HeadlessResult r = renderHeadless(test::glContext(), map, "cobbles", job);
    const double s = job.heightScale, top = s * map.maxValue();
    int checked = 0;
    for (int row = 0; row < r.camera.height; ++row) {
        for (int column = 0; column < r.camera.width; ++column) {
            const float* aov = r.frame.positionAt(column, row);
            const glm::dvec3 p = r.frame.worldPositionAt(column, row);
            const Ray ray = r.camera.pixelRay(column, row);
            if (aov[3] < 0.5f || !(ray.direction.y < 0.0)) continue;
            const glm::dvec3 entry =
                ray.origin + (top - ray.origin.y) / ray.direction.y * ray.direction;
            if (std::abs(entry.x) > 0.5 || std::abs(entry.z) > 0.5) continue;  // via a wall
            const double h0 =
                s * map.surface((entry.x + 0.5) * map.width, (entry.z + 0.5) * map.height);
            const glm::dvec2 view =
                glm::dvec2(ray.direction.x, ray.direction.z) / glm::length(ray.direction);
            const glm::dvec2 shift = glm::dvec2(p[0] - entry.x, p[2] - entry.z);
            // Float in the shader: 1e-5 world units is 0.00064 texels here.
            EXPECT_NEAR(p[1], h0, 1e-5) << column << "," << row;
            EXPECT_NEAR(shift.x, (top - h0) * view.x, 1e-5) << column << "," << row;
            EXPECT_NEAR(shift.y, (top - h0) * view.y, 1e-5) << column << "," << row;
            ++checked;
        }
    }
    EXPECT_GT(checked, 64 * 64 / 4);
    const test::Accuracy a = test::compareWithReference(
        r.frame, r.camera, traceReferencePicture(r.camera, map, job.heightScale),
        AccuracyScope::TopSurface);
    std::printf("    offset: %s\n", a.summary().c_str());
    EXPECT_GT(a.offHalfTexelPercent(), 20.0) << "no occlusion: far from the exact hits";
}

TEST_F(Peers, NormalMappingHasNoParallax) {
    // Every hit lies on the top plane of the box: most are far from the true surface.
    EXPECT_GT(measure(Method::Normal, 0).offHalfTexelPercent(), 20.0);
}

}  // namespace

namespace {

// A compile error names the library file and line it is in, on this backend's compiler
// (Mesa reports source string 0, so the file travels in the line number: ShaderSource).
TEST(ShaderErrors, NameTheLibraryFileAndLine) {
    if (!isBackendPresent(test::glBackend()))
        GTEST_SKIP() << test::missingBackendMessage(test::glBackend());
    test::ScratchDir dir;
    std::filesystem::copy(shaderDirectory(), dir.path(), std::filesystem::copy_options::recursive);
    const std::filesystem::path broken = dir / "microrelief/shading.glsl";
    std::string text = test::readText(broken);
    const std::size_t at = text.find("float diffuse = max(dot(n, l), 0.0);");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 0, "undeclaredThing();\n    ");
    const int line =
        1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
    std::ofstream(broken) << text;

    test::glContext().makeCurrent();
    try {
        ReliefRenderer renderer(test::glContext().gl(), dir.path());
        FAIL() << "the broken shader compiled";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("shading.glsl:" + std::to_string(line)), std::string::npos)
            << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    }
}

}  // namespace
