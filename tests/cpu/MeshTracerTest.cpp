// The mesh base's traversal (core/trace/MeshTracer.h): its pieces against the ray's preimage
// sampled densely (every sampled point of the prism on the ray lies on a piece, every piece is
// monotone and inside the triangle), and its hits against the independent exact reference
// (core/trace/MeshReference.h) on a flat grid, a tube, a folded tube, a UV seam and bumpy
// folded meshes, from above, grazing, from below the mesh and from inside the shell, both
// last levels; on a flat grid its fetches against the plane's multilevel traversal.
#include "microrelief/core/trace/MeshTracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "microrelief/core/base/BaseMeshes.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/MeshReference.h"
#include "microrelief/core/trace/MultilevelTracer.h"

namespace microrelief {
namespace {

constexpr double kPi = std::numbers::pi;

double uniform(std::mt19937& r, double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(r);
}

// Last column equal to the first, last row to the first: the repeated surface over [0, 1]^2
// is the plane's clamped one (MeshReferenceTest's seamless).
HeightMap seamless(HeightMap map) {
    for (int j = 0; j < map.height; ++j) map.at(map.width - 1, j) = map.at(0, j);
    for (int i = 0; i < map.width; ++i) map.at(i, map.height - 1) = map.at(i, 0);
    return map;
}

// A bumpy grid whose normals lean at random by up to `lean`: with a thick shell the prisms
// twist and fold over their neighbours.
TriangleMesh bumpyGrid(int n, double lean, std::mt19937& random) {
    TriangleMesh mesh = planeGridMesh(n, 1.0f, 1.0f);
    for (std::size_t k = 0; k < mesh.positions.size(); ++k) {
        mesh.positions[k].y = static_cast<float>(uniform(random, -0.05, 0.05));
        const glm::dvec3 normal{uniform(random, -lean, lean), 1.0, uniform(random, -lean, lean)};
        mesh.normals[k] = glm::vec3(glm::normalize(normal));
    }
    return mesh;
}

// Two triangles meeting at x = 0 whose uvs lie over heights 0.2 and 0.8: a wall between.
TriangleMesh seamMesh() {
    TriangleMesh mesh;
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::vec3 n1 = glm::normalize(glm::vec3(0.3f, 1.0f, 0.0f)),
                    n2 = glm::normalize(glm::vec3(0.0f, 1.0f, 0.3f));
    mesh.positions = {{-1, 0, 0}, {0, 0, -0.5f}, {0, 0, 0.5f}, {0, 0, -0.5f}, {1, 0, 0}, {0, 0, 0.5f}};
    mesh.normals = {up, n1, n2, n1, up, n2};
    mesh.texCoords = {{0.15f, 0.5f}, {0.35f, 0.1f}, {0.35f, 0.9f},
                      {0.65f, 0.1f}, {0.85f, 0.5f}, {0.65f, 0.9f}};
    mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
    return mesh;
}

HeightMap seamMap() {
    HeightMap map(8, 8, 0.2f);
    for (int j = 0; j < 8; ++j)
        for (int i = 4; i < 8; ++i) map.at(i, j) = 0.8f;
    return map;
}

// The world size of a texel on triangle k: sqrt(world area / (uv area W H)).
double texelSize(const TriangleMesh& mesh, const HeightMap& map, std::size_t k) {
    const glm::uvec3 t = mesh.triangles[k];
    const glm::dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const glm::dvec2 ua = mesh.texCoords[t[0]], ub = mesh.texCoords[t[1]], uc = mesh.texCoords[t[2]];
    const double world = 0.5 * glm::length(glm::cross(b - a, c - a));
    const glm::dvec2 e1 = ub - ua, e2 = uc - ua;
    const double uvArea = 0.5 * std::abs(e1.x * e2.y - e1.y * e2.x);
    return std::sqrt(world / (uvArea * map.width * map.height));
}

// ---- The pieces hold the ray's preimage ----

// The preimage of the ray at height t in triangle (P, N), solved directly: lambda and b from
// the 3 x 3 system W + lambda V = b1 A1 + b2 A2 (not the tracer's polynomials).
struct Preimage {
    double lambda;
    glm::dvec3 b;
    bool ok;
};
Preimage preimage(const Ray& ray, const glm::dvec3 p[3], const glm::dvec3 n[3], double s, double t) {
    const glm::dvec3 q = p[0] + s * t * n[0];
    const glm::dvec3 a1 = p[1] + s * t * n[1] - q, a2 = p[2] + s * t * n[2] - q;
    const glm::dmat3 m(-ray.direction, a1, a2);
    if (std::abs(glm::determinant(m)) < 1e-12) return {0.0, glm::dvec3(0.0), false};
    const glm::dvec3 x = glm::inverse(m) * (ray.origin - q);
    return {x[0], {1.0 - x[1] - x[2], x[1], x[2]}, true};
}

TEST(MeshTracer, PiecesHoldTheRaysPreimageAndAreMonotone) {
    std::mt19937 random(3);
    const HeightMap map(8, 8, 1.0f);  // H = 1
    int sampledInside = 0, piecesSeen = 0, folds = 0;
    for (int trial = 0; trial < 120; ++trial) {
        // One triangle, normals leaning up to 60 degrees, shell up to 1.5 times its size: folds.
        TriangleMesh mesh;
        for (int i = 0; i < 3; ++i) {
            mesh.positions.push_back(glm::vec3{uniform(random, -0.5, 0.5), uniform(random, -0.1, 0.1),
                                               uniform(random, -0.5, 0.5)});
            mesh.normals.push_back(glm::vec3(glm::normalize(glm::dvec3{
                uniform(random, -1.7, 1.7), 1.0, uniform(random, -1.7, 1.7)})));
            mesh.texCoords.push_back(glm::vec2{uniform(random, -1.5, 1.5), uniform(random, -1.5, 1.5)});
        }
        mesh.triangles = {{0, 1, 2}};
        const double s = uniform(random, 0.1, 1.5);
        const MeshTracer tracer(mesh, map, s);
        const double top = tracer.top();
        const glm::dvec3 p[3] = {mesh.positions[0], mesh.positions[1], mesh.positions[2]};
        const glm::dvec3 n[3] = {mesh.normals[0], mesh.normals[1], mesh.normals[2]};
        for (int r = 0; r < 10; ++r) {
            const glm::dvec3 from{uniform(random, -2, 2), uniform(random, -1, 2), uniform(random, -2, 2)};
            const glm::dvec3 to{uniform(random, -0.5, 0.5), uniform(random, 0.0, 0.8),
                                uniform(random, -0.5, 0.5)};
            const Ray ray{from, to - from};
            const double lambdaMax = 3.0;
            PrismPath path;
            std::array<MeshPiece, MeshTracer::kMaxPieces> list;
            const int count = tracer.pieces(ray, 0, lambdaMax, path, list);
            piecesSeen += count;
            const std::string where = "trial " + std::to_string(trial) + " ray " + std::to_string(r);
            // Each piece: inside the triangle, lambda in range, lambda rising, t, b, uv monotone.
            for (int k = 0; k < count; ++k) {
                const MeshPiece& piece = list[k];
                if (piece.entry == MeshSurface::Fold) ++folds;
                MeshPathPoint previous = tracer.pointOn(path, piece, 0.0);
                glm::dvec3 sign(0.0);
                glm::dvec2 uvSign(0.0);
                double tSign = 0.0;
                for (int i = 1; i <= 200; ++i) {
                    const MeshPathPoint m = tracer.pointOn(path, piece, i / 200.0);
                    ASSERT_GE(m.lambda, previous.lambda - 1e-9 * (1 + std::abs(m.lambda))) << where;
                    ASSERT_GE(m.lambda, -1e-9) << where;
                    ASSERT_LE(m.lambda, lambdaMax + 1e-9) << where;
                    for (int c = 0; c < 3; ++c) {
                        ASSERT_GE(m.b[c], -1e-7) << where << " piece " << k;
                        const double d = m.b[c] - previous.b[c];
                        if (std::abs(d) > 1e-9) {
                            ASSERT_GE(d * sign[c], 0.0) << where << " b" << c << " turns in piece " << k;
                            sign[c] = d;
                        }
                    }
                    for (int c = 0; c < 2; ++c) {
                        const double d = m.uv[c] - previous.uv[c];
                        if (std::abs(d) > 1e-9) {
                            ASSERT_GE(d * uvSign[c], 0.0) << where << " uv" << c << " turns in piece " << k;
                            uvSign[c] = d;
                        }
                    }
                    const double dt = m.t - previous.t;
                    if (std::abs(dt) > 1e-12) {
                        ASSERT_GE(dt * tSign, 0.0) << where;
                        tSign = dt;
                    }
                    ASSERT_GE(m.t, -1e-12);
                    ASSERT_LE(m.t, top + 1e-12);
                    previous = m;
                }
            }
            // Every sampled point of the prism's extended shell on the ray lies on a piece.
            for (int i = 0; i <= 400; ++i) {
                const double t = top * i / 400.0;
                const Preimage x = preimage(ray, p, n, s, t);
                if (!x.ok || x.lambda < 1e-6 || x.lambda > lambdaMax - 1e-6) continue;
                if (std::min({x.b.x, x.b.y, x.b.z}) < 1e-6) continue;
                ++sampledInside;
                bool found = false;
                for (int k = 0; k < count && !found; ++k) {
                    const MeshPiece& piece = list[k];
                    if (piece.level) continue;
                    const double lo = std::min(piece.tA, piece.tB), hi = std::max(piece.tA, piece.tB);
                    if (t < lo || t > hi || hi == lo) continue;
                    const MeshPathPoint m =
                        tracer.pointOn(path, piece, (t - piece.tA) / (piece.tB - piece.tA));
                    found = std::abs(m.lambda - x.lambda) <= 1e-6 * (1 + std::abs(x.lambda));
                }
                ASSERT_TRUE(found) << where << ": t " << t << " lambda " << x.lambda;
            }
        }
    }
    // The case as meant: many sampled points inside, several pieces a ray.
    EXPECT_GT(sampledInside, 5000);
    EXPECT_GT(piecesSeen, 400);
    std::printf("[ mesh    ] %d pieces, %d starting at a fold\n", piecesSeen, folds);
}

// ---- The pyramid's bounds over the repeated map ----

// The contract's h at texel point (X, Y) of the map repeated in u and v, written here from the
// definitions (not SurfacePatch): bilinear between sample centres, or the uniform quadratic
// B-spline of the 3 x 3 samples around the texel square, indices taken modulo the size.
double repeatedHeight(const HeightMap& map, Interpolation interpolation, double x, double y) {
    const auto sample = [&](long long i, long long j) {
        const long long w = map.width, h = map.height;
        return static_cast<double>(map.at(static_cast<int>(((i % w) + w) % w),
                                          static_cast<int>(((j % h) + h) % h)));
    };
    if (interpolation == Interpolation::Bilinear) {
        const double fx = x - 0.5, fy = y - 0.5;
        const long long i = static_cast<long long>(std::floor(fx)), j = static_cast<long long>(std::floor(fy));
        const double a = fx - i, b = fy - j;
        return (1 - a) * (1 - b) * sample(i, j) + a * (1 - b) * sample(i + 1, j) +
               (1 - a) * b * sample(i, j + 1) + a * b * sample(i + 1, j + 1);
    }
    const long long i = static_cast<long long>(std::floor(x)), j = static_cast<long long>(std::floor(y));
    const double a = x - i, b = y - j;
    const double wa[3] = {0.5 * (1 - a) * (1 - a), 0.5 + a * (1 - a), 0.5 * a * a};
    const double wb[3] = {0.5 * (1 - b) * (1 - b), 0.5 + b * (1 - b), 0.5 * b * b};
    double h = 0.0;
    for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) h += wa[p] * wb[q] * sample(i - 1 + p, j - 1 + q);
    return h;
}

TEST(MeshTracer, FootprintBoundsHoldTheRepeatedSurface) {
    // Edges that differ (a spike at each corner): the repeated surface across the period's edges
    // is not the clamped one.
    HeightMap map = synth::valueNoise(16, 8, 4.0, 2, 9);
    map.at(0, 0) = 1.5f;
    map.at(15, 7) = 1.2f;
    map.at(15, 0) = 0.0f;
    map.at(0, 7) = 1.4f;
    std::mt19937 random(13);
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        const MeshTracer tracer(planeGridMesh(1, 1.0f, 1.0f), map, 1.0, interpolation);
        int nearEdges = 0;
        for (int k = 0; k < 4000; ++k) {
            // Rectangles up to 3 texels (a few up to 40), anywhere in [-40, 40]^2, half of them
            // at the period's edges.
            const double size = k % 10 == 0 ? 40.0 : 3.0;
            glm::dvec2 lo{uniform(random, -40, 40), uniform(random, -40, 40)};
            if (k % 2 == 0) {
                lo = glm::dvec2(16.0 * std::round(lo.x / 16.0), 8.0 * std::round(lo.y / 8.0)) +
                     glm::dvec2{uniform(random, -2, 0.5), uniform(random, -2, 0.5)};
                ++nearEdges;
            }
            const glm::dvec2 hi = lo + glm::dvec2{uniform(random, 0, size), uniform(random, 0, size)};
            const double bound = tracer.footprintBound(lo, hi).bound;
            double highest = 0.0;
            for (int i = 0; i <= 24; ++i)
                for (int j = 0; j <= 24; ++j)
                    highest = std::max(highest, repeatedHeight(map, interpolation,
                                                               lo.x + (hi.x - lo.x) * i / 24.0,
                                                               lo.y + (hi.y - lo.y) * j / 24.0));
            ASSERT_GE(bound, highest - 1e-6) << "[" << lo.x << ", " << hi.x << "] x [" << lo.y
                                            << ", " << hi.y << "]";
        }
        EXPECT_GT(nearEdges, 1000);
    }
}

