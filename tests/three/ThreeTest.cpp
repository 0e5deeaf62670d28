// microrelief-three in a real browser (label three): examples/three's page, staged into the
// build tree with the package (packages/microrelief-three/CMakeLists.txt), in Debian's
// headless Chromium (WebGL 2 on SwiftShader), driven by tests/web/drive_chromium.py.
// - shading=microrelief: the relief drawn by three with the library's own shading, for
//   several cameras and bases, against microrelief-render's picture of the same flags;
// - three's Raycaster at random pixels against microrelief-render's AOV positions;
// - depth: a three.js plane crossing the relief; the depth three wrote equals the relief's
//   exact hit depth (from the AOV) where the relief is in front, the plane's where it is.
// The measurements inside the page are tests/three/checks.js; the views and the fixture,
// ThreePage.h.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <sstream>

#include "ThreePage.h"

using namespace microrelief;
using namespace microrelief::three_test;

namespace {

TEST_F(ThreePage, LibraryShadingMatchesTheRenderer) {
    std::string steps = "[";
    for (std::size_t k = 0; k < kViews.size(); ++k) {
        const View& v = kViews[k];
        steps += (k ? ", " : "") +
                 open("shading=microrelief" + (v.query.empty() ? "" : "&" + v.query), v.width,
                      v.height, "three/") +
                 ", {\"wait\": \"ready\"}, {\"screenshot\": " +
                 jsonString((dir / (v.name + "-page.png")).string()) + "}";
    }
    const PageRun page = runPage(steps + "]");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    for (std::size_t k = 0; k < kViews.size(); ++k) {
        const View& v = kViews[k];
        SCOPED_TRACE(v.name);
        const int step = 3 * static_cast<int>(k);
        ASSERT_EQ(page.at(step + 1, "state"), "ready") << page.at(step + 1, "error");
        const auto rendered = dir / (v.name + "-render.png");
        const std::string flags = v.flags + " --size " + size(v.width, v.height);
        render(flags, rendered);
        expectSamePicture(v.name, dir / (v.name + "-page.png"), rendered,
                          "microrelief-render " + flags, kLimits);
    }
}

// Raycaster.intersectObject(relief) through the centres of random pixels: the point is
// microrelief-render's AOV position of that pixel; a miss is its miss.
TEST_F(ThreePage, RaycasterHitsAreTheRenderersAovPositions) {
    for (const char* name : {"oblique", "grazing-shadows", "model", "cylinder-biquadratic"}) {
        const View& v = viewNamed(name);
        SCOPED_TRACE(v.name);
        constexpr int kPicks = 300;
        std::uint32_t state = 12345;
        const auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 8; };
        std::vector<std::pair<int, int>> pixels;
        std::string list = "[";
        for (int k = 0; k < kPicks; ++k) {
            pixels.emplace_back(static_cast<int>(next() % v.width),
                                static_cast<int>(next() % v.height));
            list += (k ? ",[" : "[") + std::to_string(pixels.back().first) + "," +
                    std::to_string(pixels.back().second) + "]";
        }
        list += "]";
        const PageRun page = runPage(
            "[" + openCompare(v) + ", {\"eval\": " +
            jsonString("threeChecks.pick(" + list +
                       ").map((h) => h ? [1, ...h.point] : [0, 0, 0, 0]).flat().join(' ')") +
            "}]");
        ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
        const std::vector<double> picked = numbers(page.at(3, "value"));
        ASSERT_EQ(picked.size(), 4 * pixels.size()) << page.at(3, "value");
        const auto aovFile = dir / (v.name + ".exr");
        renderWithAov(v, aovFile);
        const Aov aov = readAov(aovFile);
        ASSERT_EQ(aov.width, v.width);
        int hits = 0, disagreements = 0;
        double largest = 0.0;
        for (std::size_t k = 0; k < pixels.size(); ++k) {
            const float* expected = aov.at(pixels[k].first, pixels[k].second);
            const double* got = &picked[4 * k];
            if ((expected[3] == 1.0f) != (got[0] == 1.0)) {
                ++disagreements;
                continue;
            }
            if (got[0] != 1.0) continue;
            ++hits;
            const double distance =
                std::hypot(got[1] - expected[0], got[2] - expected[1], got[3] - expected[2]);
            largest = std::max(largest, distance);
            EXPECT_LE(distance, kPositionTolerance)
                << "pixel " << pixels[k].first << "," << pixels[k].second << ": picked " << got[1]
                << "," << got[2] << "," << got[3] << ", AOV " << expected[0] << "," << expected[1]
                << "," << expected[2];
        }
        std::printf("    %-22s %d hits of %d, largest distance %.3g, hit/miss disagreements %d\n",
                    v.name.c_str(), hits, kPicks, largest, disagreements);
        EXPECT_GT(hits, 40) << "too few hits to say anything";
        EXPECT_LE(disagreements, kMaxHitMissDisagreement * pixels.size());
    }
}

// A plane crossing the relief, drawn by three (MeshBasicMaterial) in the same scene: at a
// grid of pixels the depth three wrote is the nearer of the relief's exact hit (the AOV's
// position projected by three's camera) and the plane's own depth. Also with three's
// logarithmic depth buffer (checks.js: depthLogarithmic, a renderer of its own), where both
// depths are log2(1 + w) / log2(far + 1); its slope in w here is about 0.27 (w about 1.3,
// far 4), so the hits' 1e-6 world units stay far inside the same tolerances.
TEST_F(ThreePage, AMeshCrossingTheReliefCutsItAtTheHitDepth) {
    struct Case {
        const char* view;
        bool logarithmic;
    };
    for (const Case& c : {Case{"oblique", false}, Case{"model", false}, Case{"oblique", true}}) {
        const View& v = viewNamed(c.view);
        const std::string name = v.name + (c.logarithmic ? "-logarithmic" : "");
        SCOPED_TRACE(name);
        const auto aovFile = dir / (v.name + ".exr");
        renderWithAov(v, aovFile);
        const Aov aov = readAov(aovFile);
        ASSERT_EQ(aov.width, v.width);
        std::vector<std::pair<int, int>> pixels;
        std::string list = "[", points = "[";
        for (int row = 3; row < v.height; row += 6) {
            for (int column = 3; column < v.width; column += 6) {
                pixels.emplace_back(column, row);
                const float* p = aov.at(column, row);
                list += (pixels.size() > 1 ? ",[" : "[") + std::to_string(column) + "," +
                        std::to_string(row) + "]";
                std::ostringstream point;
                point.precision(9);
                if (p[3] == 1.0f)
                    point << "[" << p[0] << "," << p[1] << "," << p[2] << "]";
                else
                    point << "null";
                points += (pixels.size() > 1 ? "," : "") + point.str();
            }
        }
        list += "]";
        points += "]";
        // Just below the cobbles' tops, a little tilted: their tops stand above it, the rest under.
        const std::string call =
            std::string(c.logarithmic ? "threeChecks.depthLogarithmic(" : "threeChecks.depth(") +
            list + ", " + points +
            ", [0, 0.065, 0], [0.04, 1, 0.02], 0.25, 4)" +
            (c.logarithmic ? ".then((r) => r" : "") +
            ".map((d) => [d.read, d.plane ?? NaN, d.relief ?? NaN, d.edge ? 1 : 0]).flat().join(' ')" +
            (c.logarithmic ? ")" : "");
        const PageRun page = runPage(
            "[" + openCompare(v) + ", {\"eval\": " + jsonString(call) + "}, {\"screenshot\": " +
            jsonString((dir / (name + "-crossing.png")).string()) + "}]");
        ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
        for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
        const std::vector<double> depths = numbers(page.at(3, "value"));
        ASSERT_EQ(depths.size(), 4 * pixels.size()) << page.at(3, "value");
        int reliefInFront = 0, planeInFront = 0, aovHits = 0;
        double largestRelief = 0.0, largestPlane = 0.0;
        for (std::size_t k = 0; k < pixels.size(); ++k) {
            const double read = depths[4 * k], plane = depths[4 * k + 1],
                         relief = depths[4 * k + 2];
            if (depths[4 * k + 3] == 1.0) continue;  // on the square's edge
            const double planeDepth = std::isnan(plane) || plane < 0.0 || plane > 1.0 ? 1.0 : plane;
            const double reliefDepth = std::isnan(relief) ? 1.0 : relief;
            const double expected = std::min(planeDepth, reliefDepth);
            aovHits += !std::isnan(relief);
            if (!std::isnan(relief) && std::abs(relief - planeDepth) > kDepthTolerance)
                (relief < planeDepth ? reliefInFront : planeInFront) += 1;
            double& largest = expected == reliefDepth ? largestRelief : largestPlane;
            largest = std::max(largest, std::abs(read - expected));
            EXPECT_NEAR(read, expected,
                        expected == reliefDepth ? kDepthTolerance : kPlaneDepthTolerance)
                << "pixel " << pixels[k].first << "," << pixels[k].second << ": relief " << relief
                << ", plane " << plane;
        }
        std::printf(
            "    %-18s %zu pixels, %d relief hits: relief in front at %d, the plane at %d; largest "
            "depth difference %.3g (relief), %.3g (plane)\n",
            name.c_str(), pixels.size(), aovHits, reliefInFront, planeInFront, largestRelief,
            largestPlane);
        EXPECT_GT(reliefInFront, 20) << "the plane must leave cobbles standing above it";
        EXPECT_GT(planeInFront, 20) << "the plane must hide part of the relief";
    }
}

