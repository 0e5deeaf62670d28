// microrelief-viewer in a real window on an X server (CTest runs it under xvfb-run), driven
// the way a script would: --frames N --screenshot FILE --print-command. Each view's
// screenshot must match what microrelief-render draws headless (EGL) when given the
// command line the viewer prints for it, so "copy as command" reproduces the view.
// Skips where there is no X display.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

// Both programs run the same shaders on Mesa's llvmpipe (the viewer through GLX on Xvfb,
// the renderer through EGL, held to software below), the same rays (the command line
// carries every number exactly) and the same arithmetic, so the pictures are expected
// to be identical, and are: max 0 for every view here. The margins allow only what two
// front ends of one driver might do differently without being wrong, a level of
// rounding in a colour channel (max), on at most a few percent of the channels (mean,
// in levels of 255). A ray that hits on one side and misses on the other, a camera off
// by a rounding of a printed number, a different size, light or map all fail it.
constexpr int kMaxChannelDifference = 1;
constexpr double kMeanChannelDifference = 0.05;

// glvnd's description of Mesa's EGL (Debian's libegl-mesa0).
constexpr const char* kMesaEglVendor = "/usr/share/glvnd/egl_vendor.d/50_mesa.json";

using test::difference;
using test::Difference;
using test::Image;
using test::readImage;

std::string keepForInspection(const std::string& name, const Image& actual, const Image& expected) {
    return test::keepForInspection("viewer-failures", name, actual, expected);
}

struct RunResult {
    int status = -1;
    std::string out, err;
};

class ViewerUnderX : public ::testing::Test {
protected:
    void SetUp() override {
        const char* display = std::getenv("DISPLAY");
        if (!display || !*display) GTEST_SKIP() << "no X display (CTest runs this under xvfb-run)";
    }

    RunResult run(const std::string& command) {
        const std::string line =
            command + " > " + (dir / "stdout").string() + " 2> " + (dir / "stderr").string();
        const int raw = std::system(line.c_str());
        std::ifstream out(dir / "stdout"), err(dir / "stderr");
        std::ostringstream o, e;
        o << out.rdbuf();
        e << err.rdbuf();
        return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, o.str(), e.str()};
    }

    // One frame's --window-screenshot of a width x height window and --screenshot of its 3D
    // view (which compareWithRender holds to microrelief-render's picture); empty images
    // where either is missing or of another size.
    struct WindowPictures {
        Image window, view;
    };
    WindowPictures windowScreenshot(const std::string& name, int width, int height) {
        const auto file = dir / (name + "-window.png");
        const std::string size = std::to_string(width) + "x" + std::to_string(height);
        WindowPictures pictures{{},
                                compareWithRender(name, "--size " + size,
                                                  "--window-screenshot " + file.string(), "", 1)};
        pictures.window = readImage(file);
        for (const Image* image : {&pictures.window, &pictures.view}) {
            EXPECT_EQ(image->width, width) << name;
            EXPECT_EQ(image->height, height) << name;
            if (image->width != width || image->height != height) return {};
        }
        return pictures;
    }

    // Renders `flags` in the viewer, then the command line it prints with
    // microrelief-render, and compares the two pictures. Returns the viewer's picture.
    // `renderExtra` goes to microrelief-render after the printed command (a map saved by
    // the viewer in place of the one it opened). The viewer draws `frames` frames.
    Image compareWithRender(const std::string& name, const std::string& flags,
                            const std::string& extra = "", const std::string& renderExtra = "",
                            int frames = 3) {
        const auto viewerPicture = dir / (name + "-viewer.png"),
                   renderPicture = dir / (name + "-render.png");
        // The renderer's shaders: the build tree's copy, which microrelief-render reads too.
        const RunResult viewer =
            run(std::string(MICRORELIEF_VIEWER_EXE) + " --shader-dir " + MICRORELIEF_SHADERS +
                " --frames " + std::to_string(frames) + " --print-command --screenshot " +
                viewerPicture.string() + " " + flags + " " + extra);
        EXPECT_EQ(viewer.status, 0) << viewer.err;
        const std::string printed = lastLine(viewer.out);
        EXPECT_EQ(printed.rfind("microrelief-render ", 0), 0u) << viewer.out;
        if (viewer.status != 0 || printed.rfind("microrelief-render ", 0) != 0) return {};

        // Software EGL for the renderer, as the viewer on Xvfb has: a GPU's own EGL may
        // round differently (not wrongly), which is not what this test is about.
        const std::string software =
            std::filesystem::exists(kMesaEglVendor)
                ? std::string("__EGL_VENDOR_LIBRARY_FILENAMES=") + kMesaEglVendor + " "
                : std::string();
        const std::string command = software + "LIBGL_ALWAYS_SOFTWARE=1 " + MICRORELIEF_RENDER_EXE +
                                    printed.substr(std::string("microrelief-render").size());
        const RunResult render =
            run(command + " " + renderExtra + " --quiet --out " + renderPicture.string());
        EXPECT_EQ(render.status, 0) << command << "\n" << render.err;
        const Image actual = readImage(viewerPicture), expected = readImage(renderPicture);
        EXPECT_GT(actual.width, 0) << name;
        EXPECT_EQ(actual.width, expected.width) << name;
        EXPECT_EQ(actual.height, expected.height) << name;
        if (actual.width == 0 || actual.width != expected.width || actual.height != expected.height)
            return actual;

        const Difference d = difference(actual, expected, 0, 0, actual.width, actual.height);
        std::printf("    %-10s max %3d, mean %.4f levels\n", name.c_str(), d.max, d.mean);
        if (d.max > kMaxChannelDifference || d.mean > kMeanChannelDifference) {
            ADD_FAILURE() << name
                          << ": the viewer's picture differs from microrelief-render's (max "
                          << d.max << ", mean " << d.mean << " levels); see "
                          << keepForInspection(name, actual, expected)
                          << "\n  render command: " << command;
        }
        return actual;
    }

    static std::string lastLine(const std::string& text) {
        std::istringstream in(text);
        std::string line, last;
        while (std::getline(in, line)) {
            if (!line.empty()) last = line;
        }
        return last;
    }

    test::ScratchDir dir;
};

