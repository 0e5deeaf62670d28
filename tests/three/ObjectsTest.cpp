// Relief and its materials behaving as three.js objects do (issue 48), in examples/three's
// compare page (shading=microrelief) in headless Chromium: a renderer with reversed depth
// builds a map, draws and picks; a material assigned after construction draws at the next
// render, one material is shared by reliefs, three's own materials are refused in one line;
// clone and copy; heightScale, interpolation and base set after construction; toJSON read by
// ObjectLoader and made a relief again. The page-side checks are tests/three/objects.js;
// one page load serves every test (SwiftShader compiles each relief program for 7 to 11 s).
#include <map>
#include <optional>

#include "ThreePage.h"

using namespace microrelief;
using namespace microrelief::three_test;

namespace {

// The checks in the order the page runs them (step 3 onwards), then a screenshot of the
// last picture drawn (liveOptions': the relief whose base became a sphere).
const std::vector<std::string> kChecks = {"reversedDepth", "assignedMaterial", "sharedMaterial",
                                          "cloneAndCopy",  "json",             "liveOptions"};

using Fields = std::map<std::string, std::string>;

Fields fields(const std::string& text) {
    Fields out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        const auto equals = line.find('=');
        if (equals != std::string::npos) out[line.substr(0, equals)] = line.substr(equals + 1);
    }
    return out;
}

class ThreeObjects : public ThreePage {
protected:
    // The page's answers to every check, run once for the suite.
    const Fields& check(const std::string& name) {
        static std::optional<PageRun> page;
        static std::map<std::string, Fields> answers;
        if (!page) {
            std::string steps = "[" +
                                open("shading=microrelief", viewNamed("oblique").width,
                                     viewNamed("oblique").height, "three/") +
                                ", {\"wait\": \"ready\"}, {\"eval\": " +
                                jsonString(test::readText(MICRORELIEF_THREE_TESTS_DIR "/objects.js")) +
                                "}";
            for (const std::string& c : kChecks)
                steps += ", {\"eval\": " + jsonString("objectChecks." + c + "()") + "}";
            steps += ", {\"screenshot\": " + jsonString((dir / "live-base-sphere.png").string()) + "}]";
            page = runPage(steps);
            for (const std::string& line : page->log) std::printf("    page: %s\n", line.c_str());
            for (std::size_t k = 0; k < kChecks.size(); ++k)
                answers[kChecks[k]] = fields(page->at(3 + static_cast<int>(k), "value"));
        }
        EXPECT_EQ(page->at(1, "state"), "ready") << page->at(1, "error") << page->err;
        const Fields& answer = answers[name];
        for (const auto& [key, value] : answer) std::printf("    %s.%s = %s\n", name.c_str(), key.c_str(), value.c_str());
        EXPECT_TRUE(answer.count("error") == 0) << name << " threw: " << answer.at("error");
        EXPECT_FALSE(answer.empty()) << name << ": no answer (the page did not run it)";
        return answer;
    }

    static double number(const Fields& f, const std::string& key) {
        const auto found = f.find(key);
        return found == f.end() ? std::nan("") : std::strtod(found->second.c_str(), nullptr);
    }

    static std::string text(const Fields& f, const std::string& key) {
        const auto found = f.find(key);
        return found == f.end() ? std::string("(none)") : found->second;
    }

    // Two pictures the page's renderer drew with the same program and the same uniforms: the
    // same bytes (the GPU is deterministic; anything else is a uniform or a box that differs).
    static void expectSamePixels(const Fields& f, const std::string& key) {
        EXPECT_EQ(number(f, key + ".max"), 0.0) << key << ": " << number(f, key + ".differing")
                                                << " channels differ, mean " << number(f, key + ".mean");
        EXPECT_GT(number(f, key + ".covered"), 0.05) << key << ": hardly any relief drawn";
    }

    // A change that must show: at least 1 % of the channels move.
    static void expectChanged(const Fields& f, const std::string& key) {
        EXPECT_GT(number(f, key + ".differing"), 0.01 * 4 * 240 * 180) << key << ": the change does not show";
    }
};

// Reversed depth (three's reversedDepthBuffer): the map's passes and the picks drew with a
// bare THREE.Camera, which three turns to reversed depth through updateProjectionMatrix, a
// method it lacks ("camera.updateProjectionMatrix is not a function"). The picture against
// the page's standard-depth one: the rays come from another projection matrix (the same
// camera, reversed: the same rays up to rounding), so tests/web's thresholds (kLimits); the
// picks within kPositionTolerance of the page's relief's.
TEST_F(ThreeObjects, AReversedDepthRendererBuildsDrawsAndPicks) {
    const Fields& f = check("reversedDepth");
    if (text(f, "reversed") == "false") GTEST_SKIP() << "this WebGL has no EXT_clip_control: three falls back to standard depth";
    EXPECT_EQ(text(f, "reversed"), "true");
    EXPECT_LE(number(f, "picture.over"), kLimits.differentPixels);
    EXPECT_LE(number(f, "picture.mean"), kLimits.mean);
    EXPECT_GT(number(f, "picture.covered"), 0.3);
    EXPECT_GT(number(f, "hits"), 40);
    EXPECT_EQ(number(f, "disagreements"), 0);
    EXPECT_LE(number(f, "largest"), kPositionTolerance);
}

