// The base-surface seam (core/base/BaseSurface.h) and the wrapped pyramid: the bounds the
// traversal relies on, property-tested against the path of the ray densely sampled. A
// bound that is ever on the wrong side of a sampled point fails here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "microrelief/core/base/BaseMeshes.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

constexpr double kPi = std::numbers::pi;

// Random lines in the canonical frame that pass through the shell of radius up to 1.3:
// through random points near the surface, some almost through the axis or a pole, some
// parallel to the axis.
FrameRay randomLine(std::mt19937& random, int kind) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), radius(0.0, 1.3);
    std::normal_distribution<double> normal;
    glm::dvec3 through{unit(random), unit(random), unit(random)};
    through *= radius(random) / std::max(glm::length(through), 1e-9);
    glm::dvec3 dir(normal(random), normal(random), normal(random));
    if (kind == 1) through.x = through.z = 1e-7 * unit(random);  // next to the axis
    if (kind == 2) dir.x = dir.z = 0.0;                          // along the axis
    if (kind == 3) {                                             // at a pole, nearly
        through = {1e-6 * unit(random), 1.05, 1e-6 * unit(random)};
    }
    if (glm::length(dir) < 1e-6) dir.y = 1.0;
    const double back = 2.0 + 3.0 * std::abs(unit(random));
    return {through - back * dir / glm::length(dir), dir / glm::length(dir)};
}

struct Curved {
    const char* name;
    BaseShape shape;
    int width, height;
};

const Curved kCurved[] = {
    {"cylinder 64x32", BaseShape::cylinder(), 64, 32},
    {"cylinder 5x3", BaseShape::cylinder(0.5, 2.0), 5, 3},
    {"sphere 128x64", BaseShape::sphere(), 128, 64},
    {"ellipsoid 7x9", BaseShape::ellipsoid({0.3, 0.6, 0.2}), 7, 9},
    {"sphere 1x1", BaseShape::sphere(), 1, 1},
};

// Whether X lies in the footprint's X range, which may wrap across u = 0.
bool inRangeX(double x, const Footprint& f, int width) {
    return (x >= f.lo.x && x <= f.hi.x) || (x + width >= f.lo.x && x + width <= f.hi.x);
}

}  // namespace

TEST(BaseSurface, CurvedFootprintHoldsThePathOfEverySegment) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> zeroOne(0.0, 1.0);
    for (const Curved& c : kCurved) {
        const auto surface = BaseSurface::make(c.shape, c.width, c.height, 0.2, 1.0);
        int wrapped = 0, wide = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            const FrameRay ray = randomLine(random, trial % 7 == 0 ? 1 + (trial / 7) % 3 : 0);
            // Segments from slivers to the whole chord.
            const double ta = 6.0 * zeroOne(random), length = std::pow(zeroOne(random), 3.0) * 4.0;
            const double tb = ta + length;
            const Footprint f = surface->footprint(ray, ta, tb);
            wrapped += f.hi.x > c.width;
            wide += f.hi.x - f.lo.x > 0.25 * c.width;
            ASSERT_LE(f.lo.x, f.hi.x);
            ASSERT_GE(f.lo.x, 0.0);
            ASSERT_LT(f.lo.x, c.width);
            for (int k = 0; k <= 400; ++k) {
                const double t = ta + (tb - ta) * k / 400.0;
                const glm::dvec3 m = surface->mapPoint(ray.at(t));
                ASSERT_TRUE(inRangeX(m.x, f, c.width))
                    << c.name << " trial " << trial << " X " << m.x << " outside [" << f.lo.x
                    << ", " << f.hi.x << "]";
                ASSERT_GE(m.y, f.lo.y) << c.name << " trial " << trial;
                ASSERT_LE(m.y, f.hi.y) << c.name << " trial " << trial;
                ASSERT_GE(m.z, f.lowest) << c.name << " trial " << trial << " at t " << t;
            }
            ASSERT_GE(f.drop, 0.0);
            EXPECT_DOUBLE_EQ(surface->lowest(ray, ta, tb), f.lowest);
        }
        // The cases the footprint has to get right happened.
        EXPECT_GT(wrapped, 20) << c.name;
        EXPECT_GT(wide, 5) << c.name;
    }
}

