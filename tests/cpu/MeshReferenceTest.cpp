// The mesh's exact reference (core/trace/MeshReference.h) against the other exact
// references where the mesh is their base (a flat grid is the plane, a fine tube the
// cylinder), against hits known in closed form (the wall at a UV seam, the mesh itself from
// below, the eye inside the shell, a folded shell's far side, a ray lying in one offset plane
// of a curved triangle), and, on folded meshes with random normals and a twisted prism,
// against the contract's definition of a hit checked point by point.
#include "microrelief/core/trace/MeshReference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "microrelief/core/base/BaseMeshes.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/ReferenceTracer.h"

namespace microrelief {
namespace {

constexpr double kPi = std::numbers::pi;

// The map with its last column equal to its first and its last row equal to its first:
// over [0, 1]^2 its surface repeated (the mesh's addressing) is then the surface clamped to
// the edge (the plane's) and the surface wrapped in u (the cylinder's), bilinear and
// biquadratic alike: wherever the two rules read different samples those samples are equal.
HeightMap seamless(HeightMap map) {
    for (int j = 0; j < map.height; ++j) map.at(map.width - 1, j) = map.at(0, j);
    for (int i = 0; i < map.width; ++i) map.at(i, map.height - 1) = map.at(i, 0);
    return map;
}

// The contract's h(uv), repeated in u and v, through HeightMap::surface (independent of
// the reference's own patches): wrapped in u by surface(), repeated in v here, which for a
// seamless() map is the same as its clamping.
double contractHeight(const HeightMap& map, Interpolation interpolation, glm::dvec2 uv) {
    const double u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
    return map.surface(u * map.width, v * map.height, true, interpolation);
}

MeshSurface expectedSurface(const ReferenceHit& hit) {
    if (hit.t == 0.0) return MeshSurface::Inside;
    switch (hit.face) {
        case HitFace::Top:
            return MeshSurface::Top;
        case HitFace::Bottom:
            return MeshSurface::Base;
        case HitFace::WallX:
        case HitFace::WallZ:
            return MeshSurface::Wall;
        default:
            return MeshSurface::None;
    }
}

const char* surfaceName(MeshSurface surface) {
    switch (surface) {
        case MeshSurface::None:
            return "none";
        case MeshSurface::Top:
            return "top";
        case MeshSurface::Base:
            return "base";
        case MeshSurface::Wall:
            return "wall";
        case MeshSurface::Fold:
            return "fold";
        case MeshSurface::Inside:
            return "inside";
    }
    return "?";
}

// ---- A flat grid is the plane ----

// Rays of one kind over the plane's box [-1/2, 1/2] x [0, top] x [-1/4, 1/4].
struct RayFamily {
    const char* name;
    // A ray drawn with `random`; `top` is the shell's height, s max h.
    Ray (*make)(std::mt19937& random, double top);
};

double uniform(std::mt19937& random, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(random);
}

glm::dvec3 inFootprint(std::mt19937& random, double ylo, double yhi) {
    return {uniform(random, -0.5, 0.5), uniform(random, ylo, yhi), uniform(random, -0.25, 0.25)};
}

// An eye on a circle of radius 1 around the footprint, at height y.
glm::dvec3 around(std::mt19937& random, double y) {
    const double angle = uniform(random, 0.0, 2.0 * kPi);
    return {std::cos(angle), y, std::sin(angle)};
}

const RayFamily kPlaneRays[] = {
    {"from above",
     [](std::mt19937& r, double top) {
         const glm::dvec3 eye = {uniform(r, -1, 1), uniform(r, 0.2, 1.0), uniform(r, -1, 1)};
         return Ray{eye, inFootprint(r, 0.0, top) - eye};
     }},
    {"grazing, 1e-3",
     [](std::mt19937& r, double top) {
         const glm::dvec3 eye = around(r, uniform(r, 0.0, top));
         glm::dvec3 d = inFootprint(r, 0.0, 0.0) - eye;
         d.y = uniform(r, -1e-3, 1e-3);
         return Ray{eye, d};
     }},
    {"grazing, 1e-9",
     [](std::mt19937& r, double top) {
         const glm::dvec3 eye = around(r, uniform(r, 0.0, top));
         glm::dvec3 d = inFootprint(r, 0.0, 0.0) - eye;
         d.y = uniform(r, -1e-9, 1e-9);
         return Ray{eye, d};
     }},
    {"grazing, 1e-15",
     [](std::mt19937& r, double top) {
         const glm::dvec3 eye = around(r, uniform(r, 0.0, top));
         glm::dvec3 d = inFootprint(r, 0.0, 0.0) - eye;
         d.y = uniform(r, -1e-15, 1e-15);
         return Ray{eye, d};
     }},
    {"level",  // parallel to every offset plane: the level pieces
     [](std::mt19937& r, double top) {
         const glm::dvec3 eye = around(r, uniform(r, 0.0, top));
         glm::dvec3 d = inFootprint(r, 0.0, 0.0) - eye;
         d.y = 0.0;
         return Ray{eye, d};
     }},
    {"through the border walls",
     [](std::mt19937& r, double top) {
         const glm::dvec3 eye = around(r, uniform(r, 0.0, 0.5 * top));
         const glm::dvec3 aim = inFootprint(r, 0.0, top);
         return Ray{eye, aim - eye};
     }},
    {"from below",
     [](std::mt19937& r, double top) {
         const glm::dvec3 eye = {uniform(r, -1, 1), uniform(r, -1.0, -0.1), uniform(r, -1, 1)};
         return Ray{eye, inFootprint(r, 0.0, top) - eye};
     }},
    {"from inside the shell",  // in the solid or in the air between its bumps
     [](std::mt19937& r, double top) {
         const glm::dvec3 eye = inFootprint(r, 0.0, top);
         const glm::dvec3 d = {uniform(r, -1, 1), uniform(r, -1, 1), uniform(r, -1, 1)};
         return Ray{eye, d};
     }},
};

// Both references solve the same solid in double precision to about 1e-12 of the scene
// (the plane's quadratic per cell; the mesh's bisection to 1e-12 of its diagonal). A hit on
// a surface met at a grazing angle g moves along the ray by the rounding over g; on these
// noise maps the surface at a hit is sloped, so 1e-9 holds for rays down to level ones.
constexpr double kSamePosition = 1e-9;

// Noise, and noise with plateaus at 0 (there the top is the mesh: from above a Top hit,
// from below a Base one).
HeightMap withZeroPlateaus(HeightMap map) {
    for (float& h : map.samples) h = std::max(0.0f, 2.0f * h - 1.0f);
    return map;
}

TEST(MeshReference, AFlatGridIsThePlane) {
    // 32 x 16: the footprint a = 1, b = 1/2, exact in float, as are the grid's n = 8 steps.
    const HeightMap noise = seamless(synth::valueNoise(32, 16, 5.0, 3, 7));
    for (const HeightMap& map : {noise, withZeroPlateaus(noise)}) {
        const double s = 0.1, top = s * map.maxValue();
        for (const Interpolation interpolation :
             {Interpolation::Bilinear, Interpolation::Biquadratic}) {
            // uv over [0, 1]^2, and shifted by whole periods: the map repeats in u and v.
            for (const glm::vec2 shift : {glm::vec2(0.0f), glm::vec2(1.0f, -2.0f)}) {
                const MeshReference mesh(planeGridMesh(8, 1.0f, 0.5f, shift), map, s, interpolation);
                const ReferenceTracer plane(
                    ReliefGeometry{&map, s, BaseShape::plane(), interpolation});
                std::mt19937 random(11);
                for (const RayFamily& family : kPlaneRays) {
                    int hits = 0;
                    for (int k = 0; k < 150; ++k) {
                        const Ray ray = family.make(random, top);
                        const ReferenceHit expected = plane.trace(ray);
                        const MeshHit hit = mesh.trace(ray);
                        const std::string where =
                            std::string(family.name) + ", " + interpolationName(interpolation) +
                            ", shift " + std::to_string(shift.x) + ", ray " + std::to_string(k);
                        ASSERT_EQ(static_cast<bool>(hit), static_cast<bool>(expected)) << where;
                        if (!hit) continue;
                        ++hits;
                        EXPECT_NEAR(hit.t * glm::length(ray.direction),
                                    expected.t * glm::length(ray.direction), kSamePosition)
                            << where;
                        EXPECT_LE(glm::length(hit.position - expected.position), kSamePosition)
                            << where;
                        EXPECT_EQ(hit.surface, expectedSurface(expected))
                            << where << ": " << surfaceName(hit.surface);
                        // The hit's own report: uv (less the shift) and height are the plane's.
                        EXPECT_NEAR(hit.uv.x - shift.x, expected.uv.x, 1e-9) << where;
                        EXPECT_NEAR(hit.uv.y - shift.y, expected.uv.y, 1e-9) << where;
                        EXPECT_NEAR(s * hit.height, expected.position.y, 1e-9) << where;
                        // The outward normal: the plane's (top, walls, bottom), to the
                        // slopes' change over the positions' 1e-9 and rounding.
                        if (hit.surface != MeshSurface::Inside) {
                            EXPECT_LE(glm::length(hit.normal - expected.normal), 1e-6)
                                << where << ": " << surfaceName(hit.surface);
                        }
                    }
                    // Each family reaches the relief often (the level and grazing ones from
                    // any height in the shell): no family passes by missing.
                    EXPECT_GT(hits, 40) << family.name;
                }
            }
        }
    }
}

// ---- A fine tube is the cylinder ----

TEST(MeshReference, AFineTubeIsCloseToTheCylinder) {
    const double radius = 0.3, length = 1.0, s = 0.1;  // the cylinder's s: of the radius
    const HeightMap map = seamless(synth::valueNoise(32, 16, 5.0, 3, 5));
    const int around = 256;
    // The tessellation's error, a radial distance: the mesh's point at height t over a
    // chord is (1 + s t) R D(b) with |D| in [cos a, 1], a = pi / around (B = R D exactly),
    // so the top lies up to (1 + s max h) R (1 - cos a) = 2.5e-5 inside the cylinder's.
    // Its angle departs from the linear uv's by at most 0.13 a^3 (the arctangent of a
    // chord's parameter against the parameter), 3.8e-8 of a turn, 1e-6 texels, which moves
    // h by less than 1e-6 s R here; float positions and normals add 1e-7 R.
    const double chordGap = (1.0 + s * map.maxValue()) * radius * (1.0 - std::cos(kPi / around));
    const double radialError = chordGap + 1e-6 * radius;
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        const MeshReference mesh(
            cylinderTubeMesh(around, 4, static_cast<float>(radius), static_cast<float>(length), false), map,
            s * radius, interpolation);
        const ReferenceTracer cylinder(
            ReliefGeometry{&map, s, BaseShape::cylinder(radius, length), interpolation});
        std::mt19937 random(5);
        int compared = 0;
        for (int k = 0; k < 300; ++k) {
            // At a point of the side, from outside, within 40 degrees of the inward normal:
            // the relief's slopes (under 0.1) keep every hit at an angle, so a radial error e
            // moves it by e over the cosine of the incidence along the ray.
            const double phi = uniform(random, -kPi, kPi), y = uniform(random, -0.4, 0.4);
            const glm::dvec3 outward(std::sin(phi), 0.0, std::cos(phi));
            const glm::dvec3 aim = radius * outward + glm::dvec3(0.0, y, 0.0);
            glm::dvec3 away =
                outward + glm::dvec3{uniform(random, -0.6, 0.6), uniform(random, -0.6, 0.6),
                                     uniform(random, -0.6, 0.6)};
            if (glm::dot(glm::normalize(away), outward) < std::cos(40.0 * kPi / 180.0)) continue;
            const Ray ray{aim + 1.5 * glm::normalize(away), -glm::normalize(away)};
            const ReferenceHit expected = cylinder.trace(ray);
            if (!expected || expected.face != HitFace::Top) continue;
            const MeshHit hit = mesh.trace(ray);
            const std::string where =
                std::string(interpolationName(interpolation)) + ", ray " + std::to_string(k);
            ASSERT_TRUE(hit) << where;
            EXPECT_EQ(hit.surface, MeshSurface::Top) << where;
            const double incidence = std::abs(glm::dot(ray.direction, expected.normal));
            EXPECT_LE(glm::length(hit.position - expected.position), radialError / incidence)
                << where;
            // The map's point agrees to the same error over the side's texel size.
            EXPECT_NEAR(hit.uv.x - std::floor(hit.uv.x), expected.uv.x, 1e-4) << where;
            EXPECT_NEAR(hit.uv.y, expected.uv.y, 1e-4) << where;
            ++compared;
        }
        EXPECT_GT(compared, 100);
        // Rays that pass the column by more than the shell: misses for both.
        for (int k = 0; k < 50; ++k) {
            const double phi = uniform(random, -kPi, kPi);
            const glm::dvec3 outward(std::sin(phi), 0.0, std::cos(phi));
            const glm::dvec3 side(std::cos(phi), uniform(random, -0.3, 0.3), -std::sin(phi));
            const Ray ray{2.0 * outward + 0.4 * side, -outward};
            EXPECT_FALSE(cylinder.trace(ray));
            EXPECT_FALSE(mesh.trace(ray)) << "miss " << k;
        }
    }
}

// ---- The wall at a UV seam ----

// Two triangles of one quad whose uvs lie in two regions of the map, heights 0.2 and 0.8:
// where they meet (the edge from (0, 0, -1/2) to (0, 0, 1/2), its vertices duplicated with
// two uvs) the higher prism's wall stands between t = 0.2 and 0.8. The edge's normals lean
// two different ways, so that wall is a ruled surface, not a plane.
struct SeamCase {
    HeightMap map;
    TriangleMesh mesh;
    double s = 0.5;
    glm::dvec3 p1{0.0, 0.0, -0.5}, p2{0.0, 0.0, 0.5};
    // As the mesh holds them, in float.
    glm::dvec3 n1 = glm::vec3(glm::normalize(glm::dvec3(0.3, 1.0, 0.0)));
    glm::dvec3 n2 = glm::vec3(glm::normalize(glm::dvec3(0.0, 1.0, 0.3)));

