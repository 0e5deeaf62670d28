// The parts of microrelief-viewer that need no window: the camera controller (never
// flips, keeps the command line's camera exactly until the first rotation, reaches
// grazing angles and the inside of the relief's box), "copy as command" read back by
// the same flags, picking, the shader folder watch, the sculpting's history (what
// counts as an edit, what undo takes back) and scripted dabs, the names of the files the
// viewer writes, how a paged map's view is refined over frames, and the key bindings.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <fstream>
#include <sstream>
#include <thread>

#include "CameraController.h"
#include "InputBindings.h"
#include "MapFile.h"
#include "OutputFiles.h"
#include "PageRefiner.h"
#include "ShaderWatcher.h"
#include "StrokeHistory.h"
#include "TestSupport.h"
#include "ViewerOptions.h"
#include "microrelief/core/Error.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/ReliefFiles.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

Camera startCamera() {
    Camera camera;
    camera.eye = {0.8, 0.5, 0.85};
    camera.target = {0.0, -0.03, 0.0};
    camera.up = {0.0, 1.0, 0.0};
    camera.fovyDegrees = 45.0;
    return camera;
}

// The camera's screen-up vector, as the renderer resolves it.
glm::dvec3 screenUp(const Camera& camera) {
    return glm::normalize(resolveCamera(camera, 64, 64, 1.0).up);
}

TEST(CameraController, KeepsTheStartCameraExactlyUntilTheFirstRotation) {
    const Camera start = startCamera();
    CameraController controller(start);
    EXPECT_EQ(controller.camera().eye, start.eye);
    EXPECT_EQ(controller.camera().target, start.target);
    EXPECT_EQ(controller.camera().up, start.up);
    controller.orbit(30.0, -10.0);
    controller.reset();
    EXPECT_EQ(controller.camera().eye, start.eye);
    EXPECT_EQ(controller.camera().target, start.target);
}

TEST(CameraController, OrbitNeverFlipsAtThePoles) {
    CameraController controller(startCamera());
    const double distance = controller.distance();
    // Drag far past both poles, in steps, with some sideways motion: the pitch clamps,
    // the screen's up keeps pointing up (no flip) and the distance stays.
    for (double dy : {40.0, -40.0}) {
        for (int step = 0; step < 200; ++step) {
            controller.orbit(3.0, dy);
            const Camera& c = controller.camera();
            ASSERT_LE(std::abs(controller.pitchDegrees()),
                      CameraController::kPitchLimitDegrees + 1e-9);
            ASSERT_GT(glm::dot(screenUp(c), glm::dvec3(0, 1, 0)), 0.0)
                << "flipped at step " << step;
            ASSERT_NEAR(controller.distance(), distance, 1e-9);
            ASSERT_NO_THROW(resolveCamera(c, 64, 64, 1.0));
        }
        EXPECT_NEAR(std::abs(controller.pitchDegrees()), CameraController::kPitchLimitDegrees,
                    1e-6);
    }
}

TEST(CameraController, DragDirectionsFollowTheConventions) {
    CameraController controller(startCamera());
    const double pitch = controller.pitchDegrees();
    controller.orbit(0.0, 20.0);  // drag down: the eye rises, the view looks further down
    EXPECT_LT(controller.pitchDegrees(), pitch);
    const glm::dvec3 eye = controller.camera().eye;
    const glm::dvec3 right = glm::normalize(resolveCamera(controller.camera(), 64, 64, 1.0).right);
    controller.orbit(20.0, 0.0);  // drag right: the relief turns right, the eye moves left
    EXPECT_LT(glm::dot(controller.camera().eye - eye, right), 0.0);
}

