// The reference tracer on curved bases (core/trace/CurvedReference.cpp) against cases with a
// known answer: a constant map is a column or an ellipsoid of known radius, one raised
// sample peaks at a known point, a ray along the axis meets a cap or a pole, the seam joins
// the map's last column to its first; and, on random maps, every hit lies on the solid's
// boundary with no point of the ray before it inside, every miss stays outside.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <tuple>

#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

constexpr double kPi = std::numbers::pi;

// The spec's definitions, for the tests' own checks.
struct Solid {
    ReliefGeometry relief;
    glm::dvec3 frame(const glm::dvec3& world) const { return world / relief.base.frameScale(); }
    bool cylinder() const { return relief.base.kind == BaseKind::Cylinder; }
    double radial(const glm::dvec3& q) const {
        return cylinder() ? std::hypot(q.x, q.z) : glm::length(q);
    }
    glm::dvec2 mapXY(const glm::dvec3& q) const {
        const HeightMap& m = *relief.map;
        double u = 0.5 + std::atan2(q.x, q.z) / (2.0 * kPi);
        u -= std::floor(u);
        const double v = cylinder() ? 0.5 * (1.0 - q.y)
                                    : std::acos(std::clamp(q.y / glm::length(q), -1.0, 1.0)) / kPi;
        return {u * m.width, v * m.height};
    }
    double surfaceRadius(const glm::dvec3& q) const {
        const glm::dvec2 xy = mapXY(q);
        return 1.0 +
               relief.heightScale * relief.map->surface(xy.x, xy.y, true, relief.interpolation);
    }
    // Inside by more than `margin` (canonical units).
    bool deepInside(const glm::dvec3& world, double margin) const {
        const glm::dvec3 q = frame(world);
        if (cylinder() && std::abs(q.y) >= 1.0 - margin) return false;
        return radial(q) < surfaceRadius(q) - margin;
    }
};

Ray through(const glm::dvec3& from, const glm::dvec3& to) {
    return {from, to - from};
}

// The first t >= 0 at which the ray enters the unit ball (or the unit column between the
// caps when `column`) scaled by `scale`: the solid of a constant map.
std::optional<double> enterScaled(const Ray& ray, const glm::dvec3& scale, bool column, bool& cap) {
    const glm::dvec3 o = ray.origin / scale, d = ray.direction / scale;
    glm::dvec3 oo = o, dd = d;
    if (column) oo.y = dd.y = 0.0;
    const double a = glm::dot(dd, dd), b = glm::dot(oo, dd), c = glm::dot(oo, oo) - 1.0;
    double t0 = -HUGE_VAL, t1 = HUGE_VAL;
    if (a > 0.0) {
        const double disc = b * b - a * c;
        if (disc < 0.0) return std::nullopt;
        t0 = (-b - std::sqrt(disc)) / a;
        t1 = (-b + std::sqrt(disc)) / a;
    } else if (c > 0.0) {
        return std::nullopt;
    }
    cap = false;
    if (column) {
        if (d.y == 0.0) {
            if (std::abs(o.y) > 1.0) return std::nullopt;
        } else {
            const double s0 = std::min((-1.0 - o.y) / d.y, (1.0 - o.y) / d.y);
            const double s1 = std::max((-1.0 - o.y) / d.y, (1.0 - o.y) / d.y);
            cap = s0 > t0;
            t0 = std::max(t0, s0);
            t1 = std::min(t1, s1);
        }
    }
    if (t0 > t1 || t1 < 0.0) return std::nullopt;
    return std::max(t0, 0.0);
}

struct ConstantCase {
    const char* name;
    BaseShape base;
};

}  // namespace

TEST(CurvedReference, AConstantMapIsAColumnOrAnEllipsoidOfKnownRadius) {
    const HeightMap map = synth::flat(12, 7, 0.5f);
    const double s = 0.2;  // the surface at radius 1.1 in the frame
    const ConstantCase cases[] = {{"cylinder", BaseShape::cylinder(0.3, 1.0)},
                                  {"sphere", BaseShape::sphere(0.5)},
                                  {"ellipsoid", BaseShape::ellipsoid({0.3, 0.6, 0.2})}};
    std::mt19937 random(21);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (const ConstantCase& c : cases) {
        const ReliefGeometry relief{&map, s, c.base};
        const bool column = c.base.kind == BaseKind::Cylinder;
        glm::dvec3 scale = c.base.frameScale() * 1.1;
        if (column) scale.y = c.base.frameScale().y;  // the caps stay at +-L/2
        int hits = 0, caps = 0;
        for (int k = 0; k < 2000; ++k) {
            const glm::dvec3 eye = 1.5 * glm::dvec3{unit(random), unit(random), unit(random)};
            const glm::dvec3 aim = 0.5 * glm::dvec3{unit(random), unit(random), unit(random)};
            const Ray ray = through(eye, aim);
            bool cap = false;
            const auto exact = enterScaled(ray, scale, column, cap);
            if (exact && *exact == 0.0) continue;  // the eye inside the solid
            const ReferenceHit hit = traceReference(relief, ray);
            ASSERT_EQ(static_cast<bool>(hit), exact.has_value()) << c.name << " ray " << k;
            if (!hit) continue;
            ++hits;
            caps += cap;
            EXPECT_NEAR(hit.t, *exact, 1e-9) << c.name << " ray " << k;
            EXPECT_EQ(hit.face, cap ? HitFace::Cap : HitFace::Top) << c.name << " ray " << k;
            // The normal of the scaled ball or column.
            glm::dvec3 q = hit.position / scale;
            if (column && !cap) q.y = 0.0;
            const glm::dvec3 n =
                cap ? glm::dvec3(0.0, q.y > 0 ? 1.0 : -1.0, 0.0) : glm::normalize(q / scale);
            EXPECT_GT(glm::dot(hit.normal, n), 1.0 - 1e-9) << c.name << " ray " << k;
        }
        EXPECT_GT(hits, 500) << c.name;
        if (column) {
            EXPECT_GT(caps, 50);
        }
    }
}

