// BrowserTest.h: what the browser tests share (tests/web, tests/three): Debian's Chromium,
// headless, WebGL 2 through SwiftShader, driven over the DevTools protocol by
// drive_chromium.py with the page's own server (web/serve.py); microrelief-render on Mesa's
// software device for the pictures and AOVs to hold the pages against. Needs the target to
// define MICRORELIEF_CHROMIUM, MICRORELIEF_PYTHON3, MICRORELIEF_DRIVER, MICRORELIEF_WEB_ROOT
// and MICRORELIEF_RENDER_EXE (tests/web/CMakeLists.txt: microrelief_browser_test).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "TestSupport.h"

namespace microrelief::browser {

// glvnd's description of Mesa's EGL: microrelief-render on the software device, whatever
// GPU the machine has, as the page's SwiftShader is software too.
constexpr const char* kMesaEglVendor = "/usr/share/glvnd/egl_vendor.d/50_mesa.json";

using test::Image;
using test::readImage;

inline std::string quote(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

inline std::string jsonString(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '\n') {
            out += "\\n";
            continue;
        }
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

// What the driver reports: "STEP.KEY" -> value, and the page's console errors.
struct PageRun {
    int status = -1;
    std::map<std::string, std::string> values;
    std::vector<std::string> log;
    std::string err;

    std::string at(int step, const std::string& key) const {
        const auto found = values.find(std::to_string(step) + "." + key);
        return found == values.end() ? std::string() : found->second;
    }
};

inline std::string unescape(const std::string& text) {
    std::string out;
    for (std::size_t k = 0; k < text.size(); ++k) {
        if (text[k] == '\\' && k + 1 < text.size()) {
            out += text[++k] == 'n' ? '\n' : text[k];
        } else {
            out += text[k];
        }
    }
    return out;
}

// How far a browser's picture may be from microrelief-render's: a pixel is different when a
// channel differs by more than `differentLevels`; at most `differentPixels` (a fraction) may
// be, and the mean over all channels stays under `mean` levels. Each test says why its numbers.
struct PictureThresholds {
    int differentLevels;
    double differentPixels;
    double mean;
};

// Per pixel: the largest channel difference; the mean over channels.
struct PictureDifference {
    double differentPixels = 0.0;  // fraction of pixels with a channel over differentLevels
    double mean = 0.0;             // levels, over all channels
    int max = 0;
};

inline PictureDifference compare(const Image& a, const Image& b, int differentLevels) {
    PictureDifference d;
    double sum = 0.0;
    std::size_t different = 0;
    for (int row = 0; row < a.height; ++row) {
        for (int column = 0; column < a.width; ++column) {
            int largest = 0;
            for (int c = 0; c < 3; ++c) {
                const int delta = std::abs(a.at(column, row, c) - b.at(column, row, c));
                largest = std::max(largest, delta);
                sum += delta;
            }
            different += largest > differentLevels;
            d.max = std::max(d.max, largest);
        }
    }
    const double pixels = static_cast<double>(a.width) * a.height;
    d.differentPixels = different / pixels;
    d.mean = sum / (3.0 * pixels);
    return d;
}

// The fixture: Chromium and python3 found (or the test failed or skipped, as
// MICRORELIEF_ALLOW_MISSING_BROWSER says), a scratch folder, the driver and the renderer.
class BrowserTest : public ::testing::Test {
protected:
    // Chromium and python3: where CMake found them, else in /usr/bin or on PATH now (a build
    // configured before scripts/setup.sh installed them).
    void SetUp() override {
        chromium_ = findProgram(MICRORELIEF_CHROMIUM, "chromium");
        python_ = findProgram(MICRORELIEF_PYTHON3, "python3");
        for (const auto& [program, package] :
             {std::pair{chromium_, "chromium"}, std::pair{python_, "python3"}}) {
            if (!program.empty()) continue;
            const char* allow = std::getenv("MICRORELIEF_ALLOW_MISSING_BROWSER");
            const std::string why = std::string("no ") + package + " (Debian package " + package +
                                    "; bash scripts/setup.sh installs it)";
            if (allow && std::string(allow) == "1") GTEST_SKIP() << why;
            FAIL() << why << "; MICRORELIEF_ALLOW_MISSING_BROWSER=1 skips these tests instead";
        }
    }

    static std::string findProgram(const std::string& configured, const std::string& name) {
        std::vector<std::filesystem::path> candidates = {configured, "/usr/bin/" + name};
        const char* path = std::getenv("PATH");
        std::istringstream dirs(path ? path : "");
        for (std::string d; std::getline(dirs, d, ':');)
            if (!d.empty()) candidates.push_back(std::filesystem::path(d) / name);
        for (const std::filesystem::path& candidate : candidates) {
            std::error_code ec;
            if (!candidate.empty() && std::filesystem::is_regular_file(candidate, ec) &&
                access(candidate.c_str(), X_OK) == 0)
                return candidate.string();
        }
        return {};
    }

    // The page (web/, a 32 x 24 canvas) opened and, once ready (step 1's state), the value
    // of `script` (step 2's): for tests that reach into the page's objects.
    PageRun evalOnReadyPage(const std::string& script) {
        return runPage("[" + open("", 32, 24) +
                       ", {\"wait\": \"ready\"}, {\"eval\": " + jsonString(script) + "}]");
    }

    // Whether runPage's browser offers WebGPU (drive_chromium.py --webgpu: SwiftShader).
    enum class Gpu { WebGL2Only, WithWebGPU };

    // Runs `steps` (a JSON array of drive_chromium.py's steps) in one browser, the pages
    // served from `root` (a folder holding web/, shaders/ and assets/ and web/serve.py).
    PageRun runPage(const std::string& steps,
                    const std::filesystem::path& root = MICRORELIEF_WEB_ROOT,
                    Gpu gpu = Gpu::WebGL2Only) {
        const auto stepsFile = dir / "steps.json", flat = dir / "result.txt",
                   json = dir / "result.json";
        std::ofstream(stepsFile) << steps;
        std::filesystem::remove(flat);
        const std::string command = python_ + " " + MICRORELIEF_DRIVER + " --chromium " +
                                    chromium_ + " --root " + quote(root.string()) +
                                    " --steps " + stepsFile.string() + " --out " + json.string() +
                                    " --flat " + flat.string() +
                                    (gpu == Gpu::WithWebGPU ? " --webgpu" : "");
        const test::RunResult run = test::runCommand(command, dir.path());
        PageRun page;
        page.status = run.status;
        page.err = run.err;
        std::ifstream in(flat);
        std::string line;
        while (std::getline(in, line)) {
            const std::size_t tab = line.find('\t');
            if (tab == std::string::npos) continue;
            const std::string key = line.substr(0, tab), value = unescape(line.substr(tab + 1));
            if (key == "log") {
                page.log.push_back(value);
            } else {
                page.values[key] = value;
            }
        }
        EXPECT_EQ(page.status, 0) << "the browser did not run every step:\n" << page.err;
        return page;
    }

    // microrelief-render with `flags` (the rest of a command line) into `out`.
    void render(const std::string& flags, const std::filesystem::path& out) {
        const std::string software =
            std::filesystem::exists(kMesaEglVendor)
                ? std::string("__EGL_VENDOR_LIBRARY_FILENAMES=") + kMesaEglVendor + " "
                : std::string();
        const test::RunResult r =
            test::runCommand(software + "LIBGL_ALWAYS_SOFTWARE=1 " + MICRORELIEF_RENDER_EXE + " " +
                                 flags + " --quiet --out " + out.string(),
                             dir.path());
        EXPECT_EQ(r.status, 0) << flags << "\n" << r.err;
    }

    // The page's picture against microrelief-render's, within the thresholds above.
    void expectSamePicture(const std::string& name, const std::filesystem::path& page,
                           const std::filesystem::path& rendered, const std::string& how,
                           const PictureThresholds& limits) {
        const Image actual = readImage(page), expected = readImage(rendered);
        ASSERT_GT(actual.width, 0) << name << ": no screenshot";
        ASSERT_GT(expected.width, 0) << name << ": no picture from microrelief-render";
        ASSERT_EQ(actual.width, expected.width) << name;
        ASSERT_EQ(actual.height, expected.height) << name;
        const PictureDifference d = compare(actual, expected, limits.differentLevels);
        std::printf("    %-22s different pixels %.4f %%, mean %.4f levels, max %d\n", name.c_str(),
                    100.0 * d.differentPixels, d.mean, d.max);
        if (d.differentPixels > limits.differentPixels || d.mean > limits.mean) {
            ADD_FAILURE() << name << ": the page's picture differs from microrelief-render's ("
                          << 100.0 * d.differentPixels << " % of pixels over "
                          << limits.differentLevels << " levels, mean " << d.mean
                          << " levels); see "
                          << test::keepForInspection(failures_, name, actual, expected) << "\n  "
                          << how;
        }
    }

    static std::string size(int width, int height) {
        return std::to_string(width) + "x" + std::to_string(height);
    }

    // The step that opens the page on `query` at W x H, canvas alone (clean=1); `page` a
    // folder under web/ ("three/") or empty for web/ itself.
    static std::string open(const std::string& query, int width, int height,
                            const std::string& page = "") {
        return "{\"open\": " +
               jsonString("clean=1&size=" + size(width, height) +
                          (query.empty() ? "" : "&" + query)) +
               (page.empty() ? "" : ", \"page\": " + jsonString(page)) + ", \"size\": [" +
               std::to_string(width) + ", " + std::to_string(height) + "]}";
    }

    test::ScratchDir dir;
    std::string chromium_, python_;
    std::string failures_ = "web-failures";  // beside the test log: actual, expected, diff
};

}  // namespace microrelief::browser