TEST(CameraController, StartingStraightDownKeepsTheScreenOrientation) {
    // The top-down view of the spec (up = -z): the first rotation must not spin it.
    Camera top;
    top.eye = {0.0, 1.5, 0.0};
    top.target = {0.0, 0.0, 0.0};
    top.up = {0.0, 0.0, -1.0};
    CameraController controller(top);
    controller.orbit(0.0, -1.0);  // a nudge away from the pole
    EXPECT_GT(glm::dot(screenUp(controller.camera()), glm::dvec3(0, 0, -1)), 0.99);
}

TEST(CameraController, ZoomPassesThroughTheTargetIntoTheBox) {
    CameraController controller(startCamera());
    for (int step = 0; step < 200; ++step) controller.zoom(1.0);
    EXPECT_GE(controller.distance(), CameraController::kMinDistance * 0.999);
    // It went past the old target, on along the view direction.
    const glm::dvec3 view = glm::normalize(startCamera().target - startCamera().eye);
    EXPECT_GT(glm::dot(controller.camera().eye - startCamera().target, view), 0.5);
}

TEST(CameraController, FlyReachesGrazingAnglesInsideTheBox) {
    CameraController controller(startCamera());
    controller.look(0.0, -85.0);  // drag up: look up, to about the horizon
    for (int step = 0; step < 45; ++step) controller.fly({0.0, -0.01, 0.0});  // down
    controller.fly({0.0, 0.0, 0.6});
    const Camera& c = controller.camera();
    // Inside the box of a map scaled by 0.1, looking nearly along the surface.
    EXPECT_LT(c.eye.y, 0.1);
    EXPECT_LT(std::abs(c.eye.x), 0.5);
    EXPECT_LT(std::abs(c.eye.z), 0.5);
    EXPECT_LT(std::abs(controller.pitchDegrees()), 10.0);
    EXPECT_NO_THROW(resolveCamera(c, 64, 64, 1.0));
}

TEST(CameraController, LookTurnsAboutTheEye) {
    CameraController controller(startCamera());
    const glm::dvec3 eye = controller.camera().eye;
    controller.look(50.0, -30.0);
    EXPECT_EQ(controller.camera().eye, eye);
    controller.setTarget({0.1, 0.0, 0.1});
    EXPECT_EQ(controller.camera().eye, eye);
    EXPECT_EQ(controller.camera().target, glm::dvec3(0.1, 0.0, 0.1));
}

// --- "copy as command": what the viewer writes, the same flags read back exactly.

std::vector<std::string> splitWords(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string word; in >> word;) words.push_back(word);
    return words;
}

ViewerOptions parseWords(std::vector<std::string> words) {
    std::vector<char*> argv;
    for (std::string& word : words) argv.push_back(word.data());
    ParseResult<ViewerOptions> parsed =
        parseViewerOptions(static_cast<int>(argv.size()), argv.data());
    EXPECT_TRUE(parsed.options) << parsed.message;
    return parsed.options ? *parsed.options : ViewerOptions{};
}