// three's shadow maps and the relief (checks.js: shadows), for each kind of light that
// casts them: a sphere's shadow falls on the relief's hit points whose ray towards the light
// meets the sphere, and the relief's shadow on a ground square falls where the ray from the
// ground towards the light meets the relief (traced from the light's shadow camera:
// orthographic for the directional light, perspective for the spot light, the six faces of a
// cube for the point light, whose distance material writes the hit's depth). Points within
// `margin` world units of the answer changing are left out; every other one must agree.
// The margins: 0.01 is 13 texels of the directional map (0.8 mm) and 6 of the spot light's
// (about 1.6 mm at the relief); the point light's cube faces of 1024 texels over 90 degrees
// have about 3 mm texels at the relief, so 0.015 (5 texels). three's PCF filter and its bias
// blur about two texels.
TEST_F(ThreePage, ShadowMapsFallWhereTheRaysTowardsTheLightAreBlocked) {
    const View& v = viewNamed("oblique");
    struct Case {
        const char* what;
        const char* kind;
        const char* light;  // a direction (directional) or a position
        double margin;
        int step;
    };
    const std::vector<Case> cases = {
        {"receive", "directional", "[-0.45, 0.8, -0.35]", 0.01, 2},
        {"cast", "directional", "[-0.8, 0.35, -0.5]", 0.01, 3},
        {"receive", "spot", "[-0.6, 1.1, -0.45]", 0.01, 2},
        {"cast", "spot", "[-1.0, 0.45, -0.6]", 0.01, 3},
        {"receive", "point", "[-0.6, 1.1, -0.45]", 0.015, 2},
        {"cast", "point", "[-1.0, 0.45, -0.6]", 0.015, 3},
    };
    std::string steps = "[" + openCompare(v);
    for (const Case& c : cases) {
        std::string list = "[";
        for (int row = 1; row < v.height; row += c.step)
            for (int column = 1; column < v.width; column += c.step)
                list += (list.size() > 1 ? ",[" : "[") + std::to_string(column) + "," +
                        std::to_string(row) + "]";
        const std::string name = std::string(c.what) + "-" + c.kind;
        steps += ", {\"eval\": " +
                 jsonString(std::string("threeChecks.shadows('") + c.what + "', " + list + "], " +
                            c.light + ", [0.02, 0.3, 0.05], " + std::to_string(c.margin) + ", '" +
                            c.kind + "').flat().join(' ')") +
                 "}, {\"screenshot\": " + jsonString((dir / (name + ".png")).string()) + "}";
    }
    const PageRun page = runPage(steps + "]");
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const std::string name = std::string(cases[k].what) + "-" + cases[k].kind;
        SCOPED_TRACE(name);
        const std::vector<double> answers = numbers(page.at(3 + 2 * static_cast<int>(k), "value"));
        ASSERT_FALSE(answers.empty()) << page.at(3 + 2 * static_cast<int>(k), "value");
        int shadowed = 0, lit = 0, wrong = 0;
        for (std::size_t j = 0; j + 1 < answers.size(); j += 2) {
            if (answers[j] < 0) continue;
            (answers[j] == 1 ? shadowed : lit) += 1;
            wrong += answers[j] != answers[j + 1];
        }
        std::printf(
            "    %-20s %d points shadowed, %d lit by the geometry; the picture disagrees at %d\n",
            name.c_str(), shadowed, lit, wrong);
        EXPECT_EQ(wrong, 0);
        EXPECT_GT(shadowed, 50) << "too few shadowed points to say anything";
        EXPECT_GT(lit, 50) << "too few lit points to say anything";
    }
}

// ReliefStandardMaterial's selfShadow (checks.js: selfShadow) against microrelief-render's
// --shadows hard for the same camera and light: a pixel is shadowed in the page where the
// exact shadow takes more than half of what the directional light adds there (pixels where
// it adds under 24 levels are left out), and for microrelief-render where its AOV's shadow
// channel is 0 on a hit. Both run the library's mr_hardShadow from the same pixel's hit;
// the hits of the two GPUs differ by about 1e-6 world units, and a shadow ray that grazes a
// cobble's edge may flip with that: at most 0.5 % of the compared pixels may disagree
// (seen: none of 5818; the light, 11 degrees up, shadows 260 of them).
TEST_F(ThreePage, SelfShadowIsTheRenderersHardShadow) {
    const View& v = viewNamed("oblique");
    const std::string light = "-0.8,0.2,-0.5";  // low (11 degrees), for long shadows between the cobbles
    const PageRun page =
        runPage("[" + openCompare(v) + ", {\"eval\": " +
                jsonString("threeChecks.selfShadow([" + light + "]).join(' ')") + "}]");
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    const std::vector<double> seen = numbers(page.at(3, "value"));
    ASSERT_EQ(seen.size(), static_cast<std::size_t>(v.width * v.height)) << page.at(3, "value");
    const auto aovFile = dir / "hard.exr";
    render("--shadows hard --light=" + light + " --size " + size(v.width, v.height) + " --aov " +
               aovFile.string(),
           dir / "hard.png");
    auto input = OIIO::ImageInput::open(aovFile.string());
    ASSERT_TRUE(input) << aovFile;
    ASSERT_EQ(input->spec().nchannels, 5) << "no shadow channel in the AOV";
    ASSERT_EQ(input->spec().width, v.width);
    std::vector<float> aov(static_cast<std::size_t>(v.width) * v.height * 5);
    ASSERT_TRUE(input->read_image(0, 0, 0, 5, OIIO::TypeDesc::FLOAT, aov.data()));
    int shadowed = 0, lit = 0, wrong = 0;
    for (std::size_t k = 0; k < seen.size(); ++k) {
        const float* p = &aov[5 * k];
        if (seen[k] < 0 || p[3] != 1.0f) continue;
        const int expected = p[4] == 0.0f;
        (expected ? shadowed : lit) += 1;
        wrong += expected != seen[k];
    }
    std::printf("    %d pixels shadowed by microrelief-render, %d lit; selfShadow disagrees at %d\n",
                shadowed, lit, wrong);
    EXPECT_GT(shadowed, 100) << "too few shadowed pixels to say anything";
    EXPECT_GT(lit, 1000) << "too few lit pixels to say anything";
    EXPECT_LE(wrong, 0.005 * (shadowed + lit));
}

