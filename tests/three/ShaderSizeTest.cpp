// The relief's shaders as three.js compiles them (suite ThreeShaders, ctest three.shaders;
// issue 48, "Small shaders" and "Cost"): the GLSL the package ships stripped of comments and
// of functions no shader calls (packages/microrelief-three/scripts/strip_glsl.mjs) yet every
// function some #if branch calls kept, each program under a stated size, reliefs of the
// same options sharing their programs, renderer.compileAsync warming a relief up. The
// page-side measurements are tests/three/shaders.js, evaluated in examples/three's page
// (the ThreePage fixture, ThreePage.h); the sizes are read from a renderer whose context
// compiles nothing, so that the test costs one SwiftShader compile (the warm-up's), not one
// per variant. The pictures themselves are ctest three's (ThreePage.*, against
// microrelief-render), run unchanged on the stripped shaders.
#include <map>
#include <sstream>

#include "ThreePage.h"

using namespace microrelief;
using namespace microrelief::three_test;

namespace {

// The most bytes each relief fragment program may have, as three hands it to WebGL (its own
// chunks resolved, the library and the glue spliced in). Measured 2026-12-06 with three
// 0.187 (docs/perf/2026-12-06-three-shader-size.md): Standard 151,834 and Physical 151,852
// bytes, the depth material's 84,450, the distance material's 80,954, ReliefShadingMaterial's
// 68,972, the pick's 65,973 (the same on every base: the base is a define). The bounds leave
// 15 % over those for the library's growth and for three's chunks over the peer range; the
// shaders as they were before the stripping (239 kB, 172 kB, 168 kB, 156 kB, 153 kB: their
// comments) are 60 kB or more over each.
const std::map<std::string, long> kMaxProgramBytes = {
    {"standard", 175000}, {"physical", 175000}, {"depth", 97000},
    {"distance", 97000},  {"shading", 80000},   {"pick", 80000},
};
// The GLSL strings of generated/glsl.js together: measured 75,519 bytes (177,181 before).
constexpr long kMaxGeneratedBytes = 87000;

class ThreeShaders : public ThreePage {
protected:
    // examples/three (shading=microrelief, a small canvas) with shaders.js loaded, then each
    // of `scripts` evaluated: their values are steps 3, 4, ...
    PageRun runChecks(const std::vector<std::string>& scripts, int width = 32, int height = 24) {
        std::string steps = "[" + open("shading=microrelief", width, height, "three/") +
                            ", {\"wait\": \"ready\"}, {\"eval\": " +
                            jsonString(test::readText(std::string(MICRORELIEF_THREE_TESTS_DIR) +
                                                      "/shaders.js")) +
                            "}";
        for (const std::string& script : scripts)
            steps += ", {\"eval\": " + jsonString(script) + "}";
        return runPage(steps + "]");
    }