    SeamCase() : map(8, 8, 0.2f) {
        for (int j = 0; j < 8; ++j)
            for (int i = 4; i < 8; ++i) map.at(i, j) = 0.8f;
        // Constant over both triangles for either interpolation: the low one's uvs within
        // X in [1, 3], the high one's within [5, 7] (a biquadratic square reads its
        // neighbours; a bilinear cell only its own samples).
        const glm::vec3 up(0.0f, 1.0f, 0.0f);
        mesh.positions = {{-1, 0, 0},    glm::vec3(p1), glm::vec3(p2),
                          glm::vec3(p1), {1, 0, 0},     glm::vec3(p2)};
        mesh.normals = {up, glm::vec3(n1), glm::vec3(n2), glm::vec3(n1), up, glm::vec3(n2)};
        mesh.texCoords = {{0.15f, 0.5f}, {0.35f, 0.1f}, {0.35f, 0.9f},
                          {0.65f, 0.1f}, {0.85f, 0.5f}, {0.65f, 0.9f}};
        mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
    }

    // Where the ray meets the wall X = (1 - w) P1 + w P2 + s t ((1 - w) N1 + w N2), w in
    // [0, 1]: Newton on (lambda, w, t) from the middle of the wall, to a residual of 1e-14.
    std::optional<glm::dvec3> wallHit(const Ray& ray) const {
        glm::dvec3 x(1.0, 0.5, 0.5);  // lambda, w, t
        const auto residual = [&](const glm::dvec3& at) {
            const double lambda = at[0], w = at[1], t = at[2];
            return ray.origin + lambda * ray.direction -
                   ((1 - w) * p1 + w * p2 + s * t * ((1 - w) * n1 + w * n2));
        };
        for (int k = 0; k < 50; ++k) {
            const double w = x[1], t = x[2];
            const glm::dmat3 jacobian(ray.direction, -(p2 - p1) - s * t * (n2 - n1),
                                      -s * ((1 - w) * n1 + w * n2));
            x -= glm::inverse(jacobian) * residual(x);
        }
        if (glm::length(residual(x)) > 1e-14 || x[1] < 0.0 || x[1] > 1.0) return std::nullopt;
        return x;
    }
};

TEST(MeshReference, TheWallAtAUvSeamIsHit) {
    const SeamCase seam;
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        const MeshReference reference(seam.mesh, seam.map, seam.s, interpolation);
        // From the low side, level and slanted, between the two tops: into the high wall.
        for (const double y : {0.15, 0.22, 0.3, 0.34}) {
            for (const double z : {-0.3, 0.0, 0.25}) {
                for (const double slope : {0.0, -0.05, 0.05}) {
                    const Ray ray{{-0.5, y, z}, {1.0, slope, 0.1}};
                    const auto expected = seam.wallHit(ray);
                    ASSERT_TRUE(expected);
                    const double t = (*expected)[2];
                    ASSERT_GT(t, 0.2);  // the case as meant: above the low top, below the high
                    ASSERT_LT(t, 0.8);
                    const MeshHit hit = reference.trace(ray);
                    const std::string where = "y " + std::to_string(y) + " z " + std::to_string(z) +
                                              " slope " + std::to_string(slope);
                    ASSERT_TRUE(hit) << where;
                    EXPECT_EQ(hit.surface, MeshSurface::Wall)
                        << where << ": " << surfaceName(hit.surface);
                    EXPECT_EQ(hit.triangle, 1u) << where;
                    EXPECT_NEAR(hit.t, (*expected)[0], 1e-9) << where;
                    EXPECT_NEAR(hit.height, t, 1e-9) << where;
                    EXPECT_NEAR(hit.barycentric[1], 0.0, 1e-9) << where;  // on edge 0-2
                    // The ruled wall's normal dX/dw x dX/dt there, facing the low side the
                    // ray comes from.
                    const double w = (*expected)[1];
                    glm::dvec3 normal = glm::normalize(
                        glm::cross((seam.p2 - seam.p1) + seam.s * t * (seam.n2 - seam.n1),
                                   (1 - w) * seam.n1 + w * seam.n2));
                    if (normal.x > 0.0) normal = -normal;
                    EXPECT_LE(glm::length(hit.normal - normal), 1e-9) << where;
                }
            }
        }
        // Level above the high top (t = 0.8 at about 0.39 up): over both prisms, a miss.
        EXPECT_FALSE(reference.trace({{-0.5, 0.45, 0.0}, {1.0, 0.0, 0.1}}));
        // Level below the low top: the ray starts inside the low prism.
        const MeshHit inside = reference.trace({{-0.5, 0.05, 0.0}, {1.0, 0.0, 0.1}});
        EXPECT_EQ(inside.surface, MeshSurface::Inside);
        EXPECT_EQ(inside.triangle, 0u);
    }
}