// relief.material = ... after construction draws at the next render (it threw inside
// render(): the material was never attached); three's own materials get one line naming the
// relief material to use instead ("attachRelief is not a function" before).
TEST_F(ThreeObjects, AMaterialAssignedAfterConstructionDraws) {
    const Fields& f = check("assignedMaterial");
    expectSamePixels(f, "shaded");
    expectSamePixels(f, "standard");
    EXPECT_EQ(text(f, "plainAssigned"),
              "Relief: the material must be a ReliefStandardMaterial, ReliefPhysicalMaterial or "
              "ReliefShadingMaterial, not a MeshStandardMaterial (new "
              "ReliefStandardMaterial().copy(material) traces the relief with its parameters)");
    EXPECT_EQ(text(f, "plainConstructed"),
              "Relief: the material must be a ReliefStandardMaterial, ReliefPhysicalMaterial or "
              "ReliefShadingMaterial, not a MeshPhysicalMaterial (new "
              "ReliefPhysicalMaterial().copy(material) traces the relief with its parameters)");
    EXPECT_EQ(text(f, "basic"),
              "Relief: the material must be a ReliefStandardMaterial, ReliefPhysicalMaterial or "
              "ReliefShadingMaterial, not a MeshBasicMaterial");
    EXPECT_EQ(text(f, "kept"), "true") << "a refused material must leave the relief's own";
}

// Two reliefs (different height scales and places) sharing one material draw what the same
// two draw with a material each (they were refused: "this material already belongs to
// another Relief"): library-shaded, three-lit, and with different last levels (one material,
// two program variants); the uniform uploads a frame are counted, as the comment in
// materials.js reports them.
TEST_F(ThreeObjects, ReliefsShareAMaterial) {
    const Fields& f = check("sharedMaterial");
    expectSamePixels(f, "picture");
    expectChanged(f, "alone");
    expectSamePixels(f, "standard");
    expectSamePixels(f, "variants");
    // Counts, not times: the switch between reliefs uploads what a switch between materials
    // does (seen 9 calls a frame either way).
    EXPECT_GT(number(f, "uniformCalls.shared"), 0);
    EXPECT_LE(number(f, "uniformCalls.shared"), number(f, "uniformCalls.own"));
}

// clone() and copy() (clone threw: "the first argument must be a ReliefMap"): the clone
// shares the map and material, has its own box, uniforms and shadow materials, draws the
// same picture; a change to it leaves the original as it was.
TEST_F(ThreeObjects, CloneAndCopyDrawTheSamePicture) {
    const Fields& f = check("cloneAndCopy");
    expectSamePixels(f, "cloned");
    expectSamePixels(f, "originalAfterChange");
    expectChanged(f, "cloneChanged");
    expectSamePixels(f, "copied");
    for (const char* what : {"map", "material", "uniforms", "geometry", "depth"})
        EXPECT_EQ(text(f, std::string("shares.") + what), "true") << what;
}

// heightScale, interpolation and base set after construction take effect at the next render
// (they were silently ignored): the picture is a relief constructed with them, and it
// changed; a base the map's wrapU does not suit is refused with the constructor's message.
TEST_F(ThreeObjects, OptionsSetAfterConstructionTakeEffect) {
    const Fields& f = check("liveOptions");
    for (const char* option : {"heightScale", "interpolation", "base"}) {
        SCOPED_TRACE(option);
        expectSamePixels(f, std::string(option) + ".live");
        expectChanged(f, std::string(option) + ".change");
    }
    EXPECT_EQ(text(f, "base.refused"),
              "Relief: a plane base needs a map built with wrapU: false (its u does not wrap)");
    EXPECT_EQ(text(f, "base.refused"), text(f, "base.constructorRefused"));
    EXPECT_EQ(text(f, "base.kept"), "ellipsoid") << "a refused base must leave the relief's own";
    EXPECT_EQ(text(f, "base.ellipsoid"),
              "Relief: an ellipsoid base needs a map built with wrapU: true (its u wraps round)");
    EXPECT_EQ(text(f, "badHeightScale"), "Relief: heightScale must be a positive finite number");
    EXPECT_EQ(text(f, "badInterpolation"),
              "Relief: interpolation 'trilinear' (expected bilinear or biquadratic)");
}

// toJSON writes what ObjectLoader reads: a plain Mesh (the box, its material's three record)
// with the options in userData.microrelief; Relief.fromMesh makes the relief again from it
// and the map, drawing the same picture (ObjectLoader made an Object3D of type 'Relief').
TEST_F(ThreeObjects, ToJsonIsReadByObjectLoaderAndMadeAReliefAgain) {
    const Fields& f = check("json");
    EXPECT_EQ(text(f, "isMesh"), "true");
    EXPECT_EQ(text(f, "type"), "Mesh");
    EXPECT_EQ(text(f, "name"), "floor");
    EXPECT_NEAR(number(f, "heightScale"), 0.1, 1e-6);
    expectSamePixels(f, "same");
    EXPECT_EQ(text(f, "restoredType"), "Relief");
    EXPECT_EQ(text(f, "restoredName"), "floor");
    EXPECT_EQ(text(f, "lit.type"), "MeshStandardMaterial");
    EXPECT_EQ(number(f, "lit.roughness"), 0.3);
    EXPECT_EQ(text(f, "lit.selfShadow"), "true");
    EXPECT_EQ(text(f, "lit.material"), "true");
    EXPECT_NEAR(number(f, "lit.heightScale"), 0.2, 1e-6);
    EXPECT_EQ(text(f, "wrongMap"),
              "Relief.fromMesh: the relief was drawn with a 256 x 256 map, not this 7 x 256 one");
    EXPECT_EQ(text(f, "notRelief"),
              "Relief.fromMesh: the mesh has no userData.microrelief (not written by a Relief's "
              "toJSON)");
}

}  // namespace
