// The installed package, used the way an engine uses it (issue 13): the build installed
// into a scratch prefix; examples/headless and examples/renderer configured with
// find_package(microrelief) against it, built and run, their pictures held to
// microrelief-render's for the same camera; a program that links microrelief::core alone,
// built through find_package and through pkg-config, run, and its binary checked to load no
// GL, EGL, OpenImageIO or GLFW library. One scratch install serves every test (it takes a
// while).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "TestSupport.h"
#include "microrelief/Version.h"

using namespace microrelief;

namespace {

const std::string kCmake = MICRORELIEF_CMAKE_COMMAND;
const std::string kGenerator = MICRORELIEF_CMAKE_GENERATOR;
const std::filesystem::path kBuild = MICRORELIEF_BUILD_DIR;
const std::filesystem::path kSource = MICRORELIEF_SOURCE_DIR;

std::string quote(const std::filesystem::path& path) {
    return "'" + path.string() + "'";
}

class Package : public ::testing::Test {
protected:
    // Installed once for the suite.
    static void SetUpTestSuite() {
        scratch_ = std::make_unique<test::ScratchDir>();
        const test::RunResult r = test::runCommand(
            kCmake + " --install " + quote(kBuild) + " --prefix " + quote(prefix()),
            *scratch_ / "");
        installed_ = r.status == 0;
        installLog_ = r.out + r.err;
    }
    static void TearDownTestSuite() { scratch_.reset(); }

    void SetUp() override { ASSERT_TRUE(installed_) << "cmake --install failed:\n" << installLog_; }

    static std::filesystem::path prefix() { return *scratch_ / "prefix"; }

    // Configures and builds the CMake project in `source` against the install in
    // `installed` (default: the whole package's); its build folder.
    static std::filesystem::path buildAgainstInstall(const std::filesystem::path& source,
                                                     const std::string& name,
                                                     const std::filesystem::path& installed = {}) {
        const std::filesystem::path build = *scratch_ / name;
        const test::RunResult configure =
            test::runCommand(kCmake + " -S " + quote(source) + " -B " + quote(build) + " -G '" +
                                 kGenerator + "' -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=" +
                                 quote(installed.empty() ? prefix() : installed),
                             *scratch_ / "");
        EXPECT_EQ(configure.status, 0) << configure.out << configure.err;
        const test::RunResult compile =
            test::runCommand(kCmake + " --build " + quote(build), *scratch_ / "");
        EXPECT_EQ(compile.status, 0) << compile.out << compile.err;
        return build;
    }