// ---- From below the mesh, and from inside the shell ----

// The point where the ray meets the plane of triangle `k` at t = 0, if inside it.
std::optional<glm::dvec3> meshPoint(const TriangleMesh& mesh, std::size_t k, const Ray& ray) {
    const glm::uvec3 tri = mesh.triangles[k];
    const glm::dvec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]],
                     c = mesh.positions[tri[2]];
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double lambda = glm::dot(a - ray.origin, n) / glm::dot(ray.direction, n);
    const glm::dvec3 p = ray.origin + lambda * ray.direction;
    const double area = glm::dot(n, n);
    const double b1 = glm::dot(glm::cross(p - a, c - a), n) / area;
    const double b2 = glm::dot(glm::cross(b - a, p - a), n) / area;
    if (b1 < 0.0 || b2 < 0.0 || b1 + b2 > 1.0 || lambda < 0.0) return std::nullopt;
    return glm::dvec3(lambda, b1, b2);
}

TEST(MeshReference, FromBelowTheMeshAndFromInsideTheShell) {
    const HeightMap map = seamless(synth::valueNoise(16, 16, 4.0, 2, 3));
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        // A coarse tube, normals outward: its hollow is below the mesh. From the axis
        // outward, a ray meets the mesh itself (the chord polygon) at t = 0 first.
        const TriangleMesh mesh = cylinderTubeMesh(12, 2, 0.25f, 1.0f, false);
        const MeshReference reference(mesh, map, 0.05, interpolation);
        std::mt19937 random(8);
        for (int k = 0; k < 100; ++k) {
            // Level enough to reach the tube (radius 1/4) before its open ends (|y| = 1/2).
            const double angle = uniform(random, 0.0, 2.0 * kPi);
            const Ray ray{{uniform(random, -0.05, 0.05), uniform(random, -0.3, 0.3),
                           uniform(random, -0.05, 0.05)},
                          {std::cos(angle), uniform(random, -0.3, 0.3), std::sin(angle)}};
            const MeshHit hit = reference.trace(ray);
            ASSERT_TRUE(hit) << k;
            EXPECT_EQ(hit.surface, MeshSurface::Base) << k << ": " << surfaceName(hit.surface);
            EXPECT_EQ(hit.height, 0.0) << k;
            const auto expected = meshPoint(mesh, hit.triangle, ray);
            ASSERT_TRUE(expected) << k;
            EXPECT_NEAR(hit.t, (*expected)[0], 1e-9) << k;
            EXPECT_NEAR(hit.barycentric[1], (*expected)[1], 1e-9) << k;
            EXPECT_NEAR(hit.barycentric[2], (*expected)[2], 1e-9) << k;
            // The mesh triangle's own normal, towards the hollow the ray comes from.
            const glm::uvec3 tri = mesh.triangles[hit.triangle];
            glm::dvec3 normal = glm::normalize(
                glm::cross(glm::dvec3(mesh.positions[tri[1]] - mesh.positions[tri[0]]),
                           glm::dvec3(mesh.positions[tri[2]] - mesh.positions[tri[0]])));
            if (glm::dot(normal, ray.direction) > 0.0) normal = -normal;
            EXPECT_LE(glm::length(hit.normal - normal), 1e-12) << k;
        }
        // From inside the shell, in the solid: X(b, t) for t below h, any direction; the hit
        // is the origin itself.
        for (int k = 0; k < 100; ++k) {
            const std::size_t index = random() % mesh.triangles.size();
            const glm::uvec3 tri = mesh.triangles[index];
            double b1 = uniform(random, 0, 1), b2 = uniform(random, 0, 1);
            if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
            const glm::dvec3 b(1.0 - b1 - b2, b1, b2);
            glm::dvec3 point(0.0), normal(0.0);
            glm::dvec2 uv(0.0);
            for (int i = 0; i < 3; ++i) {
                point += b[i] * glm::dvec3(mesh.positions[tri[i]]);
                normal += b[i] * glm::dvec3(mesh.normals[tri[i]]);
                uv += b[i] * glm::dvec2(mesh.texCoords[tri[i]]);
            }
            const double t = uniform(random, 0.05, 0.95) * contractHeight(map, interpolation, uv);
            const Ray ray{point + 0.05 * t * normal,
                          {uniform(random, -1, 1), uniform(random, -1, 1), uniform(random, -1, 1)}};
            const MeshHit hit = reference.trace(ray);
            ASSERT_TRUE(hit) << k;
            EXPECT_EQ(hit.surface, MeshSurface::Inside) << k << ": " << surfaceName(hit.surface);
            EXPECT_EQ(hit.t, 0.0) << k;
        }
    }
}

