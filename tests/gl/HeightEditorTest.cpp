// Sculpting on the GPU (gl/HeightEditor.h): after a series of brush strokes the
// render's hits match the exact reference for the edited map (read back from the GPU),
// with the usual thresholds, on the plane and on a cylinder, both last levels; the
// pyramids equal a CPU build of the edited map; undo returns the exact previous map,
// stroke by stroke; and each brush does what it says, across a curved base's seam too.
// On the backend named by --backend=.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "GlTestBackend.h"
#include "SweepCases.h"
#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/ReferenceTracer.h"
#include "microrelief/gl/AnimatedHeights.h"
#include "microrelief/gl/HeightEditor.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefRenderer.h"
#include "microrelief/peers/MaxMipPyramid.h"

using namespace microrelief;

namespace {

// The thresholds of every accuracy test (SweepCases.h): hit/miss may flip for at most
// 0.1 % of pixels (rays grazing a ridge), hits off by more than half a texel for at most
// 0.2 % of hit pixels, none out of budget.
using test::kMaxCoverageMismatchPercent;
using test::kMaxOffHalfTexelPercent;

class Sculpting : public test::GlTest {
protected:
    static void expectPyramidOf(const ReliefRenderer& renderer, const HeightMap& map,
                                const std::string& what) {
        const ReliefTextures& textures = *renderer.textures();
        const MaxPyramid cpu(map, textures.wrapsU(), BoundPrecision::Half);
        for (int level = 0; level < cpu.windowLevelCount(); ++level) {
            ASSERT_EQ(textures.readWindowLevel(gl(), level), cpu.windowLevelData(level))
                << what << ", window level " << level;
        }
        if (textures.hasMaxMipPyramid()) {
            const MaxMipPyramid maxMip(cpu);
            for (int level = 0; level < maxMip.levelCount(); ++level) {
                ASSERT_EQ(textures.readAlignedLevel(gl(), level), maxMip.levelData(level))
                    << what << ", aligned level " << level;
            }
        }
        EXPECT_EQ(renderer.maxHeight(), cpu.maxHeight()) << what;
    }

    static bool sameBits(const HeightMap& a, const HeightMap& b) {
        if (a.samples.size() != b.samples.size()) return false;
        for (std::size_t k = 0; k < a.samples.size(); ++k) {
            if (std::bit_cast<std::uint32_t>(a.samples[k]) !=
                std::bit_cast<std::uint32_t>(b.samples[k]))
                return false;
        }
        return true;
    }

    // A few strokes of every brush, a dozen dabs each along a line.
    static void sculpt(HeightEditor& editor, ReliefRenderer& renderer, glm::dvec2 size) {
        const Brush brushes[] = {{BrushMode::Raise, 7.0, 0.3f},
                                 {BrushMode::Lower, 5.0, 0.25f},
                                 {BrushMode::Smooth, 6.0, 0.8f},
                                 {BrushMode::Flatten, 4.5, 0.7f, 0.45f},
                                 {BrushMode::Raise, 3.0, 1.2f}};
        int stroke = 0;
        for (const Brush& brush : brushes) {
            const glm::dvec2 from = size * glm::dvec2(0.15 + 0.1 * stroke, 0.2);
            const glm::dvec2 to = size * glm::dvec2(0.85 - 0.05 * stroke, 0.8);
            for (int k = 0; k < 12; ++k) editor.dab(renderer, glm::mix(from, to, k / 11.0), brush);
            editor.endStroke();
            ++stroke;
        }
    }
};

}  // namespace