TEST(BaseSurface, CurvedLowestIsAttained) {
    // Not just below the path: the lowest height is the path's own minimum, so a bound
    // this tight is what the traversal compares (within the margin).
    std::mt19937 random(12);
    for (const Curved& c : kCurved) {
        const auto surface = BaseSurface::make(c.shape, c.width, c.height, 0.1, 1.0);
        for (int trial = 0; trial < 500; ++trial) {
            const FrameRay ray = randomLine(random, 0);  // unit direction
            double sampled = HUGE_VAL;
            for (int k = 0; k <= 2000; ++k)
                sampled = std::min(sampled, surface->mapPoint(ray.at(1.0 + k / 1000.0)).z);
            // Between samples 1e-3 apart the radial distance changes by 1e-3 at most.
            const double lowest = surface->lowest(ray, 1.0, 3.0);
            EXPECT_LE(lowest, sampled) << c.name;
            EXPECT_GE(lowest, sampled - 1e-3 / 0.1 - 1e-9) << c.name;
        }
    }
}

TEST(BaseSurface, CrossingsLieOnTheirBoundaries) {
    std::mt19937 random(13);
    std::uniform_real_distribution<double> zeroOne(0.0, 1.0);
    for (const Curved& c : kCurved) {
        const auto base = BaseSurface::make(c.shape, c.width, c.height, 0.1, 1.0);
        const auto& surface = dynamic_cast<const CurvedSurface&>(*base);
        int crossedX = 0, crossedY = 0;
        for (int trial = 0; trial < 2000; ++trial) {
            const FrameRay ray = randomLine(random, 0);
            const double x = std::floor(zeroOne(random) * c.width) + 0.5;
            if (const auto t = surface.crossX(ray, x, -1e300)) {
                ++crossedX;
                const double at = surface.mapX(ray.at(*t));
                EXPECT_NEAR(std::remainder(at - x, c.width), 0.0, 1e-9) << c.name;
            }
            const double y = std::floor(zeroOne(random) * c.height) + 0.5;
            if (y >= c.height) continue;
            // Where the traversal needs it: in the shell, away from the centre, where every
            // cone meets and the latitude turns on a pin.
            if (const auto t = surface.crossY(ray, y, -1e9, 1e9);
                t && surface.radial(ray.at(*t)) > 0.5) {
                ++crossedY;
                EXPECT_NEAR(surface.mapY(ray.at(*t)), y, 1e-7) << c.name;
            }
        }
        EXPECT_GT(crossedX, 500) << c.name;
        EXPECT_GT(crossedY, 500) << c.name;
    }
}

TEST(BaseSurface, LatitudeTurnsOnceWhereTheTurnSays) {
    const auto base = BaseSurface::make(BaseShape::sphere(), 16, 16, 0.1, 1.0);
    const auto& surface = dynamic_cast<const CurvedSurface&>(*base);
    std::mt19937 random(14);
    for (int trial = 0; trial < 500; ++trial) {
        const FrameRay ray = randomLine(random, 0);
        const auto turn = surface.turnY(ray);
        ASSERT_TRUE(turn);
        // Y is monotone on either side of the turn.
        const auto y = [&](double t) { return surface.mapY(ray.at(t)); };
        const double before = y(*turn - 1e-3) - y(*turn - 2e-3),
                     after = y(*turn + 2e-3) - y(*turn + 1e-3);
        EXPECT_LE(before * after, 1e-12) << trial;
    }
}

TEST(BaseSurface, DescendToIsNeverLate) {
    std::mt19937 random(15);
    std::uniform_real_distribution<double> height(0.0, 1.0);
    for (const Curved& c : kCurved) {
        const auto surface = BaseSurface::make(c.shape, c.width, c.height, 0.2, 1.0);
        for (int trial = 0; trial < 1000; ++trial) {
            const FrameRay ray = randomLine(random, 0);
            const double h = height(random);
            const double t = surface->descendTo(ray, 0.0, 8.0, h);
            ASSERT_GE(t, 0.0);
            ASSERT_LE(t, 8.0);
            for (int k = 0; k < 200 && t > 0.0; ++k) {
                const double before = t * k / 200.0;
                ASSERT_GT(surface->mapPoint(ray.at(before)).z, h - 1e-9) << c.name;
            }
        }
    }
}

