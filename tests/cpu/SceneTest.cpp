// The scene as values (core/scene/Scene.h): validation reports every wrong value by its field,
// messages name fields for the printer to spell, and equality sees every member, since the
// renderers and the viewer rebuild on a desc that differs.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "microrelief/core/Error.h"
#include "microrelief/core/scene/Scene.h"

using namespace microrelief;

namespace {

struct Broken {
    const char* field;  // the field the error must name
    std::function<void(ReliefDesc&, ViewDesc&)> breakIt;
};

// One wrong value per case, each on an otherwise valid scene.
std::vector<Broken> brokenScenes() {
    using R = ReliefDesc;
    using V = ViewDesc;
    return {
        {"map.load.channel", [](R& r, V&) { r.map.load.channel = -1; }},
        {"map.samples", [](R& r, V&) { r.map.samples = std::make_shared<HeightMap>(); }},
        {"base.radius", [](R& r, V&) { r.base = BaseShape::cylinder(-1.0); }},
        {"heightScale", [](R& r, V&) { r.heightScale = 0.0f; }},
        {"heightScale", [](R& r, V&) { r.heightScale = std::nanf(""); }},
        {"tiles", [](R& r, V&) { r.tiles = {0, 1}; }},
        {"tiles", [](R& r, V&) { r.tiles = {1, kMaxTiles + 1}; }},
        {"animation", [](R& r, V&) { r.animation = "storm"; }},
        {"animation", [](R& r, V&) { r.animation = "waves", r.tiles = {2, 1}; }},
        {"time", [](R& r, V&) { r.animation = "waves", r.time = 2e9; }},
        {"camera.eye", [](R&, V& v) { v.camera.eye = {1e30, 0.0, 0.0}; }},
        {"camera.eye", [](R&, V& v) { v.camera.target = v.camera.eye; }},
        {"camera.up", [](R&, V& v) { v.camera.up = {0.0, 0.0, 0.0}; }},
        {"camera.up", [](R&, V& v) { v.camera.up = v.camera.target - v.camera.eye; }},
        {"camera.fovyDegrees", [](R&, V& v) { v.camera.fovyDegrees = 180.0; }},
        {"size", [](R&, V& v) { v.width = 0; }},
        {"size", [](R&, V& v) { v.width = v.height = kMaxPictureSide; }},
        {"method.steps", [](R&, V& v) { v.method.steps = 0; }},
        {"method.pixelError", [](R&, V& v) { v.method.pixelError = -1.0f; }},
        {"shading.lightDirection", [](R&, V& v) { v.shading.lightDirection = glm::vec3(0.0f); }},
        {"shading.lightPosition", [](R&, V& v) { v.shading.lightPosition = glm::vec3(1e30f); }},
        {"shading.lightSizeDegrees", [](R&, V& v) { v.shading.lightSizeDegrees = 90.0f; }},
        {"background", [](R&, V& v) { v.background = {-1.0f, 0.0f, 0.0f}; }},
        // Together: shadows take an exact method; maxmip's quadtree does not tile.
        {"shading.shadows",
         [](R&, V& v) { v.shading.shadows = ShadowMode::Hard, v.method.method = Method::Pom; }},
        {"method", [](R& r, V& v) { r.tiles = {2, 2}, v.method.method = Method::MaxMip; }},
        {"method", [](R& r, V& v) { r.base = BaseShape::sphere(), v.method.method = Method::Steep; }},
    };
}

}  // namespace

TEST(Scene, TheDefaultsAreAValidScene) {
    EXPECT_TRUE(validateScene(ReliefDesc{}, ViewDesc{}).empty());
}