// ---- The hits against the reference ----

struct Agreement {
    int rays = 0, hits = 0, hitMiss = 0, farOff = 0, surfaceDiffers = 0;
    double worstTexels = 0.0;
    long long fetches = 0, pieces = 0, prisms = 0;
};

// Traces `rays` with both; counts hit/miss disagreements and hits more than `texels` off
// (in texels of the reference hit's triangle).
Agreement compare(const TriangleMesh& mesh, const HeightMap& map, double s,
                  Interpolation interpolation, const std::vector<Ray>& rays, double texels,
                  const std::string& name) {
    const MeshReference reference(mesh, map, s, interpolation);
    const MeshTracer tracer(mesh, map, s, interpolation);
    Agreement a;
    for (std::size_t k = 0; k < rays.size(); ++k) {
        const MeshHit expected = reference.trace(rays[k]);
        MeshTraceStats stats;
        const MeshTraceHit hit = tracer.trace(rays[k], &stats);
        EXPECT_FALSE(stats.exhausted) << name << " ray " << k;
        ++a.rays;
        a.fetches += stats.fetches;
        a.pieces += stats.pieces;
        a.prisms += stats.triangles;
        if (static_cast<bool>(expected) != static_cast<bool>(hit)) {
            ++a.hitMiss;
            continue;
        }
        if (!hit) continue;
        ++a.hits;
        const double off = glm::length(hit.position - expected.position) /
                           texelSize(mesh, map, expected.triangle);
        a.worstTexels = std::max(a.worstTexels, off);
        if (off > texels) ++a.farOff;
        if (hit.surface != expected.surface) ++a.surfaceDiffers;
    }
    std::printf("[ mesh    ] %-34s %s: %d rays, %d hits, %d hit/miss, %d > %.0e texel (worst %.2e), "
                "%d surface kinds differ; per ray %.1f fetches, %.2f prisms, %.2f pieces\n",
                name.c_str(), interpolation == Interpolation::Bilinear ? "bilinear" : "biquadratic",
                a.rays, a.hits, a.hitMiss, a.farOff, texels, a.worstTexels, a.surfaceDiffers,
                static_cast<double>(a.fetches) / a.rays, static_cast<double>(a.prisms) / a.rays,
                static_cast<double>(a.pieces) / a.rays);
    return a;
}

