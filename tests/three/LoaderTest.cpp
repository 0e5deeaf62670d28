// ReliefMapLoader (packages/microrelief-three/src/loader.js) as three.js's own loaders
// behave, and three's ordinary `map` from a TextureLoader as the relief's albedo (suite
// ThreeLoader, ctest three.loader). The page-side measurements are tests/three/loader.js,
// evaluated in examples/three's page (the ThreePage fixture, ThreePage.h).
#include <map>
#include <sstream>

#include "ThreePage.h"

using namespace microrelief;
using namespace microrelief::three_test;

namespace {

class ThreeLoader : public ThreePage {
protected:
    // examples/three (shading=microrelief, the oblique view) with loader.js loaded, then
    // each of `scripts` evaluated: their values are steps 3, 4, ...
    PageRun runChecks(const std::vector<std::string>& scripts) {
        const View& v = viewNamed("oblique");
        std::string steps = "[" + open("shading=microrelief", v.width, v.height, "three/") +
                            ", {\"wait\": \"ready\"}, {\"eval\": " +
                            jsonString(test::readText(std::string(MICRORELIEF_THREE_TESTS_DIR) +
                                                      "/loader.js")) +
                            "}";
        for (const std::string& script : scripts) steps += ", {\"eval\": " + jsonString(script) + "}";
        return runPage(steps + "]");
    }
};

// "key rest of the line" lines as a map.
std::map<std::string, std::string> keyed(const std::string& text) {
    std::map<std::string, std::string> out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t space = line.find(' ');
        out[line.substr(0, space)] = space == std::string::npos ? "" : line.substr(space + 1);
    }
    return out;
}

// The bundled 16-bit map through ReliefMapLoader (setPath, a LoadingManager, progress) is
// loadReliefMap's to the bit (its 16 bits kept: samples no 8-bit decode could give); the
// manager starts, sees the progress of its items and finishes after the loader's onLoad,
// every item done; THREE.Cache serves a second load without a request; wrapU is passed on.
// Bad input (a missing file: HTTP 404; a file that is no image) is one line naming the
// URL and the reason, to onError and as loadAsync's rejection, and the manager's onError
// once with the URL (its onLoad follows, as three's managers call it once every item has
// ended, failed ones included). Seen red: before loader.js (no ReliefMapLoader: the page's
// TypeError "ReliefMapLoader is not a constructor"), and with a loader reading through
// loadHeights (fetch) instead of three's FileLoader: no progress events, the manager's one
// item, two requests with the cache on.
TEST_F(ThreeLoader, ALoaderLoadsAsThreesLoadersDo) {
    const PageRun page = runChecks({"threeLoaderChecks.loading()"});
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    const std::string value = page.at(3, "value");
    std::printf("%s\n", value.c_str());
    const auto seen = keyed(value);
    auto get = [&](const std::string& key) {
        const auto found = seen.find(key);
        return found == seen.end() ? std::string("(missing)") : found->second;
    };
    EXPECT_EQ(get("isLoader"), "1");
    EXPECT_EQ(get("isReliefMap"), "1 256x256 ../../assets/cobbles.png");
    EXPECT_EQ(get("differing"), "0 of 65536");
    EXPECT_GT(std::atoi(get("sixteenBit").c_str()), 1000) << "the map's low bytes were lost";
    EXPECT_EQ(get("progressEvents").substr(get("progressEvents").size() - 1), "1")
        << "no progress event reached the whole file: " << get("progressEvents");
    // The manager: started, its two items (the loader's and its FileLoader's) done, loaded
    // after the loader's onLoad.
    EXPECT_EQ(get("managerEvents"), "start,progress 1/2,progress 2/2,load");
    EXPECT_EQ(get("onLoadBeforeManagerLoad"), "1");
    EXPECT_EQ(get("wrapU"), "1 1");
    EXPECT_EQ(get("fetchesForTwoLoads"), "1") << "THREE.Cache did not serve the second load";
    EXPECT_EQ(get("missing"), "HeightMapError: no-such-map.png: cannot be read (HTTP 404)");
    EXPECT_EQ(get("missingAsync"), "HeightMapError: no-such-map.png: cannot be read (HTTP 404)");
    EXPECT_EQ(get("missingManager"), "error no-such-map.png; load");
    EXPECT_EQ(get("notAnImage"),
              "HeightMapError: index.html: not a PNG, nor an image this browser decodes");
    EXPECT_EQ(get("notAnImageAsync"),
              "HeightMapError: index.html: not a PNG, nor an image this browser decodes");
    EXPECT_EQ(get("notAnImageManager"), "error index.html; load");
}

// three's ordinary `map` (THREE.TextureLoader, colorSpace sRGB, three's default flipY) on a
// ReliefStandardMaterial is the relief's albedo: three samples it at the hit's uv (three's
// convention, row 0 of the image at uv.y = 1), so the floor looks as with the package's
// albedoMap (loadAlbedo), within the filtering that differs: albedoMap is filtered over the
// pixel's footprint from ray differentials, `map` by the GPU's mip selection from the
// derivatives of the hit's uv, which jump at cobble edges and silhouettes (a blurrier mip
// there, and along the box's cut side walls, where the uv changes along one axis only).
// Seen (240 x 180, oblique, 18216 relief pixels): 'map' 10.9 % of the pixels over 8 levels
// (the walls and the cobbles' edges), a mean of 2.7 levels; the control with the image
// upside down (flipY false) 87 %, 26 levels: the measure sees a wrong map.
TEST_F(ThreeLoader, ThreesOwnMapIsTheAlbedo) {
    const PageRun page = runChecks({"threeLoaderChecks.albedo()"});
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    const std::string value = page.at(3, "value");
    std::printf("%s\n", value.c_str());
    std::istringstream lines(value);
    int cases = 0;
    for (std::string line; std::getline(lines, line);) {
        std::istringstream fields(line);
        std::string name;
        double covered = 0, different = 1, mean = 1e9;
        fields >> name >> covered >> different >> mean;
        SCOPED_TRACE(line);
        ++cases;
        EXPECT_GT(covered, 5000) << "too few relief pixels to say anything";
        if (name == "map") {
            EXPECT_LT(different, 0.2);
            EXPECT_LT(mean, 4.0);
        } else {
            EXPECT_GT(different, 0.5) << "the upside-down map is not seen: the measure cannot fail";
            EXPECT_GT(mean, 15.0) << "the upside-down map is not seen: the measure cannot fail";
        }
    }
    EXPECT_EQ(cases, 2) << value;
}

}  // namespace