TEST(Scene, EachWrongValueIsReportedByItsFieldAndNamedInItsMessage) {
    for (const Broken& broken : brokenScenes()) {
        ReliefDesc relief;
        ViewDesc view;
        broken.breakIt(relief, view);
        const std::vector<FieldError> errors = validateScene(relief, view);
        ASSERT_EQ(errors.size(), 1u) << broken.field;
        EXPECT_EQ(errors[0].field, broken.field) << errors[0].message;
        EXPECT_TRUE(isSceneField(errors[0].field)) << errors[0].field;
        EXPECT_NE(errors[0].message.find("{" + errors[0].field + "}"), std::string::npos)
            << errors[0].message;
    }
}

TEST(Scene, EveryWrongValueIsReportedAtOnce) {
    ReliefDesc relief;
    ViewDesc view;
    relief.heightScale = -1.0f;
    view.width = 0;
    view.method.pixelError = -1.0f;
    std::vector<std::string> fields;
    for (const FieldError& e : validateScene(relief, view)) fields.push_back(e.field);
    EXPECT_EQ(fields, (std::vector<std::string>{"heightScale", "size", "method.pixelError"}));
    try {
        throwIfInvalid(validateScene(relief, view));
        ADD_FAILURE() << "no error thrown";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_EQ(std::string(e.what()).rfind("heightScale must be", 0), 0u) << e.what();
    }
}

// A light the shader gets in float, checked while it is still the caller's double: 1e-300
// would be stored as zero.
TEST(Scene, DirectionsAreCheckedBeforeFloatRoundsThemToZero) {
    std::vector<FieldError> errors;
    checkDirection(errors, "shading.lightDirection", {1e-300, 0.0, 0.0});
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].message.find("its largest component must be at least"), std::string::npos)
        << errors[0].message;
    errors.clear();
    checkDirection(errors, "shading.lightDirection", {1e-3, 0.0, 0.0});
    EXPECT_TRUE(errors.empty());
}

TEST(Scene, EqualitySeesEveryMember) {
    const ReliefDesc relief;
    const ViewDesc view;
    EXPECT_EQ(relief, ReliefDesc{});
    EXPECT_EQ(view, ViewDesc{});
    const std::vector<std::function<void(ReliefDesc&)>> reliefChanges = {
        [](ReliefDesc& r) { r.map.samples = std::make_shared<HeightMap>(2, 2); },
        [](ReliefDesc& r) { r.map.file = "a.png"; },
        [](ReliefDesc& r) { r.map.load.channel = 1; },
        [](ReliefDesc& r) { r.map.load.normalize = true; },
        [](ReliefDesc& r) { r.map.load.maxSide = 64; },
        [](ReliefDesc& r) { r.albedo.kind = AlbedoSource::Kind::None; },
        [](ReliefDesc& r) { r.albedo = {AlbedoSource::Kind::File, "c.png"}; },
        [](ReliefDesc& r) { r.base = BaseShape::cylinder(); },
        [](ReliefDesc& r) { r.interpolation = Interpolation::Biquadratic; },
        [](ReliefDesc& r) { r.tiles = {2, 1}; },
        [](ReliefDesc& r) { r.heightScale = 0.2f; },
        [](ReliefDesc& r) { r.model = ModelTransform::fromRows({2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}); },
        [](ReliefDesc& r) { r.animation = "waves"; },
        [](ReliefDesc& r) { r.time = 1.0; },
    };
    for (std::size_t i = 0; i < reliefChanges.size(); ++i) {
        ReliefDesc changed = relief;
        reliefChanges[i](changed);
        EXPECT_NE(changed, relief) << "relief change " << i;
    }
    const std::vector<std::function<void(ViewDesc&)>> viewChanges = {
        [](ViewDesc& v) { v.camera.eye.x += 0.5; },
        [](ViewDesc& v) { v.camera.target.y += 0.5; },
        [](ViewDesc& v) { v.camera.up = {1, 0, 0}; },
        [](ViewDesc& v) { v.camera.fovyDegrees = 30.0; },
        [](ViewDesc& v) { v.width = 64; },
        [](ViewDesc& v) { v.height = 64; },
        [](ViewDesc& v) { v.method.method = Method::MaxMip; },
        [](ViewDesc& v) { v.method.setSteps(7); },
        [](ViewDesc& v) { v.method.pixelError = 2.0f; },
        [](ViewDesc& v) { v.shading.lightDirection = {1, 1, 1}; },
        [](ViewDesc& v) { v.shading.lightPosition = glm::vec3(1, 1, 1); },
        [](ViewDesc& v) { v.shading.shadows = ShadowMode::Soft; },
        [](ViewDesc& v) { v.shading.lightSizeDegrees = 3.0f; },
        [](ViewDesc& v) { v.shading.albedo = {1, 0, 0}; },
        [](ViewDesc& v) { v.shading.view = DebugView::Normal; },
        [](ViewDesc& v) { v.background = {1, 1, 1}; },
    };
    for (std::size_t i = 0; i < viewChanges.size(); ++i) {
        ViewDesc changed = view;
        viewChanges[i](changed);
        EXPECT_NE(changed, view) << "view change " << i;
    }
}