// Shadow acne on the three-lit example's floor (examples/three/cobbles.js; checks.js:
// shadowAcne): the example's scene drawn as it is (A) and with the floor out of three's
// shadow map (B), the only difference the floor meeting its own depth there; of the lit
// floor pixels, those that A darkens by more than a quarter of what the sun adds. First with
// the example's own sun.shadow.normalBias, then with none, which must show the acne: the
// measure can fail, in the same run. Seen (240 x 180, about 9560 lit floor pixels of 17675):
// normalBias 0: 87 % darker; 0.001: 22 %; 0.002: 0.4 %; the example's 0.01: 0.23 % (22
// pixels, not acne: thin slivers of lit stone where the box's side walls cut the cobbles,
// narrower than a shadow texel of 3 mm, and one at the foot of a gap); 0.04: 1.9 % (the
// larger offset carries lookups into shadow on lit flanks beside the gaps).
TEST_F(ThreePage, TheExamplesFloorHasNoShadowAcne) {
    // 1 %: four times what the example's bias leaves, a twentieth of what a third of a
    // shadow texel of bias (0.001) leaves and an eightieth of the acne without any.
    constexpr double kMaxDarkerFraction = 0.01;
    // The control without bias must be well over the limit, not just over it: ten times.
    constexpr double kMinAcneFraction = 10 * kMaxDarkerFraction;
    struct Case {
        const char* name;
        const char* normalBias;  // JavaScript: null is the example's own
        bool acne;
    };
    // The control: a normalBias that cancels the rule's offset for the example's sun (PCF
    // radius 1, a 512 map over 1.6 units), three's lookup as it was without the rule.
    const std::vector<Case> cases = {{"example", "null", false},
                                     {"rule-cancelled", "-(1 + Math.SQRT2) * 1.6 / 512", true}};
    const View& v = viewNamed("oblique");
    std::string steps =
        "[" + open("", v.width, v.height, "three/") +
        ", {\"wait\": \"ready\"}, {\"eval\": " + jsonString(test::readText(MICRORELIEF_CHECKS_JS)) +
        "}";
    for (const Case& c : cases) {
        const std::string name = std::string("acne-") + c.name;
        steps +=
            ", {\"eval\": " +
            jsonString(std::string("threeChecks.withoutFloorInShadowMap(") + c.normalBias + ")") +
            "}, {\"screenshot\": " + jsonString((dir / (name + "-without.png")).string()) +
            "}, {\"eval\": " +
            jsonString(std::string("threeChecks.shadowAcne(") + c.normalBias + ").join(' ')") +
            "}, {\"screenshot\": " + jsonString((dir / (name + "-with.png")).string()) + "}";
    }
    const PageRun page = runPage(steps + "]");
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Case& c = cases[k];
        const std::string name = std::string("acne-") + c.name;
        SCOPED_TRACE(name);
        const std::string value = page.at(5 + 4 * static_cast<int>(k), "value");
        const std::vector<double> seen = numbers(value);
        ASSERT_EQ(seen.size(), 4u) << value;
        const double bias = seen[0], floorPixels = seen[1], lit = seen[2], darker = seen[3];
        const double fraction = lit > 0 ? darker / lit : 0.0;
        std::printf(
            "    %-14s normalBias %g: %.0f floor pixels, %.0f lit, %.0f (%.2f %%) darker with the "
            "floor in the shadow map\n",
            name.c_str(), bias, floorPixels, lit, darker, 100.0 * fraction);
        EXPECT_GT(lit, 4000) << "too few lit floor pixels to say anything";
        const bool wrong = c.acne ? fraction < kMinAcneFraction : fraction > kMaxDarkerFraction;
        if (!wrong) continue;
        const test::Image with = test::readImage(dir / (name + "-with.png")),
                          without = test::readImage(dir / (name + "-without.png"));
        ADD_FAILURE() << (c.acne ? "no acne seen without a bias: the measure cannot fail"
                                 : "shadow acne: the floor's lit stones darken in its own shadow")
                      << " (" << 100.0 * fraction << " % of the lit floor pixels, limit "
                      << 100.0 * (c.acne ? kMinAcneFraction : kMaxDarkerFraction)
                      << " %); with (actual) and without the floor in the map (expected): "
                      << test::keepForInspection(failures_, name, with, without);
    }
}

// The CPU pyramid path against the GPU's (checks.js: pyramids): the windows pyramid of the
// bundled map and of an odd-sized map (37 x 23, so every level's halving rounds), with and
// without wrapU, built by shaders/pyramid/'s passes into R16F render targets and by the
// C++ MaxPyramid compiled to WebAssembly. Both compute the same maxima of the same float
// samples, scaled by 2^-S and rounded up to a half by the same rule, so every texel of every
// level must be equal to the bit, and S and the max height the same.
TEST_F(ThreePage, TheWebAssemblyPyramidIsTheGpusToTheBit) {
    const View& v = viewNamed("oblique");
    const PageRun page =
        runPage("[" + openCompare(v) + ", {\"eval\": \"threeChecks.pyramids()\"}]");
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    std::istringstream lines(page.at(3, "value"));
    int cases = 0;
    for (std::string line; std::getline(lines, line);) {
        std::istringstream fields(line);
        std::string name, gpu, cpu;
        long levels = 0, texels = 0, differing = -1, sameScale = 0;
        fields >> name >> levels >> texels >> differing >> sameScale >> gpu >> cpu;
        SCOPED_TRACE(line);
        std::printf("    %-14s %ld levels, %ld texels, %ld differ; built on %s and %s\n",
                    name.c_str(), levels, texels, differing, gpu.c_str(), cpu.c_str());
        ++cases;
        EXPECT_EQ(gpu, "gpu");
        EXPECT_EQ(cpu, "cpu");
        EXPECT_GT(levels, 5) << "the level counts differ (-1) or too few";
        EXPECT_EQ(differing, 0);
        EXPECT_EQ(sameScale, 1) << "S or the max height differ";
    }
    EXPECT_EQ(cases, 4) << page.at(3, "value");
}

// Bad input (checks.js: refusals): a map larger than the GPU takes, a file that is no image,
// a missing EXT_color_buffer_float for the GPU pyramid: each one error of the package's own
// class naming the cause, and the scene's picture afterwards the same to the bit.
TEST_F(ThreePage, BadInputIsOneClearErrorAndTheSceneKeepsDrawing) {
    const View& v = viewNamed("oblique");
    const PageRun page = runPage("[" + openCompare(v) +
                                 ", {\"screenshot\": " + jsonString((dir / "before.png").string()) +
                                 "}, {\"eval\": \"threeChecks.refusals()\"}, {\"screenshot\": " +
                                 jsonString((dir / "after.png").string()) + "}]");
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    const std::string lines = page.at(4, "value");
    std::printf("%s\n", lines.c_str());
    for (const char* expected : {"too large: ReliefGpuError: samples: ", "MAX_TEXTURE_SIZE",
                                 "not an image: HeightMapError: index.html: not a PNG",
                                 "no extension: ReliefGpuError: ", "no EXT_color_buffer_float"})
        EXPECT_NE(lines.find(expected), std::string::npos) << expected << "\n" << lines;
    const test::Image before = test::readImage(dir / "before.png"),
                      after = test::readImage(dir / "after.png");
    ASSERT_GT(before.width, 0);
    EXPECT_EQ(before.pixels, after.pixels) << "the scene changed after the refusals";
}

// Views the programs refuse (issue 47) are refused by the example too, with the programs'
// checks (microrelief-three's loadSceneChecks) and their messages, the example's keys for
// their flags (every case's message against microrelief-render's: tests/web/
// scene_checks_test.mjs): a singular model, a field of view whose pixels' rays float cannot
// tell apart, the eye at the target. Each is one line and the state says so.
TEST_F(ThreePage, ViewsTheProgramsRefuseAreRefusedWithTheirMessages) {
    const struct {
        std::string query, expected;
    } cases[] = {
        {"shading=microrelief&model=1,0,0,0,0,1,0,0,0,0,0,0",
         "the URL: model: the matrix is singular"},
        {"fovy=1e-37",
         "the URL: fovy 1e-37 at a picture 48 pixels high: neighbouring pixels' rays"},
        {"eye=0.5,0.5,0.5&target=0.5,0.5,0.5", "the URL: eye and target must differ"},
    };
    std::string steps;
    for (const auto& c : cases)
        steps += (steps.empty() ? "" : ", ") + open(c.query, 64, 48, "three/") +
                 ", {\"wait\": \"ready\"}";
    const PageRun page = runPage("[" + steps + "]");
    for (std::size_t k = 0; k < std::size(cases); ++k) {
        SCOPED_TRACE(cases[k].query);
        const int step = 2 * static_cast<int>(k) + 1;
        EXPECT_EQ(page.at(step, "state"), "error");
        EXPECT_NE(page.at(step, "error").find(cases[k].expected), std::string::npos)
            << page.at(step, "error");
        EXPECT_EQ(page.at(step, "error").find('\n'), std::string::npos) << "one line";
    }
}

