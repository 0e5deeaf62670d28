// The pieces of microrelief-render's camera paths that need no GL: turntable cameras,
// camera files (CSV and JSON lines, per-row flags, every refusal with its file, line
// and reason), output name patterns, frame ranges and shards (Slurm's variables
// included), the manifest and the progress line.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include "CameraPath.h"
#include "Csv.h"
#include "FramePattern.h"
#include "FrameSelection.h"
#include "Manifest.h"
#include "Progress.h"
#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/io/ImageFile.h"

using namespace microrelief;

namespace {

// The message of the Error(BadInput) that `f` throws, its fields named by their flags as
// microrelief-render prints it; fails the test if it throws none.
template <class F>
std::string badInputMessage(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
        return e.message(flagName);
    }
    ADD_FAILURE() << "no error thrown";
    return {};
}

#define EXPECT_BAD_INPUT(statement, ...)                                         \
    do {                                                                         \
        const std::string message = badInputMessage([&] { (void)(statement); }); \
        for (const std::string& part : std::vector<std::string>{__VA_ARGS__})    \
            EXPECT_NE(message.find(part), std::string::npos)                     \
                << "expected '" << part << "' in: " << message;                  \
    } while (false)

// ---- output name patterns ----

TEST(FramePattern, ExpandsFramesWithPythonsIntegerFormats) {
    const FramePattern p("out/view-{frame:04d}.png", "--out");
    EXPECT_TRUE(p.uses("frame"));
    EXPECT_EQ(p.expand("frame", 7), "out/view-0007.png");
    EXPECT_EQ(p.expand("frame", 12345), "out/view-12345.png");  // a width is a minimum
    EXPECT_EQ(FramePattern("{frame}", "--out").expand("frame", 7), "7");
    EXPECT_EQ(FramePattern("{frame:d}", "--out").expand("frame", 7), "7");
    EXPECT_EQ(FramePattern("{frame:3d}", "--out").expand("frame", 7), "  7");
    EXPECT_EQ(FramePattern("a{{b}}-{frame:02d}.exr", "--aov").expand("frame", 3), "a{b}-03.exr");
    const FramePattern plain("out/one.png", "--out");
    EXPECT_FALSE(plain.uses("frame"));
    EXPECT_EQ(plain.expand("frame", 3), "out/one.png");
    EXPECT_EQ(FramePattern("m-{shard}-of-{shards}.csv", "--manifest", {"shard", "shards"})
                  .expand({{"shard", 2}, {"shards", 16}}),
              "m-2-of-16.csv");
}

TEST(FramePattern, RefusesWhatItCannotExpand) {
    EXPECT_BAD_INPUT(FramePattern("v-{fram}.png", "--out"), "--out", "{fram}", "{frame}");
    EXPECT_BAD_INPUT(FramePattern("v-{frame:04x}.png", "--out"), "--out", "0Nd");
    EXPECT_BAD_INPUT(FramePattern("v-{frame:}.png", "--out"), "0Nd");
    EXPECT_BAD_INPUT(FramePattern("v-{frame:-4d}.png", "--out"), "0Nd");
    EXPECT_BAD_INPUT(FramePattern("v-{frame.png", "--aov"), "--aov", "unmatched '{'");
    EXPECT_BAD_INPUT(FramePattern("v-frame}.png", "--out"), "unmatched '}'");
    EXPECT_BAD_INPUT(FramePattern("m-{frame}.csv", "--manifest", {"shard", "shards"}), "--manifest",
                     "{frame}");
}

TEST(FramePattern, FixedFolderIsTheFolderBeforeAnyField) {
    EXPECT_EQ(FramePattern("out/view-{frame}.png", "--out").fixedFolder(), "out");
    EXPECT_EQ(FramePattern("out/{frame}/view.png", "--out").fixedFolder(), "out");
    EXPECT_EQ(FramePattern("a/b/c.png", "--out").fixedFolder(), "a/b");
    EXPECT_EQ(FramePattern("view-{frame}.png", "--out").fixedFolder(), "");
    EXPECT_EQ(FramePattern("/v-{frame}.png", "--out").fixedFolder(), "/");
}

// ---- frame ranges and shards ----

TEST(FrameSelection, ParsesRanges) {
    FrameRange r = parseFrameRange("3-7");
    EXPECT_EQ(r.first, 3);
    EXPECT_EQ(r.last, 7);
    r = parseFrameRange("3-");
    EXPECT_EQ(r.first, 3);
    EXPECT_FALSE(r.last);
    r = parseFrameRange("5");
    EXPECT_EQ(r.first, 5);
    EXPECT_EQ(r.last, 5);
    for (const char* bad : {"", "-3", "7-3", "a-b", "3-x", "1.5", "3-4-5", " 3-4"})
        EXPECT_BAD_INPUT(parseFrameRange(bad), "--frames", std::string("'") + bad + "'");
}

TEST(FrameSelection, ParsesShards) {
    const Shard s = parseShard("3/4");
    EXPECT_EQ(s.index, 3);
    EXPECT_EQ(s.count, 4);
    for (const char* bad : {"4/4", "-1/4", "1/0", "1", "x/y", "1/4/5", "/4", "0/"})
        EXPECT_BAD_INPUT(parseShard(bad), "--shard", std::string("'") + bad + "'");
}