TEST_F(ViewerUnderX, DefaultViewMatchesTheRenderer) {
    const Image picture = compareWithRender("default", "--size 200x150");
    EXPECT_EQ(picture.width, 200);
    EXPECT_EQ(picture.height, 150);
}

// A map wider than the GL's textures (16384 on llvmpipe) is read through pages within
// --memory and refined over frames: --frames 3 draws on until the view wants no page, and
// the screenshot is microrelief-render's exact picture. With a pool smaller than the view
// reads at once the view stays coarse in parts, and the viewer says so. (--frames 1: the
// first frame alone draws the coarse bounds; the viewer draws on.)
TEST_F(ViewerUnderX, AMapWiderThanTheGlsTexturesRefinesToTheExactPicture) {
    const auto file = dir / "wide.png";
    test::writeWideWavesMap(file);
    const std::string view = "--size 160x120 --height " + file.string() +
                             " --eye 0.02,0.004,0.01 --target 0,0,0 --height-scale 0.002 ";
    const Image picture = compareWithRender("paged", view + "--memory 64", "", "", 1);
    EXPECT_EQ(picture.width, 160);

    const RunResult small = run(std::string(MICRORELIEF_VIEWER_EXE) + " --shader-dir " +
                                MICRORELIEF_SHADERS + " --frames 3 --screenshot " +
                                (dir / "coarse.png").string() + " " + view + "--memory 1");
    EXPECT_EQ(small.status, 0) << small.err;
    EXPECT_NE(small.out.find("raise --memory"), std::string::npos) << small.out;
    EXPECT_NE(small.err.find("coarse.png: not the exact picture"), std::string::npos) << small.err;
    const RunResult sculpt =
        run(std::string(MICRORELIEF_VIEWER_EXE) + " --frames 1 --sculpt " + view + "--memory 4");
    EXPECT_EQ(sculpt.status, 2);
    EXPECT_NE(sculpt.err.find("read through pages"), std::string::npos) << sculpt.err;
}

TEST_F(ViewerUnderX, ScreenshotIsAtSizeWhateverTheWindow) {
    // Larger than the X screen (xvfb-run's 1280x1024): the window shrinks to fit, the
    // 3D view is still rendered at exactly --size.
    const Image picture = compareWithRender("oversize", "--size 1400x120 --fovy 20");
    EXPECT_EQ(picture.width, 1400);
    EXPECT_EQ(picture.height, 120);
}