// ---- A folded shell ----

// An inward tube of radius R = 1/4 under a map whose band of columns 12..19 (u about
// 0.39..0.61, the side facing +z) is 1 and the rest 0.1, with s = 3/4: there the shell is
// three radii thick. Each point of that band's prisms is X = (s t - R) D(b): its normal
// lines cross the axis and go on to radius s - R = 1/2 on the far side, beyond the tube.
// Seen from -z, the first point of the union is on the chords between those lines' ends,
// 1/2 N_k (the ends of the interpolated normals over each edge lie on the chord), though
// the mesh there is the far side's, and the low prisms of that side lie behind it.
TEST(MeshReference, AFoldedShellGivesTheFirstHitOfTheUnion) {
    HeightMap map(32, 4, 0.1f);
    for (int j = 0; j < 4; ++j)
        for (int i = 12; i < 20; ++i) map.at(i, j) = 1.0f;
    const double radius = 0.25, s = 0.75, reach = s - radius;
    const TriangleMesh mesh = cylinderTubeMesh(64, 2, static_cast<float>(radius), 1.0f, true);
    // The ends of the normal lines of the ring at y = 0.5 (all rings have the same xz).
    std::vector<glm::dvec2> ends;
    for (int k = 0; k <= 64; ++k)
        ends.push_back(reach * glm::dvec2(mesh.normals[k].x, mesh.normals[k].z));
    // Where the line x = x0 meets that polygon on the far side (z < 0), and that chord's
    // normal in xz facing -z.
    glm::dvec3 chordNormal(0.0);
    const auto farChord = [&](double x0) -> std::optional<double> {
        for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
            const glm::dvec2 a = ends[k], b = ends[k + 1];
            if (a.y > 0.0 || (a.x - x0) * (b.x - x0) > 0.0 || a.x == b.x) continue;
            chordNormal = glm::normalize(glm::dvec3(b.y - a.y, 0.0, a.x - b.x));
            if (chordNormal.z > 0.0) chordNormal = -chordNormal;
            return a.y + (x0 - a.x) / (b.x - a.x) * (b.y - a.y);
        }
        return std::nullopt;
    };
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        const MeshReference reference(mesh, map, s, interpolation);
        for (const double x0 : {0.0, 0.013, -0.04, 0.1, -0.17}) {
            const auto z = farChord(x0);
            ASSERT_TRUE(z);
            ASSERT_LT(*z, -2.0 * radius * 0.9);  // well beyond the tube's far side
            for (const double y0 : {-0.2, 0.1, 0.3}) {
                const std::string where = "x " + std::to_string(x0) + " y " + std::to_string(y0);
                // Level from -z: the chord, on the top of a band prism (t = 1).
                const MeshHit hit = reference.trace({{x0, y0, -2.0}, {0.0, 0.0, 1.0}});
                ASSERT_TRUE(hit) << where;
                EXPECT_EQ(hit.surface, MeshSurface::Top)
                    << where << ": " << surfaceName(hit.surface);
                EXPECT_NEAR(hit.position.z, *z, 1e-9) << where;
                EXPECT_NEAR(hit.height, 1.0, 1e-9) << where;
                // The top there (h = 1 flat) is the offset triangle at t = 1, along the
                // chord: its normal, facing the ray, though D points away from the mesh.
                // (x = 0 is a chord's end, on an edge of the solid, where either side's
                // normal is the surface's.)
                if (x0 != 0.0) {
                    EXPECT_LE(glm::length(hit.normal - chordNormal), 1e-6) << where;
                }
                const glm::dvec2 uv = hit.uv - glm::floor(hit.uv);
                EXPECT_GT(uv.x, 12.5 / 32) << where;  // a band prism's, from the other side
                EXPECT_LT(uv.x, 19.5 / 32) << where;
            }
            // Down along the axis (parallel to every offset plane of the tube's triangles:
            // the level pieces) just inside the chord: through the wall at the tube's end,
            // y = 1/2; just outside it, nothing.
            const MeshHit end = reference.trace({{x0, 2.0, *z + 0.01}, {0.0, -1.0, 0.0}});
            ASSERT_TRUE(end) << x0;
            EXPECT_EQ(end.surface, MeshSurface::Wall) << x0 << ": " << surfaceName(end.surface);
            EXPECT_NEAR(end.position.y, 0.5, 1e-9) << x0;
            // That wall, between two horizontal normal lines of the end ring, is the plane
            // y = 1/2: its normal +y, out of the tube.
            if (x0 != 0.0) {
                EXPECT_LE(glm::length(end.normal - glm::dvec3(0.0, 1.0, 0.0)), 1e-9) << x0;
            }
            EXPECT_FALSE(reference.trace({{x0, 2.0, *z - 0.01}, {0.0, -1.0, 0.0}})) << x0;
        }
    }
}