    static std::unique_ptr<test::ScratchDir> scratch_;
    static bool installed_;
    static std::string installLog_;
};

std::unique_ptr<test::ScratchDir> Package::scratch_;
bool Package::installed_ = false;
std::string Package::installLog_;

// The example's own shader traces with the library and shades as microrelief-render
// does, through the same camera: the same float rays, the same library code, the same
// hits. They differ in how the numbers reach the shader (uniforms, a uniform block) and in
// the proxy (a full-screen triangle, the box), so the colours may differ by rounding: at
// most one level in any channel for 0.1 % of channel values (a level is 1/255), a mean
// below 0.02 levels, and nothing beyond 2 levels. A hit that turned into a miss would be
// tens of levels off.
TEST_F(Package, ExampleBuiltAgainstTheInstallRendersWhatTheRendererRenders) {
    const std::filesystem::path build =
        buildAgainstInstall(kSource / "examples" / "headless", "example");
    struct View {
        const char* name;
        std::string camera;
    };
    for (const View& v :
         {View{"default", "--size 320x180"},
          View{"close", "--eye 0.3,0.18,0.32 --target 0,0,0 --fovy 50 --size 200x150"}}) {
        const std::filesystem::path example = *scratch_ / (std::string(v.name) + "-example.png");
        const std::filesystem::path render = *scratch_ / (std::string(v.name) + "-render.png");
        const test::RunResult a = test::runCommand(
            quote(build / "relief-headless") + " " + v.camera + " --out " + quote(example),
            *scratch_ / "");
        ASSERT_EQ(a.status, 0) << a.out << a.err;
        const test::RunResult b = test::runCommand(
            quote(MICRORELIEF_RENDER_EXE) + " -q --albedo none " + v.camera + " --out " + quote(render),
            *scratch_ / "");
        ASSERT_EQ(b.status, 0) << b.out << b.err;
        const test::Image actual = test::readImage(example), expected = test::readImage(render);
        ASSERT_EQ(actual.width, expected.width);
        ASSERT_EQ(actual.height, expected.height);
        const test::Difference d =
            test::difference(actual, expected, 0, 0, actual.width, actual.height);
        const std::size_t values = 3u * actual.width * actual.height;
        std::printf("    %s: max %d levels, mean %.4f, %zu of %zu values more than 1 apart\n",
                    v.name, d.max, d.mean, d.overOne, values);
        const bool ok = d.max <= 2 && d.mean < 0.02 && d.overOne * 1000 <= values;
        EXPECT_TRUE(ok) << v.name << ": "
                        << test::keepForInspection("package-failures", v.name, actual, expected);
    }
}

// examples/renderer (docs/api.md's walk-through) draws with the library's renderer from the
// scene value: its picture is microrelief-render's, pixel for pixel (the same programs,
// the same pyramid texels whichever builds them, the same camera resolved against the map),
// with the bundled map's colours and without them (a map file of its own). Its pick at the
// centre by the relief on the CPU lands within half a texel of the picture's hit (a texel
// of the 256-texel bundled map on the plane's unit side: 1/256; accuracy.md holds the twin
// and the shader to half of one).
TEST_F(Package, RendererExampleDrawsWhatMicroreliefRenderDraws) {
    const std::filesystem::path build =
        buildAgainstInstall(kSource / "examples" / "renderer", "renderer-example");
    struct Case {
        const char* name;
        std::string map;  // flags for both programs
    };
    const std::string cobbles = quote(kSource / "assets" / "cobbles.png");
    for (const Case& c : {Case{"bundled", ""}, Case{"file", "--height " + cobbles}}) {
        const std::filesystem::path example = *scratch_ / (std::string(c.name) + "-renderer.png");
        const std::filesystem::path render = *scratch_ / (std::string(c.name) + "-render.png");
        const test::RunResult a = test::runCommand(
            quote(build / "relief-renderer") + " " + c.map + " --out " + quote(example),
            *scratch_ / "");
        ASSERT_EQ(a.status, 0) << a.out << a.err;
        const test::RunResult b =
            test::runCommand(quote(MICRORELIEF_RENDER_EXE) + " -q --size 640x360 " + c.map +
                                 " --out " + quote(render),
                             *scratch_ / "");
        ASSERT_EQ(b.status, 0) << b.out << b.err;
        const test::Image actual = test::readImage(example), expected = test::readImage(render);
        ASSERT_EQ(actual.width, expected.width);
        ASSERT_EQ(actual.height, expected.height);
        const test::Difference d =
            test::difference(actual, expected, 0, 0, actual.width, actual.height);
        EXPECT_EQ(d.max, 0) << c.name << ": "
                            << test::keepForInspection("package-failures", c.name, actual,
                                                       expected);

        glm::dvec3 gpu, cpu;
        const std::size_t at = a.out.find("centre: ");
        ASSERT_NE(at, std::string::npos) << c.name << ": no pick at the centre\n" << a.out;
        ASSERT_EQ(std::sscanf(a.out.c_str() + at, "centre: gpu %lf %lf %lf, cpu %lf %lf %lf",
                              &gpu.x, &gpu.y, &gpu.z, &cpu.x, &cpu.y, &cpu.z),
                  6)
            << a.out;
        EXPECT_LT(glm::length(gpu - cpu), 0.5 / 256) << c.name << ": " << a.out;
    }
}

// microrelief::core needs the C++ standard library and GLM only: a program that links it
// alone loads no GL, EGL, OpenImageIO or GLFW library, however it is built.
void expectCoreOnly(const test::RunResult& run, const test::RunResult& ldd) {
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("hit at y = 0.0499"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("microrelief " MICRORELIEF_VERSION_STRING), std::string::npos)
        << run.out;
    ASSERT_EQ(ldd.status, 0) << ldd.err;
    for (const char* library : {"libGL", "libEGL", "libOpenGL", "libOpenImageIO", "libglfw"})
        EXPECT_EQ(ldd.out.find(library), std::string::npos) << library << " in\n" << ldd.out;
    EXPECT_NE(ldd.out.find("libstdc++"), std::string::npos) << ldd.out;  // ldd did list it
}

TEST_F(Package, CoreAloneThroughFindPackageLinksNoGlOrImageLibrary) {
    const std::filesystem::path build =
        buildAgainstInstall(kSource / "tests" / "package" / "core_only", "core-only");
    const std::filesystem::path program = build / "core-only";
    expectCoreOnly(test::runCommand(quote(program), *scratch_ / ""),
                   test::runCommand("ldd " + quote(program), *scratch_ / ""));
}

TEST_F(Package, CoreAloneThroughPkgConfig) {
    const std::filesystem::path program = *scratch_ / "core-only-pc";
    const std::string flags = "PKG_CONFIG_PATH=" + quote(prefix() / "lib" / "pkgconfig") + " " +
                              MICRORELIEF_PKG_CONFIG + " --cflags --libs microrelief-core";
    const test::RunResult compile =
        test::runCommand(std::string(MICRORELIEF_CXX_COMPILER) + " -std=c++20 " +
                             quote(kSource / "tests" / "package" / "core_only" / "main.cpp") +
                             " -o " + quote(program) + " $(" + flags + ")",
                         *scratch_ / "");
    ASSERT_EQ(compile.status, 0) << compile.out << compile.err;
    expectCoreOnly(test::runCommand(quote(program), *scratch_ / ""),
                   test::runCommand("ldd " + quote(program), *scratch_ / ""));
}

// Every component's pkg-config file names the installed data and shader folders (pkgdatadir,
// shaderdir: the CMake package's microrelief_DATA_DIR and microrelief_SHADER_DIR), through
// its relocatable prefix.
TEST_F(Package, PkgConfigNamesTheDataAndShaderFolders) {
    for (const char* component : {"microrelief-core", "microrelief-peers", "microrelief-io",
                                  "microrelief-gl", "microrelief-headless", "microrelief-glfw"}) {
        auto variable = [&](const char* name) {
            const test::RunResult run = test::runCommand(
                "PKG_CONFIG_PATH=" + quote(prefix() / "lib" / "pkgconfig") + " " +
                    MICRORELIEF_PKG_CONFIG + " --variable=" + name + " " + component,
                *scratch_ / "");
            EXPECT_EQ(run.status, 0) << component << ": " << run.err;
            std::string value = run.out;
            while (!value.empty() && (value.back() == '\n' || value.back() == ' '))
                value.pop_back();
            return std::filesystem::path(value);
        };
        const std::filesystem::path data = variable("pkgdatadir"), shaders = variable("shaderdir");
        EXPECT_TRUE(std::filesystem::is_regular_file(data / "assets" / "cobbles.png"))
            << component << ": pkgdatadir " << data;
        EXPECT_TRUE(
            std::filesystem::is_regular_file(shaders / "microrelief" / "multilevel_trace.glsl"))
            << component << ": shaderdir " << shaders;
    }
}

// The licence travels with the install (issue 48): the repository's LICENSE, as it is, in
// share/doc/microrelief, where a distribution's package keeps it.
TEST_F(Package, TheLicenceIsInstalledWithThePackage) {
    const std::filesystem::path licence = prefix() / "share" / "doc" / "microrelief" / "LICENSE";
    ASSERT_TRUE(std::filesystem::is_regular_file(licence)) << licence << " is not installed";
    EXPECT_EQ(test::readText(licence), test::readText(kSource / "LICENSE"));
    EXPECT_NE(test::readText(licence).find("MIT License"), std::string::npos);
}

// The library configured with its core alone (MICRORELIEF_LIBRARIES=core, no programs):
// CMake is told that OpenImageIO, OpenGL, GLFW, zlib and CLI11 cannot be found, so any
// lookup of them that is REQUIRED stops the configure; glad2 must not be looked up either.
// It builds, installs only core's headers, and the core-only program builds against it.
TEST_F(Package, CoreConfiguresAndBuildsAloneWithOnlyGlm) {
    const std::filesystem::path build = *scratch_ / "core-alone";
    const std::filesystem::path corePrefix = *scratch_ / "core-alone-prefix";
    std::string disabled;
    for (const char* package : {"OpenImageIO", "OpenGL", "glfw3", "ZLIB", "CLI11", "GTest", "GDAL"})
        disabled += std::string(" -DCMAKE_DISABLE_FIND_PACKAGE_") + package + "=ON";
    const test::RunResult configure = test::runCommand(
        kCmake + " -S " + quote(kSource) + " -B " + quote(build) + " -G '" + kGenerator +
            "' -DCMAKE_BUILD_TYPE=Release -DMICRORELIEF_LIBRARIES=core"
            " -DMICRORELIEF_BUILD_APPS=OFF -DMICRORELIEF_BUILD_TESTS=OFF"
            " -DMICRORELIEF_BUILD_THREE=OFF" +
            disabled,
        *scratch_ / "");
    ASSERT_EQ(configure.status, 0) << configure.out << configure.err;
    const std::string cache = test::readText(build / "CMakeCache.txt");
    for (const char* entry :
         {"GLAD_EXECUTABLE", "OpenImageIO_DIR", "glfw3_DIR", "OPENGL_egl", "GDAL_DIR"})
        EXPECT_EQ(cache.find(entry), std::string::npos) << entry << " looked up for core alone";
    const test::RunResult compile =
        test::runCommand(kCmake + " --build " + quote(build), *scratch_ / "");
    ASSERT_EQ(compile.status, 0) << compile.out << compile.err;
    const test::RunResult install = test::runCommand(
        kCmake + " --install " + quote(build) + " --prefix " + quote(corePrefix), *scratch_ / "");
    ASSERT_EQ(install.status, 0) << install.out << install.err;
    for (const char* other : {"peers", "io", "gl", "headless", "glfw", "third_party"})
        EXPECT_FALSE(std::filesystem::exists(corePrefix / "include" / "microrelief" / other))
            << other << "'s headers installed with core alone";
    EXPECT_TRUE(std::filesystem::exists(corePrefix / "include" / "microrelief" / "core" /
                                        "GlslConstants.h"));

    const std::filesystem::path program = buildAgainstInstall(
        kSource / "tests" / "package" / "core_only", "core-alone-program", corePrefix);
    if (HasFailure()) return;
    expectCoreOnly(test::runCommand(quote(program / "core-only"), *scratch_ / ""),
                   test::runCommand("ldd " + quote(program / "core-only"), *scratch_ / ""));
}

}  // namespace