TEST_F(ViewerUnderX, GrazingViewFromInsideTheBox) {
    // A non-square map, 16-bit, with the eye inside the relief's bounding box, just
    // above the surface, looking almost level: the hardest rays of the method.
    const HeightMap map = synth::valueNoise(96, 64, 12.0, 3, 7);
    test::writeMap(dir / "noise.png", map, PixelType::UInt16);
    const double scale = 0.2, x = 0.2, z = -0.1;
    const double u = x / 1.0 + 0.5, v = z / (64.0 / 96.0) + 0.5;
    const double y = scale * map.surface(u * map.width, v * map.height) + 0.01;
    std::ostringstream flags;
    flags << "--height " << (dir / "noise.png").string() << " --height-scale " << scale
          << " --eye=" << x << ',' << y << ',' << z << " --target=-0.4," << y - 0.03
          << ",0.15 --fovy 60 --size 160x120";
    compareWithRender("grazing", flags.str());
}

TEST_F(ViewerUnderX, DebugViewLightAndNormalisation) {
    HeightMap map = synth::cobbles(80, 48, 3);
    for (float& h : map.samples) h = h * 3.0f - 1.0f;  // negative values: needs --normalize
    test::writeMap(dir / "signed.exr", map, PixelType::Float);
    const std::string map_ = "--height " + (dir / "signed.exr").string() + " --normalize ";
    compareWithRender("iterations", map_ + "--view iterations --size 120x90");
    compareWithRender("lit", map_ + "--light=0.3,0.2,-1 --eye=-0.6,-0.5,0.4 --size 120x90");
}

TEST_F(ViewerUnderX, PeerMethodsAndTheirKnobsCarryOver) {
    compareWithRender("pom", "--method pom --steps 24 --size 120x90 --background 0.5,0.2,0.1");
    compareWithRender("pixelerror", "--pixel-error 1.5 --view level --size 120x90");
}

TEST_F(ViewerUnderX, CurvedBasesCarryOver) {
    compareWithRender("cylinder",
                      "--base cylinder --radius 0.25 --length 0.9 --eye 0.7,0.4,0.9 "
                      "--target 0,0,0 --size 120x90");
    compareWithRender("ellipsoid",
                      "--base ellipsoid --radii=0.5,0.3,0.4 --method maxmip "
                      "--eye=-0.5,0.6,0.9 --target 0,0,0 --size 120x90");
}

TEST_F(ViewerUnderX, BiquadraticCarriesOver) {
    // A close-up where the two last levels differ: the viewer must trace the one it prints.
    const std::string closeUp = "--eye 0.05,0.12,0.05 --target 0,0,-0.05 --size 120x90";
    const Image smooth = compareWithRender("biquadratic", closeUp + " --interpolation biquadratic");
    const Image faceted = compareWithRender("bilinear", closeUp);
    ASSERT_EQ(smooth.width, faceted.width);
    const Difference d = difference(smooth, faceted, 0, 0, smooth.width, smooth.height);
    EXPECT_GT(d.mean, 1.0) << "the biquadratic close-up looks like the bilinear one";
}

TEST_F(ViewerUnderX, StraightDownWithTheSpecsOrientation) {
    compareWithRender("topdown", "--eye 0,1.6,0 --target 0,0,0 --up 0,0,-1 --size 96x96");
}

// Asked for one frame, the window's picture shows the panel: it was laid out in a frame
// before the first drawn one (ImGui hides a new window in the frame that sizes it).
TEST_F(ViewerUnderX, WindowScreenshotShowsThePanelOverTheView) {
    const auto [shot, view] = windowScreenshot("window", 640, 400);
    ASSERT_EQ(shot.width, 640);
    // The panel sits at the top left; the right of the window is the 3D view, untouched.
    EXPECT_GT(difference(shot, view, 20, 20, 300, 200).mean, 10.0) << "no panel at the top left";
    const Difference right = difference(shot, view, 560, 0, 640, 400);
    EXPECT_LE(right.max, 0) << "the view around the panel must be the 3D view as rendered";
}

// A window too narrow for the panel beside the view starts with the panel folded to its
// title bar: below the bar the window is the 3D view as rendered.
TEST_F(ViewerUnderX, ANarrowWindowStartsWithThePanelFolded) {
    const auto [shot, view] = windowScreenshot("narrow", 320, 240);
    ASSERT_EQ(shot.width, 320);
    // The bar: the panel's margin (8) and one line of title (about 19 pixels at scale 1).
    EXPECT_GT(difference(shot, view, 8, 8, 200, 26).mean, 10.0) << "no title bar";
    EXPECT_LE(difference(shot, view, 0, 40, 320, 240).max, 0) << "the panel hides the view";
}