// Rays over the unit footprint [-1/2, 1/2]^2 of a shell `top` high.
std::vector<Ray> gridRays(std::mt19937& random, double top, int count) {
    std::vector<Ray> rays;
    for (int k = 0; k < count; ++k) {
        const glm::dvec3 target{uniform(random, -0.45, 0.45), uniform(random, 0.0, top),
                                uniform(random, -0.2, 0.2)};
        switch (k % 5) {
            case 0: {  // from above, steep to 30 degrees
                const glm::dvec3 eye = target + glm::dvec3{uniform(random, -1, 1), uniform(random, 0.6, 2),
                                                           uniform(random, -1, 1)};
                rays.push_back({eye, target - eye});
                break;
            }
            case 1: {  // grazing: 1e-2 .. 1e-9 of a radian down
                const double phi = uniform(random, 0, 2 * kPi), g = std::pow(10.0, uniform(random, -9, -2));
                const glm::dvec3 d(std::cos(phi), -g, std::sin(phi));
                rays.push_back({target - 0.8 * d, d});
                break;
            }
            case 2: {  // from below the mesh, up
                const glm::dvec3 eye{target.x + uniform(random, -0.3, 0.3), -uniform(random, 0.1, 1),
                                     target.z + uniform(random, -0.3, 0.3)};
                rays.push_back({eye, target - eye});
                break;
            }
            case 3: {  // level, at a height in the shell
                const double phi = uniform(random, 0, 2 * kPi);
                const glm::dvec3 d(std::cos(phi), 0.0, std::sin(phi));
                rays.push_back({target - 0.8 * d, d});
                break;
            }
            default: {  // from inside the shell, any way
                rays.push_back({target, {uniform(random, -1, 1), uniform(random, -1, 1),
                                         uniform(random, -1, 1)}});
            }
        }
    }
    return rays;
}