TEST_F(Sculpting, HitsAfterStrokesMatchTheReferenceOfTheEditedMap) {
    struct Case {
        BaseShape base;
        Interpolation interpolation;
        Camera camera;
    };
    Camera planeView = test::orbitCamera(35.0, 30.0, 1.5, {0.0, 0.03, 0.0});
    Camera columnView;
    columnView.eye = {0.35, 0.45, 1.05};
    columnView.target = {0.0, 0.0, 0.0};
    columnView.fovyDegrees = 40.0;
    // Low over the map: raised stones stand out above the unedited map's box.
    const Camera grazing = test::orbitCamera(7.0, 20.0, 1.4, {0.0, 0.05, 0.0});
    const Case cases[] = {{BaseShape::plane(), Interpolation::Bilinear, planeView},
                          {BaseShape::plane(), Interpolation::Bilinear, grazing},
                          {BaseShape::plane(), Interpolation::Biquadratic, planeView},
                          {BaseShape::cylinder(), Interpolation::Bilinear, columnView}};
    for (const Case& c : cases) {
        const std::string what = baseName(c.base) + ", " + interpolationName(c.interpolation);
        const float heightScale = 0.1f;
        OffscreenTarget target(gl(), 96, 96);
        ReliefRenderer renderer(gl(), shaderDirectory());
        const HeightMap cobbles = synth::cobbles(72, 56, 3);
        renderer.apply(test::relief(c.base, c.interpolation, heightScale), &cobbles, "cobbles",
                       PyramidBuild::Gpu);
        HeightEditor editor(gl(), shaderDirectory());
        sculpt(editor, renderer, {72.0, 56.0});
        const HeightMap edited = renderer.textures()->readSamples(gl());
        expectPyramidOf(renderer, edited, what);

        const CameraFrame camera = resolveCamera(c.camera, 96, 96, 2.0);
        target.clear(glm::vec3(0.0f));
        renderer.draw(camera, ShadingOptions{});
        const RenderedFrame frame = target.read(camera.eye);
        const Accuracy accuracy = compareWithReference(
            frame, camera, ReliefGeometry{&edited, heightScale, c.base, c.interpolation});
        std::printf("    %s: %s\n", what.c_str(), accuracy.summary().c_str());
        EXPECT_LE(accuracy.coverageMismatchPercent(), kMaxCoverageMismatchPercent) << what;
        EXPECT_LE(accuracy.offHalfTexelPercent(), kMaxOffHalfTexelPercent) << what;
        EXPECT_EQ(accuracy.exhausted, 0u) << what;
        EXPECT_GT(accuracy.referenceHits, 2000u) << what;  // the relief fills the view
        // The edits show: the picture is not the unedited map's.
        const HeightMap original = synth::cobbles(72, 56, 3);
        EXPECT_FALSE(sameBits(edited, original)) << what;
    }
    EXPECT_EQ(gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(Sculpting, UndoReturnsTheExactPreviousMapStrokeByStroke) {
    for (const BaseShape& base : {BaseShape::plane(), BaseShape::cylinder()}) {
        ReliefRenderer renderer(gl(), shaderDirectory());
        const HeightMap noise = synth::whiteNoise(45, 31, 8);
        renderer.apply(test::relief(base), &noise, "noise", PyramidBuild::Gpu);
        HeightEditor editor(gl(), shaderDirectory());
        std::vector<HeightMap> before;
        const Brush brushes[] = {{BrushMode::Raise, 6.0, 0.5f},
                                 {BrushMode::Smooth, 9.0, 0.9f},
                                 {BrushMode::Lower, 4.0, 0.7f},
                                 {BrushMode::Flatten, 5.0, 1.0f, 0.2f}};
        int stroke = 0;
        for (const Brush& brush : brushes) {
            before.push_back(renderer.textures()->readSamples(gl()));
            // Overlapping dabs, some over the seam (X near 0) on the cylinder.
            for (int k = 0; k < 8; ++k)
                editor.dab(renderer, {1.0 + 5.0 * k + stroke, 4.0 + 3.0 * k}, brush);
            editor.endStroke();
            ++stroke;
        }
        EXPECT_EQ(editor.undoSteps(), 4);
        for (int step = 3; step >= 0; --step) {
            ASSERT_FALSE(editor.undo(renderer).empty());
            const HeightMap now = renderer.textures()->readSamples(gl());
            ASSERT_TRUE(sameBits(now, before[step]))
                << baseName(base) << ": after undoing stroke " << step;
            expectPyramidOf(renderer, now, baseName(base) + ", undo " + std::to_string(step));
        }
        EXPECT_TRUE(editor.undo(renderer).empty());
    }
}

TEST_F(Sculpting, EachBrushDoesWhatItSays) {
    ReliefRenderer renderer(gl(), shaderDirectory());
    const HeightMap flat = synth::flat(40, 30, 0.5f);
    renderer.apply(ReliefDesc{}, &flat, "flat", PyramidBuild::Gpu);
    HeightEditor editor(gl(), shaderDirectory());
    const glm::dvec2 centre(20.5, 15.5);  // sample (20, 15)'s centre: the falloff is 1 there

    editor.dab(renderer, centre, {BrushMode::Raise, 5.0, 0.25f});
    HeightMap h = renderer.textures()->readSamples(gl());
    EXPECT_EQ(h.at(20, 15), 0.75f);
    EXPECT_GT(h.at(22, 15), 0.5f);
    EXPECT_LT(h.at(22, 15), 0.75f);
    EXPECT_EQ(h.at(25, 15), 0.5f);           // on the rim: no change
    EXPECT_EQ(h.at(20, 21), 0.5f);           // outside: the same bits
    EXPECT_EQ(renderer.maxHeight(), 0.75f);  // the box follows the new top

    editor.dab(renderer, centre, {BrushMode::Lower, 5.0, 2.0f});  // never below 0
    h = renderer.textures()->readSamples(gl());
    EXPECT_EQ(h.at(20, 15), 0.0f);
    EXPECT_GE(h.minValue(), 0.0f);

    editor.dab(renderer, centre, {BrushMode::Flatten, 6.0, 1.0f, 0.3f});
    h = renderer.textures()->readSamples(gl());
    EXPECT_EQ(h.at(20, 15), 0.3f);

    editor.dab(renderer, {10.5, 10.5}, {BrushMode::Raise, 1.0, 0.5f});  // a one-sample spike
    editor.dab(renderer, {10.5, 10.5}, {BrushMode::Smooth, 3.0, 1.0f});
    h = renderer.textures()->readSamples(gl());
    EXPECT_NEAR(h.at(10, 10), 0.5f + 0.5f / 9.0f, 1e-6f);  // the mean of its neighbourhood
    EXPECT_GT(h.at(11, 10), 0.5f);

    // Across a cylinder's seam: a dab at X = 1 reaches columns W - 2 and W - 1 as it
    // reaches 2 and 3, at the same distances.
    ReliefRenderer column(gl(), shaderDirectory());
    column.apply(test::relief(BaseShape::cylinder()), &flat, "flat", PyramidBuild::Gpu);
    const std::vector<TexelRect> changed =
        editor.dab(column, {1.0, 15.5}, {BrushMode::Raise, 3.0, 0.4f});
    EXPECT_EQ(changed.size(), 2u);
    h = column.textures()->readSamples(gl());
    EXPECT_EQ(h.at(39, 15), h.at(2, 15));
    EXPECT_EQ(h.at(38, 15), h.at(3, 15));
    EXPECT_GT(h.at(39, 15), 0.5f);
    EXPECT_EQ(h.at(36, 15), 0.5f);
    expectPyramidOf(column, h, "the seam");
    EXPECT_EQ(gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// An animated relief (gl/AnimatedHeights.h): at each moment the pyramids, built anew on
// the GPU, equal a CPU build of the field read back, and the hits match that field's exact
// reference; the moments differ; restore() gives the map back, bit for bit.
TEST_F(Sculpting, AnimatedReliefIsRebuiltEveryFrameAndTracedExactly) {
    const HeightMap map = synth::cobbles(61, 47, 2);
    const Camera view = test::orbitCamera(30.0, 40.0, 1.5);
    for (const BaseShape& base : {BaseShape::plane(), BaseShape::sphere()}) {
        for (const std::string& name : animatedFieldNames()) {
            const std::string what = name + " on the " + baseName(base);
            OffscreenTarget target(gl(), 80, 80);
            ReliefRenderer renderer(gl(), shaderDirectory());
            renderer.apply(test::relief(base), &map, "cobbles", PyramidBuild::Gpu);
            AnimatedHeights animated(gl(), shaderDirectory(), name);
            std::vector<HeightMap> moments;
            for (const double time : {0.0, 1.3, 4.9}) {
                animated.evaluate(renderer, time);
                moments.push_back(renderer.textures()->readSamples(gl()));
                expectPyramidOf(renderer, moments.back(), what + " at " + std::to_string(time));
                const CameraFrame camera = resolveCamera(view, 80, 80, 2.0);
                target.clear(glm::vec3(0.0f));
                renderer.draw(camera, ShadingOptions{});
                const Accuracy accuracy = compareWithReference(
                    target.read(camera.eye), camera, ReliefGeometry{&moments.back(), 0.1, base});
                EXPECT_LE(accuracy.coverageMismatchPercent(), kMaxCoverageMismatchPercent)
                    << what << ": " << accuracy.summary();
                EXPECT_LE(accuracy.offHalfTexelPercent(), kMaxOffHalfTexelPercent)
                    << what << ": " << accuracy.summary();
                EXPECT_EQ(accuracy.exhausted, 0u) << what;
            }
            EXPECT_FALSE(sameBits(moments[0], moments[1])) << what;
            EXPECT_FALSE(sameBits(moments[1], moments[2])) << what;
            animated.restore(renderer);
            EXPECT_TRUE(sameBits(renderer.textures()->readSamples(gl()), map)) << what;
            expectPyramidOf(renderer, map, what + ", restored");
        }
    }
}