// Sculpting (issue 16): strokes of every brush, drawn by a script before the first frame,
// then the map saved; microrelief-render given the saved map and the printed view draws
// the viewer's picture, so what the viewer traces after the edits is the edited map,
// exactly (and the saved file is that map).
TEST_F(ViewerUnderX, SculptedReliefRendersAsItsSavedMap) {
    const auto saved = dir / "sculpted.exr";
    const std::string strokes =
        "--brush-radius 14 --brush-strength 0.15 --stroke raise,0.2,0.3,0.8,0.6 "
        "--stroke lower,0.3,0.8,0.7,0.2 --stroke smooth,0.1,0.5,0.9,0.5 "
        "--stroke flatten,0.5,0.1,0.5,0.9 --save-map " +
        saved.string();
    // The viewer keeps the bundled map's colours while it sculpts; the render is given them too.
    const Image sculpted = compareWithRender(
        "sculpted", "--size 200x150", strokes,
        "--height " + saved.string() + " --albedo " + defaultAlbedoPath().string());
    // And the edits show: the unedited map is another picture.
    const Image plain = compareWithRender("unsculpted", "--size 200x150");
    ASSERT_EQ(sculpted.width, plain.width);
    EXPECT_GT(difference(sculpted, plain, 0, 0, plain.width, plain.height).mean, 1.0);
}

// Undo returns the exact map: strokes, as many undos, and the saved map is the opened one,
// sample for sample.
TEST_F(ViewerUnderX, UndoReturnsTheOpenedMapExactly) {
    const auto saved = dir / "undone.exr";
    const RunResult r = run(std::string(MICRORELIEF_VIEWER_EXE) +
                            " --size 64x48 --brush-radius 20 --brush-strength 0.4"
                            " --stroke raise,0.1,0.1,0.9,0.9 --stroke smooth,0.9,0.1,0.1,0.9"
                            " --stroke lower,0.5,0,0.5,1 --undo 3 --save-map " +
                            saved.string());
    ASSERT_EQ(r.status, 0) << r.err;
    const HeightMap opened = loadHeightMap(defaultHeightMapPath());
    const HeightMap undone = loadHeightMap(saved);
    EXPECT_EQ(undone.samples, opened.samples);

    const auto partly = dir / "partly.exr";
    const RunResult two = run(std::string(MICRORELIEF_VIEWER_EXE) +
                              " --size 64x48 --brush-radius 20 --brush-strength 0.4"
                              " --stroke raise,0.1,0.1,0.9,0.9 --stroke lower,0.5,0,0.5,1 --undo 1"
                              " --save-map " +
                              partly.string());
    ASSERT_EQ(two.status, 0) << two.err;
    EXPECT_NE(loadHeightMap(partly).samples, opened.samples);  // one stroke is left
}

