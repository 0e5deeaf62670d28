// Self-shadows (issues 14 and 25): the hard shadow of every hit pixel against the exact
// reference, a shadow ray of the reference tracer from the renderer's own hit; and the soft
// shadow's estimate turning into the hard shadow as the light shrinks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "GlTestBackend.h"
#include "TestSupport.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

class Shadows : public test::GlTest {};

// A direction towards a light `elevation` degrees above the base plane.
glm::dvec3 lightAt(double elevationDeg, double azimuthDeg) {
    const double e = glm::radians(elevationDeg), a = glm::radians(azimuthDeg);
    return {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
}

// Where the renderer's own hit lies against the surface, and what a shadow ray from there
// meets: the exact answer the shadow AOV is held to. The hit (the AOV's world position, a
// float) lies on the surface within rounding; the reference moves it along the base's
// height axis (world y on the plane, the distance from the axis or the centre on a curved
// base) to `lift` map units above the surface under it, exactly, and traces the shadow ray
// from there in double precision.
class ShadowReference {
public:
    ShadowReference(const HeightMap& map, const RenderJob& job)
        : map_(map),
          job_(job),
          surface_(
              BaseSurface::make(job.base, map.width, map.height, job.heightScale, map.maxValue())),
          reference_(ReliefGeometry{&map, job.heightScale, job.base, job.interpolation}) {}

    // The frame height of a world point above the surface under it (map units: negative
    // inside the solid).
    double gap(const glm::dvec3& world) const {
        const glm::dvec3 m = surface_->mapPoint(frame(world));
        return m.z - map_.surface(m.x, m.y, job_.base.wrapsU(), job_.interpolation);
    }

    // The shadow ray from `world` raised or lowered to `lift` map units above the surface,
    // towards `toLight` (a direction, or a point light's position): blocked before the light.
    bool blocked(const glm::dvec3& world, double lift, const glm::dvec3& toLight,
                 bool pointLight) const {
        const glm::dvec3 start = raised(world, lift - gap(world));
        const glm::dvec3 direction = pointLight ? toLight - start : toLight;
        const ReferenceHit blocker = reference_.trace({start, direction});
        return blocker && !(pointLight && blocker.t > 1.0);
    }

    // The world length of 2^-10 texel, in map units of height: how far above the surface a
    // hit may start its shadow ray and still be held to the exact answer. Rounding puts the
    // renderer's hit a few float ulp (1e-7 of the scene) off the surface, far below this.
    double tolerance() const {
        const double texel =
            job_.base.curved() ? 2.0 * M_PI / map_.width : 1.0 / std::max(map_.width, map_.height);
        return texel / 1024.0 / job_.heightScale;
    }

private:
    glm::dvec3 frame(const glm::dvec3& world) const {
        return surface_->frameRay({world, {0.0, 0.0, 1.0}}).origin;
    }
    // `world` moved `by` map units up the height axis.
    glm::dvec3 raised(const glm::dvec3& world, double by) const {
        const double s = job_.heightScale;
        if (!job_.base.curved()) return world + glm::dvec3(0.0, s * by, 0.0);
        glm::dvec3 q = frame(world);
        glm::dvec3 axis = job_.base.kind == BaseKind::Cylinder ? glm::dvec3(q.x, 0.0, q.z) : q;
        q += (s * by) * glm::normalize(axis);
        return q * job_.base.frameScale();  // the tests' model is the identity
    }

    const HeightMap& map_;
    const RenderJob& job_;
    std::unique_ptr<BaseSurface> surface_;
    ReferenceTracer reference_;
};

// One picture's hard shadows: a map, a base and its last level, a light (a direction
// `elevation` degrees above the base plane at `azimuth`, or a point 0.6 away in that
// direction, 30 degrees higher) and the camera that looks at it.
struct ShadowCase {
    const char* name;
    const HeightMap* map;
    BaseShape base;
    Interpolation interpolation;
    double elevation, azimuth;
    bool pointLight = false;
    float heightScale = 0.1f;
    double cameraElevation = 55.0;
};

// Hard shadows held against shadow rays traced from the renderer's own hits (the AOV), not
// from the reference's: where the render says lit, the reference's ray from 2^-10 texel
// above the surface under that hit must reach the light; where it says shadowed, the ray
// from just above the surface (1e-9 map units) must be blocked. At most 0.1 % of the hit
// pixels may fail either (an occluder's edge within rounding of the ray). A shadow ray that
// starts too high passes over occluders it should meet (issue 25: 1/256 of a map unit up,
// 0.5 % to 2.5 % of the hits here lit wrongly under grazing lights, 15 to 145 of about
// 6300 disagreeing in the earlier cases at 45 to 2 degrees).
struct ShadowCount {
    int hits = 0, wrong = 0;  // top-surface hits; lit or shadowed wrongly
    ShadowCount& operator+=(const ShadowCount& o) {
        hits += o.hits;
        wrong += o.wrong;
        return *this;
    }
};

ShadowCount expectShadowsFromTheRenderersHits(const ShadowCase& c) {
    RenderJob job;
    job.width = job.height = 112;
    job.base = c.base;
    job.interpolation = c.interpolation;
    job.heightScale = c.heightScale;
    job.camera = test::orbitCamera(c.cameraElevation, 30.0, c.base.curved() ? 1.4 : 1.3);
    job.shading.shadows = ShadowMode::Hard;
    const glm::dvec3 direction = lightAt(c.elevation, c.azimuth);
    const glm::dvec3 lamp = 0.6 * lightAt(c.elevation + 30.0, c.azimuth);
    if (c.pointLight) {
        job.shading.lightPosition = glm::vec3(lamp);
    } else {
        job.shading.lightDirection = glm::vec3(direction);
    }
    const HeadlessResult r = renderHeadless(test::glContext(), *c.map, c.name, job);
    const ShadowReference reference(*c.map, job);
    const glm::dvec3 toLight = c.pointLight ? lamp : direction;
    int hits = 0, leaks = 0, falseShadows = 0, shadowed = 0, exhausted = 0;
    double worstGap = 0.0;
    for (int row = 0; row < job.height; ++row) {
        for (int column = 0; column < job.width; ++column) {
            const float* p = r.frame.positionAt(column, row);
            exhausted += r.frame.statsAt(column, row)[3] > 0.5f;
            if (p[3] < 0.5f) continue;
            const glm::dvec3 hit = r.frame.worldPositionAt(column, row);
            // The top surface's hits only: a side wall, the bottom or a cap lies below it
            // (and faces out of a convex shell: lit wherever it faces the light).
            const double gap = reference.gap(hit);
            if (std::abs(gap) > 1e-3) continue;
            ++hits;
            worstGap = std::max(worstGap, std::abs(gap));
            const bool lit = r.frame.shadowAt(column, row) > 0.5f;
            shadowed += !lit;
            if (lit) {
                leaks += reference.blocked(hit, reference.tolerance(), toLight, c.pointLight);
            } else {
                falseShadows += !reference.blocked(hit, 1e-9, toLight, c.pointLight);
            }
        }
    }
    std::printf(
        "    %-21s light %4.1f deg az %3.0f%s: %5d hits, %5d shadowed, %3d lit wrongly, "
        "%3d shadowed wrongly; the hits within %.1e map units of the surface\n",
        c.name, c.elevation, c.azimuth, c.pointLight ? " (point)" : "", hits, shadowed, leaks,
        falseShadows, worstGap);
    EXPECT_EQ(exhausted, 0) << c.name << " " << c.elevation;
    EXPECT_GT(hits, 2000) << c.name;
    EXPECT_GT(shadowed, hits / 50) << c.name << " " << c.elevation;  // something to get right
    EXPECT_LT(shadowed, hits - hits / 50) << c.name << " " << c.elevation;
    EXPECT_LE(leaks * 1000, hits) << c.name << " " << c.elevation << " deg";
    EXPECT_LE(falseShadows * 1000, hits) << c.name << " " << c.elevation << " deg";
    return {hits, leaks + falseShadows};
}

// Across a sweep an occluder's edge within rounding of a shadow ray is rare: at most 0.02 %
// of all its hits may be wrong (the start 2^-8 texel up on a curved base, as an earlier
// version had it: 0.05 %; the exact start: 0.002 %).
void expectFewWrongOverall(const ShadowCount& total) {
    std::printf("    the sweep: %d of %d hits wrong\n", total.wrong, total.hits);
    EXPECT_LE(total.wrong * 5000, total.hits);
}

// From a high light down to grazing ones (2 to 20 degrees) over rough maps.
TEST_F(Shadows, HardShadowsMeetEveryOccluderOnThePlane) {
    const HeightMap cobbles = synth::cobbles(128, 128, 31);
    const HeightMap noise = synth::valueNoise(128, 128, 6.0, 4, 32);
    const auto bilinear = Interpolation::Bilinear, biquadratic = Interpolation::Biquadratic;
    ShadowCount total;
    for (double elevation : {45.0, 20.0, 10.0, 5.0, 2.0}) {
        total += expectShadowsFromTheRenderersHits(
            {"cobbles", &cobbles, {}, bilinear, elevation, 200.0});
    }
    for (double elevation : {20.0, 10.0, 5.0, 2.0}) {
        total += expectShadowsFromTheRenderersHits(
            {"noise", &noise, {}, bilinear, elevation, 20.0, false, 0.05f});
    }
    for (double elevation : {45.0, 10.0, 3.0}) {
        total += expectShadowsFromTheRenderersHits(
            {"cobbles, biquadratic", &cobbles, {}, biquadratic, elevation, 200.0});
    }
    total +=
        expectShadowsFromTheRenderersHits({"cobbles", &cobbles, {}, bilinear, 10.0, 200.0, true});
    expectFewWrongOverall(total);
}

// The camera low, the light from its side: the lit half and the terminator in view.
TEST_F(Shadows, HardShadowsMeetEveryOccluderOnCurvedBases) {
    const HeightMap cobbles = synth::cobbles(128, 64, 33);
    const HeightMap noise = synth::valueNoise(256, 128, 6.0, 4, 34);
    const BaseShape cylinder = BaseShape::cylinder(0.3, 1.0);
    const BaseShape ellipsoid = BaseShape::ellipsoid({0.5, 0.4, 0.45});
    const auto bilinear = Interpolation::Bilinear, biquadratic = Interpolation::Biquadratic;
    ShadowCount total;
    for (double elevation : {45.0, 20.0, 10.0, 3.0}) {
        total += expectShadowsFromTheRenderersHits(
            {"cylinder", &cobbles, cylinder, bilinear, elevation, 110.0, false, 0.1f, 15.0});
        total += expectShadowsFromTheRenderersHits(
            {"ellipsoid", &cobbles, ellipsoid, bilinear, elevation, 110.0, false, 0.1f, 15.0});
    }
    for (float scale : {0.1f, 0.03f}) {
        for (double elevation : {10.0, 5.0, 3.0}) {
            total +=
                expectShadowsFromTheRenderersHits({"cylinder, noise", &noise, cylinder, bilinear,
                                                   elevation, 110.0, false, scale, 15.0});
            total +=
                expectShadowsFromTheRenderersHits({"sphere, noise", &noise, BaseShape::sphere(0.5),
                                                   bilinear, elevation, 110.0, false, scale, 15.0});
        }
    }
    for (double elevation : {45.0, 10.0, 5.0}) {
        total += expectShadowsFromTheRenderersHits({"sphere, biquadratic", &cobbles,
                                                    BaseShape::sphere(0.5), biquadratic, elevation,
                                                    110.0, false, 0.1f, 15.0});
    }
    total += expectShadowsFromTheRenderersHits(
        {"cylinder", &cobbles, cylinder, biquadratic, 10.0, 110.0, true, 0.1f, 15.0});
    expectFewWrongOverall(total);
}

// The soft shadow of a light shrinking to a point is the hard shadow: the mean difference
// between their AOVs and the penumbra (visibilities strictly between 0.02 and 0.98) shrink
// with the light's angular size, and at 0.001 degrees at most 0.1 % of hit pixels differ
// by more than a half. An 8 degree light gives a penumbra over more than 1 % of the hits
// (this map's occluders are a few texels from the shadows they cast: narrow penumbrae).
// The soft shadow against the hard one as the light shrinks, on cobblestones and on a
// one-texel wall across the light (a blocked ray that none of the leaf's five measuring
// points finds below the surface: the wall is thinner than their spacing). At 0.001
// degrees the estimate is the hard shadow: a blocked ray sees no light, a lit one all of
// it, so at most 0.1 % of hit pixels may lie between 0.02 and 0.98 or differ from the
// hard shadow by more than 0.02.
TEST_F(Shadows, SoftShadowsBecomeTheHardShadowAsTheLightShrinks) {
    struct Case {
        const char* name;
        HeightMap map;
        double elevation, azimuth;
    };
    // The wall's shadow ends on the map, where rays pass just under its ridge.
    const Case cases[] = {{"cobbles", synth::cobbles(64, 64, 23), 10.0, 200.0},
                          {"wall", synth::wallColumn(64, 64, 32), 25.0, 195.0}};
    for (const Case& c : cases) {
        RenderJob job;
        job.width = job.height = 96;
        job.camera = test::orbitCamera(50.0, 30.0, 1.5);
        job.shading.lightDirection = glm::vec3(lightAt(c.elevation, c.azimuth));
        job.shading.shadows = ShadowMode::Hard;
        const RenderedFrame hard = renderHeadless(test::glContext(), c.map, c.name, job).frame;
        double previous = 1.0;
        int previousPenumbra = 1 << 30;
        for (float size : {8.0f, 2.0f, 0.5f, 0.001f}) {
            job.shading.shadows = ShadowMode::Soft;
            job.shading.lightSizeDegrees = size;
            const RenderedFrame soft = renderHeadless(test::glContext(), c.map, c.name, job).frame;
            double sum = 0.0;
            int hits = 0, off = 0, penumbra = 0;
            for (std::size_t p = 0; p < hard.shadow.size(); ++p) {
                if (hard.position[4 * p + 3] < 0.5f) continue;
                ++hits;
                const double d = std::abs(soft.shadow[p] - hard.shadow[p]);
                sum += d;
                off += d > 0.02;
                penumbra += soft.shadow[p] > 0.02f && soft.shadow[p] < 0.98f;
            }
            const double mean = sum / hits;
            std::printf(
                "    %s, light %6.3f deg: mean |soft - hard| %.4f, %d of %d differ by > 0.02, %d "
                "in "
                "penumbra\n",
                c.name, size, mean, off, hits, penumbra);
            EXPECT_LE(mean, previous) << c.name << " " << size;
            EXPECT_LE(penumbra, previousPenumbra) << c.name << " " << size;
            previous = mean;
            previousPenumbra = penumbra;
            if (size >= 8.0f) {
                EXPECT_GT(penumbra, hits / 100) << c.name << " " << size;
            }
            if (size < 0.01f) {
                EXPECT_LE(off * 1000, hits) << c.name << " " << size;
                EXPECT_LE(penumbra * 1000, hits) << c.name << " " << size;
            }
        }
    }
}

}  // namespace