// A fake environment for --shard slurm.
EnvironmentLookup environment(std::map<std::string, std::string> variables) {
    return [variables = std::move(variables)](const char* name) -> const char* {
        const auto found = variables.find(name);
        return found == variables.end() ? nullptr : found->second.c_str();
    };
}

TEST(FrameSelection, SlurmShardsFromTheArrayVariables) {
    // Set by Slurm for --array=0-3, task 2.
    Shard s = parseShard("slurm", environment({{"SLURM_ARRAY_TASK_ID", "2"},
                                               {"SLURM_ARRAY_TASK_COUNT", "4"},
                                               {"SLURM_ARRAY_TASK_MIN", "0"},
                                               {"SLURM_ARRAY_TASK_MAX", "3"},
                                               {"SLURM_ARRAY_TASK_STEP", "1"}}));
    EXPECT_EQ(s.index, 2);
    EXPECT_EQ(s.count, 4);
    // By hand, without MIN, MAX and STEP: an array from 0.
    s = parseShard("slurm",
                   environment({{"SLURM_ARRAY_TASK_ID", "0"}, {"SLURM_ARRAY_TASK_COUNT", "4"}}));
    EXPECT_EQ(s.index, 0);
    EXPECT_EQ(s.count, 4);
    // --array=1-4 (Slurm users often count from 1): task 1 is shard 0, task 4 shard 3.
    for (int id = 1; id <= 4; ++id) {
        s = parseShard("slurm", environment({{"SLURM_ARRAY_TASK_ID", std::to_string(id)},
                                             {"SLURM_ARRAY_TASK_COUNT", "4"},
                                             {"SLURM_ARRAY_TASK_MIN", "1"},
                                             {"SLURM_ARRAY_TASK_MAX", "4"}}));
        EXPECT_EQ(s.index, id - 1);
        EXPECT_EQ(s.count, 4);
    }
    // --array=10-16:2: tasks 10, 12, 14, 16.
    s = parseShard("slurm", environment({{"SLURM_ARRAY_TASK_ID", "14"},
                                         {"SLURM_ARRAY_TASK_COUNT", "4"},
                                         {"SLURM_ARRAY_TASK_MIN", "10"},
                                         {"SLURM_ARRAY_TASK_MAX", "16"},
                                         {"SLURM_ARRAY_TASK_STEP", "2"}}));
    EXPECT_EQ(s.index, 2);
    EXPECT_EQ(s.count, 4);
}

TEST(FrameSelection, SlurmRefusesWhatIsNoArrayTaskOrNoRange) {
    EXPECT_BAD_INPUT(parseShard("slurm", environment({})), "--shard slurm",
                     "SLURM_ARRAY_TASK_ID is not set");
    EXPECT_BAD_INPUT(parseShard("slurm", environment({{"SLURM_ARRAY_TASK_ID", "3"}})),
                     "SLURM_ARRAY_TASK_COUNT is not set");
    EXPECT_BAD_INPUT(parseShard("slurm", environment({{"SLURM_ARRAY_TASK_ID", "x"},
                                                      {"SLURM_ARRAY_TASK_COUNT", "4"}})),
                     "SLURM_ARRAY_TASK_ID='x'");
    EXPECT_BAD_INPUT(parseShard("slurm", environment({{"SLURM_ARRAY_TASK_ID", "1"},
                                                      {"SLURM_ARRAY_TASK_COUNT", "0"}})),
                     "SLURM_ARRAY_TASK_COUNT='0'");
    // --array=1,4,6: three tasks, but not one range.
    EXPECT_BAD_INPUT(parseShard("slurm", environment({{"SLURM_ARRAY_TASK_ID", "4"},
                                                      {"SLURM_ARRAY_TASK_COUNT", "3"},
                                                      {"SLURM_ARRAY_TASK_MIN", "1"},
                                                      {"SLURM_ARRAY_TASK_MAX", "6"},
                                                      {"SLURM_ARRAY_TASK_STEP", "1"}})),
                     "not one range");
    // An id the array does not have: an array from 1 whose MIN was forgotten by hand
    // gives task 4 of 4, one past the end.
    EXPECT_BAD_INPUT(
        parseShard("slurm",
                   environment({{"SLURM_ARRAY_TASK_ID", "4"}, {"SLURM_ARRAY_TASK_COUNT", "4"}})),
        "SLURM_ARRAY_TASK_ID=4", "not a task of the array",
        "SLURM_ARRAY_TASK_MIN unset, taken as 0; SLURM_ARRAY_TASK_MAX unset, taken as 3",
        "SLURM_ARRAY_TASK_COUNT=4");
}

