// Post-processing sees the relief (issue 48; ctest three.post): under scene.overrideMaterial
// (MeshNormalMaterial, MeshDepthMaterial, MeshDistanceMaterial) the relief draws its traced surface, not its proxy
// box (packages/microrelief-three/src/override.js), and the ambient-occlusion passes built
// on it (GTAOPass, SSAOPass) find the crevices. examples/three's page, shading=microrelief
// (the relief alone), the oblique view; the measurements inside the page are post.js, against
// the relief's own hits (Relief.traceRays: the library's GLSL, through the same pixel
// centres).
#include <cstdio>

#include "ThreePage.h"

using namespace microrelief;
using namespace microrelief::three_test;

namespace {

class ThreePost : public ThreePage {
protected:
    // examples/three on `view` with checks.js and post.js loaded, then `calls` (expressions on
    // window.postChecks, each an eval step; a screenshot after those named in `shots`).
    PageRun run(const View& v, const std::vector<std::string>& calls,
                const std::vector<std::string>& shots = {}) {
        std::string steps = "[" + openCompare(v) + ", {\"eval\": " +
                            jsonString(test::readText(MICRORELIEF_THREE_TESTS_DIR "/post.js")) +
                            "}";
        for (std::size_t k = 0; k < calls.size(); ++k) {
            steps += ", {\"eval\": " + jsonString("postChecks." + calls[k]) + "}";
            if (k < shots.size() && !shots[k].empty())
                steps += ", {\"screenshot\": " + jsonString((dir / shots[k]).string()) + "}";
        }
        PageRun page = runPage(steps + "]");
        for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
        return page;
    }
};

// The samples: every 3rd pixel of the oblique view (4800, about 2900 of them on the relief).
constexpr int kStep = 3;
// The hits on which the drawing and the trace may disagree (drawn or not): rays through the
// silhouettes and the pixels beside exhausted ones. Seen 0 to 2 of about 2900.
constexpr double kMaxDisagreement = 0.005;

// MeshNormalMaterial as the override: the normal read back (a float target, three's
// packing n / 2 + 1 / 2) is the hit's normal in view space. The two are the same float
// computation (mr_reliefWorldNormal) of the same ray's hit, so within a float target's
// rounding, but for a hit on an edge between texels that the two round to either side of:
// seen 2022 of 2023 within 1e-3 rad, the other 0.04 rad off (SwiftShader). 1e-3 rad tells a
// normal of the wrong texel of a rounded cobble or the box's face. Red with the box: 370 of
// 2023 within (its top's normal where a cobble's top is level), up to 2.6 rad off, 98
// misses drawn (the box's margin beside the relief).
TEST_F(ThreePost, MeshNormalMaterialSeesTheTracedNormals) {
    const View& v = viewNamed("oblique");
    const PageRun page = run(v, {"normals(" + std::to_string(kStep) + ", 1e-3)"}, {"normals.png"});
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    const std::vector<double> r = numbers(page.at(4, "value"));
    ASSERT_EQ(r.size(), 7u) << page.at(4, "value") << page.err;
    const double samples = r[0], hits = r[1], drawnHits = r[3], within = r[4], largest = r[5],
                 drawnMisses = r[6];
    std::printf("    %g samples, %g hits, %g drawn, %g within 1e-3 rad, largest %g rad, %g misses drawn\n",
                samples, hits, drawnHits, within, largest, drawnMisses);
    ASSERT_GT(hits, 0.3 * samples) << "the oblique view shows the relief over a third of its pixels";
    EXPECT_GE(drawnHits, (1.0 - kMaxDisagreement) * hits) << "hits the override did not draw";
    EXPECT_LE(drawnMisses, kMaxDisagreement * hits) << "misses drawn (the proxy box?)";
    EXPECT_GE(within, (1.0 - kMaxDisagreement) * drawnHits)
        << "normals read back off the traced ones by more than 1e-3 rad (largest " << largest << ")";
}

// MeshDepthMaterial as the override, with both of three's usual packings: the depth its colour
// gives and the depth buffer holds are the hit's window depth (projected in double), as
// ThreePage.AMeshCrossingTheReliefCutsItAtTheHitDepth holds the relief's own materials
// (kDepthTolerance, its reasons; the depth range [0.25, 4]). RGBA packing in an 8-bit target
// keeps 32 bits (three's packDepthToRGBA), so the same tolerance. Seen: at most 4e-7, every
// hit drawn, no miss. Red with the box: its faces' depth, up to 5.2e-2 off, 98 misses drawn.
TEST_F(ThreePost, MeshDepthMaterialSeesTheHitDepth) {
    const View& v = viewNamed("oblique");
    const std::string step = std::to_string(kStep);
    const PageRun page = run(v, {"depths(" + step + ", 'basic')", "depths(" + step + ", 'rgba')"});
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const int k : {4, 5}) {
        SCOPED_TRACE(k == 4 ? "BasicDepthPacking" : "RGBADepthPacking");
        const std::vector<double> r = numbers(page.at(k, "value"));
        ASSERT_EQ(r.size(), 5u) << page.at(k, "value") << page.err;
        const double hits = r[0], drawnHits = r[1], colourError = r[2], bufferError = r[3],
                     drawnMisses = r[4];
        std::printf("    %g hits, %g drawn, largest error: colour %g, depth buffer %g; %g misses drawn\n",
                    hits, drawnHits, colourError, bufferError, drawnMisses);
        ASSERT_GT(hits, 1000.0);
        EXPECT_GE(drawnHits, (1.0 - kMaxDisagreement) * hits);
        EXPECT_LE(drawnMisses, kMaxDisagreement * hits) << "misses drawn (the proxy box?)";
        EXPECT_LE(colourError, kDepthTolerance) << "the packed depth is not the hit's";
        EXPECT_LE(bufferError, kDepthTolerance) << "the depth buffer is not the hit's";
    }
}