// ---- The definition of a hit, point by point, on a folded mesh ----

// The real roots in [lo, hi] of a cubic f given as a function: its coefficients from its
// values at four heights, the roots of its derivative (closed form) splitting [lo, hi] into
// monotone stretches, a sign change in one bisected on f; a double root (a fold, where two
// preimages appear) where |f| at a root of the derivative is at rounding level.
template <class F>
std::vector<double> cubicRoots(const F& f, double lo, double hi) {
    const auto at = [&](double x) { return f(lo + x * (hi - lo)); };
    // Values at x = 0, 1/3, 2/3, 1 to the power basis in x (the inverse Vandermonde).
    const double f0 = at(0.0), f1 = at(1.0 / 3.0), f2 = at(2.0 / 3.0), f3 = at(1.0);
    const double c1 = (-11.0 * f0 + 18.0 * f1 - 9.0 * f2 + 2.0 * f3) / 2.0;
    const double c2 = (18.0 * f0 - 45.0 * f1 + 36.0 * f2 - 9.0 * f3) / 2.0;
    const double c3 = (-9.0 * f0 + 27.0 * f1 - 27.0 * f2 + 9.0 * f3) / 2.0;
    std::vector<double> stops{0.0};
    // 3 c3 x^2 + 2 c2 x + c1 = 0
    const double a = 3.0 * c3, b = 2.0 * c2, c = c1;
    if (std::abs(a) > 1e-14 * (std::abs(b) + std::abs(c))) {
        const double disc = b * b - 4.0 * a * c;
        if (disc >= 0.0) {
            const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
            for (const double x : {q / a, q != 0.0 ? c / q : 0.0})
                if (x > 0.0 && x < 1.0) stops.push_back(x);
        }
    } else if (b != 0.0 && -c / b > 0.0 && -c / b < 1.0) {
        stops.push_back(-c / b);
    }
    stops.push_back(1.0);
    std::sort(stops.begin(), stops.end());
    const double scale = std::max({std::abs(f0), std::abs(f1), std::abs(f2), std::abs(f3)});
    std::vector<double> roots;
    for (std::size_t k = 0; k + 1 < stops.size(); ++k) {
        double l = stops[k], r = stops[k + 1];
        const double fl = at(l), fr = at(r);
        if (k > 0 && std::abs(fl) <= 1e-13 * scale) roots.push_back(l);  // touching
        if ((fl < 0.0) == (fr < 0.0)) continue;
        for (int i = 0; i < 80; ++i) {
            const double m = 0.5 * (l + r);
            ((at(m) < 0.0) == (fl < 0.0) ? l : r) = m;
        }
        roots.push_back(0.5 * (l + r));
    }
    for (double& x : roots) x = lo + x * (hi - lo);
    return roots;
}