// A DEM sculpted and saved with --save-map FILE.tif (issue 47: the save dropped its
// georeference) is a GeoTIFF on the same grid, in the same coordinate system, its heights
// the edited map's in metres; saved as .exr it keeps the samples and says, one warning line
// on stderr, that the ground is not kept.
TEST_F(ViewerUnderX, ASculptedDemIsSavedOnItsGround) {
    if (!readsGeoreferencedMaps()) GTEST_SKIP() << "the io component was built without GDAL";
    // The DEM: a GeoTIFF of 30 x 20 m samples in metres (saveElevationModel writes it as
    // the viewer would).
    HeightMap heights = synth::valueNoise(96, 64, 4, 2, 3);
    Georeference geo;
    geo.sampleWidthMetres = 30.0;
    geo.sampleHeightMetres = 20.0;
    geo.lowestMetres = 100.0;
    geo.highestMetres = 900.0;
    GroundPlacement placement;
    placement.geotransform = {500000.0, 30.0, 0.0, 5000000.0, 0.0, -20.0};
    saveElevationModel(dir / "dem.tif", heights, geo, placement);
    const HeightMapFile dem = loadHeightMapFile(dir / "dem.tif");
    ASSERT_TRUE(dem.georeference);

    const std::string sculpt = std::string(MICRORELIEF_VIEWER_EXE) + " --size 64x48 --height " +
                               (dir / "dem.tif").string() +
                               " --brush-radius 12 --brush-strength 0.3"
                               " --stroke raise,0.2,0.5,0.8,0.5 --save-map ";
    const RunResult tif = run(sculpt + (dir / "edited.tif").string());
    ASSERT_EQ(tif.status, 0) << tif.err;
    EXPECT_EQ(tif.err.find("warning"), std::string::npos) << tif.err;
    const RunResult exr = run(sculpt + (dir / "edited.exr").string());
    ASSERT_EQ(exr.status, 0) << exr.err;
    EXPECT_NE(exr.err.find("microrelief-viewer: warning: " + (dir / "edited.exr").string() +
                           ": saved without the elevation model's georeference"),
              std::string::npos)
        << exr.err;

    const HeightMapFile saved = loadHeightMapFile(dir / "edited.tif");
    EXPECT_EQ(saved.placement, dem.placement);
    ASSERT_TRUE(saved.georeference);
    EXPECT_EQ(saved.georeference->sampleWidthMetres, 30.0);
    EXPECT_EQ(saved.georeference->sampleHeightMetres, 20.0);
    // The same strokes' samples (the .exr: map values of the DEM's range), in metres.
    const HeightMap edited = loadHeightMap(dir / "edited.exr");
    ASSERT_EQ(saved.map.samples.size(), edited.samples.size());
    EXPECT_NE(edited.samples, dem.map.samples);  // the stroke raised it
    const Georeference& before = *dem.georeference;
    const Georeference& after = *saved.georeference;
    double worst = 0.0;
    for (std::size_t k = 0; k < edited.samples.size(); ++k) {
        const double expected =
            before.lowestMetres + edited.samples[k] * (before.highestMetres - before.lowestMetres);
        const double read =
            after.lowestMetres + saved.map.samples[k] * (after.highestMetres - after.lowestMetres);
        worst = std::max(worst, std::abs(read - expected));
    }
    EXPECT_LT(worst, 1e-3);  // metres: Float32 metres and the map's float [0, 1]
}