TEST(CurvedReference, OneRaisedSamplePeaksAtItsOwnDirection) {
    const int w = 16, h = 8, i = 5, j = 3;
    const HeightMap map = synth::spike(w, h, i, j);
    // Bilinear: the sample's height itself, 1; biquadratic: the B-spline's 3/4 x 3/4.
    for (const auto& [base, interpolation, peak] :
         std::vector<std::tuple<BaseShape, Interpolation, double>>{
             {BaseShape::sphere(0.5), Interpolation::Bilinear, 1.0},
             {BaseShape::cylinder(0.3, 1.0), Interpolation::Bilinear, 1.0},
             {BaseShape::sphere(0.5), Interpolation::Biquadratic, 0.5625},
             {BaseShape::cylinder(0.3, 1.0), Interpolation::Biquadratic, 0.5625}}) {
        const ReliefGeometry relief{&map, 0.3, base, interpolation};
        // The sample's direction: u = (i + 0.5) / W, v = (j + 0.5) / H.
        const double phi = 2.0 * kPi * ((i + 0.5) / w - 0.5), v = (j + 0.5) / h;
        glm::dvec3 q;
        if (base.kind == BaseKind::Cylinder) {
            q = {std::sin(phi), 1.0 - 2.0 * v, std::cos(phi)};
        } else {
            const double theta = kPi * v;
            q = {std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
        }
        // From outside, straight at the axis (or centre) through the sample: the peak at
        // radius 1 + s peak.
        glm::dvec3 inward = -q;
        if (base.kind == BaseKind::Cylinder) inward.y = 0.0;
        const glm::dvec3 scale = base.frameScale();
        const double radius = 1.0 + 0.3 * peak;
        const glm::dvec3 worldPeak = base.kind == BaseKind::Cylinder
                                         ? q * glm::dvec3(radius, 1.0, radius) * scale
                                         : q * radius * scale;
        const glm::dvec3 worldEye = worldPeak - 2.0 * glm::normalize(inward * scale) * 1.0;
        const ReferenceHit hit = traceReference(relief, through(worldEye, worldPeak));
        ASSERT_TRUE(hit);
        EXPECT_EQ(hit.face, HitFace::Top);
        EXPECT_NEAR(glm::length(hit.position - worldPeak), 0.0, 1e-9)
            << baseName(base) << " " << interpolationName(interpolation);
        EXPECT_NEAR(hit.uv.x, (i + 0.5) / w, 1e-9);
        EXPECT_NEAR(hit.uv.y, v, 1e-9);
    }
}

TEST(CurvedReference, ARayAlongTheAxisMeetsACapOrAPole) {
    HeightMap map = synth::valueNoise(24, 10, 5.0, 3, 4);
    {
        const ReliefGeometry column{&map, 0.1, BaseShape::cylinder(0.3, 1.0)};
        const ReferenceHit cap = traceReference(column, {{0.02, 2.0, -0.01}, {0.0, -1.0, 0.0}});
        ASSERT_TRUE(cap);
        EXPECT_EQ(cap.face, HitFace::Cap);
        EXPECT_DOUBLE_EQ(cap.position.y, 0.5);
        EXPECT_NEAR(cap.normal.y, 1.0, 1e-12);
        const ReferenceHit under = traceReference(column, {{0.02, -2.0, -0.01}, {0.0, 1.0, 0.0}});
        ASSERT_TRUE(under);
        EXPECT_EQ(under.face, HitFace::Cap);
        EXPECT_DOUBLE_EQ(under.position.y, -0.5);
        // Beside the column, along the axis: a miss.
        EXPECT_FALSE(traceReference(column, {{0.5, 2.0, 0.0}, {0.0, -1.0, 0.0}}));
    }
    {
        const ReliefGeometry globe{&map, 0.1, BaseShape::sphere(0.5)};
        // Down the axis onto the +y pole: u there is atan2(0, 0) = 0, so X = W / 2; v = 0
        // is the map's first row, clamped.
        const double top = 1.0 + 0.1 * map.surface(0.5 * map.width, 0.0, true);
        const ReferenceHit pole = traceReference(globe, {{0.0, 2.0, 0.0}, {0.0, -1.0, 0.0}});
        ASSERT_TRUE(pole);
        EXPECT_NEAR(pole.position.y, 0.5 * top, 1e-9);
        EXPECT_NEAR(pole.position.x, 0.0, 1e-12);
        const double bottom = 1.0 + 0.1 * map.surface(0.5 * map.width, map.height, true);
        const ReferenceHit south = traceReference(globe, {{0.0, -2.0, 0.0}, {0.0, 1.0, 0.0}});
        ASSERT_TRUE(south);
        EXPECT_NEAR(south.position.y, -0.5 * bottom, 1e-9);
    }
}

TEST(CurvedReference, TheSeamJoinsTheLastColumnToTheFirst) {
    // Column 0 low, column W - 1 high: at u = 0 (X = 0, the seam at -z) the surface is
    // their average.
    HeightMap map = synth::flat(8, 4, 0.0f);
    for (int j = 0; j < 4; ++j) map.at(7, j) = 1.0f;
    const ReliefGeometry globe{&map, 0.4, BaseShape::sphere(0.5)};
    const ReferenceHit seam = traceReference(globe, {{0.0, 0.0, -3.0}, {0.0, 0.0, 1.0}});
    ASSERT_TRUE(seam);
    EXPECT_NEAR(seam.position.z, -0.5 * (1.0 + 0.4 * 0.5), 1e-9);
    const ReliefGeometry column{&map, 0.4, BaseShape::cylinder(0.3, 1.0)};
    const ReferenceHit side = traceReference(column, {{0.0, 0.1, -3.0}, {0.0, 0.0, 1.0}});
    ASSERT_TRUE(side);
    EXPECT_NEAR(side.position.z, -0.3 * (1.0 + 0.4 * 0.5), 1e-9);
}

// Random maps, random rays: a hit lies on the solid's boundary, and no point of the ray
// before it lies inside; a miss has no point inside at all.
TEST(CurvedReference, RandomRaysHitTheSolidFirstWhereTheyEnterIt) {
    std::mt19937 random(22);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), zeroOne(0.0, 1.0);
    const BaseShape bases[] = {BaseShape::cylinder(0.3, 1.0), BaseShape::sphere(0.5),
                               BaseShape::ellipsoid({0.25, 0.5, 0.4}),
                               BaseShape::cylinder(0.5, 0.4)};
    int hits = 0, misses = 0, caps = 0;
    for (int trial = 0; trial < 24; ++trial) {
        const int w = 1 + static_cast<int>(zeroOne(random) * 40),
                  h = 1 + static_cast<int>(zeroOne(random) * 20);
        const HeightMap map = trial % 3 == 0 ? synth::whiteNoise(w, h, trial)
                                             : synth::valueNoise(w, h, 4.0, 3, trial);
        const BaseShape& base = bases[trial % 4];
        const Solid solid{{&map, 0.05 + 0.4 * zeroOne(random), base,
                           trial % 3 == 1 ? Interpolation::Biquadratic : Interpolation::Bilinear}};
        const glm::dvec3 box = base.boxMax(w, h, solid.relief.heightScale * map.maxValue());
        for (int n = 0; n < 40; ++n) {
            glm::dvec3 eye;
            do {
                eye = 2.0 * box * glm::dvec3{unit(random), unit(random), unit(random)};
            } while (solid.deepInside(eye, 0.0));
            // Aimed at the body, or anywhere.
            const Ray ray =
                n % 2 == 0
                    ? through(eye, 0.6 * box * glm::dvec3{unit(random), unit(random), unit(random)})
                    : Ray{eye, glm::dvec3{unit(random), unit(random), unit(random)}};
            const ReferenceHit hit = traceReference(solid.relief, ray);
            SCOPED_TRACE(testing::Message()
                         << "trial " << trial << " ray " << n << " " << baseName(base));
            const double tEnd = hit ? hit.t : 4.0;
            for (int k = 0; k < 4000; ++k) {
                const double t = tEnd * k / 4000.0 * (1.0 - 1e-9);
                ASSERT_FALSE(solid.deepInside(ray.origin + t * ray.direction, 1e-9))
                    << "inside at t = " << t << " before " << (hit ? "the hit" : "the end");
            }
            if (!hit) {
                ++misses;
                continue;
            }
            ++hits;
            const glm::dvec3 q = solid.frame(hit.position);
            if (hit.face == HitFace::Cap) {
                ++caps;
                EXPECT_NEAR(std::abs(q.y), 1.0, 1e-12);
                EXPECT_LE(solid.radial(q), solid.surfaceRadius(q) + 1e-9);
            } else {
                ASSERT_EQ(hit.face, HitFace::Top);
                EXPECT_NEAR(solid.radial(q), solid.surfaceRadius(q), 1e-8);
            }
        }
    }
    EXPECT_GT(hits, 300);
    EXPECT_GT(misses, 100);
    EXPECT_GT(caps, 10);
}