TEST(CopyAsCommand, TheRenderCommandLineReadsBackExactly) {
    SceneOptions scene;
    scene.job.map.file = "/maps/rock.exr";
    scene.job.map.load.channel = 2;
    scene.job.map.load.normalize = true;
    scene.job.heightScale = 0.0734f;
    // Values a drag produces: no short decimal form.
    scene.job.camera.eye = {0.1 + 1.0 / 3.0, -std::sqrt(2.0) / 7.0, 1e-7 * M_PI};
    scene.job.camera.target = {-0.25, 0.0, std::nextafter(0.1, 1.0)};
    scene.job.camera.up = {0.0, 1.0, 0.0};
    scene.job.camera.fovyDegrees = 37.123456789012345;
    scene.job.width = 333;
    scene.job.height = 217;
    scene.job.shading.lightDirection = {std::cos(1.1f), 0.3f, -std::sin(1.1f)};
    scene.job.shading.view = DebugView::Level;
    scene.job.background = {0.3f, 0.01f, 1.0f / 3.0f};
    scene.job.method.method = Method::Relief;
    scene.job.method.steps = 23;
    scene.job.method.pixelError = 0.7f;
    scene.job.animation = "ripples";
    scene.job.time = 1.0 / 3.0 + 40.0;  // a time the animation reached: no short form

    const std::string line = renderCommandLine(scene, "microrelief-viewer");
    const SceneOptions back = parseWords(splitWords(line)).scene;
    EXPECT_EQ(back.job.map.file, scene.job.map.file);
    EXPECT_EQ(back.job.map.load.channel, 2);
    EXPECT_TRUE(back.job.map.load.normalize);
    EXPECT_EQ(back.job.heightScale, scene.job.heightScale);
    EXPECT_EQ(back.job.camera.eye, scene.job.camera.eye) << line;
    EXPECT_EQ(back.job.camera.target, scene.job.camera.target) << line;
    EXPECT_EQ(back.job.camera.up, scene.job.camera.up);
    EXPECT_EQ(back.job.camera.fovyDegrees, scene.job.camera.fovyDegrees) << line;
    EXPECT_EQ(back.job.width, 333);
    EXPECT_EQ(back.job.height, 217);
    EXPECT_EQ(back.job.shading.lightDirection, scene.job.shading.lightDirection) << line;
    EXPECT_EQ(back.job.shading.view, DebugView::Level);
    EXPECT_EQ(back.job.background, scene.job.background) << line;
    EXPECT_EQ(back.job.method.method, Method::Relief);
    EXPECT_EQ(back.job.method.steps, 23);
    EXPECT_EQ(back.job.animation, "ripples") << line;
    EXPECT_EQ(back.job.time, scene.job.time) << line;
    EXPECT_EQ(back.job.method.pixelError, 0.7f);
}

TEST(CopyAsCommand, DefaultsStayOffTheLineAndPathsAreQuoted) {
    SceneOptions scene;
    scene.job.map.file = "/my maps/it's.png";
    const std::string line = renderCommandLine(scene);
    EXPECT_EQ(line.rfind("microrelief-render ", 0), 0u) << line;
    EXPECT_NE(line.find("--height '/my maps/it'\\''s.png'"), std::string::npos) << line;
    EXPECT_EQ(line.find("--background"), std::string::npos) << line;
    EXPECT_EQ(line.find("--channel"), std::string::npos) << line;
    EXPECT_EQ(line.find("--steps"), std::string::npos) << line;
    for (const char* flag : {"--height-scale", "--eye", "--target", "--up", "--fovy", "--size",
                             "--light", "--method", "--view"}) {
        EXPECT_NE(line.find(flag), std::string::npos) << flag << " in " << line;
    }
}

TEST(ViewerOptions, ScreenshotImpliesOneFrame) {
    const ViewerOptions o =
        parseWords({"microrelief-viewer", "--screenshot", "a.png", "--size", "20x10"});
    EXPECT_EQ(o.frames, 1);
    EXPECT_EQ(o.scene.job.width, 20);
    ASSERT_TRUE(o.screenshot);
    EXPECT_EQ(o.screenshot->string(), "a.png");
}

// The panel's colours box: offered where turning it on draws colours (albedoPath with the
// box on), whatever it says now.
TEST(ViewerOptions, ColoursAreOfferedWhereTurningThemOnDrawsSome) {
    const auto offeredAndDrawn = [](ReliefDesc relief) {
        const bool offered = albedoOffered(relief);
        relief.albedo.kind =
            relief.albedo.file.empty() ? AlbedoSource::Kind::Default : AlbedoSource::Kind::File;
        EXPECT_EQ(offered, albedoPath(relief).has_value());
        return offered;
    };
    ReliefDesc bundled;  // the bundled map, its own colours
    EXPECT_TRUE(offeredAndDrawn(bundled));
    bundled.albedo.kind = AlbedoSource::Kind::None;  // turned off: still offered
    EXPECT_TRUE(offeredAndDrawn(bundled));
    bundled.animation = "waves";  // a field that replaces the stones
    EXPECT_FALSE(offeredAndDrawn(bundled));
    bundled.animation = "flood";  // the stones under water
    EXPECT_TRUE(offeredAndDrawn(bundled));

    ReliefDesc other;
    other.map.file = "my.png";
    EXPECT_FALSE(offeredAndDrawn(other));
    other.albedo.file = "my-colours.png";  // its own, turned off
    other.albedo.kind = AlbedoSource::Kind::None;
    EXPECT_TRUE(offeredAndDrawn(other));
}

