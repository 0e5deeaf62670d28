// The files a relief's description names and what they hold (io/ReliefFiles.h): the map is
// the relief's own file, its samples in memory, or the bundled map; the colours the relief's
// own file, none, or the bundled map's, only with the bundled map's stones (not under a field
// that replaces them). Each case's files as read, and a bad albedo refused naming it.
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>

#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/io/AlbedoFile.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/ReliefFiles.h"

using namespace microrelief;

namespace {

TEST(ReliefFiles, ADescriptionReadsTheFilesItsRulesName) {
    test::ScratchDir scratch;
    const HeightMap own(6, 4, 0.25f);
    const std::filesystem::path ownFile = scratch / "own.exr";
    test::writeMap(ownFile, own, PixelType::Float);
    const std::filesystem::path colours = defaultAlbedoPath();  // any image of colours
    const auto inMemory = std::make_shared<const HeightMap>(5, 3, 0.5f);
    const HeightMap bundled = loadHeightMap(defaultHeightMapPath());
    const AlbedoImage bundledColours = loadAlbedo(defaultAlbedoPath());

    struct Case {
        const char* name;
        ReliefDesc relief;
        std::optional<std::filesystem::path> heightFile;  // none: the samples in memory
        glm::ivec2 size;
        std::optional<std::filesystem::path> albedoFile;
    };
    const auto relief = [](auto change) {
        ReliefDesc r;
        change(r);
        return r;
    };
    const Case cases[] = {
        {"the bundled map", ReliefDesc{}, defaultHeightMapPath(), {bundled.width, bundled.height},
         defaultAlbedoPath()},
        {"the bundled map, colours off",
         relief([](ReliefDesc& r) { r.albedo.kind = AlbedoSource::Kind::None; }),
         defaultHeightMapPath(), {bundled.width, bundled.height}, std::nullopt},
        {"the bundled map under waves",
         relief([](ReliefDesc& r) { r.animation = "waves"; }), defaultHeightMapPath(),
         {bundled.width, bundled.height}, std::nullopt},
        {"the bundled map under a flood",  // the flood shows the stones
         relief([](ReliefDesc& r) { r.animation = "flood"; }), defaultHeightMapPath(),
         {bundled.width, bundled.height}, defaultAlbedoPath()},
        {"a map of its own", relief([&](ReliefDesc& r) { r.map.file = ownFile; }), ownFile,
         {6, 4}, std::nullopt},
        {"a map of its own with colours",
         relief([&](ReliefDesc& r) {
             r.map.file = ownFile;
             r.albedo = {AlbedoSource::Kind::File, colours};
         }),
         ownFile, {6, 4}, colours},
        {"samples in memory", relief([&](ReliefDesc& r) { r.map.samples = inMemory; }),
         std::nullopt, {5, 3}, std::nullopt},
    };
    for (const Case& c : cases) {
        const ReliefFiles files = loadReliefFiles(c.relief);
        EXPECT_EQ(files.heightFile, c.heightFile) << c.name;
        ASSERT_TRUE(files.heights) << c.name;
        EXPECT_EQ(glm::ivec2(files.heights->width, files.heights->height), c.size) << c.name;
        EXPECT_EQ(files.albedoFile, c.albedoFile) << c.name;
        EXPECT_EQ(files.albedo.has_value(), c.albedoFile.has_value()) << c.name;
        EXPECT_EQ(albedoPath(c.relief), c.albedoFile) << c.name;
        if (files.albedo && c.albedoFile == defaultAlbedoPath()) {
            EXPECT_EQ(files.albedo->width, bundledColours.width) << c.name;
        }
    }
    // Samples in memory are shared, not copied.
    EXPECT_EQ(loadReliefFiles(cases[6].relief).heights, inMemory);
    // The heights as the file gives them (its own map here).
    EXPECT_EQ(loadReliefFiles(cases[4].relief).heights->samples, own.samples);

    // A colour file that is not there: refused naming it.
    ReliefDesc missing;
    missing.albedo = {AlbedoSource::Kind::File, scratch / "nowhere.png"};
    try {
        (void)loadReliefFiles(missing);
        ADD_FAILURE() << "a missing albedo was read";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("nowhere.png"), std::string::npos) << e.what();
    }
}