// renderer=webgpu (issue 51): the example on three's WebGPURenderer and
// microrelief-three/webgpu. shading=microrelief against microrelief-render's picture of the
// same flags, held to the WebGL entry's limits (kLimits: three.webgpu finds the two entries'
// pictures bit-identical on SwiftShader, so WebGPU is allowed nothing more), on the plane with
// the map's colours, at a grazing view with hard shadows, under a model matrix, on the
// cylinder's biquadratic last level and on the sphere; data-api says 'webgpu' once the
// first frame is drawn. The three-lit example (cobbles_webgpu.js) draws too: ready,
// 'webgpu', no box of the relief's proxy left white, and the WebGL example's picture.
TEST_F(ThreePage, RendererWebGPUDrawsTheRenderersPicture) {
    const char* names[] = {"oblique", "grazing-shadows", "model", "cylinder-biquadratic", "sphere"};
    std::string steps = "[";
    for (const char* name : names) {
        const View& v = viewNamed(name);
        steps += (steps.size() > 1 ? ", " : "") +
                 open("renderer=webgpu&shading=microrelief" + (v.query.empty() ? "" : "&" + v.query),
                      v.width, v.height, "three/") +
                 ", {\"wait\": \"ready\"}, {\"eval\": \"document.documentElement.dataset.api\"}, "
                 "{\"screenshot\": " + jsonString((dir / (v.name + "-webgpu.png")).string()) + "}";
    }
    steps += ", " + open("renderer=webgpu", 240, 180, "three/") +
             ", {\"wait\": \"ready\"}, {\"eval\": \"document.documentElement.dataset.api\"}, "
             "{\"screenshot\": " + jsonString((dir / "cobbles-webgpu.png").string()) + "}, " +
             open("", 240, 180, "three/") + ", {\"wait\": \"ready\"}, {\"screenshot\": " +
             jsonString((dir / "cobbles-webgl.png").string()) + "}]";
    const PageRun page = runPage(steps, site(), Gpu::WithWebGPU);
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    for (std::size_t k = 0; k < std::size(names); ++k) {
        const View& v = viewNamed(names[k]);
        SCOPED_TRACE(v.name);
        const int step = 4 * static_cast<int>(k);
        ASSERT_EQ(page.at(step + 1, "state"), "ready") << page.at(step + 1, "error");
        EXPECT_EQ(page.at(step + 2, "value"), "webgpu");
        const auto rendered = dir / (v.name + "-render.png");
        const std::string flags = v.flags + " --size " + size(v.width, v.height);
        render(flags, rendered);
        expectSamePicture(v.name + "-webgpu", dir / (v.name + "-webgpu.png"), rendered,
                          "microrelief-render " + flags, kLimits);
    }
    const int lit = 4 * static_cast<int>(std::size(names));
    ASSERT_EQ(page.at(lit + 1, "state"), "ready") << page.at(lit + 1, "error");
    EXPECT_EQ(page.at(lit + 2, "value"), "webgpu");
    // The floor's stones fill the middle of the picture: a proxy box drawn untraced would be
    // flat white there, a relief not drawn the clear colour (black: the renderer is opaque,
    // alpha false, as a WebGLRenderer is by default).
    const test::Image picture = test::readImage(dir / "cobbles-webgpu.png");
    ASSERT_EQ(picture.width, 240);
    int white = 0, background = 0, counted = 0;
    for (int y = 95; y < 145; ++y)
        for (int x = 85; x < 155; ++x, ++counted) {
            const int r = picture.at(x, y, 0), g = picture.at(x, y, 1), b = picture.at(x, y, 2);
            white += r > 240 && g > 240 && b > 240;
            background += r < 3 && g < 3 && b < 3;
        }
    EXPECT_LT(white, counted / 100) << "of " << counted;
    EXPECT_LT(background, counted / 100) << "of " << counted;
    // And it is the WebGL example's scene (cobbles.js), shadow maps and self-shadow included,
    // where WebGL drew anything (not its black clear colour): measured 0.73 % of those pixels
    // over 8 levels apart (138 of 18 896), mean 0.46, where three's two renderers' shadow
    // maps differ (WebGL packs the depth into RGBA8, WebGPU keeps a float: texels that close
    // flip between lit and shadowed) and the PCF filter's edges with them. Seen red with the
    // floor neither casting, receiving nor shadowing itself: 2.14 % (405), mean 1.04.
    const test::Image webgl = test::readImage(dir / "cobbles-webgl.png");
    ASSERT_EQ(webgl.width, picture.width);
    ASSERT_EQ(webgl.height, picture.height);
    int drawn = 0, apart = 0;
    double sum = 0;
    for (int y = 0; y < picture.height; ++y)
        for (int x = 0; x < picture.width; ++x) {
            int largest = 0, difference = 0;
            for (int c = 0; c < 3; ++c) {
                largest = std::max(largest, int(webgl.at(x, y, c)));
                difference = std::max(difference, std::abs(int(webgl.at(x, y, c)) - int(picture.at(x, y, c))));
            }
            if (largest < 3) continue;
            ++drawn;
            sum += difference;
            apart += difference > 8;
        }
    std::printf("    the lit example, WebGPU against WebGL: %d of %d drawn pixels over 8 levels apart, mean %.3f\n",
                apart, drawn, sum / std::max(drawn, 1));
    ASSERT_GT(drawn, picture.width * picture.height / 3);
    EXPECT_LE(apart, drawn * 3 / 200) << "over 1.5 % of the drawn pixels";
    EXPECT_LE(sum / drawn, 0.75);
}

// renderer=webgpu where the browser gives no WebGPU (Chromium without --webgpu) is one line
// saying so, not WebGL 2's picture; a bad value and what WebGPU cannot do are one line too.
TEST_F(ThreePage, RendererWebGPUWithoutWebGPUIsOneLineNotAFallback) {
    const struct {
        std::string query, expected;
    } cases[] = {
        {"renderer=webgpu&shading=microrelief", "renderer=webgpu: this browser "},
        {"renderer=webgpu", "renderer=webgl draws with WebGL 2"},
        {"renderer=vulkan", "renderer=vulkan: expected webgl, webgpu"},
    };
    std::string steps;
    for (const auto& c : cases)
        steps += (steps.empty() ? "" : ", ") + open(c.query, 64, 48, "three/") +
                 ", {\"wait\": \"ready\"}, {\"eval\": \"String(document.documentElement.dataset.api)\"}";
    const PageRun page = runPage("[" + steps + "]");
    for (std::size_t k = 0; k < std::size(cases); ++k) {
        SCOPED_TRACE(cases[k].query);
        const int step = 3 * static_cast<int>(k) + 1;
        EXPECT_EQ(page.at(step, "state"), "error");
        EXPECT_NE(page.at(step, "error").find(cases[k].expected), std::string::npos)
            << page.at(step, "error");
        EXPECT_EQ(page.at(step, "error").find('\n'), std::string::npos) << "one line";
        EXPECT_EQ(page.at(step + 1, "value"), "undefined") << "no API drawn with";
    }
    const PageRun gpu = runPage("[" + open("renderer=webgpu&shading=microrelief&pyramid=gpu", 64, 48, "three/") +
                                ", {\"wait\": \"ready\"}]", site(), Gpu::WithWebGPU);
    EXPECT_EQ(gpu.at(1, "state"), "error");
    EXPECT_NE(gpu.at(1, "error").find("pyramid=gpu: renderer=webgpu builds the max pyramid in WebAssembly"),
              std::string::npos) << gpu.at(1, "error");
}

// ---- The package as a user gets it (CTest entry three.pack) ----
//
// One pack for the whole entry (packed()): packages/microrelief-three/scripts/pack.mjs run in
// the source package as `npm run tarball` runs it, into a scratch folder (it stages a copy
// there, builds generated/ into it with em++, and runs `npm pack` on the copy); the tarball
// installed with three and @types/three into a scratch npm project (`npm install
// --prefer-offline`: from the npm cache that the package's `npm ci` filled, no network
// needed), laid out as web/three/ of a site that web/serve.py serves with examples/three's
// files. ThreeTarball's tests need node and npm, not a browser; ThreePackage runs the
// installed example in Chromium, and the WebGPU entry bundled there by Vite (web/bundle/).