// --- hot reload

TEST(ShaderWatcher, SeesEditsNewFilesAndRemovals) {
    test::ScratchDir dir;
    std::filesystem::create_directories(dir / "microrelief");
    std::ofstream(dir / "relief.frag") << "void main() {}\n";
    ShaderWatcher watcher(dir.path());
    const auto now = std::chrono::milliseconds(0);
    EXPECT_FALSE(watcher.changed(now));
    std::ofstream(dir / "microrelief" / "new.glsl") << "// new\n";
    EXPECT_TRUE(watcher.changed(now));
    EXPECT_FALSE(watcher.changed(now)) << "once per change";
    std::ofstream(dir / "relief.frag") << "void main() { }\n";  // one byte longer
    EXPECT_TRUE(watcher.changed(now));
    std::filesystem::remove(dir / "microrelief" / "new.glsl");
    EXPECT_TRUE(watcher.changed(now));
    EXPECT_FALSE(watcher.changed(std::chrono::hours(1))) << "looks at most once an interval";
}

// Saving an edited map: a float EXR holds every sample exactly; a 16-bit PNG the nearest of
// its 65536 levels; a map above 1 is refused for a PNG before anything is written, so the
// file that was there stays as it was; other formats are refused.
TEST(MapFile, SavesExactlyOrRefusesAndLeavesTheOldFile) {
    test::ScratchDir dir;
    HeightMap map = synth::whiteNoise(37, 21, 4);
    map.at(3, 4) = 0.0f;
    map.at(5, 6) = 1.0f;
    saveHeightMap(map, dir / "map.exr");
    EXPECT_EQ(loadHeightMap(dir / "map.exr").samples, map.samples);
    saveHeightMap(map, dir / "map.png");
    const HeightMap png = loadHeightMap(dir / "map.png");
    ASSERT_EQ(png.samples.size(), map.samples.size());
    for (std::size_t k = 0; k < map.samples.size(); ++k)
        ASSERT_NEAR(png.samples[k], map.samples[k], 0.5f / 65535.0f + 1e-7f) << k;
    EXPECT_EQ(png.at(5, 6), 1.0f);

    test::writeBytes(dir / "old.png", {'o', 'l', 'd'});
    map.at(7, 7) = 1.5f;
    try {
        saveHeightMap(map, dir / "old.png");
        ADD_FAILURE() << "a map above 1 was saved as a 16-bit PNG";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("save as .exr"), std::string::npos) << e.what();
    }
    EXPECT_EQ(test::readBytes(dir / "old.png"), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
    EXPECT_THROW(saveHeightMap(map, dir / "map.tif"), Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "map.tif"));
    saveHeightMap(map, dir / "old.exr");  // the float map keeps 1.5
    EXPECT_EQ(loadHeightMap(dir / "old.exr").at(7, 7), 1.5f);
}

