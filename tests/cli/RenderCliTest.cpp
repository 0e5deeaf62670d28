// microrelief-render as a user meets it (scene-and-cli.md): flags, exit statuses
// (0 success, 2 bad arguments or input, 1 anything else), exactly one error line on
// stderr naming the file and the reason, and no file written or changed on failure.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

#include "TestSupport.h"
#include "microrelief/core/Machine.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

class RenderCli : public ::testing::Test {
protected:
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

// The spec keeps the eye outside the solid: an eye under the surface still renders, with a
// warning that names the map; above it, or below the base plane, there is none.
TEST_F(RenderCli, AnEyeInsideTheSolidIsWarnedOf) {
    const auto out = (dir / "a.png").string();
    const test::RunResult inside =
        run(small + "--eye 0.05,0.005,0.05 --target -0.3,0,-0.3 --out " + out);
    EXPECT_EQ(inside.status, 0) << inside.err;
    EXPECT_NE(inside.err.find("warning: --eye lies inside the relief's solid (under the surface "
                              "of cobbles.png)"),
              std::string::npos)
        << inside.err;
    const test::RunResult column =
        run(small + "--base cylinder --eye 0,0,0.301 --target 0.3,0,0.3 --out " + out);
    EXPECT_NE(column.err.find("inside the relief's solid"), std::string::npos) << column.err;
    for (const std::string eye : {"0.05,0.2,0.05", "-0.3,-1,0.2"}) {
        const test::RunResult outside = run(small + "--eye " + eye + " --out " + out);
        EXPECT_EQ(outside.status, 0) << outside.err;
        EXPECT_EQ(outside.err.find("inside"), std::string::npos) << eye << ": " << outside.err;
    }
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
    // CLI11's own wording replaced by the programs' (parseErrorText).
    expectFailure(run(small + "--size 32x32"), 2, "--size is given more than once (see --help)");
    expectFailure(run(small + "--channel 1.5"), 2, "--channel: '1.5' is not a value it takes");
    // CLI11 names the words it did not expect last first ("maps/b.png --heigth").
    expectFailure(run(small + "--heigth maps/b.png"), 2, "error: --heigth is not an option (see");
    expectFailure(run(small + "--heigth a.png --colour"), 2,
                  "--heigth and --colour are not options");
    expectFailure(run(small + "--heigth=a.png -1"), 2, "error: --heigth is not an option (see");
    expectFailure(run(small + "a.png b.png"), 2,
                  "'a.png' and 'b.png' were not expected (options are given as --name VALUE)");
    // A word with a space in it stays one word (CLI11's message joins them with spaces).
    expectFailure(run(small + "'my map.png'"), 2,
                  "'my map.png' was not expected (options are given as --name VALUE)");
}

// The material, tiling, model and light flags (issues 13, 14): each bad value refused with one line
// naming the flag, nothing written; the albedo's file through the same checks as a height map's.
TEST_F(RenderCli, BadMaterialAndShadowFlagsExitTwoAndWriteNothing) {
    const auto out = dir / "never.png";
    const std::string to = " --out " + out.string();
    expectFailure(run(small + "--shadows sharp" + to), 2, "--shadows");
    expectFailure(run(small + "--shadows hard --method pom" + to), 2, "--shadows");
    expectFailure(run(small + "--light-size 0" + to), 2, "--light-size");
    expectFailure(run(small + "--light-size 120" + to), 2, "--light-size");
    expectFailure(run(small + "--light 0,1,0 --light-position 0,1,0" + to), 2, "--light-position");
    expectFailure(run(small + "--tile 0,2" + to), 2, "--tile");
    expectFailure(run(small + "--tile 2.5,2" + to), 2, "--tile");
    expectFailure(run(small + "--tile 2" + to), 2, "--tile");
    expectFailure(run(small + "--tile 2,2 --method maxmip" + to), 2, "--tile");
    // A whole too wide for float's entry point anywhere names the tiles, not the eye.
    expectFailure(run(small + "--tile 2048,2048 --eye 0.01,0.02,0.01" + to), 2, "with --tile");
    expectFailure(run(small + "--model 1,0,0,0,0,1,0,0,0,0,1" + to), 2, "--model");
    expectFailure(run(small + "--model 1,0,0,0,0,0,0,0,0,0,1,0" + to), 2, "--model");
    expectFailure(run(small + "--albedo " + (dir / "missing.png").string() + to), 2, "missing.png");
    expectFailure(run(small + "--albedo /dev/zero" + to), 2, "/dev/zero");
    test::writeBytes(dir / "broken.png", {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0});
    expectFailure(run(small + "--albedo " + (dir / "broken.png").string() + to), 2, "broken.png");
    EXPECT_FALSE(std::filesystem::exists(out));
}

// With shadows on, the AOV's fifth channel `shadow`: 1 lit, 0 shadowed or a miss; some
// hits of each with a low light; without shadows four channels, as before.
TEST_F(RenderCli, ShadowsAddTheShadowChannelToTheAov) {
    const auto out = dir / "lit.png", aov = dir / "lit.exr";
    const test::RunResult r = run(small + "--shadows hard --light=-0.9,0.2,-0.3 --out " +
                                  out.string() + " --aov " + aov.string());
    ASSERT_EQ(r.status, 0) << r.err;
    auto input = OIIO::ImageInput::open(aov.string());
    ASSERT_TRUE(input);
    ASSERT_EQ(input->spec().nchannels, 5);
    EXPECT_EQ(input->spec().channelnames, (std::vector<std::string>{"R", "G", "B", "A", "shadow"}));
    std::vector<float> pixels(48 * 32 * 5);
    ASSERT_TRUE(input->read_image(0, 0, 0, 5, OIIO::TypeDesc::FLOAT, pixels.data()));
    int lit = 0, shadowed = 0;
    for (std::size_t p = 0; p < pixels.size(); p += 5) {
        const float shadow = pixels[p + 4];
        EXPECT_TRUE(shadow == 0.0f || shadow == 1.0f) << shadow;
        if (pixels[p + 3] == 0.0f) {
            EXPECT_EQ(shadow, 0.0f);  // misses
            continue;
        }
        (shadow > 0.5f ? lit : shadowed) += 1;
    }
    EXPECT_GT(lit, 20);
    EXPECT_GT(shadowed, 20);
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

// --animate NAME --time T (issue 16): each field renders, held by --compare-reference to
// the heights the GPU evaluated; another moment is another picture; the same one the same
// picture; bad names and times refused with one line and nothing written.
TEST_F(RenderCli, AnimatedReliefsRenderExactlyAtAnyTime) {
    const std::string view = small + "--eye 0.8,0.55,0.85 --target 0,0,0 --compare-reference ";
    for (const char* field : {"waves", "ripples", "flood"}) {
        for (const char* time : {"0", "2.75"}) {
            const auto out = dir / (std::string(field) + "-" + time + ".png");
            const test::RunResult r =
                run(view + "--animate " + field + " --time " + time + " --base " +
                    (time[0] == '0' ? "plane" : "cylinder") + " --out " + out.string());
            ASSERT_EQ(r.status, 0) << field << ": " << r.err;
            EXPECT_NE(r.out.find("hit/miss disagreement               0 px"), std::string::npos)
                << field << " at " << time << ":\n"
                << r.out;
        }
    }
    const auto a = dir / "a.png", b = dir / "b.png", c = dir / "c.png";
    ASSERT_EQ(run(small + "--animate waves --time 1 --out " + a.string()).status, 0);
    ASSERT_EQ(run(small + "--animate waves --time 1 --out " + b.string()).status, 0);
    ASSERT_EQ(run(small + "--animate waves --time 1.5 --out " + c.string()).status, 0);
    EXPECT_EQ(test::readBytes(a), test::readBytes(b));
    EXPECT_NE(test::readBytes(a), test::readBytes(c));

    const auto never = " --out " + (dir / "never.png").string();
    expectFailure(run(small + "--animate tides" + never), 2, "--animate 'tides'");
    expectFailure(run(small + "--time 2" + never), 2, "--time needs --animate");
    expectFailure(run(small + "--animate waves --time nan" + never), 2, "--time");
    expectFailure(run(small + "--animate waves --time inf" + never), 2, "--time");
    expectFailure(run(small + "--animate waves --time=-2e9" + never), 2, "within +-1e9");
    EXPECT_FALSE(std::filesystem::exists(dir / "never.png"));
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
    test::writeBytes(dir / "empty.png", {});
    expectRefused(dir / "empty.png", "the file is empty (0 bytes)");
    // An elevation model in another of GDAL's formats: how to get one the programs read.
    test::writeBytes(dir / "dem.asc", {'n', 'c', 'o', 'l', 's'});
    expectRefused(dir / "dem.asc",
                  "'.asc'; elevation models are read as GeoTIFF (.tif) or SRTM "
                  ".hgt: gdal_translate -of GTiff converts this one");

    test::writeMap(dir / "whole.png", synth::valueNoise(64, 64, 8, 2, 1), PixelType::UInt16);
    std::vector<std::uint8_t> bytes = test::readBytes(dir / "whole.png");
    bytes.resize(bytes.size() / 2);
    test::writeBytes(dir / "truncated.png", bytes);
    expectRefused(dir / "truncated.png", "truncated");

    HeightMap nan(4, 4, 0.5f);
    nan.at(2, 3) = std::nanf("");
    test::writeMap(dir / "nan.exr", nan, PixelType::Float);
    expectRefused(dir / "nan.exr", "finite");

    HeightMap negative(4, 4, 0.5f);
    negative.at(1, 1) = -1.0f;
    test::writeMap(dir / "negative.exr", negative, PixelType::Float);
    expectRefused(dir / "negative.exr", "--normalize");

    // Wider than the loader's limit (kMaxPagedHeightMapSide), yet a small file: one row of
    // 70000 zeros.
    test::writeMap(dir / "huge.png", HeightMap(70000, 1), PixelType::UInt8);
    expectRefused(dir / "huge.png", "70000 x 1 is larger than the 65536 x 65536");

    EXPECT_EQ(filesIn(dir.path()).size(), 10u) << "no temporary file may remain";

    // Refused while its pyramid file is built: the cache folders the run made are gone.
    const test::RunResult r =
        run(small + "--height " + (dir / "truncated.png").string() + " --pyramid-cache " +
            (dir / "new" / "cache").string() + " --out " + out.string());
    expectFailure(r, 2, "truncated.png");
    EXPECT_FALSE(std::filesystem::exists(dir / "new")) << "a failed run left the folder it made";
}

// Inputs that used to hang or exhaust memory (issue 15), refused before OpenImageIO
// reads a pixel. `timeout` turns a hang into a failure instead of a stuck suite.
TEST_F(RenderCli, DevicesFifosAndLyingHeadersAreRefusedAtOnce) {
    auto expectRefused = [&](const std::string& map, const std::string& reason,
                             const std::string& flags = "") {
        const test::RunResult r = run(
            small + flags + "--height " + map + " --out " + (dir / "x.png").string(), "timeout 20");
        expectFailure(r, 2, map);
        EXPECT_NE(r.err.find(reason), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
        return r.err;
    };
    expectRefused("/dev/zero", "not a regular file");
    expectRefused("/dev/urandom", "not a regular file");
    const auto fifo = dir / "map.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expectRefused(fifo.string(), "not a regular file");
    // A 69-byte PNG whose header claims 65535 x 40000 (10 GB of floats, about 40 GiB to draw
    // through pages) and one that claims 100000 x 100000 (which used to end in
    // std::bad_alloc): refused from the header, the first for the memory available, here
    // 24 GiB whatever this machine has (core/Machine.h: the variable stands for it). Refused
    // for memory, the message offers --pyramid-cache where that would draw the picture asked
    // for, and not for a method that does not read pages.
    const auto corpus = std::filesystem::path(MICRORELIEF_FUZZ_CORPUS_DIR);
    const auto lying = (corpus / "claims_65535x40000.png").string();
    {
        const test::ScopedEnvironment available(kAvailableMemoryVariable, "24576");
        const std::string hint = " available now; --pyramid-cache FOLDER draws it from disk";
        EXPECT_NE(expectRefused(lying,
                                "65535 x 40000 samples need about 40 GiB of memory to draw, more "
                                "than the 24.0 GiB available now")
                      .find(hint),
                  std::string::npos);
        EXPECT_EQ(expectRefused(lying, "of memory to draw", "--method maxmip ").find(hint),
                  std::string::npos);
    }
    expectRefused((corpus / "claims_100000x100000.png").string(),
                  "100000 x 100000 is larger than the 65536 x 65536");
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
    // One file in two spellings (issue 15: the AOV used to replace the picture).
    std::filesystem::create_directory_symlink(dir.path(), dir / "o");
    // (o is a link to this folder; d.exr a real folder; n does not exist.)
    for (const char* other : {"n/../same.exr", "d.exr/../same.exr", "o/same.exr", "./same.exr"}) {
        expectFailure(run(small + "--out " + (dir / "same.exr").string() + " --aov " +
                          (dir / other).string()),
                      2, "the same file as");
    }
    // An output whose folder would have to be made inside a file.
    expectFailure(run(small + "--out " + (dir / "a.png" / "x.png").string()), 2, "not a folder");
    EXPECT_EQ(test::readBytes(picture), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
    EXPECT_FALSE(std::filesystem::exists(dir / "same.exr"));
}

TEST_F(RenderCli, SigtermWhileWritingLeavesNoTemporaryAndNoNewFolder) {
    // A large AOV takes a moment to write: wait until its temporary appears in the new
    // folder, then send SIGTERM. The program must die of it and leave nothing behind.
    const auto folder = dir / "new";
    const std::string command =
        std::string("( ") + MICRORELIEF_RENDER_EXE + " --size 2048x2048 --backend auto --out " +
        (folder / "deep/x.png").string() + " --aov " + (folder / "deep/x.exr").string() +
        " & pid=$!; seen=no; for i in $(seq 1200); do if ls -a " + (folder / "deep").string() +
        " 2>/dev/null | grep -q tmp; then seen=yes; break; fi; sleep 0.05; done; kill -TERM $pid; "
        "wait $pid; echo \"status=$? seen=$seen\" )";
    const test::RunResult r = test::runCommand(command, dir.path());
    EXPECT_NE(r.out.find("status=143 seen=yes"), std::string::npos) << r.out << r.err;
    EXPECT_FALSE(std::filesystem::exists(folder)) << "the folders it made must go";
}

// Numbers beyond what the shader's float arithmetic holds (core/scene/FloatLimits.h),
// refused with the reason; numbers just inside them render exactly.
TEST_F(RenderCli, NumbersTheShaderCannotHoldAreRefusedWithTheReason) {
    auto scaled = [&](const std::string& name, float factor) {
        HeightMap map = synth::valueNoise(32, 32, 8, 2, 4);
        for (float& h : map.samples) h *= factor;
        test::writeMap(dir / name, map, PixelType::Float);
        return (dir / name).string();
    };
    const std::string out = " --out " + (dir / "x.png").string();
    // Heights 3e38 at scale 1: the relief's top overflows the world (issue 15: 36.6 % of
    // pixels wrong, exit 0).
    expectFailure(run(small + "--height " + scaled("top.exr", 3e38f) + " --height-scale 1" + out),
                  2, "the relief's top");
    // Heights 1e17 at scale 1e-18 (a top of 0.1): the patch solve would overflow.
    expectFailure(
        run(small + "--height " + scaled("solve.exr", 1e17f) + " --height-scale 1e-18" + out), 2,
        "patch solve");
    // Heights 1e15 at scale 1e-16 are inside the limits, and exact.
    const test::RunResult inside =
        run(small + "--height " + scaled("inside.exr", 1e15f) +
            " --height-scale 1e-16 --compare-reference --out " + (dir / "inside.png").string());
    ASSERT_EQ(inside.status, 0) << inside.err;
    EXPECT_NE(inside.out.find("off by more than half a texel       0 px"), std::string::npos)
        << inside.out;
    // Camera and light vectors that float cannot carry, each with its own reason.
    expectFailure(run(small + "--eye 1e300,1,1" + out), 2, "--eye 1e300,1,1: each component");
    expectFailure(run(small + "--target 1,1e13,1" + out), 2, "--target 1,1e13,1: each component");
    expectFailure(run(small + "--light 1e300,0,0" + out), 2, "--light 1e300,0,0: each component");
    expectFailure(run(small + "--light 1e-300,0,0" + out), 2, "--light 1e-300,0,0: its largest");
    // An eye too far away for exact hits in float: 5000 units from a 256-texel map.
    expectFailure(run(small + "--eye 5000,1,1" + out), 2, "too far");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// Pictures wider than the GL's viewport limit (16384 on llvmpipe) are drawn in tiles;
// beyond the stated limit they are refused up front.
TEST_F(RenderCli, PicturesBeyondTheGlLimitsRenderInTilesUpToTheStatedLimit) {
    const auto wide = dir / "wide.png";
    const test::RunResult r = run("--size 20000x6 --out " + wide.string());
    ASSERT_EQ(r.status, 0) << r.err;
    auto picture = OIIO::ImageInput::open(wide.string());
    ASSERT_TRUE(picture);
    EXPECT_EQ(picture->spec().width, 20000);
    EXPECT_EQ(picture->spec().height, 6);
    for (const char* size : {"16385x16384", "65537x1", "17000x17000"}) {
        expectFailure(run(std::string("--size ") + size + " --out " + (dir / "x.png").string()), 2,
                      "at most 268435456 pixels (16384 x 16384");
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
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
    // Every backend is tried; one that is absent fails the test unless the run allows it
    // (MICRORELIEF_ALLOW_MISSING_GL), and then the test reports the skip after the others.
    std::vector<std::string> skipped;
    for (const char* backend : {"egl", "osmesa"}) {
        if (!isBackendPresent(parseBackend(backend))) {
            if (!test::missingBackendAllowed(parseBackend(backend))) {
                ADD_FAILURE() << test::missingBackendMessage(parseBackend(backend));
            } else {
                skipped.push_back(backend);
            }
            continue;
        }
        const test::RunResult r = run(std::string("--size 32x32 --backend ") + backend + " --out " +
                                      (dir / (std::string(backend) + ".png")).string());
        EXPECT_EQ(r.status, 0) << backend << ": " << r.err;
        EXPECT_NE(r.out.find(backend), std::string::npos) << r.out;
    }
    std::string why;
    for (const std::string& backend : skipped)
        why += (why.empty() ? "" : "; ") + test::missingBackendMessage(parseBackend(backend));
    if (!why.empty()) GTEST_SKIP() << why;
}

}  // namespace

// ---- issue 25: inputs that drew wrong pictures without a word ----

// Curved bases, models and fields of view beyond what the shader's float arithmetic holds
// (core/scene/FloatLimits.h), each refused with its reason; just inside, drawn exactly (the CPU
// reference: no pixel hit on one side and missed on the other, none off by half a texel,
// where the picture is not a grazing silhouette).
TEST_F(RenderCli, CurvedBasesModelsAndFieldsOfViewBeyondFloatAreRefusedOrDrawnExactly) {
    const std::string out = " --out " + (dir / "x.png").string();
    const auto exact = [&](const std::string& args, std::size_t offPixels = 0) {
        SCOPED_TRACE(args);
        const test::RunResult r =
            run(small + args + " --compare-reference -q --out " + (dir / "exact.png").string());
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find("hit/miss disagreement               0 px"), std::string::npos)
            << r.out;
        const std::string off = "off by more than half a texel";
        const std::size_t at = r.out.find(off);
        ASSERT_NE(at, std::string::npos) << r.out;
        EXPECT_LE(std::stoul(r.out.substr(at + off.size())), offPixels) << r.out;
    };
    // A cylinder 1e8 long: 12 % of pixels wrong before (every hit lost from 1e9).
    expectFailure(run(small + "--base cylinder --length 1e8" + out), 2,
                  "reaches 5e+07 world units from --eye");
    exact("--base cylinder --length 1e6");
    // A cylinder 1e-5 thick seen from 1e5 radii: 27 % of hits off by half a texel before.
    expectFailure(run(small +
                      "--base cylinder --radius 1e-5 --length 4e-5 --target 0,0,0 "
                      "--fovy 0.0006" +
                      out),
                  2, "too far from");
    exact("--base cylinder --radius 1e-3 --length 4e-3 --target 0,0,0 --fovy 0.06");
    // A model shrinking the relief 1e20 times (shaded wrong before), and one growing it
    // 1e5 times seen from 1e5 times as far (refused before by an eye check blind to the
    // model: drawn exactly now but for one silhouette pixel that grazes a stone).
    expectFailure(run(small +
                      "--model 1e-20,0,0,0,0,1e-20,0,0,0,0,1e-20,0 --eye=8e-21,5e-21,8.5e-21 "
                      "--target 0,0,0" +
                      out),
                  2, "--model shrinks the relief by 1e-20");
    expectFailure(run(small +
                      "--base sphere --model 1e-20,0,0,0,0,1e-20,0,0,0,0,1e-20,0 "
                      "--eye=8e-21,5e-21,8.5e-21 --target 0,0,0" +
                      out),
                  2, "--model (scales 1e-20 to 1e-20): the relief's normals");
    exact("--model 1e5,0,0,0,0,1e5,0,0,0,0,1e5,0 --eye=80000,50000,85000 --target=0,-3000,0", 1);
    // Invertible (determinant 1) but ill-conditioned: said so, with its condition number.
    expectFailure(run(small + "--model 1e7,0,0,0,0,1e-7,0,0,0,0,1,0" + out), 2,
                  "--model: the matrix is ill-conditioned (condition number 1e+14");
    expectFailure(run(small + "--model 1,0,0,0,0,0,0,0,0,0,1,0" + out), 2,
                  "--model: the matrix is singular");
    // A field of view whose pixels float cannot tell apart (all background before).
    expectFailure(run(small + "--fovy 1e-37" + out), 2, "--fovy 1e-37 at a picture 32 pixels high");
    expectFailure(run(small + "--fovy 0.003" + out), 2, "use --fovy 0.0035 or more");
    exact("--fovy 0.01");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// ---- issue 47: far from the world's origin ----

// A relief placed far from the world's origin and seen from close by is traced relative to
// the eye (the eye subtracted in double before anything becomes a float), so it is as exact
// as at the origin: before, at 9e5, 94.7 % of hits were more than half a texel off (p99 22
// texels), at 1e5 74 %, at 1e4 p99 0.23 texel. The AOV file still holds world positions.
// Curved bases far along their own length, seen from close by: the cylinder exact (a
// cylinder 2e6 long seen near y = 9e5 was 1.5 px off; it now meets the box's reach from the
// eye, so one 1e6 long at 4.5e5), the ellipsoid whose frame's unit is far longer than its
// texels near a tip refused with the bound in texels (radii 4e5, 0.5, 0.5: 8 silhouette
// pixels wrong of 1536 without the check, 0.5 %; 8e5 was 2.85 px off).
TEST_F(RenderCli, ReliefsFarFromTheOriginAreExactOrRefusedWithTheBound) {
    const auto exact = [&](const std::string& args, const std::string& aov = {}) {
        SCOPED_TRACE(args);
        const test::RunResult r =
            run(small + args + " --compare-reference -q --out " + (dir / "far.png").string() +
                (aov.empty() ? "" : " --aov " + aov));
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find("hit/miss disagreement               0 px"), std::string::npos)
            << r.out;
        EXPECT_NE(r.out.find("off by more than half a texel       0 px"), std::string::npos)
            << r.out;
    };
    const auto at = [](double x, double y, double z, const std::string& base = {}) {
        const auto n = [](double v) { return formatNumber(v, 10); };
        return base + " --model 1,0,0," + n(x) + ",0,1,0," + n(y) + ",0,0,1," + n(z) + " --eye " +
               n(x + 0.8) + "," + n(y + 0.5) + "," + n(z + 0.85) + " --target " + n(x) + "," +
               n(y - 0.03) + "," + n(z);
    };
    for (const double far : {1e4, 1e5, 9e5}) exact(at(far, 0, 0));
    const auto aov = dir / "far.exr";
    exact(at(9e5, -4e5, 7e5), aov.string());
    exact(at(9e5, 0, 0, "--base cylinder"));
    exact(at(0, 9e5, 0, "--base sphere"));
    // The AOV holds world positions: x near 9e5, rounded to float once.
    auto positions = OIIO::ImageInput::open(aov.string());
    ASSERT_TRUE(positions);
    std::vector<float> pixels(48 * 32 * 4);
    ASSERT_TRUE(positions->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()));
    int hits = 0;
    for (std::size_t p = 0; p < pixels.size(); p += 4) {
        if (pixels[p + 3] == 0.0f) continue;
        ++hits;
        EXPECT_NEAR(pixels[p], 9e5, 0.6);
        EXPECT_NEAR(pixels[p + 1], -4e5, 0.2);
        EXPECT_NEAR(pixels[p + 2], 7e5, 0.6);
    }
    EXPECT_GT(hits, 48 * 32 / 4);

    const std::string out = " --out " + (dir / "x.png").string();
    exact("--base cylinder --length 1e6 --eye 0.37,450000.77,0.33 --target 0.1,450000.1,0");
    expectFailure(run(small +
                      "--base ellipsoid --radii 4e5,0.5,0.5 --eye 400000.3,0.77,0.3 "
                      "--target 399999.9,0,0" +
                      out),
                  2, "of the base's shortest texel side");
    // Positions beyond double's reach for the relief's texels, and beyond 1e12 at all.
    expectFailure(run(small + at(1e11, 0, 0) + out), 2, "where double keeps positions to");
    expectFailure(run(small + "--eye 2e12,1,1" + out), 2, "--eye 2e12,1,1: each component");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// A float albedo holding NaN or infinity (drawn black before): refused, naming the file and
// the first such texel.
TEST_F(RenderCli, AlbedosHoldingNanOrInfinityAreRefusedNamingTheTexel) {
    const auto write = [&](const std::string& name, float bad) {
        std::vector<float> rgb(4 * 3 * 3, 0.5f);
        rgb[(2 * 4 + 3) * 3 + 1] = bad;  // column 3, row 2, green
        const std::string file = (dir / name).string();
        auto out = OIIO::ImageOutput::create(file);
        EXPECT_TRUE(out && out->open(file, OIIO::ImageSpec(4, 3, 3, OIIO::TypeDesc::HALF)));
        EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
        out->close();
        return file;
    };
    const std::string out = " --out " + (dir / "x.png").string();
    for (const float bad : {std::nanf(""), std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity()}) {
        const std::string file = write("bad.exr", bad);
        expectFailure(run(small + "--albedo " + file + out), 2,
                      file + ": texel (column 3, row 2), channel 1 is " +
                          (std::isnan(bad) ? "NaN" : "infinite"));
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
    const test::RunResult good = run(small + "--albedo " + write("good.exr", 0.25f) + out);
    EXPECT_EQ(good.status, 0) << good.err;
}

// What a user gave, echoed in a message, cannot break its one line: CR, newline and bytes
// that are no UTF-8 are escaped (a NUL cannot reach argv; camera files are batch.cpu's).
TEST_F(RenderCli, MessagesEscapeControlCharactersAndBytesThatAreNoUtf8) {
    const test::RunResult r =
        run(small + "--height \"$(printf 'a\\rb\\nc\\377\\303\\251.png')\" --out " +
            (dir / "x.png").string());
    expectFailure(r, 2, "a\\rb\\nc\\xFF\xc3\xa9.png: no such file");  // é stays as it is
    EXPECT_EQ(r.err.find('\r'), std::string::npos);
    EXPECT_EQ(run(small + "--height '' --out " + (dir / "x.png").string()).status, 2);
    // A camera file's field with a NUL, a CR and a byte that is no UTF-8.
    static constexpr char kRow[] = "1,2\0x\rz\xfe,3,0,0,0\n";
    std::ofstream(dir / "cams.csv", std::ios::binary)
        << "eye_x,eye_y,eye_z,target_x,target_y,target_z\n"
        << std::string(kRow, sizeof kRow - 1);  // the whole row, its NUL included
    const test::RunResult field = run(small + "--cameras " + (dir / "cams.csv").string() +
                                      " --out '" + (dir / "v{frame}.png").string() + "'");
    expectFailure(field, 2, "eye_y: '2\\x00x\\rz\\xFE' is not a number");
    EXPECT_EQ(field.err.find('\0'), std::string::npos);
}

// --light-size without soft shadows changes nothing: said so.
TEST_F(RenderCli, ALightSizeWithoutSoftShadowsIsWarnedOf) {
    const std::string out = " -q --out " + (dir / "x.png").string();
    const test::RunResult hard = run(small + "--light-size 2 --shadows hard" + out);
    ASSERT_EQ(hard.status, 0) << hard.err;
    EXPECT_NE(hard.err.find("warning: --light-size sets the light of soft shadows"),
              std::string::npos)
        << hard.err;
    const test::RunResult soft = run(small + "--light-size 2 --shadows soft" + out);
    ASSERT_EQ(soft.status, 0) << soft.err;
    EXPECT_EQ(soft.err, "");
}

namespace {

// A map wider than the GL's textures (16384 on llvmpipe): read through pages within
// --memory, drawn until exact (--compare-reference: no pixel off), the paging said; a
// --memory out of range refused in one line; the map refused from its header where its
// samples would not fit the machine's memory.
class RenderCliPaged : public RenderCli {};

TEST_F(RenderCliPaged, AMapWiderThanTheGlsTexturesIsReadThroughPages) {
    const auto file = dir / "wide.png";
    test::writeWideWavesMap(file);
    const auto out = dir / "paged.png";
    const test::RunResult r = run(small + "--height " + file.string() +
                                  " --eye 0.02,0.004,0.01 --target 0,0,0 --height-scale 0.002 "
                                  "--memory 4 --compare-reference --out " +
                                  out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("map 17000x40, paged: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("hit/miss disagreement               0 px"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("off by more than half a texel       0 px"), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::exists(out));
    expectFailure(
        run(small + "--height " + file.string() + " --memory 0 --out " + (dir / "x.png").string()),
        2, "--memory");
    // 1 MiB: 4 pages, fewer than one ray here reads (a sample page and 4 window levels').
    expectFailure(run(small + "--height " + file.string() +
                      " --eye 0.02,0.004,0.01 --target 0,0,0 --height-scale 0.002 --memory 1 "
                      "--out " +
                      (dir / "x.png").string()),
                  2, "raise the memory budget (--memory)");
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// --pyramid-cache: the map drawn from its pyramid file (io/PyramidFile.h), built once with
// its progress said, reused after; the picture is the one the map loaded whole gives; a
// corrupt file refused in one line, no picture written; what needs the whole map refused.
TEST_F(RenderCliPaged, AMapIsDrawnFromItsPyramidFileBuiltOnce) {
    HeightMap map(600, 300);
    for (int j = 0; j < map.height; ++j)
        for (int i = 0; i < map.width; ++i)
            map.at(i, j) = 0.5f + 0.4f * std::sin(i * 0.05f) * std::cos(j * 0.07f);
    const auto file = dir / "waves.png", cache = dir / "pyramids";
    test::writeMap(file, map, PixelType::UInt16);
    const std::string view = small + "--height " + file.string() +
                             " --eye 0.5,0.35,0.6 --target 0,0,0 --height-scale 0.05 ";
    const test::RunResult whole = run(view + "--out " + (dir / "whole.png").string());
    ASSERT_EQ(whole.status, 0) << whole.err;
    const std::string cached = view + "--memory 1 --pyramid-cache " + cache.string() + " --out ";
    const test::RunResult first = run(cached + (dir / "first.png").string());
    ASSERT_EQ(first.status, 0) << first.err;
    EXPECT_NE(first.err.find("building the pyramid file of " + file.string()), std::string::npos)
        << first.err;
    EXPECT_NE(first.out.find("map 600x300, paged: "), std::string::npos) << first.out;
    const test::RunResult again = run(cached + (dir / "again.png").string());
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.err, "") << "the file is reused";
    const test::Image a = test::readImage(dir / "whole.png");
    EXPECT_EQ(test::readImage(dir / "first.png").pixels, a.pixels);
    EXPECT_EQ(test::readImage(dir / "again.png").pixels, a.pixels);

    // A camera path draws every frame from the file, its pages kept from frame to frame: the
    // turntable's frames of the map loaded whole; what the file cannot draw is refused
    // before the first frame.
    ASSERT_EQ(run(view + "-q --turntable 3 --out " + (dir / "w{frame}.png").string()).status, 0);
    const test::RunResult path = run(cached + (dir / "c{frame}.png").string() + " --turntable 3");
    ASSERT_EQ(path.status, 0) << path.err;
    EXPECT_NE(path.out.find("3 rendered"), std::string::npos) << path.out;
    EXPECT_NE(path.out.find("1 map loaded"), std::string::npos) << path.out;
    for (int k = 0; k < 3; ++k) {
        const std::string frame = std::to_string(k) + ".png";
        EXPECT_EQ(test::readImage(dir / ("c" + frame)).pixels,
                  test::readImage(dir / ("w" + frame)).pixels)
            << "frame " << k;
    }
    expectFailure(run(cached + (dir / "t{frame}.png").string() + " --turntable 2 --tile 2,1"), 2,
                  "not with --tile");
    expectFailure(run(cached + (dir / "t{frame}.png").string() + " --turntable 2 --method cone"), 2,
                  "only the multilevel method reads: not --method cone");
    EXPECT_FALSE(std::filesystem::exists(dir / "t0.png"));

    // Checked against the reference on sampled pixels, read from the file.
    const test::RunResult checkedRun =
        run(cached + (dir / "checked.png").string() + " --compare-reference");
    ASSERT_EQ(checkedRun.status, 0) << checkedRun.err;
    EXPECT_NE(checkedRun.out.find("sampled pixels"), std::string::npos) << checkedRun.out;
    EXPECT_NE(checkedRun.out.find("hit/miss disagreement               0 px"), std::string::npos)
        << checkedRun.out;
    EXPECT_NE(checkedRun.out.find("off by more than half a texel       0 px"), std::string::npos)
        << checkedRun.out;
    expectFailure(run(cached + (dir / "x.png").string() + " --compare-reference --base cylinder"),
                  2, "traces the plane's reference");

    // The last page (the pyramid's 1 x 1 top, read before any draw) changed on disk.
    const std::vector<std::string> files = filesIn(cache);
    ASSERT_EQ(files.size(), 1u);
    const auto pyramid = cache / files[0];
    std::vector<std::uint8_t> bytes = test::readBytes(pyramid);
    bytes[bytes.size() - 1] ^= 0x20;
    test::writeBytes(pyramid, bytes);
    expectFailure(run(cached + (dir / "corrupt.png").string()), 2, pyramid.string() + ": page ");
    EXPECT_FALSE(std::filesystem::exists(dir / "corrupt.png"));
    bytes.resize(bytes.size() - 1000);
    test::writeBytes(pyramid, bytes);
    expectFailure(run(cached + (dir / "cut.png").string()), 2, "(truncated)");
}

}  // namespace