namespace fs = std::filesystem;

// Exactly what the tarball holds: what a consumer runs (src/'s modules, generated/), the
// declarations, package.json, README.md and LICENSE. No build inputs (glsl/, which
// generated/glsl.js holds; wasm/; scripts/), no tests, no node_modules.
const std::vector<std::string> kTarballFiles = {"package/LICENSE",
                                                "package/README.md",
                                                "package/package.json",
                                                "package/generated/glsl.js",
                                                "package/generated/manifest.json",
                                                "package/generated/png.js",
                                                "package/generated/pyramid_wasm.js",
                                                "package/generated/relief_core.js",
                                                "package/generated/relief_layout.js",
                                                "package/generated/scene_checks.js",
                                                "package/generated/scene_checks_wasm.js",
                                                "package/generated/twin_wasm.js",
                                                "package/generated/wgsl.js",
                                                "package/src/albedo.d.ts",
                                                "package/src/albedo.js",
                                                "package/src/checks.d.ts",
                                                "package/src/checks.js",
                                                "package/src/heights.d.ts",
                                                "package/src/heights.js",
                                                "package/src/index.d.ts",
                                                "package/src/index.js",
                                                "package/src/loader.d.ts",
                                                "package/src/loader.js",
                                                "package/src/map_host.js",
                                                "package/src/materials.d.ts",
                                                "package/src/materials.js",
                                                "package/src/override.js",
                                                "package/src/pyramid.d.ts",
                                                "package/src/pyramid.js",
                                                "package/src/relief.d.ts",
                                                "package/src/relief.js",
                                                "package/src/relief_host.js",
                                                "package/src/twin.d.ts",
                                                "package/src/twin.js",
                                                "package/src/three_version.js",
                                                "package/src/webgpu.d.ts",
                                                "package/src/webgpu.js"};

// The most a refusal of the package may say: one line naming the range.
const std::string kBelowTheRange =
    "Error: microrelief-three needs three >=0.182.0 (r182 or newer), but the 'three' it imports is "
    "r181";

// A program where CMake found it, else in /usr/bin or on PATH.
std::string findTool(const std::string& configured, const std::string& name) {
    std::vector<fs::path> candidates = {configured, "/usr/bin/" + name};
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "");
    for (std::string d; std::getline(dirs, d, ':');)
        if (!d.empty()) candidates.push_back(fs::path(d) / name);
    for (const fs::path& candidate : candidates) {
        std::error_code ec;
        if (!candidate.empty() && fs::is_regular_file(candidate, ec) &&
            access(candidate.c_str(), X_OK) == 0)
            return candidate.string();
    }
    return {};
}

// The package's files (node_modules left out), each with its size and time: what packing
// must leave as it was.
std::string snapshot(const fs::path& folder) {
    std::vector<std::string> lines;
    for (auto it = fs::recursive_directory_iterator(folder);
         it != fs::recursive_directory_iterator(); ++it) {
        if (it->path().filename() == "node_modules") {
            it.disable_recursion_pending();
            continue;
        }
        std::error_code ec;
        const auto time = fs::last_write_time(it->path(), ec).time_since_epoch().count();
        lines.push_back(fs::relative(it->path(), folder).string() + " " +
                        (it->is_regular_file() ? std::to_string(it->file_size()) : "dir") + " " +
                        std::to_string(time));
    }
    std::sort(lines.begin(), lines.end());
    std::string text;
    for (const std::string& line : lines) text += line + "\n";
    return text;
}

std::vector<std::string> sortedLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    std::sort(lines.begin(), lines.end());
    return lines;
}

std::string joined(const std::vector<std::string>& lines) {
    std::string text;
    for (const std::string& line : lines) text += "  " + line + "\n";
    return text;
}

struct Packed {
    std::string npm, node, emxx, missing;  // the tools, or which one is not there
    std::string env;                       // the environment the package's scripts run in
    test::ScratchDir scratch;
    fs::path tarball, site, project;  // the project: site/web/three
    test::RunResult pack, install;
    std::string before, after, listing;
    std::string three, tested;  // the three installed, and the package's (devDependencies)
    std::string vite;           // the package's Vite (devDependencies), for ThreePackage's bundle
};

test::RunResult runIn(const fs::path& folder, const std::string& command, const fs::path& scratch) {
    return test::runCommand("cd " + browser::quote(folder.string()) + " && " + command, scratch);
}

// Packed and installed once for the entry; `missing` says which tool was not there.
const Packed& packed() {
    static const std::unique_ptr<Packed> once = [] {
        auto p = std::make_unique<Packed>();
        p->npm = findTool(MICRORELIEF_NPM, "npm");
        p->emxx = findTool(MICRORELIEF_EMXX, "em++");
        p->node = findTool(MICRORELIEF_NODE_EXE, "node");
        for (const auto& [program, package] :
             {std::pair{p->npm, "npm"}, std::pair{p->emxx, "emscripten"},
              std::pair{p->node, "nodejs"}})
            if (program.empty() && p->missing.empty()) p->missing = package;
        if (!p->missing.empty()) return p;
        const fs::path source = MICRORELIEF_PACKAGE_DIR, out = p->scratch / "npm";
        p->env = "MICRORELIEF_SOURCE_DIR=" + browser::quote(MICRORELIEF_SOURCE_DIR) + " PATH=" +
                 browser::quote(fs::path(p->emxx).parent_path().string() + ":" +
                                fs::path(p->node).parent_path().string() + ":" +
                                fs::path(p->npm).parent_path().string()) +
                 ":\"$PATH\" ";
        p->before = snapshot(source);
        p->pack = runIn(source,
                        p->env + browser::quote(p->node) + " scripts/pack.mjs --out " +
                            browser::quote(out.string()),
                        p->scratch.path());
        p->after = snapshot(source);
        if (p->pack.status != 0) return p;
        for (const fs::directory_entry& entry : fs::directory_iterator(out))
            if (entry.path().extension() == ".tgz") p->tarball = entry.path();
        p->listing = runIn(p->scratch.path(), "tar tzf " + browser::quote(p->tarball.string()),
                           p->scratch.path())
                         .out;

        // The site: web/serve.py, its root page, the bundled map, examples/three's files
        // and, in web/three, the npm project.
        p->site = p->scratch / "site";
        p->project = p->site / "web" / "three";
        fs::create_directories(p->project);
        fs::create_directories(p->site / "assets");
        fs::copy_file(fs::path(MICRORELIEF_SOURCE_DIR) / "web" / "serve.py",
                      p->site / "web" / "serve.py");
        std::ofstream(p->site / "web" / "index.html") << "<a href=\"three/\">three/</a>\n";
        for (const char* asset : {"cobbles.png", "cobbles-albedo.png"})
            fs::copy_file(fs::path(MICRORELIEF_SOURCE_DIR) / "assets" / asset,
                          p->site / "assets" / asset);
        for (const fs::directory_entry& entry :
             fs::directory_iterator(fs::path(MICRORELIEF_SOURCE_DIR) / "examples" / "three"))
            fs::copy_file(entry.path(), p->project / entry.path().filename());
        std::ofstream(p->project / "package.json")
            << "{\"name\": \"scratch-three\", \"private\": true, \"type\": \"module\"}\n";
        // three at the version the package is tested with (its devDependencies), or
        // MICRORELIEF_THREE_VERSION's (another version in the peer range), and three's types.
        const auto devDependency = [&](const std::string& name) {
            const test::RunResult r =
                runIn(p->scratch.path(),
                      browser::quote(p->node) + " -p \"require('" + source.string() +
                          "/package.json').devDependencies['" + name + "']\"",
                      p->scratch.path());
            return r.out.substr(0, r.out.find('\n'));
        };
        const char* three = std::getenv("MICRORELIEF_THREE_VERSION");
        p->tested = devDependency("three");
        p->three = three && *three ? three : p->tested;
        p->vite = devDependency("vite");
        p->install = runIn(p->project,
                           p->env + browser::quote(p->npm) +
                               " install --prefer-offline --no-audit --no-fund three@" + p->three +
                               " @types/three@" + devDependency("@types/three") + " " +
                               browser::quote(p->tarball.string()),
                           p->scratch.path());
        std::printf("    packed and installed with three %s\n", p->three.c_str());
        return p;
    }();
    return *once;
}