// A DEM's map (loaded from one, then edited) saved as .tif is a GeoTIFF that lies where the
// map came from (io/HeightMapFile.h: saveElevationModel; tests/terrain checks the file with
// GDAL): read back, the same ground and the same map. Saved as .png or .exr it keeps the
// samples and the save says, in one line naming the file, what it did not keep. Seen red:
// the .tif refused for every map, the .png and .exr saved without a word.
TEST(MapFile, ADemsMapKeepsItsGroundAsAGeoTiffOrSaysItDoesNot) {
    if (!readsGeoreferencedMaps()) GTEST_SKIP() << "the io component was built without GDAL";
    test::ScratchDir dir;
    HeightMap map = synth::whiteNoise(37, 21, 4);
    map.at(3, 4) = 0.0f;
    map.at(5, 6) = 1.0f;
    MapGround ground;
    ground.georeference.sampleWidthMetres = 30.0;
    ground.georeference.sampleHeightMetres = 20.0;
    ground.georeference.lowestMetres = 100.0;
    ground.georeference.highestMetres = 420.0;
    ground.placement.geotransform = {500000.0, 30.0, 0.0, 5000000.0, 0.0, -20.0};
    EXPECT_EQ(saveHeightMap(map, dir / "dem.tif", ground), "");
    ReliefDesc relief;  // the map as the viewer reads it (io/ReliefFiles.h)
    relief.map.file = dir / "dem.tif";
    const ReliefFiles dem = loadReliefFiles(relief, ReliefParts::Heights);
    const std::optional<MapGround> loaded = mapGround(dem);
    ASSERT_TRUE(loaded);
    EXPECT_EQ(loaded->placement, ground.placement);
    EXPECT_EQ(loaded->georeference.lowestMetres, 100.0);
    EXPECT_EQ(loaded->georeference.highestMetres, 420.0);
    EXPECT_EQ(loaded->georeference.sampleHeightMetres, 20.0);
    ASSERT_EQ(dem.heights->samples.size(), map.samples.size());
    for (std::size_t k = 0; k < map.samples.size(); ++k)
        ASSERT_NEAR(dem.heights->samples[k], map.samples[k], 1e-6) << k;
    EXPECT_FALSE(mapGround(ReliefFiles{}));  // an image's

    for (const char* name : {"dem.png", "dem.exr"}) {
        const std::string said = saveHeightMap(*dem.heights, dir / name, loaded);
        EXPECT_NE(said.find(std::string(name) + ": saved without the elevation model's "
                                                "georeference"),
                  std::string::npos)
            << said;
        EXPECT_NE(said.find("save as .tif to keep it"), std::string::npos) << said;
        EXPECT_EQ(said.find('\n'), std::string::npos) << said;
        EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
    }
    EXPECT_EQ(saveHeightMap(map, dir / "image.exr"), "");  // an image's map loses nothing
    try {
        checkMapSave(dir / "image.TIFF", std::nullopt);
        ADD_FAILURE() << "an image's map was let be saved as a GeoTIFF";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("image.TIFF: a map is saved as a GeoTIFF only where "
                                             "it came from an elevation model"),
                  std::string::npos)
            << e.what();
    }
}

// The map's edit states (StrokeHistory.h), as the quit and open warnings read them: a
// stroke that changed nothing is no state; undoing back to the state saved is not an edit,
// and undoing past it is one again; another map forgets the strokes. Seen red: with
// strokeChanged counting every dab (no once-per-stroke), and with edited() comparing to
// "no strokes" instead of the state saved.
TEST(StrokeHistory, AnEditIsADifferenceFromTheStateSaved) {
    StrokeHistory history;
    EXPECT_FALSE(history.edited());
    history.startStroke();
    EXPECT_TRUE(history.strokeActive());
    EXPECT_FALSE(history.endStroke()) << "a stroke whose dabs changed nothing";
    EXPECT_FALSE(history.strokeActive());
    EXPECT_FALSE(history.edited());

    history.startStroke();  // stroke 1: three dabs, one state
    for (int dab = 0; dab < 3; ++dab) history.strokeChanged();
    EXPECT_TRUE(history.endStroke());
    EXPECT_TRUE(history.edited());
    history.saved();
    EXPECT_FALSE(history.edited());

    history.startStroke();  // stroke 2, after the save
    history.strokeChanged();
    history.strokeChanged();
    history.endStroke();
    EXPECT_TRUE(history.edited());
    history.undone();  // back to the state saved: one undo takes the whole stroke
    EXPECT_FALSE(history.edited());
    history.undone();  // before it: unsaved again
    EXPECT_TRUE(history.edited());
    history.undone();  // nothing more to take back
    EXPECT_TRUE(history.edited());

    history.clear();  // another map opened
    EXPECT_FALSE(history.edited());
    history.startStroke();
    history.strokeChanged();
    history.endStroke();
    EXPECT_TRUE(history.edited()) << "a new stroke differs from the map opened";
}