TEST(BaseSurface, ShellHoldsTheRelief) {
    std::mt19937 random(16);
    for (const Curved& c : kCurved) {
        const double top = 0.8;  // the map's max: the shell is 1 + s top
        const auto surface = BaseSurface::make(c.shape, c.width, c.height, 0.25, top);
        const bool cylinder = c.shape.kind == BaseKind::Cylinder;
        int inside = 0, outside = 0;
        for (int trial = 0; trial < 500; ++trial) {
            const FrameRay ray = randomLine(random, 0);
            const ShellSpan span = surface->clip(ray);
            for (int k = 0; k <= 1000; ++k) {
                const double t = -2.0 + 12.0 * k / 1000.0;
                const glm::dvec3 q = ray.at(t);
                const double h = surface->mapPoint(q).z, y = cylinder ? std::abs(q.y) : 0.0;
                const bool inSpan = !span.empty() && t >= span.tEnter && t <= span.tExit;
                if (h < top - 1e-6 && y < 1.0 - 1e-6) {
                    ++inside;
                    ASSERT_TRUE(inSpan) << c.name << " trial " << trial << " t " << t;
                } else if (h > top + 1e-6 || y > 1.0 + 1e-6) {
                    ++outside;
                    ASSERT_FALSE(inSpan) << c.name << " trial " << trial << " t " << t;
                }
            }
        }
        EXPECT_GT(inside, 10000) << c.name;
        EXPECT_GT(outside, 10000) << c.name;
    }
}

// The normal from the seam against the surface's own parametrisation, differentiated
// numerically: q(X, Y) = (1 + s h(X, Y)) w(X, Y) (or the cylinder's column).
TEST(BaseSurface, TopNormalIsNormalToTheSurface) {
    std::mt19937 random(17);
    std::uniform_real_distribution<double> unit(0.0, 1.0), slope(-3.0, 3.0);
    for (const Curved& c : kCurved) {
        const double s = 0.2;
        const auto surface = BaseSurface::make(c.shape, c.width, c.height, s, 1.0);
        for (int trial = 0; trial < 300; ++trial) {
            const double x = unit(random) * c.width, y = (0.05 + 0.9 * unit(random)) * c.height;
            const double h0 = unit(random);
            const glm::dvec2 g(slope(random), slope(random));
            // A plane of heights with gradient g through (x, y, h0).
            const auto point = [&](double px, double py) {
                const double h = h0 + g.x * (px - x) + g.y * (py - y), r = 1.0 + s * h;
                const double phi = 2.0 * kPi * (px / c.width - 0.5);
                if (c.shape.kind == BaseKind::Cylinder)
                    return glm::dvec3(r * std::sin(phi), 1.0 - 2.0 * py / c.height,
                                      r * std::cos(phi));
                const double theta = kPi * py / c.height;
                return r * glm::dvec3(std::sin(theta) * std::sin(phi), std::cos(theta),
                                      std::sin(theta) * std::cos(phi));
            };
            const double e = 1e-6;
            const glm::dvec3 dx = point(x + e, y) - point(x - e, y),
                             dy = point(x, y + e) - point(x, y - e);
            const glm::dvec3 n = glm::normalize(surface->topNormal(point(x, y), g));
            EXPECT_NEAR(glm::dot(n, glm::normalize(dx)), 0.0, 1e-6) << c.name;
            EXPECT_NEAR(glm::dot(n, glm::normalize(dy)), 0.0, 1e-6) << c.name;
            glm::dvec3 away = point(x, y);
            if (c.shape.kind == BaseKind::Cylinder) away.y = 0.0;
            EXPECT_GT(glm::dot(n, away), 0.0) << c.name << ": outward";
        }
    }
}

