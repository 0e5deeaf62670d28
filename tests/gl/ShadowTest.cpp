// Self-shadows (issue 14): the hard shadow of every hit pixel against the exact reference,
// a shadow ray of the reference tracer from the reference's own hit; and the soft
// shadow's estimate turning into the hard shadow as the light shrinks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "GlTestBackend.h"
#include "TestSupport.h"
#include "microrelief/render/HeadlessRender.h"
#include "microrelief/synth/SyntheticMaps.h"
#include "microrelief/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

class Shadows : public test::GlTest {};

// A direction towards a light `elevation` degrees above the base plane.
glm::dvec3 lightAt(double elevationDeg, double azimuthDeg) {
    const double e = glm::radians(elevationDeg), a = glm::radians(azimuthDeg);
    return {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
}

// Where the shader starts a shadow ray (shadow.glsl: mr_shadowRayStart), in object space:
// the hit moved 2^-8 along the unit normal of the base's frame. The frame is map space on
// the plane (X = x T + W/2, Y = z T + H/2, Z = y / s with T texels per unit), where the
// normal is (n.x / T, n.z / T, s n.y) before it is made unit; on a curved base
// q = object / frameScale, the normal frameScale n, and the offset 2^-8 of 2 pi / W.
glm::dvec3 shadowRayStart(const glm::dvec3& p, const glm::dvec3& n, const HeightMap& map, double s,
                          const BaseShape& base) {
    if (!base.curved()) {
        const double t = std::max(map.width, map.height);
        const glm::dvec3 f = glm::normalize(glm::dvec3(n.x / t, n.z / t, s * n.y)) / 256.0;
        return p + glm::dvec3(f.x / t, s * f.z, f.y / t);
    }
    const glm::dvec3 scale = base.frameScale();
    const glm::dvec3 f = glm::normalize(scale * n) * (6.28318531 / map.width / 256.0);
    return p + scale * f;
}

struct ShadowCase {
    const char* name;
    BaseShape base;
    Interpolation interpolation;
    double elevation;  // of a directional light; point lights below
    bool pointLight = false;
};

// Per pixel where both the render and the reference hit: the render's shadow AOV (1 lit,
// 0 shadowed) against the reference's answer from its own hit: shadowed when the surface
// faces away from the light, else when the reference's ray from the same start meets the
// solid before the light. At most 0.1 % of those pixels may disagree (the bound):
// the two starts differ by float rounding of the hit, which matters only where an
// occluder's edge passes within that of the ray.
void expectHardShadowsExact(const HeightMap& map, const ShadowCase& c) {
    RenderJob job;
    job.width = job.height = 96;
    job.base = c.base;
    job.interpolation = c.interpolation;
    job.camera = test::orbitCamera(50.0, 30.0, c.base.curved() ? 1.4 : 1.5);
    job.shading.shadows = ShadowMode::Hard;
    const glm::dvec3 toLight = lightAt(c.elevation, 200.0);
    // A point light: 0.6 away in the light's direction, 30 degrees higher.
    const glm::dvec3 lamp = 0.6 * lightAt(c.elevation + 30.0, 200.0);
    if (c.pointLight) {
        job.shading.lightPosition = glm::vec3(lamp);
    } else {
        job.shading.lightDirection = glm::vec3(toLight);
    }
    const HeadlessResult r = renderHeadless(test::glContext(), map, "cobbles", job);
    const ReferenceTracer reference(ReliefGeometry{&map, job.heightScale, c.base, c.interpolation});
    int both = 0, disagree = 0, shadowed = 0, exhausted = 0;
    for (int row = 0; row < job.height; ++row) {
        for (int column = 0; column < job.width; ++column) {
            exhausted += r.frame.statsAt(column, row)[3] > 0.5f;
            const ReferenceHit hit = reference.trace(r.camera.pixelRay(column, row));
            if (!hit || r.frame.positionAt(column, row)[3] < 0.5f) continue;
            ++both;
            const glm::dvec3 start =
                shadowRayStart(hit.position, hit.normal, map, job.heightScale, c.base);
            const glm::dvec3 direction = c.pointLight ? lamp - start : toLight;
            bool lit = glm::dot(hit.normal, direction) > 0.0;
            if (lit) {
                const ReferenceHit blocker = reference.trace({start, direction});
                lit = !blocker || (c.pointLight && blocker.t > 1.0);
            }
            shadowed += !lit;
            disagree += lit != (r.frame.shadowAt(column, row) > 0.5f);
        }
    }
    std::printf("    %-34s light %4.0f deg%s: %d hit pixels, %d shadowed, %d disagree\n", c.name,
                c.elevation, c.pointLight ? " (point)" : "", both, shadowed, disagree);
    EXPECT_EQ(exhausted, 0) << c.name;
    EXPECT_GT(both, 2000) << c.name;
    EXPECT_GT(shadowed, both / 20) << c.name;  // there is something to get right
    EXPECT_LT(shadowed, both - both / 20) << c.name;
    EXPECT_LE(disagree * 1000, both) << c.name;
}

TEST_F(Shadows, HardShadowsAreTheReferencesOnThePlane) {
    const HeightMap map = synth::cobbles(64, 64, 21);
    for (double elevation : {45.0, 10.0, 2.0}) {
        expectHardShadowsExact(map, {"plane, bilinear", {}, Interpolation::Bilinear, elevation});
        expectHardShadowsExact(map,
                               {"plane, biquadratic", {}, Interpolation::Biquadratic, elevation});
    }
    expectHardShadowsExact(map, {"plane, bilinear", {}, Interpolation::Bilinear, 10.0, true});
}

TEST_F(Shadows, HardShadowsAreTheReferencesOnCurvedBases) {
    const HeightMap map = synth::cobbles(64, 32, 22);
    for (double elevation : {45.0, 10.0}) {
        expectHardShadowsExact(
            map, {"cylinder", BaseShape::cylinder(0.3, 1.0), Interpolation::Bilinear, elevation});
        expectHardShadowsExact(map, {"sphere, biquadratic", BaseShape::sphere(0.5),
                                     Interpolation::Biquadratic, elevation});
    }
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