// Both are exact: the reference to 1e-12 of the scene, the tracer to its final pieces (2^-12
// texel and 2^-12 of H before the parabola, far less after it). 1e-3 texel leaves room for a
// hit on a surface met at a grazing angle, where either's rounding moves along the ray by
// itself over the angle. Hit/miss: a ray that touches the solid tangentially within the
// tolerances may count as a hit for one and not the other; none are expected on these maps.
constexpr double kTexels = 1e-3;

TEST(MeshTracer, AFlatGridAgreesWithTheReference) {
    const HeightMap noise = seamless(synth::valueNoise(32, 16, 5.0, 3, 7));
    HeightMap plateaus = noise;
    for (float& h : plateaus.samples) h = std::max(0.0f, 2.0f * h - 1.0f);
    const TriangleMesh mesh = planeGridMesh(8, 1.0f, 0.5f);
    for (const HeightMap* map : {&noise, static_cast<const HeightMap*>(&plateaus)}) {
        for (const Interpolation interpolation :
             {Interpolation::Bilinear, Interpolation::Biquadratic}) {
            std::mt19937 random(11);
            const double s = 0.1;
            const Agreement a = compare(mesh, *map, s, interpolation,
                                        gridRays(random, s * map->maxValue(), 400),
                                        kTexels, map == &noise ? "flat grid, noise" : "flat grid, plateaus");
            EXPECT_EQ(a.hitMiss, 0);
            EXPECT_EQ(a.farOff, 0);
            EXPECT_EQ(a.surfaceDiffers, 0);
            EXPECT_GT(a.hits, 250);
        }
    }
}