// Ctrl swaps raise and lower only, and every dab of a stroke flattens towards one level.
TEST(StrokeHistory, TheDabsBrushInvertsRaiseAndLowerOnly) {
    Brush brush;
    brush.radius = 5.0;
    const struct {
        BrushMode mode;
        bool invert;
        BrushMode painted;
    } cases[] = {{BrushMode::Raise, false, BrushMode::Raise},
                 {BrushMode::Raise, true, BrushMode::Lower},
                 {BrushMode::Lower, true, BrushMode::Raise},
                 {BrushMode::Smooth, true, BrushMode::Smooth},
                 {BrushMode::Flatten, true, BrushMode::Flatten}};
    for (const auto& c : cases) {
        brush.mode = c.mode;
        const Brush painted = strokeBrush(brush, 0.25f, c.invert);
        EXPECT_EQ(painted.mode, c.painted) << brushModeName(c.mode) << " invert " << c.invert;
        EXPECT_EQ(painted.level, 0.25f);
        EXPECT_EQ(painted.radius, 5.0);
    }
}

// A --stroke's dabs: from its start to its end in map texels, at most a quarter of the
// radius apart; a stroke of no length is one dab.
TEST(StrokeHistory, ScriptedDabsFallAQuarterOfTheRadiusApart) {
    ScriptedStroke stroke;
    stroke.from = {0.25, 0.5};
    stroke.to = {0.75, 0.5};
    const std::vector<glm::dvec2> dabs = scriptedDabs(stroke, {64.0, 32.0}, 8.0);
    ASSERT_EQ(dabs.size(), 17u);  // 32 texels in steps of 2
    EXPECT_EQ(dabs.front(), glm::dvec2(16.0, 16.0));
    EXPECT_EQ(dabs.back(), glm::dvec2(48.0, 16.0));
    for (std::size_t k = 1; k < dabs.size(); ++k)
        EXPECT_LE(glm::length(dabs[k] - dabs[k - 1]), 2.0 + 1e-12) << k;
    stroke.to = stroke.from;
    EXPECT_EQ(scriptedDabs(stroke, {64.0, 32.0}, 8.0), (std::vector<glm::dvec2>{{16.0, 16.0}}));
}

// A screenshot never writes over a file there (a second P within the same second gets -2,
// then -3); an edited map saves beside the others in out/, as a GeoTIFF where it is a DEM's.
// Seen red: with one try at -2 instead of counting on (the third over the second), and
// with the .tif for every map.
TEST(OutputFiles, AScreenshotNeverOverwritesAndAnEditedMapKeepsItsGround) {
    test::ScratchDir dir;
    EXPECT_EQ(screenshotPath(dir.path(), "20260101-120000"), dir / "viewer-20260101-120000.png");
    test::writeBytes(dir / "viewer-20260101-120000.png", {'p'});
    EXPECT_EQ(screenshotPath(dir.path(), "20260101-120000"),
              dir / "viewer-20260101-120000-2.png");
    test::writeBytes(dir / "viewer-20260101-120000-2.png", {'p'});
    EXPECT_EQ(screenshotPath(dir.path(), "20260101-120000"),
              dir / "viewer-20260101-120000-3.png");
    EXPECT_EQ(localTimestamp().size(), 15u) << localTimestamp();

    const std::filesystem::path out = "out";
    EXPECT_EQ(editedMapPath("maps/crater.png", false), (out / "crater-edited.exr").string());
    EXPECT_EQ(editedMapPath("/data/dem.tif", true), (out / "dem-edited.tif").string());
}

