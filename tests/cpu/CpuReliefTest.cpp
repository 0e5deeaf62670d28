// The relief on the CPU (core/trace/CpuRelief.h): world rays in, world hits out, built from
// the relief's description, placed by its model, rebuilt only for what the twin is built from.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/CpuRelief.h"
#include "microrelief/core/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

TEST(CpuRelief, PicksTheMapUnderThePixel) {
    // A ramp along u: h = u at the sample centres, so the picked height reads the uv.
    HeightMap ramp(32, 16);
    for (int j = 0; j < ramp.height; ++j) {
        for (int i = 0; i < ramp.width; ++i) ramp.at(i, j) = (i + 0.5f) / ramp.width;
    }
    CpuRelief picker;
    const auto heights = std::make_shared<const HeightMap>(ramp);
    ReliefDesc relief;
    relief.heightScale = 0.2f;
    picker.apply(relief, heights);
    Camera top;
    top.eye = {0.0, 2.0, 0.0};
    top.up = {0.0, 0.0, -1.0};
    top.fovyDegrees = 30.0;
    const CameraFrame frame = resolveCamera(top, 101, 101, 1.0);
    // The centre pixel looks straight down at u = v = 0.5.
    const std::optional<WorldHit> centre = picker.pick(frame, 50, 50);
    ASSERT_TRUE(centre);
    EXPECT_NEAR(centre->uv.x, 0.5, 1e-6);
    EXPECT_NEAR(centre->uv.y, 0.5, 1e-6);
    EXPECT_NEAR(centre->height, 0.5, 1e-6);
    EXPECT_EQ(centre->face, HitFace::Top);
    // Image row 0 is v = 0 (far side, -z); column 0 is u = 0 (-x): left of centre is lower.
    const std::optional<WorldHit> left = picker.pick(frame, 40, 50);
    ASSERT_TRUE(left);
    EXPECT_LT(left->uv.x, 0.5);
    EXPECT_NEAR(left->height, left->uv.x, 1e-6);
    EXPECT_FALSE(picker.pick(frame, 0, 0)) << "the corner ray passes beside the relief";
    EXPECT_FALSE(picker.pick(frame, -1, 50));
    EXPECT_EQ(picker.twinsBuilt(), 1);
    relief.heightScale = 0.4f;
    picker.apply(relief, heights);  // rebuilt for the new scale; h is the map's value still
    EXPECT_NEAR(picker.pick(frame, 50, 50)->height, 0.5, 1e-6);
    EXPECT_EQ(picker.twinsBuilt(), 2);
}

// The relief builds its twin again only for what the twin is built from; a model, an
// albedo, an animation's time move nothing (the model moves the ray), and the picks follow.
TEST(CpuRelief, BuildsItsTwinAgainOnlyForWhatItIsBuiltFrom) {
    const auto heights = std::make_shared<const HeightMap>(HeightMap(16, 16, 0.5f));
    Camera top;
    top.eye = {0.0, 2.0, 0.0};
    top.up = {0.0, 0.0, -1.0};
    top.fovyDegrees = 30.0;
    const CameraFrame frame = resolveCamera(top, 101, 101, 1.0);
    CpuRelief picker;
    ReliefDesc relief;
    picker.apply(relief, heights);
    ASSERT_TRUE(picker.pick(frame, 50, 50));
    EXPECT_NEAR(picker.pick(frame, 50, 50)->position.y, 0.05, 1e-6);
    relief.model = ModelTransform::fromRows({1, 0, 0, 0, 0, 1, 0, 0.25, 0, 0, 1, 0});  // up by 0.25
    relief.albedo.kind = AlbedoSource::Kind::None;
    relief.time = 2.0;
    picker.apply(relief, heights);
    EXPECT_NEAR(picker.pick(frame, 50, 50)->position.y, 0.3, 1e-6);
    EXPECT_EQ(picker.twinsBuilt(), 1);
    const std::vector<std::function<void(ReliefDesc&)>> rebuilt = {
        [](ReliefDesc& r) { r.heightScale = 0.2f; },
        [](ReliefDesc& r) { r.base = BaseShape::cylinder(0.3, 1.0); },
        [](ReliefDesc& r) { r.base = BaseShape::cylinder(0.35, 1.0); },
        [](ReliefDesc& r) { r.interpolation = Interpolation::Biquadratic; },
        [](ReliefDesc& r) { r.tiles = {2, 2}; },
    };
    for (std::size_t i = 0; i < rebuilt.size(); ++i) {
        rebuilt[i](relief);
        picker.apply(relief, heights);
        (void)picker.pick(frame, 50, 50);
        EXPECT_EQ(picker.twinsBuilt(), static_cast<int>(i) + 2) << "change " << i;
    }
    picker.apply(relief, std::make_shared<const HeightMap>(*heights));  // other heights
    (void)picker.pick(frame, 50, 50);
    EXPECT_EQ(picker.twinsBuilt(), static_cast<int>(rebuilt.size()) + 2);
}

// Placed by a model that rotates, scales unevenly and moves the relief, a world ray's hit is
// the exact reference's (which takes the model itself, core/trace/ReferenceTracer.h): the
// same t in the world ray's units, the same world point, and the reference's world normal,
// unit, over rays across the whole relief.
TEST(CpuRelief, WorldHitsAreTheReferencesUnderAModel) {
    const HeightMap map = synth::cobbles(24, 20, 7);
    ReliefDesc relief;
    relief.heightScale = 0.15f;
    // 30 degrees about y, x scaled by 2 and z by 0.5, moved by (1, -2, 3).
    const double c = std::cos(0.5235987755982988), s = std::sin(0.5235987755982988);
    relief.model = ModelTransform::fromRows({2 * c, 0, 0.5 * s, 1,  //
                                             0, 1, 0, -2,           //
                                             -2 * s, 0, 0.5 * c, 3});
    CpuRelief cpu;
    cpu.apply(relief, std::make_shared<const HeightMap>(map));
    const ReferenceTracer reference(
        ReliefGeometry{&map, relief.heightScale, relief.base, relief.interpolation, relief.model});
    int hits = 0;
    for (int k = 0; k < 200; ++k) {
        const double u = (k % 20 + 0.5) / 20.0, v = (k / 20 + 0.5) / 10.0;
        const glm::dvec3 target = relief.model.pointToWorld({u - 0.5, 0.05, v - 0.5});
        const Ray world{target + glm::dvec3(0.4, 1.5, 0.3), glm::dvec3(-0.4, -1.5, -0.3)};
        const std::optional<WorldHit> hit = cpu.intersect(world);
        const ReferenceHit exact = reference.trace(world);
        ASSERT_EQ(hit.has_value(), static_cast<bool>(exact)) << "ray " << k;
        if (!hit) continue;
        ++hits;
        EXPECT_EQ(hit->face, exact.face) << "ray " << k;
        EXPECT_NEAR(hit->t, exact.t, 1e-9) << "ray " << k;
        EXPECT_LT(glm::length(hit->position - exact.position), 1e-8) << "ray " << k;
        EXPECT_LT(glm::length(hit->normal - exact.normal), 1e-6) << "ray " << k;
        EXPECT_NEAR(glm::length(hit->normal), 1.0, 1e-12) << "ray " << k;
    }
    EXPECT_GT(hits, 150);
    EXPECT_FALSE(CpuRelief().intersect(Ray{{0, 1, 0}, {0, -1, 0}})) << "nothing before apply";
}

}  // namespace
