// The one segment walk (core/trace/SegmentWalk.h) that MultilevelTracer (plane, cylinder,
// ellipsoid) and MeshTracer (a triangle's prism) share: the refactor that made them share it
// changed no result. The table below was recorded from the two tracers' own copies of the walk
// (commit 4e85fde, before the refactor) on fixed rays for each base and two meshes: per ray the
// hit's t to the last bit, the fetches and the segments visited (and the pyramid level of the
// last read, or the pieces walked on a mesh). Every figure must come back the same.
//
// The rays and meshes are drawn from closed-form sequences, not from <random>'s distributions
// (their algorithms differ between standard libraries), so the table holds under every
// compiler that computes IEEE doubles without contraction (no FMA), with glibc's libm (the
// curved bases' atan2 and the rays' sin and cos): GCC's Release build and Clang 14's with
// ASan and UBSan (scripts/sanitize.sh's flags) gave the same figures.
//
// To print a new table (after a change meant to alter results, and only then):
//   MICRORELIEF_PRINT_WALK_TABLE=1 microrelief-cpu-tests --gtest_filter='SegmentWalk.*'
#include <gtest/gtest.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "microrelief/core/base/BaseMeshes.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/MeshTracer.h"
#include "microrelief/core/trace/MultilevelTracer.h"

using namespace microrelief;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kRaysPerCase = 24;

// One ray's figures: t of the hit (-1 for none), fetches, segments visited, and the last read's
// pyramid level (analytic bases) or the pieces walked (mesh).
struct Row {
    double t;
    int fetches, iterations, extra;
};

bool printing() { return std::getenv("MICRORELIEF_PRINT_WALK_TABLE") != nullptr; }

// The k-th point of an additive recurrence in [0, 1)^3 (the plastic number's): well spread,
// exact to reproduce.
glm::dvec3 spread(int k) {
    const double g = 1.22074408460575947536;
    return glm::fract(glm::dvec3{0.5 + k / g, 0.5 + k / (g * g), 0.5 + k / (g * g * g)});
}

// Rays from eyes around the box [lo, hi] (most above, a quarter below, a fifth grazing) towards
// points inside it.
std::vector<Ray> raysAround(const glm::dvec3& lo, const glm::dvec3& hi, int seed) {
    std::vector<Ray> rays;
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double size = glm::length(hi - lo);
    for (int k = 0; k < kRaysPerCase; ++k) {
        const glm::dvec3 a = spread(seed + 2 * k), b = spread(seed + 2 * k + 1);
        const glm::dvec3 target = lo + a * (hi - lo);
        const double elevation =
            std::asin(b.x) * (k % 4 == 3 ? -1.0 : 1.0) * (k % 5 == 0 ? 0.1 : 1.0);
        const double azimuth = 2.0 * kPi * b.y;
        const double distance = size * (0.75 + b.z);
        const glm::dvec3 eye = centre + distance * glm::dvec3{std::cos(elevation) * std::cos(azimuth),
                                                              std::sin(elevation),
                                                              std::cos(elevation) * std::sin(azimuth)};
        rays.push_back({eye, target - eye});
    }
    return rays;
}

std::string hexDouble(double x) {
    char text[64];
    std::snprintf(text, sizeof text, "%a", x);
    return text;
}

void printRows(const char* name, const std::vector<Row>& rows) {
    std::printf("    // %s\n", name);
    for (const Row& r : rows)
        std::printf("    {%s, %d, %d, %d},\n", hexDouble(r.t).c_str(), r.fetches, r.iterations,
                    r.extra);
}

void expectRows(const char* name, const std::vector<Row>& got, const Row* want) {
    if (printing()) {
        printRows(name, got);
        return;
    }
    for (int k = 0; k < kRaysPerCase; ++k) {
        SCOPED_TRACE(std::string(name) + ", ray " + std::to_string(k));
        EXPECT_EQ(hexDouble(got[k].t), hexDouble(want[k].t));  // to the last bit
        EXPECT_EQ(got[k].fetches, want[k].fetches);
        EXPECT_EQ(got[k].iterations, want[k].iterations);
        EXPECT_EQ(got[k].extra, want[k].extra);
    }
}

struct AnalyticCase {
    const char* name;
    HeightMap map;
    double scale;
    BaseShape base;
    Interpolation interpolation;
};