TEST(FrameSelection, ShardsInterleaveAndPartitionTheRange) {
    for (const int frames : {1, 7, 12, 361}) {
        for (const FrameRange range :
             {FrameRange{0, std::nullopt}, FrameRange{frames / 3, std::nullopt},
              FrameRange{frames / 4, frames - 1 - frames / 5}}) {
            std::vector<int> expected;
            for (int f = range.first; f <= range.last.value_or(frames - 1); ++f)
                expected.push_back(f);
            for (const int count : {1, 2, 3, 4, 5, 16}) {
                std::multiset<int> all;
                std::size_t smallest = expected.size(), largest = 0;
                for (int index = 0; index < count; ++index) {
                    const std::vector<int> mine = selectFrames(frames, range, {index, count});
                    EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
                    // Every count-th frame of the range, from the index-th.
                    for (std::size_t k = 0; k < mine.size(); ++k)
                        EXPECT_EQ(mine[k], range.first + index + static_cast<int>(k) * count);
                    all.insert(mine.begin(), mine.end());
                    smallest = std::min(smallest, mine.size());
                    largest = std::max(largest, mine.size());
                }
                EXPECT_EQ(std::vector<int>(all.begin(), all.end()), expected)
                    << frames << " frames, " << count << " shards: each frame exactly once";
                EXPECT_LE(largest - smallest, 1u) << "balanced shards";
            }
        }
    }
    EXPECT_EQ(selectFrames(360, parseFrameRange("10-13"), {1, 2}), (std::vector<int>{11, 13}));
}

TEST(FrameSelection, RangesPastThePathAreRefused) {
    EXPECT_BAD_INPUT(selectFrames(360, parseFrameRange("300-400"), {}), "--frames 300-400",
                     "360 frames", "0-359");
    EXPECT_BAD_INPUT(selectFrames(360, parseFrameRange("360-"), {}), "--frames 360-");
    EXPECT_EQ(selectFrames(360, parseFrameRange("359-"), {}), (std::vector<int>{359}));
}

// ---- turntables ----

SceneOptions baseScene() {
    SceneOptions base;
    base.job.camera.eye = {0.8, 0.5, 0.85};
    base.job.camera.target = {0.1, -0.03, 0.05};
    base.job.camera.fovyDegrees = 40.0;
    base.job.heightScale = 0.07f;
    base.job.background = {0.123456789f, 0.2f, 0.3f};
    base.job.shading.lightDirection = {0.1f, 0.9f, 0.123456789f};
    return base;
}

TEST(Turntable, TurnsTheEyeAboutTheTargetKeepingDistanceAndElevation) {
    const SceneOptions base = baseScene();
    const int views = 12;
    const std::vector<PathFrame> path = turntablePath(base, views);
    ASSERT_EQ(path.size(), 12u);
    const Camera& given = base.job.camera;
    // Frame 0 is the command line's camera, bit for bit.
    EXPECT_EQ(path[0].scene.job.camera.eye, given.eye);
    EXPECT_EQ(path[0].scene.job.camera.up, given.up);
    const glm::dvec3 offset = given.eye - given.target;
    const double distance = glm::length(offset);
    const double azimuth0 = std::atan2(offset.z, offset.x);
    for (int k = 0; k < views; ++k) {
        const Camera& c = path[k].scene.job.camera;
        const glm::dvec3 d = c.eye - c.target;
        EXPECT_EQ(c.target, given.target);
        EXPECT_EQ(c.fovyDegrees, given.fovyDegrees);
        EXPECT_NEAR(glm::length(d), distance, 1e-12) << k;
        EXPECT_NEAR(d.y, offset.y, 1e-15) << "the elevation stays, frame " << k;
        EXPECT_EQ(c.up, glm::dvec3(0, 1, 0)) << "the vertical up turns into itself";
        // Counter-clockwise seen from above (+y): the azimuth atan2(z, x) falls by
        // 360/N degrees a frame (x towards -z is a right-handed turn about +y).
        double turned = azimuth0 - std::atan2(d.z, d.x);
        turned = std::fmod(turned + 4.0 * M_PI, 2.0 * M_PI);
        EXPECT_NEAR(turned, 2.0 * M_PI * k / views, 1e-12) << k;
        // The rest of the scene is the command line's.
        EXPECT_EQ(path[k].scene.job.heightScale, base.job.heightScale);
        EXPECT_EQ(path[k].scene.job.background, base.job.background);
        EXPECT_EQ(path[k].scene.job.shading.lightDirection, base.job.shading.lightDirection);
        EXPECT_TRUE(path[k].flags.empty());
    }
    // A quarter turn in 4 views takes +x to -z.
    SceneOptions onAxis;
    onAxis.job.camera.eye = {1, 0.5, 0};
    onAxis.job.camera.target = {0, 0, 0};
    const std::vector<PathFrame> quarter = turntablePath(onAxis, 4);
    EXPECT_NEAR(quarter[1].scene.job.camera.eye.x, 0.0, 1e-15);
    EXPECT_NEAR(quarter[1].scene.job.camera.eye.z, -1.0, 1e-15);
    EXPECT_NEAR(quarter[2].scene.job.camera.eye.x, -1.0, 1e-15);
}

TEST(Turntable, TurnsATopViewsUpVector) {
    SceneOptions top;
    top.job.camera.eye = {0, 2, 0};
    top.job.camera.target = {0, 0, 0};
    top.job.camera.up = {0, 0, -1};
    const std::vector<PathFrame> path = turntablePath(top, 4);
    EXPECT_EQ(path[1].scene.job.camera.eye, top.job.camera.eye);
    EXPECT_NEAR(path[1].scene.job.camera.up.x, -1.0, 1e-15);
    EXPECT_NEAR(path[1].scene.job.camera.up.z, 0.0, 1e-15);
}