// The contract's solid tested at one point, written apart from the reference: for each
// triangle the heights t at which the point lies on the offset plane (the roots of the
// cubic det(Y - Q(t), A1(t), A2(t)), over [0, max h] and a little past both ends, so that a
// root at 0 or at the top is not lost to rounding), b by Cramer's rule in the offset
// triangle. The signed depth: the smallest of b_i, t and h - t (in map units; b as is),
// largest over the preimages: > 0 strictly inside, < 0 outside.
struct ContractSolid {
    const TriangleMesh& mesh;
    const HeightMap& map;
    double s;
    Interpolation interpolation;

    double depth(const glm::dvec3& y) const {
        const double top = map.maxValue();
        double best = -1.0;
        for (const glm::uvec3& tri : mesh.triangles) {
            glm::dvec3 p[3], n[3];
            for (int i = 0; i < 3; ++i) {
                p[i] = mesh.positions[tri[i]];
                n[i] = mesh.normals[tri[i]];
            }
            // Skip triangles whose six corners' box (with a margin) misses the point.
            glm::dvec3 lo(1e300), hi(-1e300);
            for (int i = 0; i < 3; ++i) {
                for (const glm::dvec3& c : {p[i], p[i] + s * top * n[i]}) {
                    lo = glm::min(lo, c);
                    hi = glm::max(hi, c);
                }
            }
            if (glm::any(glm::lessThan(y, lo - 0.01)) || glm::any(glm::greaterThan(y, hi + 0.01)))
                continue;
            const auto corner = [&](int i, double t) { return p[i] + s * t * n[i]; };
            const auto det = [&](double t) {
                const glm::dvec3 q = corner(0, t);
                return glm::dot(y - q, glm::cross(corner(1, t) - q, corner(2, t) - q));
            };
            for (const double t : cubicRoots(det, -0.01 * top, 1.01 * top)) {
                const glm::dvec3 q0 = corner(0, t), e1 = corner(1, t) - q0, e2 = corner(2, t) - q0;
                const glm::dvec3 m = glm::cross(e1, e2);
                const double b1 = glm::dot(glm::cross(y - q0, e2), m) / glm::dot(m, m);
                const double b2 = glm::dot(glm::cross(e1, y - q0), m) / glm::dot(m, m);
                const glm::dvec3 bary(1.0 - b1 - b2, b1, b2);
                // At a focal height the offset triangle is a segment or a point (m = 0) and
                // b is not defined: no preimage taken there (UBSan saw the NaN uv's cast).
                if (!std::isfinite(b1) || !std::isfinite(b2)) continue;
                glm::dvec2 uv(0.0);
                for (int i = 0; i < 3; ++i) uv += bary[i] * glm::dvec2(mesh.texCoords[tri[i]]);
                const double h = contractHeight(map, interpolation, uv);
                best = std::max(best, std::min({bary.x, bary.y, bary.z, t, h - t}));
            }
        }
        return best;
    }
};

// A bumpy tube, normals inward and tilted at random by up to 0.4: the offset triangles
// fold across caustics (a shell of 0.6 against a radius about 0.25), no focal line.
TriangleMesh bumpyFoldedTube(std::uint32_t seed) {
    std::mt19937 random(seed);
    TriangleMesh mesh = cylinderTubeMesh(10, 2, 0.25f, 0.8f, true);
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const float r = static_cast<float>(uniform(random, 0.8, 1.2));
        mesh.positions[v].x *= r;
        mesh.positions[v].z *= r;
        const glm::vec3 tilt{uniform(random, -0.4, 0.4), uniform(random, -0.4, 0.4),
                             uniform(random, -0.4, 0.4)};
        mesh.normals[v] = glm::normalize(mesh.normals[v] + tilt);
    }
    return mesh;
}

// One triangle whose normals part by up to 70 degrees: its side walls are strongly twisted
// ruled surfaces that a ray can cross twice, and its map path curves, b and uv turning
// inside it; its uvs span the map twice over.
TriangleMesh twistedPrism() {
    TriangleMesh mesh;
    mesh.positions = {{-0.3f, 0.0f, -0.2f}, {0.3f, 0.0f, -0.2f}, {0.0f, 0.0f, 0.3f}};
    mesh.normals = {glm::normalize(glm::vec3(-0.8f, 1.0f, 0.3f)),
                    glm::normalize(glm::vec3(0.5f, 1.0f, 0.9f)),
                    glm::normalize(glm::vec3(0.2f, 1.0f, -1.2f))};
    mesh.texCoords = {{0.0f, 0.0f}, {2.0f, 0.3f}, {0.7f, 1.8f}};
    mesh.triangles = {{0, 1, 2}};
    return mesh;
}

struct FoldedCase {
    std::string name;
    TriangleMesh mesh;
    HeightMap map;
    double s;
    double eyeRadius;  // eyes around the y axis at this distance, aimed near the origin
    int rays = 300;
    int samples = 60;  // points of each ray checked before its hit
};