// A save that fails leaves the file that was there as it was: a map raised above 1, which a
// 16-bit PNG cannot hold, is refused (exit 2, one line naming the file) before anything is
// written.
TEST_F(ViewerUnderX, AFailedSaveLeavesTheOldFileUntouched) {
    const auto file = dir / "keep.png";
    test::writeBytes(file, {'o', 'l', 'd'});
    const RunResult r = run(std::string(MICRORELIEF_VIEWER_EXE) +
                            " --size 64x48 --brush-radius 10 --brush-strength 2"
                            " --stroke raise,0.5,0.5,0.6,0.5 --save-map " +
                            file.string());
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("keep.png"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("save as .exr"), std::string::npos) << r.err;
    EXPECT_EQ(test::readBytes(file), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

// A full disk (a file size limit below each output, as tests/cli/FullDiskCliTest.cpp has
// it): --save-map onto an earlier save of the map fails with one line and exit 1 and leaves
// that file as it was, byte for byte; so does --screenshot; no temporary is left. (The map
// the viewer opened is never written: ViewerCli.OutputsThatAreInputsAreRefused.)
TEST_F(ViewerUnderX, AFullDiskLeavesTheMapAndTheScreenshotAsTheyWere) {
    const auto map = dir / "map.png", saved = dir / "saved.png", shot = dir / "shot.bmp";
    test::writeMap(map, synth::valueNoise(128, 128, 4, 2, 7), PixelType::UInt16);
    std::filesystem::copy_file(map, saved);
    const std::vector<std::uint8_t> original = test::readBytes(saved);
    const std::string viewer = std::string(MICRORELIEF_VIEWER_EXE) + " --size 64x48 ";
    const test::RunResult save = test::runCommandWithFileSizeLimit(
        viewer + "--height " + map.string() + " --stroke raise,0.2,0.5,0.8,0.5 --save-map " +
            saved.string(),
        original.size() / 2);
    test::expectOneLineFailure(save, "microrelief-viewer", 1,
                               saved.string() + ": cannot write (File too large)");
    EXPECT_EQ(test::readBytes(saved), original);

    // 64 x 48 RGB as a BMP: 9270 bytes.
    const std::vector<std::uint8_t> old = {'o', 'l', 'd'};
    test::writeBytes(shot, old);
    const test::RunResult screenshot =
        test::runCommandWithFileSizeLimit(viewer + "--screenshot " + shot.string(), 4096);
    test::expectOneLineFailure(screenshot, "microrelief-viewer", 1,
                               shot.string() + ": cannot write (File too large)");
    EXPECT_EQ(test::readBytes(shot), old);
    EXPECT_EQ(test::hiddenFilesIn(dir.path()), std::vector<std::string>{});
    // The premise: without the limit both are written.
    EXPECT_EQ(run(viewer + "--height " + map.string() + " --save-map " + saved.string() +
                  " --screenshot " + shot.string())
                  .status,
              0);
    EXPECT_GT(std::filesystem::file_size(shot), 4096u);
}

// An animated relief: the viewer's last frame is microrelief-render's at the time the
// viewer prints (a script steps 1/30 s a frame from --time).
TEST_F(ViewerUnderX, AnimatedReliefCarriesOverAtItsTime) {
    compareWithRender("waves", "--animate waves --time 1.25 --size 160x120");
    compareWithRender("flood", "--animate flood --time 3 --size 160x120 --eye 0.5,0.4,0.6");
    // The first frame is drawn at --time itself; the third two steps on.
    for (const auto& [frames, time] :
         {std::pair{"1", " --time=1.25 "}, {"3", " --time=1.3166666666666669 "}}) {
        const RunResult r =
            run(std::string(MICRORELIEF_VIEWER_EXE) + " --animate waves --time 1.25" +
                " --size 64x48 --print-command --frames " + frames);
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(lastLine(r.out).find(time), std::string::npos) << frames << ": " << r.out;
    }
}

// Input a person gives faster than a slow frame (llvmpipe: about 200 ms while sculpting),
// through the X server (xdotool, XTEST): a quick Ctrl+Z (Ctrl up again before the frame
// reads it) undoes; Esc with edits not saved warns and keeps the window; undone back to
// the map opened, the map is not edited and Esc quits. Each step waits for the viewer's
// line (-v prints one as a stroke ends), up to 60 s; the whole script is killed at 180 s.
TEST_F(ViewerUnderX, QuickKeysTakeEffectAndEscWarnsOfUnsavedEdits) {
    if (std::system("command -v xdotool > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "xdotool is not installed (scripts/setup.sh installs it)";
    const auto log = dir / "viewer.log";
    const std::string script =
        "log='" + log.string() + "'\nviewer_exe='" + MICRORELIEF_VIEWER_EXE + "'\n" + R"sh(
set -u
"$viewer_exe" -v --size 800x600 --no-panel > "$log" 2>&1 &
viewer=$!
trap 'kill $viewer 2> /dev/null' EXIT
# Waits until the log holds $2 lines with $1 (or 60 s).
waitfor() {
    for i in $(seq 300); do
        [ "$(grep -c -- "$1" "$log")" -ge "${2:-1}" ] && return 0
        sleep 0.2
    done
    echo "timed out waiting for '$1'"
    exit 1
}
timeout 60 xdotool search --sync --onlyvisible --name microrelief-viewer > /dev/null || { echo "no window"; exit 1; }
waitfor 'GL: '
sleep 1  # the first frames drawn
xdotool mousemove 400 300 key b
waitfor 'sculpting: on'
xdotool mousemove 370 300 mousedown 1; sleep 0.5; xdotool mousemove 400 310; sleep 0.5
xdotool mousemove 430 320; sleep 0.5; xdotool mouseup 1
waitfor 'stroke drawn: 1 to undo'
xdotool key Escape
waitfor 'edits not saved'
xdotool key --delay 0 ctrl+z
waitfor 'undone: 0 stroke'
xdotool key Escape
for i in $(seq 150); do kill -0 $viewer 2> /dev/null || break; sleep 0.2; done
kill -0 $viewer 2> /dev/null && { echo "still running after the last Esc"; exit 1; }
wait $viewer
echo "exit $?"
)sh";
    const auto file = dir / "drive.sh";
    std::ofstream(file) << script;
    const RunResult r = run("timeout 180 bash " + file.string());
    const std::string text = test::readText(log);
    EXPECT_EQ(r.status, 0) << r.out << r.err << "\n" << text;
    EXPECT_NE(r.out.find("exit 0"), std::string::npos) << r.out << "\n" << text;
}

}  // namespace