TEST(Turntable, RefusesNoViewsAndDegenerateCameras) {
    EXPECT_BAD_INPUT(turntablePath(baseScene(), 0), "--turntable");
    SceneOptions same = baseScene();
    same.job.camera.target = same.job.camera.eye;
    EXPECT_BAD_INPUT(turntablePath(same, 4), "--eye and --target must differ");
}

// ---- camera files ----

const std::string kColumns = "eye_x,eye_y,eye_z,target_x,target_y,target_z";

TEST(CameraFile, ReadsCsvInAnyColumnOrder) {
    const SceneOptions base = baseScene();
    const std::string text =
        "# cameras for the paper's video\r\n"
        "\r\n"
        "target_x, target_y, target_z, fovy, eye_x, eye_y, eye_z, up_x, up_y, up_z\r\n"
        "0,0,0,30,1,2,3,0,1,0\r\n"
        "  # a comment between rows\n"
        "0.5,-0.25,1e-3,,-1,2.5,+3,,,\n";
    const std::vector<PathFrame> path = parseCameraFile(text, "cams.csv", base);
    ASSERT_EQ(path.size(), 2u);
    EXPECT_EQ(path[0].scene.job.camera.eye, glm::dvec3(1, 2, 3));
    EXPECT_EQ(path[0].scene.job.camera.target, glm::dvec3(0, 0, 0));
    EXPECT_EQ(path[0].scene.job.camera.fovyDegrees, 30.0);
    EXPECT_EQ(path[0].origin, "cams.csv: line 4 (frame 0)");
    EXPECT_EQ(path[1].scene.job.camera.eye, glm::dvec3(-1, 2.5, 3));
    EXPECT_EQ(path[1].scene.job.camera.target, glm::dvec3(0.5, -0.25, 1e-3));
    // Empty fields take the command line's values.
    EXPECT_EQ(path[1].scene.job.camera.fovyDegrees, base.job.camera.fovyDegrees);
    EXPECT_EQ(path[1].scene.job.camera.up, base.job.camera.up);
    EXPECT_EQ(path[1].origin, "cams.csv: line 6 (frame 1)");
    // Rows without flags keep the command line's scene exactly.
    EXPECT_EQ(path[1].scene.job.background, base.job.background);
    EXPECT_EQ(path[1].scene.job.heightScale, base.job.heightScale);
}

TEST(CameraFile, ReadsJsonLines) {
    const SceneOptions base = baseScene();
    const std::string text =
        "{\"eye\": [1, 2, 3], \"target\": [0, 0, 0], \"fovy\": 30}\n"
        "\n"
        "{\"target\":[0.5,-0.25,1e-3],\"eye\":[-1,2.5,3],\"up\":null,\"flags\":\"--view "
        "\\\"normal\\\" --height m\\u00e4p.png\"}\n";
    const std::vector<PathFrame> path = parseCameraFile(text, "cams.jsonl", base);
    ASSERT_EQ(path.size(), 2u);
    EXPECT_EQ(path[0].scene.job.camera.eye, glm::dvec3(1, 2, 3));
    EXPECT_EQ(path[0].scene.job.camera.fovyDegrees, 30.0);
    EXPECT_EQ(path[1].scene.job.camera.target, glm::dvec3(0.5, -0.25, 1e-3));
    EXPECT_EQ(path[1].scene.job.camera.up, base.job.camera.up);
    EXPECT_EQ(path[1].scene.job.shading.view, DebugView::Normal);
    ASSERT_TRUE(path[1].scene.job.map.file);
    EXPECT_EQ(*path[1].scene.job.map.file, "m\xc3\xa4p.png");
    EXPECT_EQ(path[1].origin, "cams.jsonl: line 3 (frame 1)");
}

TEST(CameraFile, RowFlagsGoOnTopOfTheCommandLinesSceneExactly) {
    SceneOptions base = baseScene();
    base.job.map.file = "maps/a.png";
    base.job.map.load.normalize = true;
    base.job.method.setSteps(100);
    base.job.shading.lightSizeDegrees = 5.0f;  // used only once a row turns soft shadows on
    const std::string text = kColumns +
                             ",flags\n"
                             "1,1,1,0,0,0,\"--light -1,1,0 --normalize --height-scale 0.2\"\n"
                             "1,1,1,0,0,0,--height maps/b.png --channel 1 --size 32x16\n"
                             "1,1,1,0,0,0,--method maxmip --view iterations\n"
                             "1,1,1,0,0,0,--shadows soft\n";
    const std::vector<PathFrame> path = parseCameraFile(text, "cams.csv", base);
    ASSERT_EQ(path.size(), 4u);
    EXPECT_EQ(path[3].scene.job.shading.shadows, ShadowMode::Soft);
    EXPECT_EQ(path[3].scene.job.shading.lightSizeDegrees, 5.0f);
    const RenderJob& a = path[0].scene.job;
    EXPECT_EQ(path[0].flags, "--light -1,1,0 --normalize --height-scale 0.2");
    EXPECT_EQ(a.shading.lightDirection, glm::vec3(-1, 1, 0));
    EXPECT_EQ(a.heightScale, 0.2f);
    // What the row leaves alone is the command line's, bit for bit: the background's
    // nine digits, the light of the other rows, the map and its load options.
    EXPECT_EQ(a.background, base.job.background);
    EXPECT_EQ(*path[0].scene.job.map.file, "maps/a.png");
    EXPECT_TRUE(path[0].scene.job.map.load.normalize);
    EXPECT_EQ(a.method.steps, 100);
    EXPECT_EQ(a.camera.fovyDegrees, base.job.camera.fovyDegrees);
    const SceneOptions& b = path[1].scene;
    EXPECT_EQ(*b.job.map.file, "maps/b.png");
    EXPECT_EQ(b.job.map.load.channel, 1);
    EXPECT_TRUE(b.job.map.load.normalize);
    EXPECT_EQ(b.job.width, 32);
    EXPECT_EQ(b.job.height, 16);
    EXPECT_EQ(b.job.shading.lightDirection, base.job.shading.lightDirection);
    EXPECT_EQ(b.job.heightScale, base.job.heightScale);
    EXPECT_EQ(path[2].scene.job.method.method, Method::MaxMip);
    EXPECT_EQ(path[2].scene.job.shading.view, DebugView::Iterations);
    EXPECT_EQ(path[2].scene.job.camera.eye, glm::dvec3(1, 1, 1));
}