// One part asked for: the other is not read (a file that is not there refuses nothing).
// A map named alone (microrelief-bench's --maps entries): its file or the bundled map, read
// as its load options say, as a description holding it reads it.
TEST(ReliefFiles, AMapSourceNamesItsFileOrTheBundledMap) {
    test::ScratchDir scratch;
    const std::filesystem::path ownFile = scratch / "tall.exr";
    HeightMap tall(4, 2, 1.0f);
    tall.at(3, 1) = 4.0f;
    test::writeMap(ownFile, tall, PixelType::Float);

    EXPECT_EQ(heightMapPath(MapSource{}), defaultHeightMapPath());
    MapSource own;
    own.file = ownFile;
    own.load.normalize = true;
    EXPECT_EQ(heightMapPath(own), ownFile);

    ReliefDesc relief;
    relief.map = own;
    EXPECT_EQ(heightMapPath(relief), ownFile);
    const ReliefFiles files = loadReliefFiles(relief, ReliefParts::Heights);
    EXPECT_EQ(files.heightFile, ownFile);
    ASSERT_TRUE(files.heights);
    EXPECT_EQ(files.heights->maxValue(), 1.0f);  // normalised: 4 read as 1
    relief.map = MapSource{};
    EXPECT_EQ(heightMapPath(relief), defaultHeightMapPath());
}

TEST(ReliefFiles, APartAskedForReadsOnlyItsFiles) {
    test::ScratchDir scratch;
    const std::filesystem::path ownFile = scratch / "own.exr";
    test::writeMap(ownFile, HeightMap(6, 4, 0.25f), PixelType::Float);

    ReliefDesc noColours;  // its own map, its colour file not there
    noColours.map.file = ownFile;
    noColours.albedo = {AlbedoSource::Kind::File, scratch / "nowhere.png"};
    const ReliefFiles heights = loadReliefFiles(noColours, ReliefParts::Heights);
    EXPECT_EQ(heights.heightFile, ownFile);
    ASSERT_TRUE(heights.heights);
    EXPECT_EQ(heights.heights->width, 6);
    EXPECT_FALSE(heights.albedoFile);
    EXPECT_FALSE(heights.albedo);

    ReliefDesc noMap;  // the bundled colours named, its map not there
    noMap.map.file = scratch / "nowhere.exr";
    noMap.albedo = {AlbedoSource::Kind::File, defaultAlbedoPath()};
    const ReliefFiles colours = loadReliefFiles(noMap, ReliefParts::Albedo);
    EXPECT_FALSE(colours.heightFile);
    EXPECT_FALSE(colours.heights);
    EXPECT_EQ(colours.albedoFile, defaultAlbedoPath());
    EXPECT_TRUE(colours.albedo);
    // The bundled map's own colours, by the same rule as both parts read together.
    EXPECT_EQ(loadReliefFiles(ReliefDesc{}, ReliefParts::Albedo).albedoFile, defaultAlbedoPath());

    EXPECT_THROW((void)loadReliefFiles(noColours), Error);
    EXPECT_THROW((void)loadReliefFiles(noMap), Error);
}

// The heights a host edits: those read from a file handed over (the very samples, no copy);
// samples the description holds copied, the shared ones left as they were.
TEST(ReliefFiles, HeightsTakenToEditAreTheCallersOwn) {
    test::ScratchDir scratch;
    const std::filesystem::path ownFile = scratch / "own.exr";
    test::writeMap(ownFile, HeightMap(6, 4, 0.25f), PixelType::Float);
    ReliefDesc fromFile;
    fromFile.map.file = ownFile;
    ReliefFiles read = loadReliefFiles(fromFile, ReliefParts::Heights);
    const HeightMap* samples = read.heights.get();
    const std::shared_ptr<HeightMap> taken = read.takeHeights();
    EXPECT_EQ(taken.get(), samples);  // handed over, not copied
    EXPECT_FALSE(read.heights);
    EXPECT_EQ(taken.use_count(), 1);  // the caller's alone

    const auto shared = std::make_shared<const HeightMap>(5, 3, 0.5f);
    ReliefDesc inMemory;
    inMemory.map.samples = shared;
    ReliefFiles given = loadReliefFiles(inMemory, ReliefParts::Heights);
    const std::shared_ptr<HeightMap> copy = given.takeHeights();
    ASSERT_TRUE(copy);
    EXPECT_NE(copy.get(), shared.get());
    copy->at(0, 0) = 1.0f;
    EXPECT_EQ(shared->at(0, 0), 0.5f);  // the description's samples untouched
    EXPECT_EQ(copy->at(1, 1), 0.5f);
}

}  // namespace