// A shell thinner than double resolves against the eye's distance (s = 1e-18 of a unit grid:
// every t of a piece one lambda in double), rays from above: each hit on the top as the
// reference has it, not on the mesh (the piece's direction from lambda's derivative,
// MeshTracer's forward; seen red with la <= lb alone: 0 of 200 hits on the top).
TEST(MeshTracer, AShellThinnerThanDoubleResolvesIsHitOnItsTop) {
    const HeightMap map = seamless(synth::valueNoise(32, 16, 5.0, 3, 7));
    const TriangleMesh mesh = planeGridMesh(4, 1.0f, 1.0f);
    const double s = 1e-18;
    const MeshTracer tracer(mesh, map, s);
    const MeshReference reference(mesh, map, s);
    std::mt19937 random(5);
    int hits = 0, top = 0;
    for (int k = 0; k < 200; ++k) {
        const glm::dvec3 target{uniform(random, -0.45, 0.45), 0.0, uniform(random, -0.45, 0.45)};
        const glm::dvec3 eye{uniform(random, -1.0, 1.0), uniform(random, 0.3, 1.0), uniform(random, -1.0, 1.0)};
        const Ray ray{eye, target - eye};
        const MeshTraceHit hit = tracer.trace(ray);
        const MeshHit expected = reference.trace(ray);
        ASSERT_EQ(static_cast<bool>(hit), static_cast<bool>(expected));
        if (!hit) continue;
        ++hits;
        EXPECT_EQ(expected.surface, MeshSurface::Top);
        if (hit.surface == MeshSurface::Top) ++top;
        EXPECT_LT(glm::length(hit.position - expected.position), 1e-9);
    }
    EXPECT_GT(hits, 150);
    EXPECT_EQ(top, hits);
}