TEST(CameraFile, BadFilesNameTheFileTheLineAndTheReason) {
    const SceneOptions base;
    const auto parse = [&](const std::string& text, const std::string& source = "cams.csv") {
        return parseCameraFile(text, source, base);
    };
    // Columns.
    EXPECT_BAD_INPUT(parse("eye_x,eye_y,eye_z,target_x,target_y\n1,1,1,0,0\n"), "cams.csv",
                     "line 1", "no column target_z");
    EXPECT_BAD_INPUT(parse(kColumns + ",up_x,up_y\n1,1,1,0,0,0,0,1\n"), "line 1", "no column up_z");
    EXPECT_BAD_INPUT(parse(kColumns + ",fov\n1,1,1,0,0,0,40\n"), "line 1", "unknown column 'fov'");
    EXPECT_BAD_INPUT(parse(kColumns + ",eye_x\n1,1,1,0,0,0,1\n"), "eye_x appears twice");
    EXPECT_BAD_INPUT(parse("1,1,1,0,0,0\n"), "line 1", "must name the columns");
    EXPECT_BAD_INPUT(parse("# nothing\n\n"), "cams.csv", "no cameras");
    EXPECT_BAD_INPUT(parse(kColumns + "\n"), "cams.csv", "no cameras");
    // Fields.
    const std::string good = "1,1,1,0,0,0\n";
    EXPECT_BAD_INPUT(parse(kColumns + "\n" + good + "1,1,1,0,0\n"), "cams.csv", "line 3 (frame 1)",
                     "5 fields", "6 columns");
    EXPECT_BAD_INPUT(parse(kColumns + "\n" + good + "1,abc,1,0,0,0\n"), "line 3 (frame 1)",
                     "eye_y: 'abc' is not a number");
    EXPECT_BAD_INPUT(parse(kColumns + "\n" + good + "1,1,1,0,0,1x\n"),
                     "target_z: '1x' is not a number");
    for (const char* notFinite : {"nan", "NaN", "inf", "-Infinity", "1e999"}) {
        EXPECT_BAD_INPUT(parse(kColumns + "\n" + good + "1,1," + notFinite + ",0,0,0\n"),
                         "line 3 (frame 1)", "eye_z", "is not a finite number");
    }
    EXPECT_BAD_INPUT(parse(kColumns + "\n" + good + "1,,1,0,0,0\n"), "line 3 (frame 1)",
                     "eye_y is empty");
    EXPECT_BAD_INPUT(parse(kColumns + "\n" + good + "1,\"1,1,0,0,0\n"), "line 3 (frame 1)",
                     "unclosed quote");
    // Cameras: the third row of three, after comments.
    EXPECT_BAD_INPUT(
        parse("# c\n" + kColumns + "\n" + good + "# c\n" + good + "0.5,0.5,0.5,0.5,0.5,0.5\n"),
        "cams.csv: line 6 (frame 2)", "the eye and the target are the same point");
    // Positions beyond kMaxWorldPosition, as --eye and --target have it (a row's eye of 1e300
    // was called the target's point, one of 1.0000000005e12 drawn).
    EXPECT_BAD_INPUT(parse(kColumns + "\n1e300,0,0,0,0,0\n"), "line 2 (frame 0)",
                     "--eye 1e+300,0,0: each component must lie within +-1e+12");
    EXPECT_BAD_INPUT(parse(kColumns + "\n1,1,1,2e12,0,0\n"), "line 2 (frame 0)",
                     "--target 2e+12,0,0: each component must lie within +-1e+12");
    EXPECT_BAD_INPUT(parse(kColumns + ",up_x,up_y,up_z\n0,1,0,0,0,0,0,2,0\n"), "line 2 (frame 0)",
                     "--up must not be parallel");
    EXPECT_BAD_INPUT(parse(kColumns + ",fovy\n1,1,1,0,0,0,180\n"), "line 2 (frame 0)",
                     "fovy must lie strictly between 0 and 180");
    // Row flags.
    EXPECT_BAD_INPUT(parse(kColumns + ",flags\n1,1,1,0,0,0,\"--eye 1,2,3\"\n"), "line 2 (frame 0)",
                     "--eye is not a row flag");
    EXPECT_BAD_INPUT(parse(kColumns + ",flags\n1,1,1,0,0,0,--fovy 30\n"),
                     "--fovy is not a row flag");
    EXPECT_BAD_INPUT(parse(kColumns + ",flags\n1,1,1,0,0,0,--no-such-flag\n"), "line 2 (frame 0)",
                     "flags: --no-such-flag is not an option; a row's flags are");
    EXPECT_BAD_INPUT(parse(kColumns + ",flags\n1,1,1,0,0,0,--out x.png\n"),
                     "flags: --out is not an option; a row's flags are", "are the command line's");
    EXPECT_BAD_INPUT(parse(kColumns + ",flags\n1,1,1,0,0,0,--steps 0\n"), "line 2 (frame 0)",
                     "--steps must lie in 1..65536");
    EXPECT_BAD_INPUT(parse(kColumns + ",flags\n1,1,1,0,0,0,--method fast\n"), "unknown --method");
}