std::vector<AnalyticCase> analyticCases() {
    return {
        {"plane cobbles 64 bilinear", synth::cobbles(64, 64, 1), 0.15, BaseShape::plane(),
         Interpolation::Bilinear},
        {"plane spike 16x9 bilinear (floor exits)", synth::spike(16, 9, 3, 4), 0.3,
         BaseShape::plane(), Interpolation::Bilinear},
        {"plane cobbles 48x40 biquadratic", synth::cobbles(48, 40, 3), 0.2, BaseShape::plane(),
         Interpolation::Biquadratic},
        {"cylinder cobbles 64 bilinear", synth::cobbles(64, 64, 1), 0.15, BaseShape::cylinder(),
         Interpolation::Bilinear},
        {"sphere white 21x11 bilinear", synth::whiteNoise(21, 11, 5), 0.2, BaseShape::sphere(0.4),
         Interpolation::Bilinear},
        {"ellipsoid spike biquadratic", synth::spike(16, 9, 3, 4), 0.5,
         BaseShape::ellipsoid({0.3, 0.5, 0.2}), Interpolation::Biquadratic},
    };
}

std::vector<Row> analyticRows(const AnalyticCase& c, int seed) {
    const MultilevelTracer twin(c.map, c.scale, c.base, c.interpolation);
    const double top = c.scale * c.map.maxValue();
    const glm::dvec3 lo = c.base.boxMin(c.map.width, c.map.height, top),
                     hi = c.base.boxMax(c.map.width, c.map.height, top);
    std::vector<Row> rows;
    for (const Ray& ray : raysAround(lo, hi, seed)) {
        TraversalStats stats;
        const auto hit = twin.intersect(ray, &stats);
        rows.push_back({hit ? hit->t : -1.0, stats.fetches, stats.iterations, stats.stopLevel});
    }
    return rows;
}

// A wavy n x n grid over [-0.5, 0.5]^2 whose normals lean by up to 0.4 and whose uv runs over
// [0, 1.5]^2 (the map repeats): with a thick shell its prisms twist and fold.
TriangleMesh wavyGrid(int n) {
    TriangleMesh mesh;
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
            const double y = 0.05 * std::sin(7.0 * u + 3.0 * v) * std::cos(5.0 * v);
            const glm::dvec3 normal{0.4 * std::sin(11.0 * u - 4.0 * v), 1.0,
                                    0.4 * std::cos(9.0 * v + 2.0 * u)};
            mesh.positions.push_back({static_cast<float>(u - 0.5), static_cast<float>(y),
                                      static_cast<float>(v - 0.5)});
            mesh.normals.push_back(glm::vec3(glm::normalize(normal)));
            mesh.texCoords.push_back({static_cast<float>(1.5 * u), static_cast<float>(1.5 * v)});
        }
    }
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const unsigned k = j * (n + 1) + i, right = k + 1, up = k + n + 1;
            mesh.triangles.push_back({k, up, right});
            mesh.triangles.push_back({right, up, up + 1});
        }
    }
    return mesh;
}

std::vector<Row> meshRows(const TriangleMesh& mesh, const HeightMap& map, double scale,
                          Interpolation interpolation, const glm::dvec3& lo, const glm::dvec3& hi,
                          int seed) {
    const MeshTracer tracer(mesh, map, scale, interpolation);
    std::vector<Row> rows;
    for (const Ray& ray : raysAround(lo, hi, seed)) {
        MeshTraceStats stats;
        const MeshTraceHit hit = tracer.trace(ray, &stats);
        rows.push_back({hit ? hit.t : -1.0, stats.fetches, stats.iterations, stats.pieces});
    }
    return rows;
}

