// ThreePage.h: what the microrelief-three browser tests share (ThreeTest.cpp and the suites
// beside it): the views (examples/three's URL and microrelief-render's flags), their
// thresholds, and the ThreePage fixture that opens examples/three in headless Chromium.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "BrowserTest.h"

namespace microrelief::three_test {

using browser::jsonString;
using browser::PageRun;


// The same rays through the same GLSL on two software GPUs, so tests/web's thresholds and
// reasons (WebPageTest.cpp: 8 levels, 0.2 % of pixels, a mean of 0.6 levels). Seen over these
// views (Chromium on SwiftShader against llvmpipe, 2026-12-03): no pixel over 8 levels but in
// the sphere (0.013 %: 2 pixels at grazing edges, up to 54 levels), means 0.05 to 0.16
// levels. Seen red: the height scale 2 % off puts 0.16 to 11 % of the pixels over 8 levels
// and the mean up to 2.8 levels (six of the seven views fail).
constexpr browser::PictureThresholds kLimits = {8, 0.002, 0.6};

// A hit position from the two GPUs: the same float ray, traced to the same root by the
// same subdivision; they differ by the last bits of the ray's set-up (three's Raycaster
// builds the ray in double, microrelief-render's shader in float) and of the root's
// interpolation: seen at most 1.5e-6 world units. 1e-5 is a two-hundredth of a texel of the
// 512-texel bundled map on its unit plane: a hit on the wrong cobble, a wrong height scale
// (10 %: up to 0.01) or a box face instead of the surface is far outside it.
constexpr double kPositionTolerance = 1e-5;
// Pixels whose rays graze a silhouette may hit on one GPU and miss on the other: at most
// this fraction of the picked pixels (1 in 200) may disagree on hit or miss.
constexpr double kMaxHitMissDisagreement = 0.005;

// Window depths (three's default: [0, 1], not reversed; a 32-bit float depth texture) with
// the camera's depth range set to [0.25, 4] (microrelief-render's near plane, a ten-thousandth
// of its far one, leaves the depth buffer a resolution of about 1e-3 world units here). The
// AOV's hits and SwiftShader's differ by about 1e-6 world units, 3e-7 in window depth at a
// distance of 1.3; a float's step near 1 is 6e-8. 2e-6 keeps those out and catches the box's
// face written instead of the hit (1e-2 and more) or a hit a hundredth of the height scale
// off (about 2e-4).
constexpr double kDepthTolerance = 2e-6;
// The plane's own depth, where it is in front, is the rasteriser's: vertices snapped to a
// sub-pixel grid (SwiftShader: 1/16 pixel here) move it by up to a sixteenth of its depth's
// change over one pixel, which reaches 1e-3 along the bottom rows: seen 1.5e-5.
constexpr double kPlaneDepthTolerance = 1e-4;

// A view as the page's URL and as microrelief-render's flags.
struct View {
    std::string name, query, flags;
    int width, height;
};

// The cameras and bases of the issue: top, oblique (the default), grazing with the exact
// shadows, the camera inside the box, an affine model transform, a cylinder with the
// biquadratic last level, a sphere.
inline const std::vector<View> kViews = {
    {"oblique", "", "", 240, 180},
    {"top-down", "eye=0,1.6,0&target=0,0,0&up=0,0,-1&albedo=none",
     "--eye=0,1.6,0 --target=0,0,0 --up=0,0,-1 --albedo none", 160, 160},
    {"grazing-shadows", "eye=0.75,0.1,0.55&target=-0.2,0.02,-0.1&fovy=50&shadows=hard",
     "--eye=0.75,0.1,0.55 --target=-0.2,0.02,-0.1 --fovy 50 --shadows hard", 240, 180},
    {"inside-the-box", "eye=0.12,0.085,0.2&target=-0.4,0.03,-0.35&fovy=70",
     "--eye=0.12,0.085,0.2 --target=-0.4,0.03,-0.35 --fovy 70", 240, 180},
    {"model", "model=0.8,-0.3,0,0.05,0.3,0.8,0,0.02,0,0,0.9,-0.03&eye=0.9,0.6,0.7&target=0,0,0",
     "--model=0.8,-0.3,0,0.05,0.3,0.8,0,0.02,0,0,0.9,-0.03 --eye=0.9,0.6,0.7 --target=0,0,0", 240,
     180},
    {"cylinder-biquadratic",
     "base=cylinder&radius=0.25&length=0.9&interpolation=biquadratic&eye=0.7,0.4,0.9&target=0,0,0",
     "--base cylinder --radius 0.25 --length 0.9 --interpolation biquadratic --eye=0.7,0.4,0.9 "
     "--target=0,0,0",
     200, 150},
    {"sphere", "base=sphere&albedo=none&target=0,0,0&height-scale=0.15&eye=0.9,0.5,0.9",
     "--base sphere --albedo none --target=0,0,0 --height-scale 0.15 --eye=0.9,0.5,0.9", 200, 150},
    // Far from three's origin (issue 47): traced relative to the camera, the eye and the
    // model's translation subtracted in double (src/relief.js, prepareDraw); before, the
    // world positions' float step there (0.06) was 15 texels of the bundled map.
    {"far-from-the-origin",
     "model=1,0,0,900000,0,1,0,-400000,0,0,1,700000&eye=900000.8,-399999.5,700000.85&"
     "target=900000,-400000.03,700000",
     "--model=1,0,0,900000,0,1,0,-400000,0,0,1,700000 --eye=900000.8,-399999.5,700000.85 "
     "--target=900000,-400000.03,700000",
     160, 120},
};

inline const View& viewNamed(const std::string& name) {
    for (const View& v : kViews)
        if (v.name == name) return v;
    std::abort();
}

using test::Aov;
using test::readAov;

// The numbers of a space-separated list (NaN spelt as JavaScript does).
inline std::vector<double> numbers(const std::string& text) {
    std::vector<double> out;
    std::istringstream in(text);
    for (std::string token; in >> token;) out.push_back(std::strtod(token.c_str(), nullptr));
    return out;
}

class ThreePage : public browser::BrowserTest {
protected:
    // The folder the pages are served from: the build tree's (MICRORELIEF_WEB_ROOT, with the
    // package's own three), or MICRORELIEF_THREE_SITE's: a copy of it with another three in
    // web/three/node_modules/three (tests/three/three_range.py, ctest three.range: the
    // oldest three of the peer range and the newest on the registry).
    static std::filesystem::path site() {
        const char* other = std::getenv("MICRORELIEF_THREE_SITE");
        return other && *other ? std::filesystem::path(other)
                               : std::filesystem::path(MICRORELIEF_WEB_ROOT);
    }