// A paged view refined over frames against a pool of `capacity` pages (a stand-in for
// PagedPyramid::loadWhatFitsKeepingRead: it loads what fits beside the pages kept): 600
// wanted pages load 256, 256 and 88 over three draws, each kept for the next load and each
// a new generation; a draw that wants none is exact. Another view forgets what was kept; a
// view that needs more than the pool holds loads what fits, then stops refining, said once.
// Seen red: with the kept pages not passed on (the third load fits a pool of 300), and with
// kPagesPerFrame ignored.
TEST(PageRefiner, AViewLoadsItsPagesOverFramesUntilExactOrThePoolIsFull) {
    std::size_t capacity = 700;
    std::vector<std::size_t> loads;
    const PageRefiner::Load load = [&](const std::vector<int>& pages,
                                       const std::vector<int>& keep) -> std::size_t {
        if (keep.size() >= capacity) return 0;
        loads.push_back(std::min(pages.size(), capacity - keep.size()));
        return loads.back();
    };
    std::vector<int> wanted(600);
    for (int k = 0; k < 600; ++k) wanted[static_cast<std::size_t>(k)] = k;

    PageRefiner refiner;
    EXPECT_EQ(refiner.progress(), "exact");
    EXPECT_FALSE(refiner.afterDraw(true, wanted, load));
    EXPECT_TRUE(refiner.refining());
    EXPECT_EQ(refiner.progress(), "refining, 600 wanted");
    EXPECT_FALSE(refiner.afterDraw(false, {wanted.begin() + 256, wanted.end()}, load));
    EXPECT_FALSE(refiner.afterDraw(false, {wanted.begin() + 512, wanted.end()}, load));
    EXPECT_EQ(loads, (std::vector<std::size_t>{256, 256, 88}));
    EXPECT_EQ(refiner.kept(), wanted);
    EXPECT_EQ(refiner.generation(), 3);
    EXPECT_FALSE(refiner.afterDraw(false, {}, load));
    EXPECT_FALSE(refiner.refining());
    EXPECT_EQ(refiner.progress(), "exact");
    EXPECT_EQ(refiner.generation(), 3) << "a draw that wanted nothing is the last";

    capacity = 300;  // another view, in a smaller pool
    EXPECT_FALSE(refiner.afterDraw(true, wanted, load));
    EXPECT_EQ(refiner.kept().size(), 256u) << "the last view's pages are not kept for this one";
    EXPECT_FALSE(refiner.afterDraw(false, {wanted.begin() + 256, wanted.end()}, load));
    EXPECT_EQ(refiner.kept().size(), 300u) << "what fits is loaded";
    EXPECT_TRUE(refiner.afterDraw(false, {wanted.begin() + 300, wanted.end()}, load));
    EXPECT_TRUE(refiner.poolTooSmall());
    EXPECT_FALSE(refiner.refining());
    EXPECT_EQ(refiner.progress(), "coarse in parts, raise --memory");
    EXPECT_FALSE(refiner.afterDraw(false, {wanted.begin() + 300, wanted.end()}, load))
        << "said once a view";
    EXPECT_EQ(refiner.generation(), 5);
    EXPECT_EQ(loads, (std::vector<std::size_t>{256, 256, 88, 256, 44}));

    refiner.noPages();
    EXPECT_FALSE(refiner.pagesWanted());
    EXPECT_FALSE(refiner.poolTooSmall());
}