// Tests of the packed and installed package without a browser.
class ThreeTarball : public ::testing::Test {
protected:
    void SetUp() override {
        const Packed& p = packed();
        if (!p.missing.empty()) {
            const std::string why = "no " + p.missing + " (Debian package " + p.missing +
                                    "; bash scripts/setup.sh installs it): packing needs it";
            const char* allow = std::getenv("MICRORELIEF_ALLOW_MISSING_BROWSER");
            if (allow && std::string(allow) == "1") GTEST_SKIP() << why;
            FAIL() << why << "; MICRORELIEF_ALLOW_MISSING_BROWSER=1 skips this test instead";
        }
        ASSERT_EQ(p.pack.status, 0) << p.pack.out << p.pack.err;
        ASSERT_EQ(p.install.status, 0) << p.install.out << p.install.err;
    }

    // node tests/three/node_checks.mjs `cases` in `folder` (a project that installed the package).
    std::string nodeChecks(const fs::path& folder, const std::string& cases) {
        const test::RunResult r =
            runIn(folder,
                  browser::quote(packed().node) + " " +
                      browser::quote(
                          (fs::path(MICRORELIEF_THREE_TESTS_DIR) / "node_checks.mjs").string()) +
                      " " + cases,
                  dir.path());
        EXPECT_EQ(r.status, 0) << r.out << r.err;
        std::printf("%s", r.out.c_str());
        return r.out;
    }

    test::ScratchDir dir;
};

// Packing leaves the source package as it was: no generated/, no tarball, no file touched.
// Red before pack.mjs: npm pack's prepack wrote generated/ into the package's folder.
TEST_F(ThreeTarball, PackingWritesNothingIntoTheSourceTree) {
    const Packed& p = packed();
    EXPECT_EQ(p.before, p.after) << "packing changed packages/microrelief-three";
    EXPECT_FALSE(fs::exists(fs::path(MICRORELIEF_PACKAGE_DIR) / "generated"));
    EXPECT_EQ(p.tarball.filename(), "microrelief-three-0.1.0.tgz");
    EXPECT_NE(p.pack.out.find(p.tarball.filename().string()), std::string::npos) << p.pack.out;
}

// The tarball's files, exactly, and its package.json as well-kept three.js addons have it.
TEST_F(ThreeTarball, TheTarballHoldsExactlyWhatAConsumerRuns) {
    const Packed& p = packed();
    std::vector<std::string> expected = kTarballFiles;
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(sortedLines(p.listing), expected) << "the tarball holds:\n"
                                                << joined(sortedLines(p.listing)) << "expected:\n"
                                                << joined(expected);
    const fs::path installed = p.project / "node_modules" / "microrelief-three";
    EXPECT_EQ(test::readText(installed / "LICENSE"),
              test::readText(fs::path(MICRORELIEF_SOURCE_DIR) / "LICENSE"));
    const test::RunResult fields =
        runIn(installed,
              browser::quote(p.node) +
                  " -e \"const p = require('./package.json'); console.log(["
                  "p.license, p.types, p.sideEffects, Object.keys(p.exports['.']).join(' '), "
                  "p.exports['.'].types, Object.keys(p.exports).join(' '), "
                  "p.repository.type, p.repository.url, p.repository.directory, "
                  "p.peerDependencies.three, 'scripts' in p].join('\\n'))\"",
              dir.path());
    EXPECT_EQ(
        fields.out,
        "MIT\n./src/index.d.ts\nfalse\ntypes default\n./src/index.d.ts\n. ./webgpu ./package.json\ngit\n"
        "git+https://github.com/microrelief/microrelief.git\npackages/"
        "microrelief-three\n>=0.182.0\nfalse\n")
        << fields.err;
    // Packed with em++: the WebAssembly itself, not the stubs of a package packed without it.
    EXPECT_EQ(
        test::readText(installed / "generated" / "pyramid_wasm.js").find("no WebAssembly pyramid"),
        std::string::npos);
    EXPECT_EQ(test::readText(installed / "generated" / "scene_checks_wasm.js")
                  .find("no WebAssembly scene checks"),
              std::string::npos);
}

// The declarations (src/*.d.ts), installed from the tarball with three's own types, under
// tsc --noEmit --strict (the package's TypeScript, its devDependency): tests/three/typecheck's
// usage.ts (the API in use, and misuses that must be errors) and exports.ts, which
// typecheck/exports.mjs writes from what each entry, 'microrelief-three' and
// 'microrelief-three/webgpu', exports at run time (each declared, and nothing more: red with
// webgpu.d.ts's wgslItems dropped, TS2339, and a kNotThere added), with node's module
// resolution and a bundler's. Red before: TS7016, no
// declaration file for 'microrelief-three'.
TEST_F(ThreeTarball, TheDeclarationsTypecheckUnderStrict) {
    const Packed& p = packed();
    const fs::path tsc = fs::path(MICRORELIEF_PACKAGE_DIR) / "node_modules" / ".bin" / "tsc";
    ASSERT_TRUE(fs::exists(tsc))
        << tsc << ": no TypeScript: `npm ci` in packages/microrelief-three (bash scripts/setup.sh)";
    const fs::path check = p.project / "typecheck",
                   from = fs::path(MICRORELIEF_THREE_TESTS_DIR) / "typecheck";
    fs::create_directories(check);
    for (const char* file : {"usage.ts", "tsconfig.json"})
        fs::copy_file(from / file, check / file, fs::copy_options::overwrite_existing);
    const test::RunResult exports =
        runIn(check, browser::quote(p.node) + " " + browser::quote((from / "exports.mjs").string()),
              dir.path());
    ASSERT_EQ(exports.status, 0) << exports.out << exports.err;
    std::printf("    %s names exported at run time\n",
                exports.out.substr(0, exports.out.find('\n')).c_str());
    for (const char* resolution : {"", " --module esnext --moduleResolution bundler"}) {
        SCOPED_TRACE(*resolution ? "bundler" : "nodenext");
        const test::RunResult r =
            runIn(check,
                  browser::quote(tsc.string()) + " --noEmit --strict -p tsconfig.json" + resolution,
                  dir.path());
        EXPECT_EQ(r.status, 0) << r.out << r.err;
    }
}

// Below the oldest three in the range, each call that makes a relief is one line naming
// the range (three 0.170 failed inside three's renderer: "Invalid value used as weak map
// key"; 0.171 to 0.181 put a relief's point-light shadow in the wrong places), and the
// installed three passes: the installed package beside a three that is the installed one
// with REVISION '181'. Red before three_version.js: the calls went on.
TEST_F(ThreeTarball, BelowTheOldestThreeEachReliefIsOneLineNamingTheRange) {
    const Packed& p = packed();
    const fs::path old = dir / "old-three", modules = old / "node_modules";
    fs::create_directories(modules / "three");
    fs::copy(p.project / "node_modules" / "microrelief-three", modules / "microrelief-three",
             fs::copy_options::recursive);
    std::ofstream(modules / "three" / "package.json")
        << "{\"name\": \"three\", \"version\": \"0.181.0\", \"type\": \"module\", \"exports\": "
           "{\".\": \"./index.js\"}}\n";
    std::ofstream(modules / "three" / "index.js")
        << "export * from '"
        << (p.project / "node_modules" / "three" / "build" / "three.module.js").string()
        << "';\nexport const REVISION = '181';\n";
    std::ofstream(old / "package.json") << "{\"name\": \"old-three\", \"private\": true}\n";
    const std::vector<std::string> refused = sortedLines(nodeChecks(old, "revision"));
    ASSERT_EQ(refused.size(), 5u);
    for (const std::string& line : refused)
        EXPECT_EQ(line.substr(line.find(' ') + 1), kBelowTheRange) << line;
    for (const std::string& line : sortedLines(nodeChecks(p.project, "revision")))
        EXPECT_EQ(line.substr(line.find(' ') + 1), "ok")
            << "the installed three " << p.three << ": " << line;
}