// The pyramid of a wrapped map bounds the surface across the seam: the finest texels at
// the seam see the other side's samples, and a footprint across it reads both parts.
// core/base/BaseMeshes.h's meshes lie on the bases they copy, by the bases' own mapping
// (BaseType::objectPoint, the inverse of BaseSurface::mapPoint): each vertex is the object
// point over its texture coordinate times the map's size at height 0, and its normal the
// base's top normal there (a flat map: gradient 0; BaseSurface::topNormal at the frame point
// BaseSurface::frameRay gives it), or its opposite for an inward tube. Seen red with the
// tube's phi a quarter turn off and with the grid's z taken from u.
TEST(BaseMeshes, EachVertexLiesWhereItsBaseMapsItsTextureCoordinate) {
    const int width = 64, height = 32;
    const double s = 0.1;
    struct Case {
        const char* name;
        BaseShape base;
        TriangleMesh mesh;
        double normalSign;
    };
    const std::vector<Case> cases = {
        {"grid", BaseShape::plane(), planeGridMesh(8, 1.0f, 0.5f), 1.0},
        {"tube", BaseShape::cylinder(0.5, 2.0), cylinderTubeMesh(24, 6, 0.5f, 2.0f), 1.0},
        {"inward tube", BaseShape::cylinder(0.5, 2.0), cylinderTubeMesh(24, 6, 0.5f, 2.0f, true),
         -1.0}};
    for (const Case& c : cases) {
        const BaseType& type = baseType(c.base);
        const auto surface = BaseSurface::make(c.base, width, height, s, 1.0);
        for (std::size_t k = 0; k < c.mesh.vertexCount(); ++k) {
            const glm::dvec2 texel = glm::dvec2(c.mesh.texCoords[k]) * glm::dvec2(width, height);
            const glm::dvec3 expected = type.objectPoint(c.base, width, height, s, texel, 0.0);
            // The mesh's float positions: within a few float ulps of the unit.
            EXPECT_LT(glm::length(glm::dvec3(c.mesh.positions[k]) - expected), 1e-6)
                << c.name << " vertex " << k;
            const glm::dvec3 q = surface->frameRay(Ray{expected, glm::dvec3(0.0, 0.0, 1.0)}).origin;
            const glm::dvec3 normal = surface->worldNormal(surface->topNormal(q, glm::dvec2(0.0)));
            EXPECT_NEAR(glm::dot(normal, glm::dvec3(c.mesh.normals[k])), c.normalSign, 1e-6)
                << c.name << " vertex " << k;
        }
    }
}

TEST(MaxPyramidWrapped, BoundsTheSurfaceAcrossTheSeam) {
    std::mt19937 random(18);
    for (auto [w, h] :
         std::vector<std::pair<int, int>>{{1, 1}, {2, 3}, {13, 6}, {64, 32}, {100, 7}}) {
        HeightMap map = synth::whiteNoise(w, h, static_cast<std::uint32_t>(w + 7 * h));
        // The seam's two sides differ sharply.
        for (int j = 0; j < h; ++j) {
            map.at(0, j) = 0.0f;
            map.at(w - 1, j) = 1.0f;
        }
        const MaxPyramid p(map, true);
        std::uniform_real_distribution<double> x(0.0, w), y(0.0, h), unit(0.0, 1.0);
        for (int trial = 0; trial < 3000; ++trial) {
            glm::dvec2 lo(x(random), y(random));
            const glm::dvec2 size{std::pow(unit(random), 2.0) * w, std::pow(unit(random), 2.0) * h};
            glm::dvec2 hi = glm::min(lo + size, glm::dvec2(lo.x + w, h));
            const BoundRead read = p.footprintBound(lo, hi);
            const double bound = read.bound;
            // One window, or one on each side of the seam, each a fetch the shader counts.
            ASSERT_EQ(read.fetches, hi.x >= w ? 2 : 1)
                << w << "x" << h << " footprint [" << lo.x << ", " << hi.x << "]";
            for (int b = 0; b <= 40; ++b) {
                for (int a = 0; a <= 40; ++a) {
                    const double px = lo.x + (hi.x - lo.x) * a / 40.0,
                                 py = lo.y + (hi.y - lo.y) * b / 40.0;
                    const double surface = map.surface(std::fmod(px, w), py, true);
                    ASSERT_GE(bound, surface - 1e-12)
                        << w << "x" << h << " footprint [" << lo.x << ", " << hi.x << "] x ["
                        << lo.y << ", " << hi.y << "] at " << px << "," << py;
                }
            }
        }
        // The seam texel sees the other side: at X = 0 the surface is the average of
        // columns W - 1 (1) and 0 (0). Clamped, it would be column 0's 0 there.
        for (int j = 0; j < h && w > 1; ++j) EXPECT_GE(p.block(0, 0, j), 0.5f) << w << "x" << h;
    }
}
