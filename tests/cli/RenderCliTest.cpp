// microrelief-render as a user meets it (scene-and-cli.md): flags, exit statuses
// (0 success, 2 bad arguments or input, 1 anything else), exactly one error line on
// stderr naming the file and the reason, and no file written or changed on failure.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstdlib>

#include "TestSupport.h"
#include "context/GlContext.h"
#include "synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

class RenderCli : public ::testing::Test {
protected:
    // Runs microrelief-render with `args` (already shell-quoted where needed).
    // Runs microrelief-render with `args` (already shell-quoted where needed).
    test::RunResult run(const std::string& args, const std::string& environment = "") {
        return test::runCommand(environment + " " + MICRORELIEF_RENDER_EXE + " " + args,
                                dir.path());
    }

    // Asserts the spec's failure shape and returns the message.
    static void expectFailure(const test::RunResult& r, int status, const std::string& mentions) {
        test::expectOneLineFailure(r, "microrelief-render", status, mentions);
    }

    std::vector<std::string> filesIn(const std::filesystem::path& folder) {
        std::vector<std::string> names;
        for (const auto& e : std::filesystem::directory_iterator(folder))
            names.push_back(e.path().filename());
        std::sort(names.begin(), names.end());
        return names;
    }

    test::ScratchDir dir;
    const std::string small = " --size 48x32 --backend auto ";
};

TEST_F(RenderCli, HelpAndVersionExitZero) {
    const test::RunResult help = run("--help");
    EXPECT_EQ(help.status, 0);
    for (const char* flag : {"--height", "--height-scale", "--eye", "--target", "--up", "--fovy",
                             "--size", "--out", "--aov", "--backend", "--channel", "--normalize"}) {
        EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
    }
    const test::RunResult version = run("--version");
    EXPECT_EQ(version.status, 0);
    EXPECT_NE(version.out.find("microrelief-render"), std::string::npos);
}

TEST_F(RenderCli, DefaultMapRendersThePictureAndTheAov) {
    const auto out = dir / "view.png", aov = dir / "view.exr";
    const test::RunResult r = run(small + "--out " + out.string() + " --aov " + aov.string());
    ASSERT_EQ(r.status, 0) << r.err;
    auto picture = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(picture);
    EXPECT_EQ(picture->spec().width, 48);
    EXPECT_EQ(picture->spec().height, 32);
    auto positions = OIIO::ImageInput::open(aov.string());
    ASSERT_TRUE(positions);
    const OIIO::ImageSpec& spec = positions->spec();
    ASSERT_EQ(spec.nchannels, 4);
    EXPECT_EQ(spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
    EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
    std::vector<float> pixels(48 * 32 * 4);
    ASSERT_TRUE(positions->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()));
    int hits = 0;
    for (std::size_t p = 0; p < pixels.size(); p += 4) {
        if (pixels[p + 3] == 0.0f) {
            EXPECT_EQ(pixels[p] + pixels[p + 1] + pixels[p + 2], 0.0f);
            continue;
        }
        ASSERT_EQ(pixels[p + 3], 1.0f);
        ++hits;
        EXPECT_LE(std::abs(pixels[p]), 0.5f + 1e-5f);
        EXPECT_LE(std::abs(pixels[p + 2]), 0.5f + 1e-5f);
        EXPECT_GE(pixels[p + 1], 0.0f);
        EXPECT_LE(pixels[p + 1], 0.1f + 1e-5f);
    }
    EXPECT_GT(hits, 48 * 32 / 4);
    EXPECT_EQ(filesIn(dir.path()),
              (std::vector<std::string>{"stderr", "stdout", "view.exr", "view.png"}))
        << "no temporary file may remain";
}

TEST_F(RenderCli, NegativeCoordinatesInBothSpellings) {
    const auto a = dir / "a.png", b = dir / "b.png";
    ASSERT_EQ(run(small + "--eye=-0.7,0.5,-0.6 --out " + a.string()).status, 0);
    ASSERT_EQ(run(small + "--eye -0.7,0.5,-0.6 --out " + b.string()).status, 0);
    EXPECT_EQ(test::readBytes(a), test::readBytes(b));
    const test::RunResult below = run(small + "--eye -0.3,-1,0.2 --out " + a.string());
    EXPECT_EQ(below.status, 0) << below.err;
}