// A base and a map that disagree on wrapU: the base named as asked, with its article ("a
// ellipsoid base" before).
TEST_F(ThreeTarball, AWrapUMismatchNamesTheBaseAsAsked) {
    EXPECT_EQ(nodeChecks(packed().project, "base"),
              "ellipsoid: TypeError: Relief: an ellipsoid base needs a map built with wrapU: true "
              "(its u wraps round)\n"
              "sphere: TypeError: Relief: a sphere base needs a map built with wrapU: true (its u "
              "wraps round)\n"
              "cylinder: TypeError: Relief: a cylinder base needs a map built with wrapU: true "
              "(its u wraps round)\n"
              "plane: TypeError: Relief: a plane base needs a map built with wrapU: false (its u "
              "does not wrap)\n");
}

// Packed where there is no em++ (PATH holds node, npm, sh and python3 alone: python3 runs
// cmake/generate_contracts.py for generated/relief_layout.js): the same files, a note
// saying what is left out, and the WebAssembly's two uses each refuse in one line at run
// time; the tarball with em++ runs both (the installed project). Red before: npm pack
// failed ("no em++ on PATH").
TEST_F(ThreeTarball, PackedWithoutEmscriptenTheWebAssemblyRefusesInOneLine) {
    const Packed& p = packed();
    const fs::path bin = dir / "bin", out = dir / "npm", project = dir / "no-wasm";
    fs::create_directories(bin);
    const std::string python = findTool("", "python3");
    ASSERT_FALSE(python.empty()) << "no python3 (the build needs it)";
    for (const std::string& tool : {p.node, p.npm, std::string("/bin/sh"), python})
        fs::create_symlink(tool, bin / fs::path(tool).filename());
    const test::RunResult pack =
        runIn(MICRORELIEF_PACKAGE_DIR,
              "MICRORELIEF_SOURCE_DIR=" + browser::quote(MICRORELIEF_SOURCE_DIR) +
                  " PATH=" + browser::quote(bin.string()) + " " + browser::quote(p.node) +
                  " scripts/pack.mjs --out " + browser::quote(out.string()),
              dir.path());
    ASSERT_EQ(pack.status, 0) << pack.out << pack.err;
    EXPECT_EQ(pack.err,
              "microrelief-three pack: note: no em++ on PATH (Debian package emscripten): packing "
              "without the "
              "WebAssembly, so the CPU pyramid path and the scene checks refuse at run time\n");
    const fs::path tarball = out / "microrelief-three-0.1.0.tgz";
    std::vector<std::string> expected = kTarballFiles;
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(sortedLines(
                  runIn(dir.path(), "tar tzf " + browser::quote(tarball.string()), dir.path()).out),
              expected);
    // Unpacked as npm would install it, beside the project's three.
    fs::create_directories(project / "node_modules");
    ASSERT_EQ(runIn(project,
                    "tar xzf " + browser::quote(tarball.string()) +
                        " && mv package node_modules/microrelief-three",
                    dir.path())
                  .status,
              0);
    fs::create_directory_symlink(p.project / "node_modules" / "three",
                                 project / "node_modules" / "three");
    std::ofstream(project / "package.json") << "{\"name\": \"no-wasm\", \"private\": true}\n";
    EXPECT_EQ(nodeChecks(project, "wasm"),
              "checks: Error: microrelief-three: no WebAssembly scene checks in this package "
              "(packed without emscripten, "
              "--no-wasm): loadSceneChecks is unavailable\n"
              "cpu: Error: microrelief-three: no WebAssembly pyramid in this package (packed "
              "without emscripten, --no-wasm): "
              "pyramid 'cpu' is unavailable; 'gpu' needs EXT_color_buffer_float\n"
              "pick: Error: microrelief-three: no WebAssembly twin in this package (packed without "
              "emscripten, --no-wasm): picks are traced on the GPU; pickWith 'cpu' is unavailable\n");
    EXPECT_EQ(nodeChecks(p.project, "wasm"), "checks: ok\ncpu: ok\npick: ok\n");
}