    // BrowserTest's runPage, served from site() unless told otherwise.
    PageRun runPage(const std::string& steps, const std::filesystem::path& root = site(),
                    Gpu gpu = Gpu::WebGL2Only) {
        return browser::BrowserTest::runPage(steps, root, gpu);
    }

    void SetUp() override {
        failures_ = "three-failures";
        browser::BrowserTest::SetUp();
        if (HasFatalFailure() || IsSkipped()) return;
        const std::filesystem::path page = site() / "web/three/index.html";
        if (!std::filesystem::exists(page)) {
            const char* allow = std::getenv("MICRORELIEF_ALLOW_MISSING_BROWSER");
            const std::string why = "examples/three is not staged (" + page.string() +
                                    "): configure with node and `npm ci` in "
                                    "packages/microrelief-three (bash scripts/setup.sh)";
            if (allow && std::string(allow) == "1") GTEST_SKIP() << why;
            FAIL() << why;
        }
    }

    // The steps that open examples/three on `query` (shading=microrelief) and load checks.js.
    static std::string openCompare(const View& v) {
        return open("shading=microrelief" + (v.query.empty() ? "" : "&" + v.query), v.width,
                    v.height, "three/") +
               ", {\"wait\": \"ready\"}, {\"eval\": " +
               jsonString(test::readText(MICRORELIEF_CHECKS_JS)) + "}";
    }

    void renderWithAov(const View& v, const std::filesystem::path& aov) {
        render(v.flags + " --size " + size(v.width, v.height) + " --aov " + aov.string(),
               dir / (v.name + "-render.png"));
    }
};

}  // namespace microrelief::three_test
