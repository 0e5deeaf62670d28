// The mesh base's proxy (core/base/MeshProxy.h) against the exact reference
// (core/trace/MeshReference.h): every hit the reference finds on triangle k at ray
// parameter lambda is preceded by a crossing of one of k's proxy triangles (or the ray
// starts inside k's proxy), on flat, curved and folded meshes under noise maps; each
// triangle's proxy is a closed surface wound outward; H_tri is above the surface sampled
// densely over its triangle, bilinear and biquadratic.
#include "microrelief/core/base/MeshProxy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "microrelief/core/base/BaseMeshes.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/MeshReference.h"

namespace microrelief {
namespace {

constexpr double kPi = std::numbers::pi;

double uniform(std::mt19937& random, double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(random);
}

// ---- Meshes (as MeshReferenceTest builds them) ----

// An inward tube, bumpy, its normals tilted at random by up to 0.4: with a shell of 0.6
// against a radius of about 0.25 its prisms fold across caustics.
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

// One triangle whose normals part by up to 70 degrees (twisted, non-planar side walls),
// its uvs spanning the map twice over.
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

HeightMap withZeroPlateaus(HeightMap map) {
    for (float& h : map.samples) h = std::max(0.0f, 2.0f * h - 1.0f);
    return map;
}

struct ProxyCase {
    std::string name;
    TriangleMesh mesh;
    HeightMap map;
    double s;
};

std::vector<ProxyCase> proxyCases() {
    std::vector<ProxyCase> cases;
    const HeightMap noise = synth::valueNoise(32, 16, 5.0, 3, 7);
    cases.push_back({"flat grid", planeGridMesh(8, 1.0f, 0.5f), noise, 0.1});
    // Plateaus at 0: flat proxies (the triangle itself) beside thick ones.
    cases.push_back({"flat grid, zero plateaus", planeGridMesh(8, 1.0f, 0.5f),
                     withZeroPlateaus(synth::valueNoise(8, 8, 2.0, 1, 3)), 0.1});
    cases.push_back({"tube", cylinderTubeMesh(24, 3, 0.3f, 1.0f, false), noise, 0.05});
    for (const std::uint32_t seed : {14u, 20u}) {
        cases.push_back({"bumpy folded tube " + std::to_string(seed), bumpyFoldedTube(seed),
                         synth::valueNoise(16, 8, 3.0, 2, 9 + seed), 0.6});
    }
    cases.push_back({"inward tube, focal line", cylinderTubeMesh(12, 2, 0.25f, 0.8f, true),
                     synth::valueNoise(16, 8, 3.0, 2, 4), 0.6});
    cases.push_back({"twisted prism", twistedPrism(), synth::valueNoise(8, 8, 2.0, 2, 6), 0.5});
    return cases;
}

// ---- Rays against proxy triangles, in double ----

// The ray parameter where the ray crosses triangle (a, b, c), edges and corners included
// (to 1e-12 in barycentrics), or -1.
double crossing(const Ray& ray, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 e1 = b - a, e2 = c - a;
    const glm::dvec3 p = glm::cross(ray.direction, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return -1.0;
    const glm::dvec3 q = ray.origin - a;
    const double u = glm::dot(q, p) / det;
    const glm::dvec3 r = glm::cross(q, e1);
    const double v = glm::dot(ray.direction, r) / det;
    if (u < -1e-12 || v < -1e-12 || u + v > 1.0 + 1e-12) return -1.0;
    return glm::dot(e2, r) / det;
}

// Whether `point` is on the inner side of every proxy triangle of mesh triangle k (the
// triangles wound counter-clockwise from outside: inside is behind each one's plane).
bool insideProxy(const MeshProxy& proxy, std::size_t k, const glm::dvec3& point) {
    for (std::uint32_t f = proxy.firstProxyTriangle[k]; f < proxy.firstProxyTriangle[k + 1]; ++f) {
        const glm::dvec3 a = proxy.positions[3 * f], b = proxy.positions[3 * f + 1],
                         c = proxy.positions[3 * f + 2];
        const glm::dvec3 n = glm::cross(b - a, c - a);
        if (glm::dot(n, n) == 0.0) continue;
        if (glm::dot(n, point - a) > 0.0) return false;
    }
    return true;
}

// The least parameter >= 0 at which the ray crosses a proxy triangle of k, or -1.
double firstCrossing(const MeshProxy& proxy, std::size_t k, const Ray& ray) {
    double best = -1.0;
    for (std::uint32_t f = proxy.firstProxyTriangle[k]; f < proxy.firstProxyTriangle[k + 1]; ++f) {
        const double mu = crossing(ray, proxy.positions[3 * f], proxy.positions[3 * f + 1],
                                   proxy.positions[3 * f + 2]);
        if (mu >= 0.0 && (best < 0.0 || mu < best)) best = mu;
    }
    return best;
}

// ---- The tests ----

TEST(MeshProxy, EachTrianglesProxyIsAClosedSurfaceWoundOutward) {
    for (const ProxyCase& c : proxyCases()) {
        const MeshProxy proxy = buildMeshProxy(c.mesh, c.map, c.s);
        ASSERT_EQ(proxy.firstProxyTriangle.size(), c.mesh.triangles.size() + 1) << c.name;
        ASSERT_EQ(proxy.positions.size(), 3 * proxy.triangleCount()) << c.name;
        ASSERT_EQ(proxy.topHeights.size(), c.mesh.triangles.size()) << c.name;
        EXPECT_GT(proxy.padding, 0.0);
        int flat = 0;
        for (std::size_t k = 0; k < c.mesh.triangles.size(); ++k) {
            const std::string where = c.name + ", triangle " + std::to_string(k);
            const std::uint32_t first = proxy.firstProxyTriangle[k];
            const std::uint32_t last = proxy.firstProxyTriangle[k + 1];
            // At most 8: a convex polyhedron of 6 vertices has at most 8 triangular faces
            // (the axis-aligned box the builder falls back on would be 12).
            EXPECT_LE(last - first, 8u) << where;
            EXPECT_GE(last - first, 2u) << where;
            // Closed: every directed edge once, and its reverse once (by float position).
            std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> edges;
            const auto key = [](const glm::vec3& v) { return std::array<float, 3>{v.x, v.y, v.z}; };
            double volume = 0.0;
            for (std::uint32_t f = first; f < last; ++f) {
                EXPECT_EQ(proxy.meshTriangles[f], k) << where;
                for (int e = 0; e < 3; ++e)
                    ++edges[{key(proxy.positions[3 * f + e]),
                             key(proxy.positions[3 * f + (e + 1) % 3])}];
                const glm::dvec3 a = proxy.positions[3 * f], b = proxy.positions[3 * f + 1],
                                 cc = proxy.positions[3 * f + 2];
                volume += glm::dot(a, glm::cross(b, cc)) / 6.0;
            }
            for (const auto& [edge, count] : edges) {
                EXPECT_EQ(count, 1) << where;
                const auto reverse = edges.find({edge.second, edge.first});
                EXPECT_TRUE(reverse != edges.end() && reverse->second == 1) << where;
            }
            if (proxy.topHeights[k] == 0.0f) {
                ++flat;  // the triangle both ways round: no volume
                EXPECT_EQ(last - first, 2u) << where;
                continue;
            }
            // Wound outward: the enclosed volume is positive, and the prism's points (its
            // corners, its centre) are behind every face's plane.
            EXPECT_GT(volume, 0.0) << where;
            const glm::uvec3 tri = c.mesh.triangles[k];
            const double top = c.s * proxy.topHeights[k];
            for (const glm::dvec3 b : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0),
                                       glm::dvec3(0, 0, 1), glm::dvec3(1.0 / 3.0)}) {
                for (const double t : {0.0, 0.5, 1.0}) {
                    glm::dvec3 x(0.0);
                    for (int i = 0; i < 3; ++i)
                        x += b[i] * (glm::dvec3(c.mesh.positions[tri[i]]) +
                                     t * top * glm::dvec3(c.mesh.normals[tri[i]]));
                    EXPECT_TRUE(insideProxy(proxy, k, x)) << where << " at t " << t;
                }
            }
        }
        if (c.name == "flat grid, zero plateaus") {
            EXPECT_GT(flat, 0);
        }
    }
}

// Rays of several kinds about a mesh whose shell lies in the box [lo, hi].
Ray randomRay(std::mt19937& random, const glm::dvec3& lo, const glm::dvec3& hi, int kind) {
    const glm::dvec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const double reach = 2.0 * glm::length(half);
    const auto inBox = [&] {
        return glm::dvec3{uniform(random, lo.x, hi.x), uniform(random, lo.y, hi.y),
                          uniform(random, lo.z, hi.z)};
    };
    const auto direction = [&] {
        glm::dvec3 d;
        do {
            d = {uniform(random, -1, 1), uniform(random, -1, 1), uniform(random, -1, 1)};
        } while (glm::length(d) > 1.0 || glm::length(d) < 0.1);
        return d;
    };
    switch (kind) {
        case 0: {  // from outside the shell's box, at a point of it
            const glm::dvec3 eye = centre + reach * glm::normalize(direction());
            return {eye, inBox() - eye};
        }
        case 1: {  // grazing: nearly level (in y), from anywhere in the box's height
            glm::dvec3 eye = centre + reach * glm::normalize(direction());
            eye.y = uniform(random, lo.y, hi.y);
            glm::dvec3 d = inBox() - eye;
            d.y = uniform(random, -1e-3, 1e-3) * glm::length(d);
            return {eye, d};
        }
        default:  // from inside the shell's box, any way
            return {inBox(), direction()};
    }
}

TEST(MeshProxy, EveryReferenceHitCrossesItsPrismsProxyFirst) {
    int inside = 0;
    for (const ProxyCase& c : proxyCases()) {
        const MeshProxy proxy = buildMeshProxy(c.mesh, c.map, c.s);
        glm::dvec3 lo(1e300), hi(-1e300);
        for (std::size_t k = 0; k < c.mesh.triangles.size(); ++k) {
            for (int i = 0; i < 3; ++i) {
                const glm::uvec3 tri = c.mesh.triangles[k];
                for (const double t : {0.0, static_cast<double>(proxy.topHeights[k])}) {
                    const glm::dvec3 x = glm::dvec3(c.mesh.positions[tri[i]]) +
                                         c.s * t * glm::dvec3(c.mesh.normals[tri[i]]);
                    lo = glm::min(lo, x);
                    hi = glm::max(hi, x);
                }
            }
        }
        for (const Interpolation interpolation :
             {Interpolation::Bilinear, Interpolation::Biquadratic}) {
            const MeshReference reference(c.mesh, c.map, c.s, interpolation);
            std::mt19937 random(17);
            int crossed = 0;
            for (int k = 0; k < 600; ++k) {
                const Ray ray = randomRay(random, lo, hi, k % 3);
                const MeshHit hit = reference.trace(ray);
                if (!hit) continue;
                const std::string where = c.name + ", " + interpolationName(interpolation) +
                                          ", ray " + std::to_string(k) + ", triangle " +
                                          std::to_string(hit.triangle);
                // The reference's hit may lie up to a few tolerance() past the true one
                // (MeshReference.h), which matters only where a proxy has no padding: the
                // flat proxy of a triangle under heights 0, crossed exactly at the hit.
                const double slack = 4.0 * reference.tolerance() / glm::length(ray.direction);
                const double mu = firstCrossing(proxy, hit.triangle, ray);
                if (mu >= 0.0 && mu <= hit.t + slack) {
                    ++crossed;
                } else {
                    // No crossing before the hit: the ray must start inside that proxy.
                    EXPECT_TRUE(insideProxy(proxy, hit.triangle, ray.origin))
                        << where << ": first crossing " << mu << ", hit at " << hit.t;
                    ++inside;
                }
            }
            EXPECT_GT(crossed, 100) << c.name;
        }
    }
    // Rays that start in the solid (or in a hull) are exercised too.
    EXPECT_GT(inside, 50);
}

// An eye inside a prism's solid (or anywhere in its hull) is named by hullsThatMayHold,
// so that the renderer draws that hull without culling; an eye far off names none.
TEST(MeshProxy, AnEyeInsideAHullIsNamed) {
    std::mt19937 random(5);
    for (const ProxyCase& c : proxyCases()) {
        const MeshProxy proxy = buildMeshProxy(c.mesh, c.map, c.s);
        for (int n = 0; n < 200; ++n) {
            const std::size_t k = random() % c.mesh.triangles.size();
            const glm::uvec3 tri = c.mesh.triangles[k];
            double b1 = uniform(random, 0, 1), b2 = uniform(random, 0, 1);
            if (b1 + b2 > 1.0) b1 = 1.0 - b1, b2 = 1.0 - b2;
            const glm::dvec3 b(1.0 - b1 - b2, b1, b2);
            // Up to the top height: in the hull, whether or not under the map's surface.
            const double t = uniform(random, 0.0, 1.0) * proxy.topHeights[k];
            glm::dvec3 eye(0.0);
            for (int i = 0; i < 3; ++i)
                eye += b[i] * (glm::dvec3(c.mesh.positions[tri[i]]) +
                               c.s * t * glm::dvec3(c.mesh.normals[tri[i]]));
            const std::vector<std::uint32_t> named = hullsThatMayHold(proxy, eye);
            EXPECT_TRUE(std::binary_search(named.begin(), named.end(), k))
                << c.name << ", triangle " << k;
            // Local where the shell is thin against the triangles (the folded tubes' hulls
            // overlap across the tube, as their prisms do): a few neighbours.
            if (c.name == "flat grid" || c.name == "tube") {
                EXPECT_LE(named.size(), 16u) << c.name;
            }
        }
        EXPECT_TRUE(hullsThatMayHold(proxy, glm::dvec3(10.0, 10.0, 10.0)).empty()) << c.name;
    }
}

// h(uv) repeated in u and v: the map tiled 3 x 3 and read in its middle tile, where the
// neighbours' samples are the repeated map's (an evaluation apart from the builder's).
double repeatedHeight(const HeightMap& tiled, Interpolation interpolation, glm::dvec2 uv) {
    const int w = tiled.width / 3, h = tiled.height / 3;
    const double u = uv.x - std::floor(uv.x) + 1.0, v = uv.y - std::floor(uv.y) + 1.0;
    return tiled.surface(u * w, v * h, false, interpolation);
}

TEST(MeshProxy, TheTopHeightIsAboveTheSurfaceOverItsTriangle) {
    // A fine grid over a coarse map, uvs shifted and scaled past [0, 1] (repeat), on a
    // spiky map (a lone 1 among small noise), so that a triangle near the spike's texel
    // but not over it sees the spike only through its interpolation's reach.
    HeightMap map = synth::valueNoise(8, 8, 2.0, 1, 5);
    for (float& x : map.samples) x *= 0.1f;
    map.at(5, 2) = 1.0f;
    map.at(0, 7) = 0.8f;  // at the corner: reached across the repeat
    const HeightMap tiled = repeatMap(map, 3, 3);
    TriangleMesh mesh = planeGridMesh(24, 1.0f, 1.0f);
    for (glm::vec2& t : mesh.texCoords) t = 1.3f * t - glm::vec2(0.4f, 0.15f);
    const std::vector<float> bounds = [&] {
        std::vector<float> h;
        for (const glm::uvec3& tri : mesh.triangles)
            h.push_back(topHeight(map, mesh.texCoords[tri[0]], mesh.texCoords[tri[1]],
                                  mesh.texCoords[tri[2]]));
        return h;
    }();
    int local = 0;
    double tightest = 1.0;  // the least (H_tri - max sampled) / H_tri, to show the bound bites
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
            const glm::uvec3 tri = mesh.triangles[k];
            double sampled = 0.0;
            constexpr int kSteps = 24;
            for (int i = 0; i <= kSteps; ++i) {
                for (int j = 0; i + j <= kSteps; ++j) {
                    const double b1 = static_cast<double>(i) / kSteps;
                    const double b2 = static_cast<double>(j) / kSteps;
                    const glm::dvec2 uv = (1.0 - b1 - b2) * glm::dvec2(mesh.texCoords[tri[0]]) +
                                          b1 * glm::dvec2(mesh.texCoords[tri[1]]) +
                                          b2 * glm::dvec2(mesh.texCoords[tri[2]]);
                    sampled = std::max(sampled, repeatedHeight(tiled, interpolation, uv));
                }
            }
            ASSERT_GE(bounds[k], sampled) << interpolationName(interpolation) << ", triangle " << k;
            tightest = std::min(tightest, (bounds[k] - sampled) / bounds[k]);
            local += bounds[k] < map.maxValue();
        }
    }
    EXPECT_GT(local, 0);        // not the global max everywhere
    EXPECT_LT(tightest, 0.05);  // and somewhere close to the surface's own max
    // A box over the whole map, or not finite: the map's largest sample.
    EXPECT_EQ(topHeight(map, {0.0, 0.0}, {3.0, 0.5}, {0.2, 5.0}), map.maxValue());
    EXPECT_EQ(topHeight(map, {0.0, 0.0}, {NAN, 0.5}, {0.2, 0.1}), map.maxValue());
}

}  // namespace
}  // namespace microrelief