TEST(CameraFile, BadJsonLinesNameTheFileTheLineAndTheReason) {
    const SceneOptions base;
    const auto parse = [&](const std::string& rows) {
        return parseCameraFile("{\"eye\": [1, 1, 1], \"target\": [0, 0, 0]}\n" + rows, "cams.jsonl",
                               base);
    };
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, 1]}\n"), "cams.jsonl", "line 2 (frame 1)",
                     "no \"target\"");
    EXPECT_BAD_INPUT(parse("{\"target\": [1, 1, 1]}\n"), "no \"eye\"");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1], \"target\": [0, 0, 0]}\n"),
                     "eye must be an array of three numbers");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, \"1\", 1], \"target\": [0, 0, 0]}\n"),
                     "eye[1] is not a number");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, abc, 1], \"target\": [0, 0, 0]}\n"),
                     "eye[1]: 'abc' is not a number");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, NaN], \"target\": [0, 0, 0]}\n"), "line 2 (frame 1)",
                     "eye[2]: 'NaN' is not a finite number");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, 1], \"target\": [1, 1, 1]}\n"), "line 2 (frame 1)",
                     "the eye and the target are the same point");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, 1], \"target\": [0, 0, 0],}\n"), "line 2 (frame 1)",
                     "not a JSON object", "column");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, 1], \"target\": [0, 0, 0]\n"), "not a JSON object");
    EXPECT_BAD_INPUT(parse("[1, 1, 1]\n"), "not a JSON object");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, 1], \"target\": [0, 0, 0], \"fov\": 3}\n"),
                     "unknown key \"fov\"");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, 1], \"eye\": [2, 2, 2], \"target\": [0, 0, 0]}\n"),
                     "\"eye\" appears twice");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, 1], \"target\": [0, 0, 0], \"fovy\": \"30\"}\n"),
                     "fovy is not a number");
    EXPECT_BAD_INPUT(parse("{\"eye\": [1, 1, 1], \"target\": [0, 0, 0], \"flags\": 3}\n"),
                     "flags must be a string");
    EXPECT_BAD_INPUT(
        parse("{\"eye\": [1, 1, 1], \"target\": [0, 0, 0], \"flags\": \"--target 1,2,3\"}\n"),
        "line 2 (frame 1)", "--target is not a row flag");
}

// Issue 25: a spreadsheet's "CSV UTF-8" starts with a byte order mark, which is no part of
// the first column's name; --help and empty values in row flags get a plain reason, not
// CLI11's internal text or the default taken silently.
TEST(CameraFile, AByteOrderMarkIsSkippedAndHelpOrEmptyRowFlagsAreRefused) {
    const SceneOptions base;
    const auto parse = [&](const std::string& text) {
        return parseCameraFile(text, "cams.csv", base);
    };
    const std::vector<PathFrame> path = parse("\xEF\xBB\xBF" + kColumns + "\n1,2,3,0,0,0\n");
    ASSERT_EQ(path.size(), 1u);
    EXPECT_EQ(path[0].scene.job.camera.eye, glm::dvec3(1, 2, 3));
    const auto jsonl = parseCameraFile("\xEF\xBB\xBF{\"eye\": [1, 2, 3], \"target\": [0, 0, 0]}\n",
                                       "cams.jsonl", base);
    ASSERT_EQ(jsonl.size(), 1u);
    for (const char* help : {"--help", "-h", "--light 0,1,0 --help"}) {
        EXPECT_BAD_INPUT(parse(kColumns + ",flags\n1,1,1,0,0,0,\"" + help + "\"\n"),
                         "cams.csv: line 2 (frame 0): flags: --help is not a row flag");
    }
    EXPECT_BAD_INPUT(parse(kColumns + ",flags\n1,1,1,0,0,0,--height ''\n"),
                     "line 2 (frame 0): flags: --height");
}