// `npm pack` in the source folder is refused in one line that names the way (npm run
// tarball), before anything is written: its prepack runs pack.mjs --refuse-in-place. Red
// before: it built generated/ into the folder and packed it there.
TEST_F(ThreeTarball, NpmPackInTheSourceFolderIsRefused) {
    const Packed& p = packed();
    const fs::path source = MICRORELIEF_PACKAGE_DIR;
    const std::string before = snapshot(source);
    const test::RunResult r = runIn(source,
                                    p.env + browser::quote(p.npm) + " pack --pack-destination " +
                                        browser::quote(dir.path().string()),
                                    dir.path());
    EXPECT_NE(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.err.find("microrelief-three pack: error: npm pack of the source folder would ship "
                         "its build inputs "
                         "and no generated/: run `npm run tarball`"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(snapshot(source), before) << "npm pack changed packages/microrelief-three";
    for (const fs::directory_entry& entry : fs::directory_iterator(dir.path()))
        EXPECT_NE(entry.path().extension(), ".tgz") << entry.path();
}

// The installed example in Chromium (ThreePage: the browser and the staged example).
class ThreePackage : public ThreePage {
protected:
    void SetUp() override {
        ThreePage::SetUp();
        if (HasFatalFailure() || IsSkipped()) return;
        const Packed& p = packed();
        if (!p.missing.empty()) {
            const std::string why = "no " + p.missing + " (Debian package " + p.missing +
                                    "; bash scripts/setup.sh installs it): packing needs it";
            const char* allow = std::getenv("MICRORELIEF_ALLOW_MISSING_BROWSER");
            if (allow && std::string(allow) == "1") GTEST_SKIP() << why;
            FAIL() << why << "; MICRORELIEF_ALLOW_MISSING_BROWSER=1 skips this test instead";
        }
        ASSERT_EQ(p.pack.status, 0) << p.pack.out << p.pack.err;
        ASSERT_EQ(p.install.status, 0) << p.install.out << p.install.err;
    }
};

// The example installed from the tarball draws the three-lit scene the build tree's staged
// example draws (the same code, the same three, the same browser: the same picture; with
// another three, MICRORELIEF_THREE_VERSION, it is only drawn), and its shading=microrelief
// picture, with the pyramid built by the tarball's WebAssembly, is microrelief-render's
// (kLimits) with any three, drawn by its WebGL entry and by its WebGPU entry (renderer=webgpu).
TEST_F(ThreePackage, TheTarballInstalledIntoAScratchProjectRunsTheExample) {
    const fs::path root = packed().site, project = packed().project;
    EXPECT_TRUE(fs::exists(project / "node_modules" / "three" / "build" / "three.module.js"));

    // The example, installed and staged: the three-lit scene in both, and the installed one's
    // library shading with the CPU (WebAssembly) pyramid.
    const View& v = viewNamed("oblique");
    const auto cobbles = [&](const std::string& name) {
        return open("", v.width, v.height, "three/") +
               ", {\"wait\": \"ready\"}, {\"screenshot\": " + jsonString((dir / name).string()) +
               "}";
    };
    const PageRun staged = runPage("[" + cobbles("staged-cobbles.png") + "]");
    ASSERT_EQ(staged.at(1, "state"), "ready") << staged.at(1, "error");
    const PageRun page =
        runPage("[" + cobbles("installed-cobbles.png") + ", " +
                    open("shading=microrelief&pyramid=cpu", v.width, v.height, "three/") +
                    ", {\"wait\": \"ready\"}, {\"screenshot\": " +
                    jsonString((dir / "installed-compare.png").string()) + "}]",
                root);
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    ASSERT_EQ(page.at(4, "state"), "ready") << page.at(4, "error");

    // The three-lit scene is drawn: not the background alone (a third of the pixels or more
    // differ from the top-left one, which is the black clear colour: seen 43.7 %, the floor,
    // the sphere and the knot), and equal to the staged example's picture.
    const test::Image installedCobbles = test::readImage(dir / "installed-cobbles.png"),
                      stagedCobbles = test::readImage(dir / "staged-cobbles.png");
    ASSERT_EQ(installedCobbles.width, v.width);
    ASSERT_EQ(stagedCobbles.width, v.width);
    std::size_t notBackground = 0;
    for (int row = 0; row < v.height; ++row)
        for (int column = 0; column < v.width; ++column)
            for (int c = 0; c < 3; ++c)
                if (std::abs(installedCobbles.at(column, row, c) - installedCobbles.at(0, 0, c)) >
                    8) {
                    ++notBackground;
                    break;
                }
    std::printf("    installed example: %.1f %% of the pixels not the background\n",
                100.0 * notBackground / (v.width * v.height));
    EXPECT_GT(notBackground, v.width * v.height / 3) << "the installed example drew too little";
    const browser::PictureDifference d = browser::compare(installedCobbles, stagedCobbles, 0);
    std::printf("    installed against staged: %.4f %% of the pixels differ, max %d\n",
                100.0 * d.differentPixels, d.max);
    // Only with the staged example's three: three's own shading changes between versions
    // (three 0.171 against 0.187: 41 % of the pixels, up to 13 levels, the plain sphere
    // and knot as much as the relief).
    if (packed().three == packed().tested)
        EXPECT_EQ(d.max, 0) << "the installed example's picture is not the staged one's; see "
                            << test::keepForInspection(failures_, "installed-cobbles",
                                                       installedCobbles, stagedCobbles);
    else
        std::printf(
            "    (three %s installed, the staged example's is %s: not held to its picture)\n",
            packed().three.c_str(), packed().tested.c_str());
    const auto rendered = dir / "oblique-render.png";
    render(v.flags + " --size " + size(v.width, v.height), rendered);
    expectSamePicture("installed-compare", dir / "installed-compare.png", rendered,
                      "microrelief-render --size " + size(v.width, v.height), kLimits);

    // The installed package's WebGPU entry ('microrelief-three/webgpu', the tarball's
    // src/webgpu.js and generated/wgsl.js) draws the same picture under renderer=webgpu.
    const PageRun gpu = runPage("[" + open("renderer=webgpu&shading=microrelief", v.width, v.height, "three/") +
                                    ", {\"wait\": \"ready\"}, {\"eval\": \"document.documentElement.dataset.api\"}, "
                                    "{\"screenshot\": " + jsonString((dir / "installed-webgpu.png").string()) + "}]",
                                root, Gpu::WithWebGPU);
    for (const std::string& line : gpu.log) std::printf("    page: %s\n", line.c_str());
    ASSERT_EQ(gpu.at(1, "state"), "ready") << gpu.at(1, "error");
    EXPECT_EQ(gpu.at(2, "value"), "webgpu");
    expectSamePicture("installed-webgpu", dir / "installed-webgpu.png", rendered,
                      "microrelief-render --size " + size(v.width, v.height), kLimits);
}

// The WebGPU entry as a consumer who bundles gets it: tests/three/typecheck/vite's app.ts (the
// WebGPU example's shading=microrelief scene, from examples/three's compare.js, renderers.js
// and view.js, with imports of 'three/webgpu' and 'microrelief-three/webgpu') in app/ of the
// scratch project, with Vite (the package's devDependency, installed there from the npm
// cache), typechecked by tsc --strict against the tarball's declarations and @types/three,
// bundled by `vite build` into web/bundle/, and run from there in Chromium with WebGPU. The
// bundle holds what the entry loads: each WGSL module of generated/wgsl.js (its first line)
// and the WebAssembly of generated/pyramid_wasm.js and twin_wasm.js (their base64, whole),
// and the page draws microrelief-render's picture (kLimits) on WebGPU (data-api).
TEST_F(ThreePackage, TheWebGPUEntryBundledByViteRunsTheExample) {
    const Packed& p = packed();
    const fs::path project = p.project, app = project / "app", bundle = p.site / "web" / "bundle",
                   installed = project / "node_modules" / "microrelief-three";
    const test::RunResult install =
        runIn(project,
              p.env + browser::quote(p.npm) +
                  " install --prefer-offline --no-audit --no-fund vite@" + p.vite,
              dir.path());
    ASSERT_EQ(install.status, 0) << install.out << install.err << "\n(vite@" << p.vite
                                 << " comes from the npm cache that `npm ci` in "
                                    "packages/microrelief-three fills: bash scripts/setup.sh)";
    fs::create_directories(app);
    for (const char* file : {"index.html", "app.ts", "tsconfig.json"})
        fs::copy_file(fs::path(MICRORELIEF_THREE_TESTS_DIR) / "typecheck" / "vite" / file,
                      app / file, fs::copy_options::overwrite_existing);

    const fs::path tsc = fs::path(MICRORELIEF_PACKAGE_DIR) / "node_modules" / ".bin" / "tsc";
    ASSERT_TRUE(fs::exists(tsc))
        << tsc << ": no TypeScript: `npm ci` in packages/microrelief-three (bash scripts/setup.sh)";
    const test::RunResult typecheck = runIn(
        app, browser::quote(tsc.string()) + " --noEmit --strict -p tsconfig.json", dir.path());
    EXPECT_EQ(typecheck.status, 0) << typecheck.out << typecheck.err;
    const test::RunResult build = runIn(
        project,
        browser::quote(p.node) + " node_modules/vite/bin/vite.js build app --base ./ --outDir " +
            browser::quote(bundle.string()) + " --emptyOutDir --logLevel warn",
        dir.path());
    ASSERT_EQ(build.status, 0) << build.out << build.err;

    // What the bundle holds: its files' text, each WGSL module's first line and the two
    // WebAssembly modules' base64 in it.
    std::string bundled;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(bundle))
        if (entry.is_regular_file()) bundled += test::readText(entry.path());
    const test::RunResult headers =
        runIn(installed,
              browser::quote(p.node) +
                  " -e \"import('./generated/wgsl.js').then(({wgsl}) => { for (const text of "
                  "Object.values(wgsl)) console.log(text.split(String.fromCharCode(10))[0]); })\"",
              dir.path());
    ASSERT_EQ(headers.status, 0) << headers.err;
    const std::vector<std::string> modules = sortedLines(headers.out);
    EXPECT_GE(modules.size(), 6u) << headers.out;  // each base, both last levels
    for (const std::string& header : modules)
        EXPECT_TRUE(bundled.find(header) != std::string::npos) << "not in the bundle: " << header;
    for (const char* wasm : {"pyramid_wasm.js", "twin_wasm.js"}) {
        // The longest data URL in it (emscripten's SINGLE_FILE: the module's bytes; the
        // prefix alone is there too, as the string it tests URLs with).
        const std::string text = test::readText(installed / "generated" / wasm);
        std::string base64;
        for (std::size_t from = text.find("data:application/octet-stream;base64,");
             from != std::string::npos;
             from = text.find("data:application/octet-stream;base64,", from + 1)) {
            const std::string url = text.substr(from, text.find_first_of("\"'`", from) - from);
            if (url.size() > base64.size()) base64 = url;
        }
        ASSERT_GT(base64.size(), 10000u) << wasm << ": no WebAssembly in it";
        EXPECT_TRUE(bundled.find(base64) != std::string::npos)
            << wasm << "'s WebAssembly (" << base64.size() << " characters) is not in the bundle";
    }
    std::printf("    bundle: %.1f MB, %zu WGSL modules\n", bundled.size() / 1e6, modules.size());

    const View& v = viewNamed("oblique");
    const PageRun gpu = runPage(
        "[" + open("renderer=webgpu&shading=microrelief", v.width, v.height, "bundle/") +
            ", {\"wait\": \"ready\"}, {\"eval\": \"document.documentElement.dataset.api\"}, "
            "{\"screenshot\": " +
            jsonString((dir / "bundled-webgpu.png").string()) + "}]",
        p.site, Gpu::WithWebGPU);
    for (const std::string& line : gpu.log) std::printf("    page: %s\n", line.c_str());
    ASSERT_EQ(gpu.at(1, "state"), "ready") << gpu.at(1, "error");
    EXPECT_EQ(gpu.at(2, "value"), "webgpu");
    const auto rendered = dir / "oblique-render.png";
    render(v.flags + " --size " + size(v.width, v.height), rendered);
    expectSamePicture("bundled-webgpu", dir / "bundled-webgpu.png", rendered,
                      "microrelief-render --size " + size(v.width, v.height), kLimits);
}

}  // namespace