// The key table (docs/viewer.md): cases as data, each named by its key. Ctrl+S saves only
// out of fly mode, where S flies back; Z and S alone do nothing. Seen red: with Ctrl+S
// saving in fly mode, and with the debug views counted from key 0.
TEST(InputBindings, KeysGiveTheCommandsTheTableNames) {
    const struct {
        const char* name;
        int key, mods;
        bool flyMode;
        ViewerCommand command;
    } cases[] = {
        {"Esc", GLFW_KEY_ESCAPE, 0, false, ViewerCommand::Quit},
        {"F", GLFW_KEY_F, 0, false, ViewerCommand::ToggleFly},
        {"R", GLFW_KEY_R, 0, false, ViewerCommand::ResetView},
        {"Tab", GLFW_KEY_TAB, 0, false, ViewerCommand::TogglePanel},
        {"P", GLFW_KEY_P, 0, false, ViewerCommand::Screenshot},
        {"F12", GLFW_KEY_F12, 0, false, ViewerCommand::Screenshot},
        {"C", GLFW_KEY_C, 0, false, ViewerCommand::CopyCommand},
        {"V", GLFW_KEY_V, 0, false, ViewerCommand::ToggleVsync},
        {"B", GLFW_KEY_B, 0, false, ViewerCommand::ToggleSculpt},
        {"Ctrl+Z", GLFW_KEY_Z, GLFW_MOD_CONTROL, false, ViewerCommand::Undo},
        {"Z", GLFW_KEY_Z, 0, false, ViewerCommand::None},
        {"Ctrl+S", GLFW_KEY_S, GLFW_MOD_CONTROL, false, ViewerCommand::SaveMap},
        {"Ctrl+S flying", GLFW_KEY_S, GLFW_MOD_CONTROL, true, ViewerCommand::None},
        {"S", GLFW_KEY_S, 0, false, ViewerCommand::None},
        {"[", GLFW_KEY_LEFT_BRACKET, 0, false, ViewerCommand::ShrinkBrush},
        {"]", GLFW_KEY_RIGHT_BRACKET, 0, false, ViewerCommand::GrowBrush},
        {"Space", GLFW_KEY_SPACE, 0, false, ViewerCommand::TogglePlay},
        {"7", GLFW_KEY_7, 0, false, ViewerCommand::None},
    };
    for (const auto& c : cases)
        EXPECT_EQ(keyCommand(c.key, c.mods, c.flyMode), c.command) << c.name;
    for (int k = 0; k < 6; ++k) {
        int view = -1;
        EXPECT_EQ(keyCommand(GLFW_KEY_1 + k, 0, false, &view), ViewerCommand::DebugView) << k + 1;
        EXPECT_EQ(view, k) << "key " << k + 1;
    }
}

// W flies forward, A left, E up; a drag with L held turns the light a quarter turn per 400
// window units and never takes it to the horizon or the zenith.
TEST(InputBindings, FlyKeysAndTheLightDrag) {
    EXPECT_EQ(flyDirection([](int key) { return key == GLFW_KEY_W || key == GLFW_KEY_A; }),
              glm::dvec3(-1.0, 0.0, 1.0));
    EXPECT_EQ(flyDirection([](int key) { return key == GLFW_KEY_E || key == GLFW_KEY_Q; }),
              glm::dvec3(0.0));
    const glm::vec3 light = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));  // 45 degrees up
    const glm::vec3 across = turnLight(light, 400.0, 0.0);  // a quarter turn about y
    EXPECT_NEAR(across.x, 0.0, 1e-6);
    EXPECT_NEAR(across.y, std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(across.z, std::sqrt(0.5), 1e-6);
    // A float's y near 1 read back through asin: its rounding (6e-8) grows by 1/cos(89.5
    // degrees), about 115; 1e-4 radians is a hundredth of a degree.
    EXPECT_NEAR(std::asin(turnLight(light, 0.0, -1e4).y), glm::radians(89.5), 1e-4);
    EXPECT_NEAR(std::asin(turnLight(light, 0.0, 1e4).y), glm::radians(0.5), 1e-4);
    EXPECT_NEAR(glm::length(turnLight(light, 123.0, 45.0)), 1.0, 1e-6);
}

}  // namespace