// Fields in messages: what() spells them as the desc does; a program gives its own names;
// braces that name no field (a file's, a pattern's) stay as they are.
TEST(Scene, ErrorsNameTheirFieldsAsTheReaderSpellsThem) {
    const Error e(ErrorKind::BadInput, "{camera.eye} and {camera.target} must differ in {frame}.png {");
    EXPECT_STREQ(e.what(), "camera.eye and camera.target must differ in {frame}.png {");
    const auto flags = [](const std::string& field) { return "--" + field.substr(field.find('.') + 1); };
    EXPECT_EQ(e.message(flags), "--eye and --target must differ in {frame}.png {");
    EXPECT_EQ(e.after("cams.csv: line 2: ").message(flags),
              "cams.csv: line 2: --eye and --target must differ in {frame}.png {");
    EXPECT_EQ(Error(ErrorKind::Runtime, std::string("a\0b", 3)).message(flags), "a\\x00b");
}

// What a pyramid is built from: the heights, the addressing, the tiles; nothing else of a
// relief (the one pyramid bounds either last level's surface).
TEST(Scene, ReliefsShareAPyramidUnlessTheirHeightsAddressingOrTilesDiffer) {
    const ReliefDesc relief;
    const std::vector<std::function<void(ReliefDesc&)>> kept = {
        [](ReliefDesc& r) { r.heightScale = 0.3f; },
        [](ReliefDesc& r) {
            r.model = ModelTransform::fromRows({2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0});
        },
        [](ReliefDesc& r) { r.albedo.kind = AlbedoSource::Kind::None; },
        [](ReliefDesc& r) { r.animation = "waves", r.time = 3.0; },
        [](ReliefDesc& r) { r.interpolation = Interpolation::Biquadratic; },
    };
    for (std::size_t i = 0; i < kept.size(); ++i) {
        ReliefDesc changed = relief;
        kept[i](changed);
        EXPECT_TRUE(samePyramid(changed, relief)) << "kept " << i;
    }
    ReliefDesc cylinder = relief, sphere = relief;
    cylinder.base = BaseShape::cylinder(0.3, 1.0);
    sphere.base = BaseShape::sphere(0.4);
    EXPECT_TRUE(samePyramid(cylinder, sphere));  // u wraps on both
    EXPECT_FALSE(samePyramid(cylinder, relief));  // and not on the plane
    const std::vector<std::function<void(ReliefDesc&)>> rebuilt = {
        [](ReliefDesc& r) { r.map.file = "b.png"; },
        [](ReliefDesc& r) { r.map.load.channel = 2; },
        [](ReliefDesc& r) { r.map.load.normalize = true; },
        [](ReliefDesc& r) {
            r.tiles = {1, 3};
        },
    };
    for (std::size_t i = 0; i < rebuilt.size(); ++i) {
        ReliefDesc changed = relief;
        rebuilt[i](changed);
        EXPECT_FALSE(samePyramid(changed, relief)) << "rebuilt " << i;
    }
}