// clang-format off
// Recorded before the refactor (see the top): 6 analytic cases, then 2 meshes, 24 rays each.
const Row kRecorded[] = {
    // plane cobbles 64 bilinear
    {0x1.8eb91be935504p-1, 1, 0, 0},
    {0x1.f1380f16fbe4p-1, 3, 3, 1},
    {0x1.fd141a0b17f76p-1, 6, 4, 2},
    {0x1.f2649829c43adp-1, 0, 0, 0},
    {0x1.e66d44b2e691dp-1, 3, 3, 2},
    {0x1.648066f8fa7e7p-1, 8, 5, 1},
    {0x1.ece3745d8b27ep-1, 5, 2, 2},
    {0x1.d30bca071f1d5p-1, 0, 0, 0},
    {0x1.fdc46583b3e5ap-1, 9, 6, 2},
    {0x1.f23966d7522b3p-1, 1, 0, 0},
    {0x1.9ff981ad6a5bfp-1, 29, 8, 2},
    {0x1.bbabaa5629422p-1, 17, 5, 1},
    {0x1.cb7918bb3d45bp-1, 2, 2, 1},
    {0x1.0257b5a790571p+0, 15, 7, 2},
    {0x1.0c4fa2782176fp+0, 4, 1, -1},
    {0x1.b9447c16851e6p-1, 9, 5, 1},
    {0x1.f30e25de6198p-1, 9, 5, 1},
    {0x1.df74f9a82a44p-1, 1, 1, -1},
    {0x1.ea12af223a04bp-1, 10, 4, 1},
    {0x1.82b74c6c8d2ap-1, 0, 0, 0},
    {0x1.f87ea2498598ap-1, 1, 0, 0},
    {0x1.f2bcfdc34cff4p-1, 19, 7, 1},
    {0x1.62c72494e6646p-1, 9, 6, 2},
    {0x1.fa7fcf8d9df41p-1, 0, 0, 0},
    // plane spike 16x9 bilinear (floor exits)
    {-0x1p+0, 13, 5, 2},
    {0x1.068e4d52ccfaap+0, 5, 3, 1},
    {-0x1p+0, 6, 3, 2},
    {0x1.b8096ca26e1ep-1, 0, 0, 0},
    {0x1.07ef027f13a36p+0, 5, 1, -1},
    {-0x1p+0, 20, 7, 1},
    {0x1.25a5cfc7b6b96p+0, 4, 1, -1},
    {0x1.c365e523ae35dp-1, 0, 0, 0},
    {0x1.119f82cbd677p+0, 12, 5, 1},
    {-0x1p+0, 1, 1, 1},
    {-0x1p+0, 2, 1, 3},
    {-0x1p+0, 10, 3, 1},
    {-0x1p+0, 1, 1, 1},
    {0x1.1886e30fdf43dp+0, 8, 1, -1},
    {0x1.184952cb51f9ep+0, 5, 1, -1},
    {-0x1p+0, 12, 5, 2},
    {0x1.1f77912aa5201p+0, 15, 6, 1},
    {-0x1p+0, 1, 1, 0},
    {-0x1p+0, 1, 1, 2},
    {-0x1p+0, 19, 5, 2},
    {-0x1p+0, 2, 1, 1},
    {-0x1p+0, 1, 1, 1},
    {-0x1p+0, 12, 3, 1},
    {0x1.b126dcc931863p-1, 0, 0, 0},
    // plane cobbles 48x40 biquadratic
    {0x1.5757e29864088p-1, 21, 5, 1},
    {0x1.ee4d02a982511p-1, 14, 3, 2},
    {0x1.239fd2e2dc5a8p+0, 17, 5, 1},
    {0x1.df84fffcc2771p-1, 0, 0, 0},
    {0x1.fb9e5c8ed5dbap-1, 35, 4, 1},
    {0x1.2709a6eb3db5fp-1, 4, 0, 0},
    {0x1.eba19e460c16ep-1, 4, 0, 0},
    {0x1.a6bbd3f489cf5p-1, 0, 0, 0},
    {0x1.df37915e42b29p-1, 4, 0, 0},
    {0x1.e1c69b1fa5a23p-1, 9, 2, 2},
    {0x1.65977d96e70ap-1, 21, 5, 1},
    {0x1.fcebc8a09fe54p-1, 0, 0, 0},
    {0x1.f52ea5af28e3ap-1, 29, 3, 2},
    {0x1.149e4a288c55bp+0, 60, 9, 1},
    {0x1.bfee9d078c6b5p-1, 9, 2, 2},
    {0x1.7e60ce6dcbc81p-1, 4, 0, 0},
    {0x1.dd1c751c2fab9p-1, 22, 6, 1},
    {0x1.f9e01d5f7a4aap-1, 4, 0, 0},
    {0x1.c721eb2d02a01p-1, 11, 3, 1},
    {0x1.b098efaa6d13ep-1, 12, 4, 1},
    {0x1.b676195d815c6p-1, 4, 0, 0},
    {0x1.e90f2d3dc427fp-1, 41, 6, 1},
    {0x1.9aae01a245f21p-1, 26, 6, 1},
    {0x1.e78df66d59995p-1, 0, 0, 0},
    // cylinder cobbles 64 bilinear
    {0x1.0001dba810344p+0, 4, 3, 1},
    {0x1.8c4c84398476bp-1, 5, 4, 1},
    {0x1.5f0f0f17e5ebep-1, 5, 3, 1},
    {-0x1p+0, 0, 0, -1},
    {0x1.de0bf42a8dd94p-1, 6, 4, 2},
    {0x1.9b17a73fa001cp-1, 4, 3, 1},
    {0x1.ddaa230334e95p-1, 1, 0, 0},
    {0x1.7584f69cad0b6p-1, 5, 3, 1},
    {0x1.a1a98db1b0e09p-1, 4, 3, 2},
    {0x1.bbf79e8bef60ap-1, 1, 0, 0},
    {0x1.86822b531698dp-1, 4, 3, 2},
    {-0x1p+0, 0, 0, -1},
    {0x1.dd60fc919126fp-1, 1, 0, 0},
    {0x1.c42f2ddc6dfbbp-1, 8, 3, 2},
    {0x1.923f937ab6515p-1, 1, 0, 0},
    {0x1.c659c687a5695p-1, 5, 2, 1},
    {0x1.a2ed9c2fb5394p-1, 5, 3, 1},
    {0x1.0c9818e04226dp-1, 1, 0, 0},
    {0x1.4d2219663d523p-1, 6, 4, 1},
    {0x1.68c404d8c0729p-1, 4, 3, 1},
    {0x1.b894f2d748299p-1, 4, 3, 1},
    {0x1.57861fa3b4cacp-1, 5, 4, 1},
    {0x1.567306a9dfbccp-1, 1, 0, 0},
    {0x1.4da6c1c0e8b99p-1, 8, 5, 1},
    // sphere white 21x11 bilinear
    {0x1.6671d0327b016p-1, 4, 3, 0},
    {0x1.b41a77425fe8ap-1, 4, 3, 0},
    {0x1.67da569e16f02p-1, 3, 2, 1},
    {0x1.051035f33dc82p+0, 2, 1, 2},
    {0x1.9b9dc5ccfeeaap-1, 4, 3, 0},
    {0x1.56c620eb376f1p-1, 3, 2, 1},
    {-0x1p+0, 0, 0, -1},
    {-0x1p+0, 0, 0, -1},
    {-0x1p+0, 4, 1, 2},
    {0x1.bef15f7347282p-1, 2, 1, 2},
    {0x1.d48eff41f8becp-1, 5, 2, 1},
    {-0x1p+0, 0, 0, -1},
    {0x1.7490fc56297bdp-1, 3, 2, 2},
    {0x1.c4d5cf8799da1p-1, 4, 2, 2},
    {0x1.31e3592fe0a18p-1, 9, 3, 1},
    {0x1.d08fc57eb8cf3p-1, 5, 3, 0},
    {-0x1p+0, 0, 0, -1},
    {-0x1p+0, 0, 0, -1},
    {0x1.6a037432f7951p-1, 4, 3, 0},
    {-0x1p+0, 0, 0, -1},
    {0x1.02c92d1b7195ep+0, 5, 2, 2},
    {0x1.a2159210c4735p-1, 4, 3, 0},
    {0x1.3d9f350bc798ep+0, 5, 2, 1},
    {0x1.c9d20cc2d9caep-1, 4, 3, 0},
    // ellipsoid spike biquadratic
    {-0x1p+0, 0, 0, -1},
    {-0x1p+0, 1, 1, 1},
    {0x1.10d3ceceed39p+0, 7, 2, 2},
    {-0x1p+0, 0, 0, -1},
    {-0x1p+0, 34, 1, 1},
    {-0x1p+0, 25, 1, 2},
    {-0x1p+0, 0, 0, -1},
    {0x1.9dfaf44040a09p-1, 9, 3, 0},
    {0x1.259e0b9cc0594p+0, 13, 1, 2},
    {-0x1p+0, 1, 1, 2},
    {0x1.e1b23f0e113b6p-1, 6, 2, 1},
    {-0x1p+0, 0, 0, -1},
    {0x1.a2774c8237b73p-1, 6, 2, 1},
    {0x1.9dc2585ef5231p-1, 7, 2, 2},
    {-0x1p+0, 1, 1, 2},
    {-0x1p+0, 1, 1, 2},
    {0x1.bad254e96f409p-1, 6, 2, 2},
    {-0x1p+0, 30, 6, 0},
    {-0x1p+0, 5, 5, 0},
    {-0x1p+0, 25, 1, 2},
    {-0x1p+0, 21, 1, 2},
    {0x1.ad899077db997p-1, 6, 2, 2},
    {-0x1p+0, 0, 0, -1},
    {-0x1p+0, 26, 1, 1},
    // mesh tube cobbles 128 bilinear
    {-0x1p+0, 0, 0, 0},
    {-0x1p+0, 7, 3, 2},
    {0x1.c868e7a7e365bp-1, 14, 4, 2},
    {0x1.56d75e314dbd5p-1, 4, 2, 1},
    {0x1.cc8abd865e171p-1, 1, 0, 1},
    {0x1.96f22b5e9d0cp-1, 5, 1, 1},
    {0x1.2637d2b58eee4p-1, 4, 1, 1},
    {0x1.626ee8e94f78dp-1, 6, 2, 1},
    {0x1.d5de722f0fe0ep-1, 1, 0, 1},
    {0x1.cf98ccfdb1c6bp-1, 7, 3, 2},
    {0x1.6de1d20426839p-1, 4, 1, 1},
    {0x1.9a76ed6d63a61p-1, 1, 0, 1},
    {0x1.640e1c3c6d323p-1, 3, 1, 1},
    {0x1.e12746ae47adcp-1, 7, 3, 2},
    {0x1.015d4789deb1dp+0, 15, 5, 2},
    {0x1.aacc9db12193ep-1, 3, 1, 1},
    {0x1.7efbbea605e2dp-1, 6, 2, 1},
    {0x1.ca37020c54654p-1, 7, 3, 1},
    {0x1.a2cd02fdcba2dp-1, 3, 1, 1},
    {0x1.d95fdf75d92f5p-1, 1, 0, 1},
    {0x1.021f4facfbc4cp+0, 3, 1, 1},
    {0x1.e634b08a773e5p-1, 14, 6, 3},
    {-0x1p+0, 0, 0, 0},
    {0x1.a43354a25e8aep-1, 4, 2, 1},
    // mesh wavy grid cobbles 96 biquadratic (folds)
    {0x1.250f8f44d297dp-1, 12, 0, 3},
    {0x1.4575b7f85c37dp-1, 4, 0, 1},
    {0x1.050d082106a13p+0, 36, 4, 1},
    {0x1.2268ddbe43227p+0, 4, 0, 1},
    {0x1.eb33dea1fd2ffp-1, 28, 4, 2},
    {0x1.ce57b16dbfd1fp-2, 38, 8, 2},
    {0x1.2ee52b4ad4202p-1, 4, 0, 1},
    {0x1.d2a3baaf43d5ep-1, 12, 0, 3},
    {0x1.0d2e39182cf29p+0, 30, 6, 1},
    {0x1.3a196d284b048p-1, 115, 11, 1},
    {0x1.ff923b98ca212p-1, 4, 0, 1},
    {0x1.7f1294bc306f5p-1, 4, 0, 1},
    {0x1.249ab05863098p+0, 8, 0, 2},
    {0x1.e3988b8199d13p-1, 13, 1, 2},
    {0x1.0a267d28351bap+0, 38, 10, 2},
    {0x1.fcf0c02e37a6fp-2, 4, 0, 1},
    {0x1.efd68d50c496ap-1, 51, 7, 2},
    {0x1.1075ad043392bp+0, 131, 14, 4},
    {0x1.bdc1be5ddc69ep-1, 14, 2, 1},
    {0x1.ce48fa8b04b9ap-1, 8, 0, 2},
    {-0x1p+0, 20, 4, 4},
    {0x1.e816a5944b48ap-1, 4, 0, 1},
    {0x1.e30dffafdec53p-1, 41, 5, 2},
    {-0x1p+0, 36, 7, 3},
};
// clang-format on

}  // namespace

TEST(SegmentWalk, TheAnalyticBasesWalkAsBeforeTheSharing) {
    const std::vector<AnalyticCase> cases = analyticCases();
    for (std::size_t c = 0; c < cases.size(); ++c) {
        expectRows(cases[c].name, analyticRows(cases[c], 7 + 50 * static_cast<int>(c)),
                   kRecorded + c * kRaysPerCase);
    }
}

TEST(SegmentWalk, TheMeshWalksAsBeforeTheSharing) {
    const std::size_t first = analyticCases().size() * kRaysPerCase;
    expectRows("mesh tube cobbles 128 bilinear",
               meshRows(cylinderTubeMesh(12, 4, 0.3f, 1.0f), synth::cobbles(128, 128, 4), 0.1,
                        Interpolation::Bilinear, {-0.4, -0.5, -0.4}, {0.4, 0.5, 0.4}, 401),
               kRecorded + first);
    expectRows("mesh wavy grid cobbles 96 biquadratic (folds)",
               meshRows(wavyGrid(6), synth::cobbles(96, 96, 5), 0.25, Interpolation::Biquadratic,
                        {-0.5, -0.05, -0.5}, {0.5, 0.3, 0.5}, 503),
               kRecorded + first + kRaysPerCase);
}