// A turntable's frames are made when asked for, each the one turntablePath makes.
TEST(Turntable, APathOfAMillionViewsHoldsNoFrame) {
    const SceneOptions base = baseScene();
    const CameraPath path = CameraPath::turntable(base, 1000000);
    EXPECT_EQ(path.size(), 1000000);
    const std::vector<PathFrame> eight = turntablePath(base, 8);
    const CameraPath lazy = CameraPath::turntable(base, 8);
    for (int k = 0; k < 8; ++k) {
        EXPECT_EQ(lazy.frame(k).scene.job.camera.eye, eight[k].scene.job.camera.eye) << k;
        EXPECT_EQ(lazy.frame(k).origin, eight[k].origin) << k;
    }
    EXPECT_EQ(path.frame(250000).scene.job.camera.eye,
              turntablePath(base, 4)[1].scene.job.camera.eye);
    EXPECT_BAD_INPUT(CameraPath::turntable(base, 0), "--turntable");
}

TEST(CameraFile, FilesThatAreNotThereOrNotFiles) {
    test::ScratchDir dir;
    EXPECT_BAD_INPUT(readCameraFile(dir / "missing.csv", {}), "missing.csv", "no such file");
    EXPECT_BAD_INPUT(readCameraFile(dir.path(), {}), "not a regular file");
    std::ofstream(dir / "one.csv") << kColumns << "\n1,1,1,0,0,0\n";
    EXPECT_EQ(readCameraFile(dir / "one.csv", {}).size(), 1u);
}

TEST(CameraFile, CameraFlagsAreExact) {
    Camera c;
    c.eye = {0.1 + 0.2, -1e-7, 1.0 / 3.0};
    c.up = {0, 0, -1};
    c.fovyDegrees = 37.5;
    EXPECT_EQ(cameraFlags(c),
              "--eye=0.30000000000000004,-1e-07,0.3333333333333333 --target=0,-0.03,0 "
              "--up=0,0,-1 --fovy 37.5");
}

// A message of the library names scene fields; microrelief-render prints each as its flag.
// Every field has one but the samples in memory, which only a library user can give.
TEST(SceneFlags, EveryFieldAMessageMayNameHasAFlag) {
    std::vector<std::string> fields = sceneFields();
    for (const std::string& size : baseSizeFields()) fields.push_back(size);
    for (const std::string& field : fields) {
        if (field == "map.samples") continue;
        EXPECT_EQ(flagName(field).rfind("--", 0), 0u) << field << " has no flag";
    }
    EXPECT_EQ(Error(ErrorKind::BadInput, "{camera.eye} and {camera.target} must differ").message(flagName),
              "--eye and --target must differ");
    // A base's sizes take their flags from their fields (the table of bases), one flag a
    // field: none of them is another field's flag, and a size shared by bases has one count.
    EXPECT_EQ(Error(ErrorKind::BadInput, "{base.radius} and {base.radii}").message(flagName),
              "--radius and --radii");
    // A field of a size's form that no base has is no flag: the message keeps the field.
    EXPECT_EQ(flagName("base.minorRadius"), "base.minorRadius");
    std::set<std::string> flags;
    for (const std::string& field : fields) {
        if (field == "map.samples") continue;
        EXPECT_TRUE(flags.insert(flagName(field)).second) << flagName(field) << " twice";
    }
    std::map<std::string, int> counts;
    for (const BaseType& type : baseTypes())
        for (const BaseSize& size : type.sizes)
            EXPECT_EQ(counts.try_emplace(size.field, size.count).first->second, size.count)
                << size.field << " of " << type.name;
}

// ---- CSV, manifest, progress ----

TEST(Csv, QuotesWhatNeedsItAndReadsItBack) {
    for (const std::string field : {"plain", "", "a,b", "say \"hi\"", " padded ", "--eye=1,2,3"}) {
        const auto back = splitCsvLine(csvField(field) + "," + csvField(field));
        ASSERT_TRUE(back) << field;
        EXPECT_EQ(*back, (std::vector<std::string>{field, field})) << csvField(field);
    }
    EXPECT_EQ(csvField("plain"), "plain");
    EXPECT_EQ(csvField("a,b"), "\"a,b\"");
    EXPECT_FALSE(splitCsvLine("\"open,1"));
    EXPECT_FALSE(splitCsvLine("\"closed\"x,1"));
    EXPECT_FALSE(splitCsvLine("in\"side,1"));
}

TEST(Manifest, AppendsRowsThatAKilledRunLeavesReadable) {
    test::ScratchDir dir;
    const auto file = dir / "sub" / "manifest.csv";
    {
        ManifestWriter m(file);
        m.append({0, "out/a b.png", "--eye=1,2,3 --light \"x\"", 12.34, "rendered"});
        m.append({1, "out/b.png", "--eye=1,2,3", 0.0, "skipped"});
    }
    EXPECT_EQ(test::readText(file),
              "frame,file,camera,ms,status\n"
              "0,out/a b.png,\"--eye=1,2,3 --light \"\"x\"\"\",12.3,rendered\n"
              "1,out/b.png,\"--eye=1,2,3\",0.0,skipped\n");
    // A row torn by a power cut: the next run starts a line of its own, the reader
    // skips the torn one.
    std::ofstream(file, std::ios::app) << "2,out/c.p";
    {
        ManifestWriter m(file);
        m.append({2, "out/c.png", "--eye=1,2,3", 5.0, "rendered"});
    }
    const std::vector<ManifestRow> rows = readManifest(file);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0].file, "out/a b.png");
    EXPECT_EQ(rows[0].camera, "--eye=1,2,3 --light \"x\"");
    EXPECT_DOUBLE_EQ(rows[0].ms, 12.3);
    EXPECT_EQ(rows[1].status, "skipped");
    EXPECT_EQ(rows[2].frame, 2);
    EXPECT_EQ(rows[2].file, "out/c.png");
    EXPECT_EQ(test::readText(file).find("frame,file", 1), std::string::npos) << "one header";
    // A torn last line is not a row.
    std::ofstream(file, std::ios::app) << "3,out/d.png,x,1.0,rendered";
    EXPECT_EQ(readManifest(file).size(), 3u);
}