TEST_F(RenderCli, BadArgumentsExitTwo) {
    expectFailure(run(small + "--size 0x10"), 2, "--size");
    expectFailure(run(small + "--eye 1,2"), 2, "--eye");
    expectFailure(run(small + "--eye 0,0,0 --target 0,0,0"), 2, "--eye");
    expectFailure(run(small + "--eye 0,1,0 --target 0,0,0 --up 0,1,0"), 2, "--up");
    expectFailure(run(small + "--height-scale -1"), 2, "--height-scale");
    expectFailure(run(small + "--fovy 180"), 2, "--fovy");
    expectFailure(run("--size 48x32 --backend vulkan"), 2, "vulkan");
    expectFailure(run(small + "--no-such-flag"), 2, "--no-such-flag");
    expectFailure(run(small + "--out " + (dir / "x.unknownext").string()), 2, "x.unknownext");
    expectFailure(run(small + "--aov " + (dir / "x.png").string()), 2, "x.png");
}

// The base surface's flags (scene-and-cli.md, "Base surfaces"): an unknown base, a size
// that is zero, negative or not finite, a size flag the base has not: exit 2, one line
// naming the flag, nothing written.
TEST_F(RenderCli, BadBaseSurfacesExitTwoAndWriteNothing) {
    const auto out = dir / "never.png";
    const std::string to = " --out " + out.string();
    expectFailure(run(small + "--base torus" + to), 2, "--base");
    expectFailure(run(small + "--base cylinder --radius 0" + to), 2, "--radius");
    expectFailure(run(small + "--base cylinder --radius -0.3" + to), 2, "--radius");
    expectFailure(run(small + "--base cylinder --length inf" + to), 2, "--length");
    expectFailure(run(small + "--base cylinder --length nan" + to), 2, "--length");
    expectFailure(run(small + "--base ellipsoid --radii 0.5,0,0.5" + to), 2, "--radii");
    expectFailure(run(small + "--base ellipsoid --radii 0.5,0.5" + to), 2, "--radii");
    expectFailure(run(small + "--base sphere --radius -1" + to), 2, "--radius");
    expectFailure(run(small + "--radius 0.3" + to), 2, "--radius");  // the plane has none
    expectFailure(run(small + "--base plane --length 2" + to), 2, "--length");
    expectFailure(run(small + "--base sphere --length 2" + to), 2, "--length");
    expectFailure(run(small + "--base sphere --radii 1,1,1" + to), 2, "--radii");
    expectFailure(run(small + "--base ellipsoid --radius 1" + to), 2, "--radius");
    expectFailure(run(small + "--base cylinder --method steep" + to), 2, "--method");
    EXPECT_FALSE(std::filesystem::exists(out));
}

// Each base renders, and --compare-reference holds it to the reference.
TEST_F(RenderCli, EveryBaseRendersExactly) {
    for (const char* base :
         {"--base plane", "--base cylinder --radius 0.3 --length 0.8", "--base sphere --radius 0.4",
          "--base ellipsoid --radii 0.45,0.35,0.3"}) {
        const auto out = dir / "base.png";
        const test::RunResult r = run(small + base + " --eye 0.9,0.5,0.8 --target 0,0,0 --out " +
                                      out.string() + " --compare-reference");
        ASSERT_EQ(r.status, 0) << base << ": " << r.err;
        EXPECT_NE(r.out.find("hit/miss disagreement               0 px"), std::string::npos)
            << base << ":\n"
            << r.out;
        EXPECT_TRUE(std::filesystem::exists(out)) << base;
    }
}

