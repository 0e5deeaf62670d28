// The scene flags' bindings (app/shared/SceneBindings.h): one for each row of the table of
// scene fields that has a flag (core/scene/SceneFields.h), registered, parsed and echoed by
// SceneFlags and renderCommandLine in one loop. Here: the rows and the bindings match (a
// row without its binding, or a binding without its row, is named); the command line
// echoed for scenes that set every field, its text and its order (pinned before the flags
// became bindings); a parse of no flags over a scene keeps the scene (the flags' seeds read
// back exactly); the rules between flags.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "SceneBindings.h"
#include "SceneOptions.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/scene/Scene.h"

namespace microrelief {
namespace {

// Every field off its default but the tiles (no animation tiles), the base's sizes with a
// space, the light a point.
SceneOptions cylinderScene() {
    SceneOptions scene;
    scene.job.map.file = "/my maps/rock.exr";
    scene.job.map.load.channel = 2;
    scene.job.map.load.normalize = true;
    scene.job.albedo = {AlbedoSource::Kind::File, "/maps/colours.png"};
    scene.job.heightScale = 0.0734f;
    scene.job.interpolation = Interpolation::Biquadratic;
    scene.job.base = BaseShape::cylinder(0.3, 1.25);
    scene.job.animation = "ripples";
    scene.job.time = 1.0 / 3.0 - 40.0;
    scene.job.camera.eye = {0.1 + 1.0 / 3.0, -std::sqrt(2.0) / 7.0, 1e-7 * M_PI};
    scene.job.camera.target = {-0.25, 0.0, std::nextafter(0.1, 1.0)};
    scene.job.camera.up = {0.0, 0.0, -1.0};
    scene.job.camera.fovyDegrees = 37.123456789012345;
    scene.job.width = 333;
    scene.job.height = 217;
    scene.job.model = ModelTransform::fromRows({0, -1, 0, 0.5, 1, 0, 0, -0.25, 0, 0, 2, 1e-3});
    scene.job.shading.lightPosition = glm::dvec3{-1.5, 2.0 / 3.0, 4.0};
    scene.job.shading.shadows = ShadowMode::Soft;
    scene.job.shading.lightSizeDegrees = 0.53f;
    scene.job.method.method = Method::Multilevel;
    scene.job.method.setSteps(23);
    scene.job.method.pixelError = 0.7f;
    scene.job.shading.view = DebugView::Level;
    scene.job.background = {0.3f, 0.01f, 1.0f / 3.0f};
    return scene;
}

// A base whose size is a vector (echoed after "="), colours off, a directional light, hard
// shadows with the default light size (not echoed), the default base kept over a map's own.
SceneOptions ellipsoidScene() {
    SceneOptions scene;
    scene.job.albedo = {AlbedoSource::Kind::None, {}};
    scene.job.base = BaseShape::ellipsoid({0.5, 0.35, 0.4});
    scene.job.shading.lightDirection = {std::cos(1.1f), 0.3f, -std::sin(1.1f)};
    scene.job.shading.shadows = ShadowMode::Hard;
    scene.job.method.method = Method::MaxMip;
    return scene;
}

// The tiles, a peer method, a light size without soft shadows (echoed), the default base
// kept over a georeferenced map's own (echoed).
SceneOptions tiledScene() {
    SceneOptions scene;
    scene.georeference.keepBase = true;
    scene.job.tiles = {2, 3};
    scene.job.method.method = Method::Relief;
    scene.job.shading.lightSizeDegrees = 2.0f;
    return scene;
}

// The mesh base (--base mesh --mesh FILE), biquadratic, the normal view.
SceneOptions meshScene() {
    SceneOptions scene;
    scene.job.onMesh = true;
    scene.job.mesh.file = "/my meshes/rock.obj";
    scene.job.heightScale = 0.02f;
    scene.job.interpolation = Interpolation::Biquadratic;
    scene.job.shading.view = DebugView::Normal;
    return scene;
}

TEST(SceneBindings, TheEchoedCommandLineIsPinned) {
    EXPECT_EQ(renderCommandLine(SceneOptions{}),
              "microrelief-render --height-scale 0.1 --eye=0.8,0.5,0.85 --target=0,-0.03,0 "
              "--up=0,1,0 --fovy 45 --size 1280x720 --light=-0.45808792,0.81437856,-0.3562906 "
              "--method multilevel --view shaded");
    EXPECT_EQ(renderCommandLine(cylinderScene(), "microrelief-viewer"),
              "microrelief-viewer --height '/my maps/rock.exr' --albedo /maps/colours.png "
              "--channel 2 --normalize --height-scale 0.0734 --interpolation biquadratic "
              "--base cylinder --radius 0.3 --length 1.25 --animate ripples "
              "--time=-39.666666666666664 "
              "--eye=0.43333333333333335,-0.20203050891044216,3.141592653589793e-07 "
              "--target=-0.25,0,0.10000000000000002 --up=0,0,-1 --fovy 37.123456789012344 "
              "--size 333x217 --model=0,-1,0,0.5,1,0,0,-0.25,0,0,2,0.001 "
              "--light-position=-1.5,0.6666666666666666,4 --shadows soft --light-size 0.53 "
              "--method multilevel --steps 23 --pixel-error 0.7 --view level --background "
              "0.3,0.01,0.33333334");
    EXPECT_EQ(renderCommandLine(ellipsoidScene()),
              "microrelief-render --albedo none --height-scale 0.1 --base ellipsoid "
              "--radii=0.5,0.35,0.4 --eye=0.8,0.5,0.85 --target=0,-0.03,0 --up=0,1,0 --fovy "
              "45 --size 1280x720 --light=0.4535961,0.3,-0.8912074 --shadows hard --method "
              "maxmip --view shaded");
    EXPECT_EQ(renderCommandLine(tiledScene()),
              "microrelief-render --height-scale 0.1 --tile 2,3 --base plane "
              "--eye=0.8,0.5,0.85 --target=0,-0.03,0 --up=0,1,0 --fovy 45 --size 1280x720 "
              "--light=-0.45808792,0.81437856,-0.3562906 --light-size 2 --method relief "
              "--view shaded");
    EXPECT_EQ(renderCommandLine(meshScene()),
              "microrelief-render --height-scale 0.02 --interpolation biquadratic --base mesh "
              "--mesh '/my meshes/rock.obj' --eye=0.8,0.5,0.85 --target=0,-0.03,0 --up=0,1,0 "
              "--fovy 45 --size 1280x720 --light=-0.45808792,0.81437856,-0.3562906 --method "
              "multilevel --view normal");
}

// A parse of no flags over a scene gives the scene back: each flag's seed is its field's
// exact text.
TEST(SceneBindings, NoFlagsOverASceneKeepIt) {
    for (const SceneOptions& scene :
         {SceneOptions{}, cylinderScene(), ellipsoidScene(), tiledScene(), meshScene()}) {
        SceneOptions parsed = scene;
        SceneFlags flags(parsed);
        CLI::App app;
        flags.addMapAndCamera(app);
        flags.addShading(app);
        app.parse(std::string(), false);
        flags.apply();
        EXPECT_TRUE(static_cast<const ReliefDesc&>(parsed.job) ==
                    static_cast<const ReliefDesc&>(scene.job))
            << renderCommandLine(parsed);
        EXPECT_TRUE(static_cast<const ViewDesc&>(parsed.job) ==
                    static_cast<const ViewDesc&>(scene.job))
            << renderCommandLine(parsed);
        EXPECT_EQ(renderCommandLine(parsed), renderCommandLine(scene));
    }
}

// A flag over a scene changes its field; the rules between flags hold over the scene's
// values too (a row of a camera file over the command line).
TEST(SceneBindings, FlagsOverASceneAndTheRulesBetweenThem) {
    const auto parse = [](SceneOptions scene, const std::string& line) {
        SceneFlags flags(scene);
        CLI::App app;
        flags.addMapAndCamera(app);
        flags.addShading(app);
        app.parse(line, false);
        flags.apply();
        return scene;
    };
    const SceneOptions cylinder = cylinderScene();
    const SceneOptions steps = parse(cylinder, "--steps 40 --method maxmip");
    EXPECT_EQ(steps.job.method.steps, 40);
    EXPECT_EQ(steps.job.method.minSteps, 10);
    EXPECT_EQ(steps.job.method.method, Method::MaxMip);
    EXPECT_EQ(steps.job.camera.eye, cylinder.job.camera.eye);
    const auto message = [&](const SceneOptions& scene, const std::string& line) {
        try {
            parse(scene, line);
        } catch (const Error& e) {
            return e.message(flagName);
        }
        return std::string("no error");
    };
    EXPECT_EQ(message(cylinder, "--light 0,1,0"),
              "--light and --light-position are two lights: give one");
    EXPECT_EQ(message(SceneOptions{}, "--time 2"), "--time needs --animate NAME");
    EXPECT_EQ(parse(cylinder, "--time 2").job.time, 2.0);
    EXPECT_EQ(message(SceneOptions{}, "--radius 2"), "--radius does not apply to --base plane");
    EXPECT_TRUE(parse(cylinder, "--radius 0.25").job.base == BaseShape::cylinder(0.25, 1.25));
    // Two wrong flags at once: the one reported is the one it has always been.
    EXPECT_EQ(message(SceneOptions{}, "--interpolation cubic --base cone"),
              "unknown --base 'cone' (expected plane, cylinder, ellipsoid, sphere or mesh)");
    // The mesh base: its file with it, no size of the analytic bases.
    const SceneOptions onMesh = parse(SceneOptions{}, "--base mesh --mesh /m/rock.obj");
    EXPECT_TRUE(onMesh.job.onMesh);
    EXPECT_EQ(onMesh.job.mesh.file, std::filesystem::path("/m/rock.obj"));
    EXPECT_EQ(message(SceneOptions{}, "--base mesh --mesh r.obj --radius 2"),
              "--radius does not apply to --base mesh");
    EXPECT_EQ(message(SceneOptions{}, "--base mesh"),
              "--base mesh needs --mesh FILE, the triangle mesh (OBJ or glTF 2.0) the map is "
              "laid over");
    EXPECT_EQ(message(SceneOptions{}, "--base sphere --mesh r.obj"),
              "--mesh is the mesh base's: give --base mesh with it (not --base sphere)");
    EXPECT_EQ(message(SceneOptions{}, "--size 5x --light 0,0,0"), "--light must not be zero");
    EXPECT_EQ(message(SceneOptions{}, "--model 1,2 --view foo --method bar"),
              "unknown --view 'foo' (expected shaded, iterations, level, normal, depth or "
              "position)");
    EXPECT_EQ(message(SceneOptions{}, "--model 1,2 --background 1,2"),
              "--background expects three numbers r,g,b, got '1,2'");
    // What a georeferenced map keeps of the flags given (core/scene/Georeference.h).
    const SceneOptions given = parse(SceneOptions{}, "--height-scale 0.2 --base plane");
    EXPECT_TRUE(given.georeference.keepHeightScale);
    EXPECT_TRUE(given.georeference.keepBase);
    EXPECT_FALSE(given.georeference.keepModel);
    EXPECT_TRUE(parse(SceneOptions{}, "--model 1,0,0,0,0,1,0,0,0,0,1,0").georeference.keepModel);
    EXPECT_EQ(parse(SceneOptions{}, "--exaggeration 3").georeference.exaggeration, 3.0);
    EXPECT_EQ(message(SceneOptions{}, "--exaggeration 2 --height-scale 0.3"),
              "--exaggeration scales a georeferenced map's true heights and --height-scale sets "
              "the height scale outright: give one");
}

// Every row with a flag has one binding and every binding a row with a flag (SceneFlags
// stops a program that starts without); a table that lost one says which.
TEST(SceneBindings, EveryRowWithAFlagHasOneBindingAndEveryBindingARow) {
    const std::span<const SceneField> table = sceneFieldTable();
    const std::span<const SceneBinding> bindings = sceneBindings();
    for (const std::string& gap : sceneBindingGaps(table, bindings)) ADD_FAILURE() << gap;
    for (const SceneBinding& binding : bindings) {
        EXPECT_TRUE(binding.add && binding.echo) << binding.path;
        EXPECT_TRUE(!binding.seed || binding.apply) << binding.path << " seeds and never reads";
    }
    // A new row with a flag and no binding.
    std::vector<SceneField> rows(table.begin(), table.end());
    rows.push_back({"shading.glow", "--glow", "G", "", "0", "", "Glow", ""});
    EXPECT_EQ(sceneBindingGaps(rows, bindings),
              std::vector<std::string>{"shading.glow: a row with the flag --glow and no binding"});
    // A binding without its row, one for a row no flag sets, one twice.
    std::vector<SceneBinding> more(bindings.begin(), bindings.end());
    more.push_back({});
    more.back().path = "shading.glow";
    more.push_back({});
    more.back().path = "map.samples";
    more.push_back(more.front());
    EXPECT_EQ(sceneBindingGaps(table, more),
              (std::vector<std::string>{"shading.glow: a binding without a row that has a flag",
                                        "map.samples: a binding without a row that has a flag",
                                        std::string(more.front().path) + ": bound twice"}));
    // A row whose binding went missing.
    std::vector<SceneBinding> fewer(bindings.begin(), bindings.end());
    fewer.erase(std::find_if(fewer.begin(), fewer.end(),
                             [](const SceneBinding& b) { return b.path == "base"; }));
    EXPECT_EQ(sceneBindingGaps(table, fewer),
              (std::vector<std::string>{"base: a row with the flag --base and no binding",
                                        "interpolation: read after base, which has no binding",
                                        "tiles: echoed before base, which has no binding"}));
    // Two read after each other: neither would be read.
    std::vector<SceneBinding> cycle(bindings.begin(), bindings.end());
    for (SceneBinding& b : cycle) {
        if (b.path == "camera.eye") b.parsedAfter = "camera.target";
        if (b.path == "camera.target") b.parsedAfter = "camera.eye";
    }
    EXPECT_EQ(sceneBindingGaps(table, cycle),
              (std::vector<std::string>{"camera.eye: read after itself",
                                        "camera.target: read after itself"}));
}

}  // namespace
}  // namespace microrelief