    // shaders.js's report (one page for the tests that read it): its lines by kind, each
    // kind's lines by the rest's first words.
    const std::multimap<std::string, std::string>& report() {
        static std::multimap<std::string, std::string> lines;
        if (!lines.empty()) return lines;
        const PageRun page = runChecks({"threeShaders.report()"});
        EXPECT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
        for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
        std::istringstream in(page.at(3, "value"));
        for (std::string line; std::getline(in, line);) {
            const std::size_t space = line.find(' ');
            if (space != std::string::npos) lines.emplace(line.substr(0, space), line.substr(space + 1));
        }
        return lines;
    }
};

// Each relief program (per base: plane, cylinder, sphere; per material: Standard, Physical,
// the library's shading, the depth and distance materials of three's shadow maps, the pick)
// is under its bound, and the package's GLSL holds no comment. Seen red before the stripping
// (every program 60 kB or more over, generated/glsl.js's library opening with the bundler's
// "// ---- microrelief: ..." line).
TEST_F(ThreeShaders, EachReliefProgramIsUnderItsBoundAndTheGlslHasNoComment) {
    const auto& lines = report();
    int programs = 0;
    for (auto [it, end] = lines.equal_range("size"); it != end; ++it) {
        std::istringstream fields(it->second);
        std::string base, program;
        long bytes = 0;
        fields >> base >> program >> bytes;
        std::printf("    %-8s %-9s %7ld bytes\n", base.c_str(), program.c_str(), bytes);
        ASSERT_TRUE(kMaxProgramBytes.count(program)) << "a program this test has no bound for: " << it->second;
        EXPECT_GT(bytes, 10000) << it->second << ": the source was not recorded";
        EXPECT_LE(bytes, kMaxProgramBytes.at(program)) << base << " " << program;
        ++programs;
    }
    EXPECT_EQ(programs, 18) << "3 bases x (3 materials, depth, distance, pick)";
    long generated = 0;
    for (auto [it, end] = lines.equal_range("generated"); it != end; ++it) {
        std::istringstream fields(it->second);
        std::string name;
        long bytes = 0;
        fields >> name >> bytes;
        generated += bytes;
    }
    std::printf("    generated/glsl.js: %ld bytes of GLSL\n", generated);
    EXPECT_GT(generated, 20000);
    EXPECT_LE(generated, kMaxGeneratedBytes);
    ASSERT_EQ(lines.count("comment"), 1u);
    EXPECT_EQ(lines.find("comment")->second, "-") << "a comment in generated/glsl.js";
}

// Every relief function (mr...) a program calls is defined in it, or is a macro or a struct:
// read from the sources, on every base, so that a function only another base's #if branch calls
// counts (the plane's programs hold the cylinder's calls too, under #if
// MICRORELIEF_BASE_WRAPS_U and the other traits: the compiler, not this test, drops them). Seen
// red with a naive stripper that counted only the references under the plane's branches (the
// default MICRORELIEF_BASE 0): mr_curvedMapX, mr_wrapIndex and 12 more missing from every
// program, the plane's page still drawing, the cylinder's failing to compile
// ('mr_curvedInsideRadius': no matching overloaded function found).
TEST_F(ThreeShaders, EveryFunctionSomeIfBranchCallsIsKept) {
    const auto& lines = report();
    int programs = 0;
    for (auto [it, end] = lines.equal_range("undefined"); it != end; ++it) {
        std::istringstream fields(it->second);
        std::string base, program, missing;
        fields >> base >> program >> missing;
        EXPECT_EQ(missing, "-") << base << " " << program << " calls functions it lacks";
        ++programs;
    }
    EXPECT_EQ(programs, 18);
}

// Reliefs of the same base, last level and material options share one program per
// renderer for their material, one for their depth material and one for their distance
// material (three's program cache: customProgramCacheKey), however many there are; another
// base is another three. Seen red with the cache keys naming the relief (its uuid): 12
// programs for four reliefs, for each material.
TEST_F(ThreeShaders, ReliefsOfTheSameOptionsShareTheirPrograms) {
    const auto& lines = report();
    int materials = 0;
    for (auto [it, end] = lines.equal_range("sharing"); it != end; ++it) {
        std::istringstream fields(it->second);
        std::string material;
        int one = 0, four = 0, mixed = 0;
        fields >> material >> one >> four >> mixed;
        SCOPED_TRACE(it->second);
        EXPECT_EQ(one, 3) << "a relief: its material, its depth and its distance material";
        EXPECT_EQ(four, one) << "four reliefs of one base made programs of their own";
        EXPECT_EQ(mixed, 2 * one) << "two on the plane and two on the cylinder";
        ++materials;
    }
    EXPECT_EQ(materials, 3);
}

// renderer.compileAsync(scene, camera) (docs/three.md, "Warming up") on a scene whose relief
// the page has not drawn (ReliefStandardMaterial on the cylinder, lit): it resolves, makes the
// relief's program, and the next frame draws the relief without making another. Seen red
// with the material given its relief only at the relief's first draw (src/relief.js without
// "material.relief = this" when the material is set): compileAsync rejected with "a
// ReliefStandardMaterial draws only on a Relief".
TEST_F(ThreeShaders, CompileAsyncWarmsUpAReliefAndTheNextFrameDrawsIt) {
    const PageRun page = runChecks({"threeShaders.warmUp().then((r) => JSON.stringify(r))"}, 160, 120);
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    const std::string value = page.at(3, "value");
    std::printf("    %s\n", value.c_str());
    auto number = [&](const std::string& key) {
        const std::size_t at = value.find("\"" + key + "\":");
        return at == std::string::npos ? -1.0 : std::strtod(value.c_str() + at + key.size() + 3, nullptr);
    };
    EXPECT_NE(value.find("\"resolved\":true"), std::string::npos) << value;
    EXPECT_GT(number("programsCompiled"), number("programsBefore")) << "compileAsync made no program";
    EXPECT_EQ(number("programsAfterFrame"), number("programsCompiled"))
        << "the frame made a program compileAsync had not";
    // The cylinder (radius 0.3, length 1) seen from 1.2 away fills about a fifth of the canvas.
    EXPECT_GT(number("lit"), 0.1 * number("pixels")) << "the relief was not drawn";
    EXPECT_LT(number("lit"), number("pixels"));
}

}  // namespace