std::vector<FoldedCase> foldedCases() {
    std::vector<FoldedCase> cases;
    // Seeds whose meshes have rays that come in through a fold (one or two each, of 300
    // rays; found by scanning seeds 0 to 119, which gave 7 such). The meshes are the same
    // whichever the compiler: every draw of several numbers is a braced list, evaluated
    // left to right (a constructor's arguments in parentheses are not: GCC drew them right
    // to left and Clang left to right, so Clang's sanitizer build had other meshes and no
    // fold at all).
    for (const std::uint32_t seed : {50u, 56u, 87u}) {
        cases.push_back({"bumpy tube, seed " + std::to_string(seed), bumpyFoldedTube(seed),
                         seamless(synth::valueNoise(16, 8, 3.0, 2, 9 + seed)), 0.6, 1.2});
    }
    // The exact inward tube: every offset triangle collapses onto the axis at t = R / s,
    // inside the map's range, where some of the map is higher and some lower.
    cases.push_back({"inward tube, focal line", cylinderTubeMesh(12, 2, 0.25f, 0.8f, true),
                     seamless(synth::valueNoise(16, 8, 3.0, 2, 4)), 0.6, 1.2});
    cases.push_back({"twisted prism, noise", twistedPrism(),
                     seamless(synth::valueNoise(8, 8, 2.0, 2, 6)), 0.5, 1.0});
    // A spike on the twisted prism: some rays pass its peak where their path over the map
    // turns in u or v (1 in 1000 here), which the bounds must see.
    cases.push_back(
        {"twisted prism, a spike", twistedPrism(), synth::spike(8, 8, 2, 3), 0.5, 1.0, 4000, 200});
    return cases;
}

TEST(MeshReference, OnFoldedMeshesTheHitIsWhereTheRayFirstEntersTheSolid) {
    int folds = 0;
    for (const FoldedCase& c : foldedCases()) {
        for (const Interpolation interpolation :
             {Interpolation::Bilinear, Interpolation::Biquadratic}) {
            const MeshReference reference(c.mesh, c.map, c.s, interpolation);
            const ContractSolid solid{c.mesh, c.map, c.s, interpolation};
            std::mt19937 rays(3);
            int hits = 0;
            for (int k = 0; k < c.rays; ++k) {
                const double angle = uniform(rays, 0.0, 2.0 * kPi);
                const glm::dvec3 eye(c.eyeRadius * std::cos(angle), uniform(rays, -0.7, 0.7),
                                     c.eyeRadius * std::sin(angle));
                const glm::dvec3 aim = {uniform(rays, -0.3, 0.3), uniform(rays, -0.45, 0.45),
                                        uniform(rays, -0.3, 0.3)};
                const Ray ray{eye, aim - eye};
                const MeshHit hit = reference.trace(ray);
                const std::string where =
                    c.name + ", " + interpolationName(interpolation) + ", ray " + std::to_string(k);
                // No point of the ray before the hit (or anywhere, for a miss) is inside by
                // more than 1e-7.
                const double end = hit ? hit.t : 2.0;
                for (int i = 0; i < c.samples; ++i) {
                    const double lambda = end * (i + 0.5) / c.samples;
                    ASSERT_LT(solid.depth(ray.origin + lambda * ray.direction), 1e-7)
                        << where << " at " << lambda;
                }
                if (!hit) continue;
                ++hits;
                EXPECT_NE(hit.surface, MeshSurface::Inside) << where;
                // The hit is on the solid to 1e-7, and where the solid has a thickness there
                // (not a map at 0, where it is the mesh itself) the ray goes in: just after it
                // a point inside (through a fold, the two new preimages part as the square
                // root of the distance, so a little further).
                EXPECT_GT(solid.depth(hit.position), -1e-7) << where;
                const double after = hit.surface == MeshSurface::Fold ? 1e-5 : 1e-7;
                if (contractHeight(c.map, interpolation, hit.uv) > 1e-6) {
                    EXPECT_GT(solid.depth(ray.origin + (hit.t + after) * ray.direction), 0.0)
                        << where << ": " << surfaceName(hit.surface);
                }
                folds += hit.surface == MeshSurface::Fold;
            }
            EXPECT_GT(hits, 50) << c.name;
        }
    }
    EXPECT_GT(folds, 0);
}

// ---- The normal at the hit ----

// The top surface Z(b_1, b_2) = X(b, h(uv(b))) of triangle k, from the mesh and the
// contract's h (contractHeight, apart from the reference's patches).
glm::dvec3 topPoint(const TriangleMesh& mesh, std::size_t k, const HeightMap& map,
                    Interpolation interpolation, double s, double b1, double b2) {
    const glm::uvec3 tri = mesh.triangles[k];
    const glm::dvec3 b(1.0 - b1 - b2, b1, b2);
    glm::dvec3 base(0.0), along(0.0);
    glm::dvec2 uv(0.0);
    for (int i = 0; i < 3; ++i) {
        base += b[i] * glm::dvec3(mesh.positions[tri[i]]);
        along += b[i] * glm::dvec3(mesh.normals[tri[i]]);
        uv += b[i] * glm::dvec2(mesh.texCoords[tri[i]]);
    }
    return base + s * contractHeight(map, interpolation, uv) * along;
}