TEST(MeshTracer, TheMapRepeatsInUAndV) {
    // uv over [-0.7, 1.6] x [-1.3, 0.9] on a map whose edges differ (a spike at a corner): the
    // footprints cross the period's edges, where the pyramid's bounds and the cells wrap.
    HeightMap map = synth::valueNoise(16, 8, 4.0, 2, 9);
    map.at(0, 0) = 1.5f;
    map.at(15, 7) = 1.2f;
    const TriangleMesh mesh = planeGridMesh(4, 1.0f, 1.0f, {-0.7f, -1.3f},
                                                  glm::vec2{1.6f, 0.9f} - glm::vec2{-0.7f, -1.3f});
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        std::mt19937 random(21);
        const double s = 0.2;
        const Agreement a = compare(mesh, map, s, interpolation, gridRays(random, s * 1.5, 500),
                                    kTexels, "repeated uv");
        EXPECT_EQ(a.hitMiss, 0);
        EXPECT_EQ(a.farOff, 0);
        EXPECT_EQ(a.surfaceDiffers, 0);
        EXPECT_GT(a.hits, 300);
    }
}

TEST(MeshTracer, CurvedFoldedAndSeamedMeshesAgreeWithTheReference) {
    const HeightMap noise = seamless(synth::valueNoise(16, 16, 4.0, 2, 3));
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        std::mt19937 random(5);
        // A tube of 24 sides, from outside towards the axis and from the axis outwards.
        {
            const double radius = 0.3, s = 0.05;
            std::vector<Ray> rays;
            for (int k = 0; k < 300; ++k) {
                const double phi = uniform(random, -kPi, kPi), y = uniform(random, -0.4, 0.4);
                const glm::dvec3 out(std::sin(phi), 0.0, std::cos(phi));
                const glm::dvec3 aim = radius * out + glm::dvec3(0.0, y, 0.0);
                const glm::dvec3 away = glm::normalize(
                    out + glm::dvec3{uniform(random, -1, 1), uniform(random, -0.5, 0.5), uniform(random, -1, 1)});
                if (k % 3 == 2)
                    rays.push_back({glm::dvec3(0.0, y, 0.0), away});  // from the axis
                else
                    rays.push_back({aim + 1.0 * away, -away});
            }
            const Agreement a = compare(cylinderTubeMesh(24, 4, 0.3f, 1.0f, false), noise, s, interpolation,
                                        rays, kTexels, "tube");
            EXPECT_EQ(a.hitMiss, 0);
            EXPECT_EQ(a.farOff, 0);
            EXPECT_GT(a.hits, 150);
        }
        // An inward tube whose shell (0.5 of the radius) passes its axis: folded prisms.
        {
            const double s = 0.5 * 0.3 / noise.maxValue() * 2.5;
            std::vector<Ray> rays;
            for (int k = 0; k < 200; ++k) {
                const glm::dvec3 eye{uniform(random, -0.25, 0.25), uniform(random, -0.6, 0.6),
                                     uniform(random, -0.25, 0.25)};
                const glm::dvec3 d{uniform(random, -1, 1), uniform(random, -0.3, 0.3), uniform(random, -1, 1)};
                rays.push_back({eye, d});
            }
            const Agreement a = compare(cylinderTubeMesh(12, 3, 0.3f, 1.0f, true), noise, s, interpolation,
                                        rays, kTexels, "inward tube, folded");
            EXPECT_EQ(a.hitMiss, 0);
            EXPECT_EQ(a.farOff, 0);
            EXPECT_GT(a.hits, 100);
        }
        // Bumpy grids with leaning normals and a shell as thick as a quad: twisted, folded prisms.
        {
            std::mt19937 meshes(9);
            const TriangleMesh mesh = bumpyGrid(4, 0.8, meshes);
            std::vector<Ray> rays = gridRays(random, 0.25, 200);
            const Agreement a = compare(mesh, noise, 0.25 / noise.maxValue(), interpolation, rays,
                                        kTexels, "bumpy folded grid");
            EXPECT_EQ(a.hitMiss, 0);
            EXPECT_EQ(a.farOff, 0);
            EXPECT_GT(a.hits, 100);
        }
        // The wall at a UV seam: level and slanted rays from the low side into the high wall.
        {
            std::vector<Ray> rays;
            for (const double y : {0.15, 0.22, 0.3, 0.34, 0.45, 0.05})
                for (const double z : {-0.3, 0.0, 0.25})
                    for (const double slope : {0.0, -0.05, 0.05, 1e-7})
                        rays.push_back({{-0.5, y, z}, {1.0, slope, 0.1}});
            const Agreement a = compare(seamMesh(), seamMap(), 0.5, interpolation, rays, kTexels,
                                        "uv seam");
            EXPECT_EQ(a.hitMiss, 0);
            EXPECT_EQ(a.farOff, 0);
            EXPECT_EQ(a.surfaceDiffers, 0);
            EXPECT_GT(a.hits, 40);
        }
    }
}