TEST_F(RenderCli, BadMapsExitTwoAndLeaveTheOutputAlone) {
    const auto out = dir / "keep.png";
    test::writeBytes(out, {'o', 'l', 'd'});
    auto expectRefused = [&](const std::filesystem::path& map, const std::string& reason) {
        const test::RunResult r =
            run(small + "--height " + map.string() + " --out " + out.string());
        expectFailure(r, 2, map.filename().string());
        EXPECT_NE(r.err.find(reason), std::string::npos) << r.err;
        EXPECT_EQ(test::readBytes(out), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
    };
    expectRefused(dir / "missing.png", "no such file");

    test::writeMap(dir / "whole.png", synth::valueNoise(64, 64, 8, 2, 1), PixelType::UInt16);
    std::vector<std::uint8_t> bytes = test::readBytes(dir / "whole.png");
    bytes.resize(bytes.size() / 2);
    test::writeBytes(dir / "truncated.png", bytes);
    expectRefused(dir / "truncated.png", "cannot read");

    HeightMap nan(4, 4, 0.5f);
    nan.at(2, 3) = std::nanf("");
    test::writeMap(dir / "nan.exr", nan, PixelType::Float);
    expectRefused(dir / "nan.exr", "finite");

    HeightMap negative(4, 4, 0.5f);
    negative.at(1, 1) = -1.0f;
    test::writeMap(dir / "negative.exr", negative, PixelType::Float);
    expectRefused(dir / "negative.exr", "--normalize");

    // Wider than llvmpipe's and most GPUs' GL_MAX_TEXTURE_SIZE (16384 or 32768), yet
    // a small file: one row of 40000 zeros.
    test::writeMap(dir / "huge.png", HeightMap(40000, 1), PixelType::UInt8);
    expectRefused(dir / "huge.png", "GL_MAX_TEXTURE_SIZE");

    EXPECT_EQ(filesIn(dir.path()).size(), 8u) << "no temporary file may remain";
}

TEST_F(RenderCli, OutputsThatCannotAllBeWrittenAreRefusedBeforeAnyIsTouched) {
    const auto picture = dir / "a.png";
    test::writeBytes(picture, {'o', 'l', 'd'});
    std::filesystem::create_directory(dir / "d.exr");
    expectFailure(run(small + "--out " + picture.string() + " --aov " + (dir / "d.exr").string()),
                  2, "d.exr");
    expectFailure(run(small + "--out " + (dir / "same.exr").string() + " --aov " +
                      (dir / "same.exr").string()),
                  2, "same.exr");
    EXPECT_EQ(test::readBytes(picture), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
    EXPECT_FALSE(std::filesystem::exists(dir / "same.exr"));
}

TEST_F(RenderCli, NormalizeRescuesNegativeMaps) {
    HeightMap negative(4, 4, 0.5f);
    negative.at(1, 1) = -1.0f;
    test::writeMap(dir / "negative.exr", negative, PixelType::Float);
    const test::RunResult r =
        run(small + "--normalize --height " + (dir / "negative.exr").string() + " --out " +
            (dir / "n.png").string());
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(RenderCli, OneByOneMapRenders) {
    test::writeMap(dir / "one.png", HeightMap(1, 1, 1.0f), PixelType::UInt8);
    const test::RunResult r = run(small + "--height " + (dir / "one.png").string() + " --out " +
                                  (dir / "o.png").string());
    EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(RenderCli, NoGlBackendExitsOneWithOneLine) {
    // No EGL vendor library and no OSMesa: nothing can make a context.
    const test::RunResult r = run(small + "--out " + (dir / "x.png").string(),
                                  "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json "
                                  "MICRORELIEF_OSMESA_LIBRARY=/nonexistent.so");
    expectFailure(r, 1, "no GL backend");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST_F(RenderCli, EachBackendOnRequest) {
    for (const char* backend : {"egl", "osmesa"}) {
        if (!isBackendPresent(parseBackend(backend))) {
            GTEST_SKIP() << backend << " is absent";  // Mesa 25.1 and later have no OSMesa
        }
        const test::RunResult r = run(std::string("--size 32x32 --backend ") + backend + " --out " +
                                      (dir / (std::string(backend) + ".png")).string());
        EXPECT_EQ(r.status, 0) << backend << ": " << r.err;
        EXPECT_NE(r.out.find(backend), std::string::npos) << r.out;
    }
}

}  // namespace