TEST(Manifest, RefusesAFileThatIsNoManifest) {
    test::ScratchDir dir;
    std::ofstream(dir / "notes.csv") << "a,b,c\n1,2,3\n";
    EXPECT_BAD_INPUT(ManifestWriter(dir / "notes.csv"), "notes.csv", "not a manifest");
    EXPECT_EQ(test::readText(dir / "notes.csv"), "a,b,c\n1,2,3\n");
    EXPECT_BAD_INPUT(ManifestWriter(dir.path()), "not a regular file");
}

TEST(Progress, SaysFrameKOfNTheRateAndTheTimeLeft) {
    EXPECT_EQ(progressLine(0, 10, 0, 0.0), "frame 0 of 10");
    EXPECT_EQ(progressLine(5, 10, 5, 2.5), "frame 5 of 10, 2 fps, 0:03 left");
    EXPECT_EQ(progressLine(10, 10, 10, 5.0), "frame 10 of 10, 2 fps, 0:00 left");
    EXPECT_EQ(progressLine(4, 3604, 4, 4.0), "frame 4 of 3604, 1 fps, 1:00:00 left");
    EXPECT_EQ(progressLine(6, 10, 2, 1.0), "frame 6 of 10, 2 fps, 0:02 left (4 skipped)");
}

TEST(Progress, DrawsOnlyWhenEnabled) {
    test::ScratchDir dir;
    const auto file = dir / "progress";
    std::FILE* out = std::fopen(file.c_str(), "w");
    {
        BatchProgress off(3, false, out);
        off.frameDone(true, 0.1);
        off.finish();
    }
    std::fflush(out);
    EXPECT_EQ(test::readText(file), "");
    {
        BatchProgress on(2, true, out);
        on.frameDone(true, 0.5);
        on.frameDone(true, 0.5);
        on.finish();
    }
    std::fclose(out);
    const std::string text = test::readText(file);
    EXPECT_NE(text.find("frame 1 of 2"), std::string::npos) << text;
    EXPECT_NE(text.find("frame 2 of 2, 2 fps, 0:00 left\n"), std::string::npos) << text;
    // The last frame's line once: finish() ends the line frameDone drew.
    EXPECT_EQ(text.find("frame 2 of 2"), text.rfind("frame 2 of 2")) << text;
}

// ---- temporaries a killed writer leaves ----

TEST(AbandonedTemporaries, AreTheTemporariesOfWritersThatAreGone) {
    test::ScratchDir dir;
    const auto target = dir / "view-0003.png";
    // A writer that dies between writing its temporary and renaming it (no unwinding,
    // no exit handlers: as under SIGKILL).
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        std::vector<std::uint8_t> pixels(4 * 4 * 3, 128);
        ImageWriteBatch batch;
        batch.write(target, {4, 4, 3, PixelType::UInt8, pixels.data(), {}});
        ::raise(SIGKILL);
    }
    // Dead but not yet reaped (a zombie: as a child killed under a parent that has not
    // waited, such as `timeout -s KILL`'s, which signal 0 still finds): already gone.
    siginfo_t info{};
    ASSERT_EQ(::waitid(P_PID, static_cast<id_t>(child), &info, WEXITED | WNOWAIT), 0);
    std::vector<std::filesystem::path> left;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        left.push_back(entry.path());
    ASSERT_EQ(left.size(), 1u) << "the killed writer's temporary";
    EXPECT_FALSE(std::filesystem::exists(target));
    EXPECT_EQ(abandonedTemporaryTarget(left[0]), std::optional{target}) << "its writer a zombie";
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status));
    const auto found = abandonedTemporaryTarget(left[0]);
    ASSERT_TRUE(found) << left[0];
    EXPECT_EQ(*found, target);

    // The same name from a process that runs (this one, its parent) is no one's leftover.
    const std::string name = left[0].filename().string();
    const std::string tag = ".tmp-" + std::to_string(child) + "-";
    ASSERT_NE(name.find(tag), std::string::npos) << name;
    for (const pid_t alive : {::getpid(), ::getppid()}) {
        std::string live = name;
        live.replace(name.find(tag), tag.size(), ".tmp-" + std::to_string(alive) + "-");
        EXPECT_FALSE(abandonedTemporaryTarget(dir / live)) << live;
    }
    for (const char* other : {"view-0003.png", ".view-0003.png", ".view.tmp-x-1.png",
                              ".view.tmp-12-.png", ".tmp-12-1.png", "view.tmp-12-1.png"})
        EXPECT_FALSE(abandonedTemporaryTarget(dir / other)) << other;
}

}  // namespace