// ---- Fetches on a flat grid against the plane's traversal ----

TEST(MeshTracer, FetchesOnAFlatGridAgainstThePlane) {
    const HeightMap map = seamless(synth::valueNoise(64, 64, 8.0, 3, 7));
    const double s = 0.05;
    const MultilevelTracer plane(map, s);
    for (const double elevation : {60.0, 20.0}) {
    for (const int n : {1, 4, 16}) {
        const TriangleMesh mesh = planeGridMesh(n, 1.0f, 1.0f);
        const MeshTracer tracer(mesh, map, s);
        // A 32 x 32 picture of the footprint, seen from `elevation` degrees up.
        double planeFetches = 0, meshFetches = 0, prismFetches = 0, prisms = 0;
        int hits = 0;
        for (int j = 0; j < 32; ++j) {
            for (int i = 0; i < 32; ++i) {
                const glm::dvec3 target((i + 0.5) / 32 - 0.5, 0.0, (j + 0.5) / 32 - 0.5);
                const double e = elevation * kPi / 180.0;
                const glm::dvec3 eye = target + glm::dvec3(0.4 * std::cos(e), std::sin(e), 0.9 * std::cos(e));
                const Ray ray{eye, target - eye};
                TraversalStats ps;
                const auto expected = plane.intersect(ray, &ps);
                MeshTraceStats ms;
                const MeshTraceHit hit = tracer.trace(ray, &ms);
                ASSERT_EQ(static_cast<bool>(hit), static_cast<bool>(expected));
                if (hit) {
                    ++hits;
                    EXPECT_LE(glm::length(hit.position - expected->position), 1e-6 / 64.0);
                }
                planeFetches += ps.fetches;
                meshFetches += ms.fetches;
                // What the renderer pays: every prism whose box the ray crosses runs a fragment.
                MeshTraceStats all;
                for (std::size_t k = 0; k < tracer.triangleCount(); ++k) {
                    const glm::dvec2 span = tracer.boxSpan(ray, k);
                    if (span.y >= 0.0 && span.x <= span.y) tracer.traceTriangle(ray, k, span.y, all);
                }
                prismFetches += all.fetches;
                prisms += all.triangles;
            }
        }
        EXPECT_GT(hits, 900);
        std::printf("[ mesh    ] 64 x 64 map, %d x %d quads, %.0f degrees: fetches per pixel plane %.1f, "
                    "mesh (first hit over prisms in order) %.1f, every prism crossed %.1f over %.1f "
                    "prisms\n",
                    n, n, elevation, planeFetches / 1024, meshFetches / 1024, prismFetches / 1024,
                    prisms / 1024);
    }
    }
}

