// Shared helpers for the tests: scratch folders, writing maps in any format, and the
// per-pixel comparison of a rendered AOV against the exact CPU reference.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/core/trace/Accuracy.h"

namespace microrelief::test {

// A fresh folder under the system temp folder, removed with its contents on destruction.
class ScratchDir {
public:
    ScratchDir();
    ~ScratchDir();
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    std::filesystem::path path_;
};

// An environment variable set for a scope and put back as it was after (in this process,
// and the programs a test runs from it).
class ScopedEnvironment {
public:
    ScopedEnvironment(const char* name, const char* value) : name_(name) {
        if (const char* before = std::getenv(name)) before_ = before;
        ::setenv(name, value, 1);
    }
    ~ScopedEnvironment() {
        if (before_)
            ::setenv(name_.c_str(), before_->c_str(), 1);
        else
            ::unsetenv(name_.c_str());
    }
    ScopedEnvironment(const ScopedEnvironment&) = delete;
    ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

private:
    std::string name_;
    std::optional<std::string> before_;
};

// Writes `map` (values in [0, 1] for integer types) as one channel of the given type.
void writeMap(const std::filesystem::path& file, const HeightMap& map, PixelType type);
// A 16-bit PNG of 17000 x 40 waves (0.5 + 0.4 sin(0.05 i) cos(0.3 j)): wider than the GL's
// textures (16384 on llvmpipe), so read through pages; for the programs' paging tests.
void writeWideWavesMap(const std::filesystem::path& file);
void writeBytes(const std::filesystem::path& file, const std::vector<std::uint8_t>& bytes);
std::vector<std::uint8_t> readBytes(const std::filesystem::path& file);
std::string readText(const std::filesystem::path& file);

// A program run as a user runs it: `command` through the shell, stdout and stderr
// captured through files in `scratch`.
struct RunResult {
    int status = -1;  // exit status, -1 when it did not exit normally
    std::string out, err;
    int errLines() const;
};
RunResult runCommand(const std::string& command, const std::filesystem::path& scratch);
// The same under a file size limit of `bytes` (RLIMIT_FSIZE, as `ulimit -f` sets it): a
// disk full for every file that would grow past it, without privileges. SIGXFSZ is
// ignored in the child, so that a write past the limit fails with EFBIG instead of
// killing the program (the programs ignore it themselves; the tests do not rely on it).
// stdout and stderr come through pipes, which the limit does not cut.
RunResult runCommandWithFileSizeLimit(const std::string& command, std::uint64_t bytes);
// The hidden files in `folder` (the writers' temporaries are hidden: ".name.tmp-...").
std::vector<std::string> hiddenFilesIn(const std::filesystem::path& folder);

// The spec's failure shape: exit `status`, exactly one stderr line starting
// "<program>: error: " and mentioning `mentions`.
void expectOneLineFailure(const RunResult& r, const std::string& program, int status,
                          const std::string& mentions);

// An 8-bit picture read back from a file (any format OpenImageIO reads), row 0 the top.
struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint8_t> pixels;
    std::uint8_t at(int column, int row, int channel) const {
        return pixels[(static_cast<std::size_t>(row) * width + column) * channels + channel];
    }
};
// Empty (width 0) when the file cannot be read.
Image readImage(const std::filesystem::path& file);

// microrelief-render's AOV (OpenEXR, float R, G, B, A): per pixel x, y, z and 1 for a hit,
// 0 for a miss; row 0 the top. Empty (width 0) when the file cannot be read.
struct Aov {
    int width = 0, height = 0;
    std::vector<float> pixels;
    const float* at(int column, int row) const {
        return &pixels[(static_cast<std::size_t>(row) * width + column) * 4];
    }
};
Aov readAov(const std::filesystem::path& file);

// The world size of one texel of `map` on triangle k of `mesh` (the mesh base's unit of
// error): sqrt(the triangle's world area over its area in texels).
double meshTexelSize(const TriangleMesh& mesh, const HeightMap& map, std::size_t k);

// Two pictures' RGB channels compared over the rectangle [x0, x1) x [y0, y1): the largest
// difference, the mean, and how many channel values differ by more than one level.
struct Difference {
    int max = 0;
    double mean = 0.0;
    std::size_t overOne = 0;
};
Difference difference(const Image& a, const Image& b, int x0, int y0, int x1, int y1);

// Actual, expected and their difference (amplified 8 times) written to
// <current folder>/<folder>/<name>-{actual,expected,diff}.png for a human to see; returns
// that pattern for the failure message.
std::string keepForInspection(const std::string& folder, const std::string& name,
                              const Image& actual, const Image& expected);

// Whether this run may go without a GL backend: MICRORELIEF_ALLOW_MISSING_GL lists the
// ones that may be absent (comma-separated: egl, osmesa, or all). Unset (as in .ci/run),
// a missing backend fails the suite instead of skipping every test that needs it, so a
// machine or CI without a working EGL cannot go green without running a shader.
bool missingBackendAllowed(Backend backend);
// The line a test prints for a missing backend: allowed (skipped) or not (failing).
std::string missingBackendMessage(Backend backend);

// A relief over `base` with `interpolation`, `heightScale` and `tiles`, the rest as
// ReliefDesc has it (designated initializers would have GCC warn of every member left out).
ReliefDesc relief(const BaseShape& base = {}, Interpolation interpolation = Interpolation::Bilinear,
                  float heightScale = 0.1f, glm::ivec2 tiles = {1, 1});

// A camera on a sphere around the origin: `elevationDeg` above the base plane,
// `azimuthDeg` around y from +x towards +z, looking at `target`.
Camera orbitCamera(double elevationDeg, double azimuthDeg, double distance,
                   glm::dvec3 target = {0, 0, 0}, double fovyDeg = 40.0);

// `frame` with its hit positions in world coordinates (positionOrigin added, in float;
// positionOrigin then 0): for tests that read them as world positions near the origin. The
// renderer writes them about the eye (RenderedFrame::positionOrigin).
RenderedFrame withWorldPositions(RenderedFrame frame);

using microrelief::Accuracy;
using microrelief::compareWithReference;
using microrelief::measureAccuracy;
using microrelief::PixelHit;

}  // namespace microrelief::test
