// The cone-stepping peers of issue 28 on the GPU (peers/ConeMap.h, shaders/microrelief/
// cone_step.glsl, relaxed_cone_step.glsl): cone, whose cones are conservative and whose
// last texel is solved exactly, is exact like the multilevel method (held to the same
// thresholds against the exact reference); rcsm runs and its error is reported, not held
// (it is wrong by design). Cone's map as the GPU builds it (PyramidBuilder::buildConeMap)
// against the CPU build, texel for texel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "ConeCases.h"
#include "GlTestBackend.h"
#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/gl/PyramidBuilder.h"
#include "microrelief/gl/ReliefTextures.h"
#include "microrelief/io/HeightMapFile.h"

using namespace microrelief;

namespace {

class ConePeers : public ::testing::Test {
protected:
    void SetUp() override {
        if (!isBackendPresent(test::glBackend()))
            GTEST_SKIP() << test::missingBackendMessage(test::glBackend());
    }

    // `renderer` holds `map` (one cone map build per map and method).
    test::Accuracy render(HeadlessRenderer& renderer, const HeightMap& map, const std::string& name,
                          Method method, const Camera& camera, int steps = 15,
                          AccuracyScope scope = AccuracyScope::AllPixels,
                          Interpolation interpolation = Interpolation::Bilinear) {
        RenderJob job;
        job.camera = camera;
        job.width = job.height = 96;
        job.method.method = method;
        job.method.steps = steps;
        job.method.refineSteps = 8;
        job.interpolation = interpolation;
        const HeadlessResult r = renderer.render(job);
        const test::Accuracy a = test::compareWithReference(
            r.frame, r.camera, ReliefGeometry{&map, job.heightScale, {}, interpolation}, scope);
        std::printf("    %-5s %-36s: %s\n", methodName(method), name.c_str(), a.summary().c_str());
        return a;
    }
};

struct ConeView {
    const char* name;
    Camera camera;
};

std::vector<ConeView> coneViews() {
    return {{"from above", test::orbitCamera(70.0, 30.0, 1.3, {0.0, 0.02, 0.0})},
            {"45 degrees", test::orbitCamera(45.0, 40.0, 1.3, {0.0, 0.02, 0.0})},
            {"grazing", test::orbitCamera(12.0, 200.0, 1.2, {0.0, 0.02, 0.0})},
            {"close", test::orbitCamera(30.0, -60.0, 0.45, {0.1, 0.0, -0.1})}};
}

// The bundled map (256 x 256, cobbles) and a rough synthetic one (value noise with a
// texel-scale octave), each from four views: cone is held to the thresholds of the exact
// methods (the maxmip peer's: hit/miss 0.1 %, hits off half a texel 0.2 %, no ray out of
// budget), with enough hits that the views see relief.
TEST_F(ConePeers, ConeIsExact) {
    const HeightMap bundled = loadHeightMap(defaultHeightMapPath());
    const HeightMap rough = synth::valueNoise(128, 128, 3.0, 3, 28);
    for (const auto& [map, name] : {std::pair{&bundled, std::string("bundled")},
                                    std::pair{&rough, std::string("noise 128")}}) {
        HeadlessRenderer renderer(test::glContext());
        renderer.setHeights(RenderJob{}, *map, name);
        for (const ConeView& view : coneViews()) {
            const std::string where = name + ", " + view.name;
            const test::Accuracy a = render(renderer, *map, where, Method::Cone, view.camera);
            EXPECT_GT(a.referenceHits, 1000u) << where;
            EXPECT_LE(a.coverageMismatchPercent(), 0.1) << where;
            EXPECT_LE(a.offHalfTexelPercent(), 0.2) << where;
            EXPECT_EQ(a.exhausted, 0u) << where;
        }
    }
}

// On the biquadratic last level cone steps over the same cone map with each apex raised
// (cone_step.glsl: mr_coneOfLastLevel) and solves the last texel on the B-spline: held to
// the same thresholds against the reference of that surface, on rough noise and on the
// CPU tests' adversarial maps (spikes, walls, steps, white noise, heights from 1e-9 to 1e3).
TEST_F(ConePeers, ConeIsExactOnTheBiquadraticLevel) {
    std::vector<std::pair<HeightMap, std::string>> maps{
        {synth::valueNoise(128, 128, 3.0, 3, 28), "noise 128"}};
    for (const test::ConeCase& c : test::coneCases()) maps.emplace_back(c.map, c.name);
    for (const auto& [map, name] : maps) {
        HeadlessRenderer renderer(test::glContext());
        RenderJob biquadratic;
        biquadratic.interpolation = Interpolation::Biquadratic;
        renderer.setHeights(biquadratic, map, name);
        for (const ConeView& view : coneViews()) {
            const std::string where = name + ", biquadratic, " + view.name;
            const test::Accuracy a = render(renderer, map, where, Method::Cone, view.camera, 15,
                                            AccuracyScope::AllPixels, Interpolation::Biquadratic);
            EXPECT_GT(a.referenceHits, 100u) << where;
            EXPECT_LE(a.coverageMismatchPercent(), 0.1) << where;
            EXPECT_LE(a.offHalfTexelPercent(), 0.2) << where;
            EXPECT_EQ(a.exhausted, 0u) << where;
        }
    }
}

// The cone map follows the samples: after an animated field replaces them on the GPU
// (gl/AnimatedHeights.h), cone is exact against the field's heights, not the map's.
TEST_F(ConePeers, ConeFollowsHeightsThatChange) {
    const HeightMap map = synth::valueNoise(64, 64, 4.0, 2, 3);
    HeadlessRenderer renderer(test::glContext());
    renderer.setHeights(RenderJob{}, map, "noise 64");
    for (const char* field : {"", "ripples"}) {
        RenderJob job;
        job.camera = test::orbitCamera(35.0, 40.0, 1.2, {0.0, 0.02, 0.0});
        job.width = job.height = 96;
        job.method.method = Method::Cone;
        job.animation = field;
        job.time = 0.7;
        const HeadlessResult r = renderer.render(job);
        const HeightMap& traced = r.animatedMap ? *r.animatedMap : map;
        const test::Accuracy a = test::compareWithReference(
            r.frame, r.camera,
            ReliefGeometry{&traced, job.heightScale, {}, Interpolation::Bilinear});
        std::printf("    cone  noise 64 %-12s: %s\n", field, a.summary().c_str());
        EXPECT_GT(a.referenceHits, 1000u) << field;
        EXPECT_LE(a.coverageMismatchPercent(), 0.1) << field;
        EXPECT_LE(a.offHalfTexelPercent(), 0.2) << field;
        EXPECT_EQ(a.exhausted, 0u) << field;
    }
}

// rcsm as published (15 relaxed cone steps, 8 binary steps) and with more steps: it runs,
// hits the relief, and its error is in the log, not held to anything. On cobbles at 128 x
// 128: the relaxed cone map of the bundled 256 x 256 takes some 40 s to build on one core
// (its brute-force construction, pruned), a quarter of that here.
TEST_F(ConePeers, RcsmRunsAndReportsItsError) {
    const HeightMap bundled = synth::cobbles(128, 128, 7);
    HeadlessRenderer renderer(test::glContext());
    renderer.setHeights(RenderJob{}, bundled, "cobbles 128");
    for (const ConeView& view : coneViews()) {
        for (int steps : {15, 60}) {
            const std::string where =
                "cobbles 128, " + std::string(view.name) + ", " + std::to_string(steps) + " steps";
            const test::Accuracy a = render(renderer, bundled, where, Method::Rcsm, view.camera,
                                            steps, AccuracyScope::TopSurface);
            EXPECT_GT(a.referenceHits, 1000u) << where;
            EXPECT_EQ(a.exhausted, 0u) << where;
        }
    }
}

// The conservative cone map built on the GPU against the CPU build (peers/ConeMap.h), on
// the CPU tests' adversarial maps (test::coneCases: spikes, walls, steps, noise, heights
// from 1e-22 to 1e3, a base 3000 high), rough noise, a non-square map and the bundled one:
// every apex the same bits, every ratio at most the CPU's, and most (90 %) the same. A GPU
// cone is then inside the CPU cone of the same texel, which cpu/ConeMapTest.cpp holds
// free of the surface against a dense reference: so is the GPU's. Seen failing with the
// final margin turned to widen the cones (1 + 2^-16): ratios above the CPU's; and, before
// the half rounding's shifts were kept below 32, on the heights below 2^-32 (apexes far
// above the CPU's and wider cones, on llvmpipe).
TEST_F(ConePeers, GpuConeMapIsTheCpuMapOrNarrower) {
    std::vector<test::ConeCase> cases = test::coneCases();
    cases.push_back({"noise 96x80", synth::valueNoise(96, 80, 3.0, 3, 28)});
    cases.push_back({"bundled", loadHeightMap(defaultHeightMapPath())});
    const GL& gl = test::glContext().gl();
    test::glContext().makeCurrent();
    PyramidBuilder builder(gl, shaderDirectory());
    test::GpuConeMapCheck check;
    for (const test::ConeCase& c : cases) {
        ReliefTextures textures(gl, c.map, c.name, false, builder);
        textures.addConeMap(gl, ReliefTextures::ConeKind::Conservative, &builder);
        EXPECT_FALSE(textures.hasMaxMipPyramid()) << c.name << ": the quadtree is not kept";
        check.add(c.name, c.map.width,
                  textures.readConeMap(gl, ReliefTextures::ConeKind::Conservative),
                  buildConservativeConeMap(c.map));
    }
    std::printf("    GPU cone map: %s\n", check.summary().c_str());
    EXPECT_EQ(check.wrong, 0u) << testing::PrintToString(check.firstWrong);
    EXPECT_GE(double(check.same), 0.9 * double(check.texels));
}

}  // namespace