// MeshDistanceMaterial as the override (a point light's record at the camera, post.js): the
// distance read back is the hit's from the light, as a fraction of the shadow camera's
// range. Its own float computation from the same hit (about the camera): seen 6e-7 of the
// range; 3e-6 (1.1e-5 world units, a two-hundredth of a texel of the bundled map) tells a
// hit off its texel or the box. Red with the box: 4.5e-2 off, 98 misses drawn.
TEST_F(ThreePost, MeshDistanceMaterialSeesTheHitDistance) {
    const View& v = viewNamed("oblique");
    const PageRun page = run(v, {"distances(" + std::to_string(kStep) + ")"});
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    const std::vector<double> r = numbers(page.at(4, "value"));
    ASSERT_EQ(r.size(), 4u) << page.at(4, "value") << page.err;
    const double hits = r[0], drawnHits = r[1], error = r[2], drawnMisses = r[3];
    std::printf("    %g hits, %g drawn, largest error %g; %g misses drawn\n", hits, drawnHits, error,
                drawnMisses);
    ASSERT_GT(hits, 1000.0);
    EXPECT_GE(drawnHits, (1.0 - kMaxDisagreement) * hits);
    EXPECT_LE(drawnMisses, kMaxDisagreement * hits) << "misses drawn (the proxy box?)";
    EXPECT_LE(error, 3e-6) << "the distance is not the hit's";
}

// GTAOPass (its raw AO buffer, radius 0.06) and SSAOPass (its blurred buffer, kernel radius
// 0.08) over the relief, read at the relief's surface hits, which the relief's own geometry
// classes (post.js, openness: 32 rays from the hit, traced by the library within the pass's
// radius): crevices (under 3/4 of the rays leave: the gaps between the cobbles) and open
// points (every ray leaves: the cobbles' tops). The crevices' mean AO is lower than the open
// points' by more than 0.1, and over 70 % of the crevice samples are darker than the open
// points' mean by 0.05. Seen: GTAO 0.65 against 1.0 (94 % darker), SSAO 0.77 to 0.78
// against 0.96 to 0.97 (98 %; SSAOPass's kernel and noise are Math.random's). Red with the
// box (a flat top, no crevice): GTAO 1.0 against 1.0 (none darker), SSAO 0.987 against
// 0.988 (0.4 %).
TEST_F(ThreePost, AmbientOcclusionPassesSeeTheCrevices) {
    const View& v = viewNamed("oblique");
    const std::string step = std::to_string(kStep);
    const PageRun page =
        run(v, {"ambientOcclusion('gtao', " + step + ", 0.06, 0.75, 1, 0.05)",
                "ambientOcclusion('ssao', " + step + ", 0.08, 0.75, 1, 0.05)"},
            {"gtao.png", "ssao.png"});
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const int k : {4, 6}) {
        SCOPED_TRACE(k == 4 ? "GTAOPass" : "SSAOPass");
        const std::vector<double> r = numbers(page.at(k, "value"));
        ASSERT_EQ(r.size(), 5u) << page.at(k, "value") << page.err;
        const double crevices = r[0], tops = r[1], creviceMean = r[2], topMean = r[3], darker = r[4];
        std::printf("    %g crevice samples (mean AO %g), %g top samples (mean %g); %g of the crevices darker\n",
                    crevices, creviceMean, tops, topMean, darker);
        ASSERT_GT(crevices, 100.0);
        ASSERT_GT(tops, 100.0);
        EXPECT_GT(topMean - creviceMean, 0.1) << "the crevices are not darker than the tops";
        EXPECT_GT(darker, 0.7) << "most crevice samples should be darker than the tops";
    }
}

}  // namespace