// smoothEdges: the walls that are no surface (issue 50's contract: walls only where the
// neighbouring prisms' heights differ). A 2 x 2 grid: each triangle's edges inside the grid
// smooth, the border's not; a tube's edges along it and diagonals smooth, its rims not; a seam
// whose uv jumps by half a period, split normals (a hard edge) and a third triangle on an
// edge keep their walls; a shift of uv by whole periods does not. Seen red: the integer shift
// not allowed, and the two sides' winding not compared (a fin on one side smooth).
TEST(MeshTracer, SmoothEdgesAreTheSharedContinuousOnes) {
    const TriangleMesh grid = planeGridMesh(2, 1.0f, 1.0f);
    const std::vector<std::uint8_t> smooth = smoothEdges(grid);
    ASSERT_EQ(smooth.size(), grid.triangles.size());
    for (std::size_t k = 0; k < grid.triangles.size(); ++k) {
        for (int i = 0; i < 3; ++i) {
            const glm::vec3 a = grid.positions[grid.triangles[k][(i + 1) % 3]],
                            b = grid.positions[grid.triangles[k][(i + 2) % 3]];
            const bool border = (a.x == b.x && std::abs(a.x) == 0.5f) || (a.z == b.z && std::abs(a.z) == 0.5f);
            EXPECT_EQ(((smooth[k] >> i) & 1u) != 0, !border) << "triangle " << k << " edge " << i;
        }
    }
    const TriangleMesh tube = cylinderTubeMesh(8, 1, 0.5f, 1.0f);
    // A tube of one quad along: each triangle has an edge along the tube (smooth), a rim (a
    // wall) and its quad's diagonal (smooth), but for the seam between u = 7/8 .. 1 and
    // u = 0 .. 1/8, whose two columns' x are sin(pi) and sin(-pi) rounded (+-9e-17 apart:
    // not the same positions, so walls, as the contract has them).
    int smoothCount = 0;
    for (const std::uint8_t bits : smoothEdges(tube))
        smoothCount += (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1);
    EXPECT_EQ(smoothCount, 2 * static_cast<int>(tube.triangles.size()) - 2);

    // Two triangles on the edge (0,0,0)-(1,0,0), the second's uv shifted by (0.5, 0) (a seam),
    // then by (1, -2) (the map's period: smooth), then its normals split, then a third triangle.
    TriangleMesh pair;
    pair.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}, {0, 0, 0}, {1, 0, 0}, {1, 0, 1}};
    pair.normals = std::vector<glm::vec3>(6, glm::vec3(0, 1, 0));
    pair.texCoords = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0}, {1.5f, 0}, {1.5f, -1}};
    pair.triangles = {{0, 1, 2}, {4, 3, 5}};
    // Edge opposite vertex 2 of triangle 0 (1 -> 0... its vertices 0, 1) and opposite vertex 2
    // of triangle 1 (4 -> 3, the other way round).
    EXPECT_EQ(smoothEdges(pair)[0], 0);
    pair.texCoords = {{0, 0}, {1, 0}, {0, 1}, {1, -2}, {2, -2}, {2, -3}};
    EXPECT_EQ(smoothEdges(pair)[0], 4);
    EXPECT_EQ(smoothEdges(pair)[1], 4);
    TriangleMesh hard = pair;
    hard.normals[3] = glm::normalize(glm::vec3(0, 1, 1));
    EXPECT_EQ(smoothEdges(hard)[0], 0);
    TriangleMesh fin = pair;
    fin.triangles[1] = {3, 4, 5};  // the same way round: both on one side of the edge
    EXPECT_EQ(smoothEdges(fin)[0], 0);
    TriangleMesh three = pair;
    three.positions.push_back({0.5f, 1, 0});
    three.normals.push_back({0, 1, 0});
    three.texCoords.push_back({0, 0});
    three.triangles.push_back({0, 1, 6});
    EXPECT_EQ(smoothEdges(three)[0], 0);
}

}  // namespace
}  // namespace microrelief