// On a tube, folded tubes and the twisted prism: a Top hit's normal is the top surface's,
// by central differences in b (a step of 1e-6: rounding 1e-10 of the derivatives, the
// truncation smaller still; a bilinear kink within the step, 1 in 1e5 hits, would show);
// every hit's normal is a unit vector facing the ray (which enters the solid there); at a
// fold the solid lies behind the normal: a step of 1e-4 of the scene back along it is
// inside, forward outside, as the contract's solid has it point by point.
TEST(MeshReference, TheNormalIsTheSurfacesOwn) {
    std::vector<FoldedCase> cases = foldedCases();
    cases.push_back({"outward tube", cylinderTubeMesh(16, 2, 0.3f, 0.8f, false),
                     seamless(synth::valueNoise(16, 8, 3.0, 2, 21)), 0.1, 1.2});
    int tops = 0, folds = 0, foldsInside = 0, foldsOutside = 0;
    for (const FoldedCase& c : cases) {
        if (c.name == "twisted prism, a spike") continue;  // the spike's kinks, 4000 rays
        for (const Interpolation interpolation :
             {Interpolation::Bilinear, Interpolation::Biquadratic}) {
            const MeshReference reference(c.mesh, c.map, c.s, interpolation);
            const ContractSolid solid{c.mesh, c.map, c.s, interpolation};
            std::mt19937 rays(3);  // as the folded test: its seeds give folds
            for (int k = 0; k < c.rays; ++k) {
                const double angle = uniform(rays, 0.0, 2.0 * kPi);
                const glm::dvec3 eye(c.eyeRadius * std::cos(angle), uniform(rays, -0.7, 0.7),
                                     c.eyeRadius * std::sin(angle));
                const glm::dvec3 aim = {uniform(rays, -0.3, 0.3), uniform(rays, -0.45, 0.45),
                                        uniform(rays, -0.3, 0.3)};
                const Ray ray{eye, aim - eye};
                const MeshHit hit = reference.trace(ray);
                if (!hit) continue;
                const std::string where = c.name + ", " + interpolationName(interpolation) +
                                          ", ray " + std::to_string(k) + ", " +
                                          surfaceName(hit.surface);
                EXPECT_NEAR(glm::length(hit.normal), 1.0, 1e-12) << where;
                EXPECT_LT(glm::dot(hit.normal, ray.direction), 0.0) << where;
                if (hit.surface == MeshSurface::Top) {
                    const double b1 = hit.barycentric[1], b2 = hit.barycentric[2], e = 1e-6;
                    const auto z = [&](double x, double y) {
                        return topPoint(c.mesh, hit.triangle, c.map, interpolation, c.s, x, y);
                    };
                    const glm::dvec3 d1 = (z(b1 + e, b2) - z(b1 - e, b2)) / (2.0 * e);
                    const glm::dvec3 d2 = (z(b1, b2 + e) - z(b1, b2 - e)) / (2.0 * e);
                    glm::dvec3 normal = glm::normalize(glm::cross(d1, d2));
                    if (glm::dot(normal, hit.normal) < 0.0) normal = -normal;
                    EXPECT_LE(glm::length(hit.normal - normal), 1e-6) << where;
                    ++tops;
                }
                if (hit.surface == MeshSurface::Fold) {
                    ++folds;
                    foldsInside += solid.depth(hit.position - 1e-4 * hit.normal) > 0.0;
                    foldsOutside += solid.depth(hit.position + 1e-4 * hit.normal) < 0.0;
                }
            }
        }
    }
    EXPECT_GT(tops, 500);
    EXPECT_GT(folds, 0);
    EXPECT_EQ(foldsInside, folds);
    EXPECT_EQ(foldsOutside, folds);
}

// ---- A ray in one offset plane of a curved triangle ----

// The twisted prism's offset triangle at t0 is planar, X(b, t0) affine in b; a ray from
// X(bOut, t0) towards X(bIn, t0) lies in that plane and walks b along a line: it enters the
// triangle where the last b_i that was negative reaches 0, through a wall, at height t0,
// below the constant map's 0.9. Exactly in the plane (c and num share the root t0), and
// displaced off it by 1e-14 (a curve that rounding leaves steep near t0). Rays that could
// meet the prism before they reach that plane's triangle (the leaning walls can put a point
// just outside the offset triangle inside the prism at another height) are left out: the
// stretch before the entry must be outside the contract's solid, checked point by point.
TEST(MeshReference, ARayInAnOffsetPlaneOfACurvedTriangle) {
    const TriangleMesh mesh = twistedPrism();
    const HeightMap map(8, 8, 0.9f);
    const double s = 0.5;
    std::mt19937 random(4);
    int compared = 0;
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        const MeshReference reference(mesh, map, s, interpolation);
        for (int k = 0; k < 200; ++k) {
            const double t0 = uniform(random, 0.05, 0.85);
            const auto offsetPoint = [&](const glm::dvec3& b) {
                glm::dvec3 x(0.0);
                for (int i = 0; i < 3; ++i)
                    x += b[i] *
                         (glm::dvec3(mesh.positions[i]) + s * t0 * glm::dvec3(mesh.normals[i]));
                return x;
            };
            // bOut: one or two b_i below 0 (outside an edge or a corner); bIn inside.
            glm::dvec3 bOut{uniform(random, -0.6, 1.2), uniform(random, -0.6, 1.2), 0.0};
            bOut.z = 1.0 - bOut.x - bOut.y;
            if (std::min({bOut.x, bOut.y, bOut.z}) >= 0.0) continue;
            glm::dvec3 bIn{uniform(random, 0.05, 0.9), uniform(random, 0.05, 0.9), 0.0};
            bIn.z = 1.0 - bIn.x - bIn.y;
            if (bIn.z < 0.05) continue;
            double entry = 0.0;  // where every b_i >= 0 along bOut + lambda (bIn - bOut)
            for (int i = 0; i < 3; ++i)
                if (bOut[i] < 0.0) entry = std::max(entry, -bOut[i] / (bIn[i] - bOut[i]));
            const glm::dvec3 b = bOut + entry * (bIn - bOut);
            // From short of the entry by 1e-3 of the way.
            const double start = std::max(0.0, entry - 1e-3);
            const ContractSolid solid{mesh, map, s, interpolation};
            bool clear = true;
            for (int i = 0; i <= 20 && clear; ++i) {
                const double lambda = start + (entry - start) * i / 21.0;
                clear = solid.depth(offsetPoint(bOut + lambda * (bIn - bOut))) < 0.0;
            }
            if (!clear) continue;
            for (const double offset : {0.0, 1e-14}) {
                const glm::dvec3 from = offsetPoint(bOut + start * (bIn - bOut));
                const Ray ray{from + glm::dvec3(0.0, offset, 0.0),
                              offsetPoint(bIn) - offsetPoint(bOut)};
                const MeshHit hit = reference.trace(ray);
                const std::string where = std::string(interpolationName(interpolation)) + ", ray " +
                                          std::to_string(k) + ", off the plane by " +
                                          std::to_string(offset);
                ASSERT_TRUE(hit) << where;
                EXPECT_EQ(hit.surface, MeshSurface::Wall)
                    << where << ": " << surfaceName(hit.surface);
                EXPECT_NEAR(hit.t, entry - start, 1e-9) << where;
                EXPECT_NEAR(hit.height, t0, 1e-9) << where;
                EXPECT_NEAR(glm::length(hit.barycentric - b), 0.0, 1e-9) << where;
                ++compared;
            }
        }
    }
    EXPECT_GT(compared, 200);
}

}  // namespace
}  // namespace microrelief
