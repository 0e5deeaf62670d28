// microrelief-bench's map entries (app/microrelief-bench/MapEntry.h): FILE[:CHANNEL][:normalize]
// read from the right, the rest the file name colons and all, and the names the report
// gives them.
#include <gtest/gtest.h>

#include <cctype>

#include "MapEntry.h"
#include "microrelief/core/Error.h"

using namespace microrelief;
using namespace microrelief::bench;

namespace {

struct EntryCase {
    const char* text;
    const char* file;
    int channel;
    bool normalize;
    const char* name;  // mapName
};

const EntryCase kEntries[] = {
    {"rock.png", "rock.png", 0, false, "rock"},
    {"dir/rock.png:1", "dir/rock.png", 1, false, "rock:1"},
    {"terrain.png:normalize", "terrain.png", 0, true, "terrain:normalize"},
    {"/maps/stone.exr:2:normalize", "/maps/stone.exr", 2, true, "stone:2:normalize"},
    {"rock.png:0", "rock.png", 0, false, "rock"},  // channel 0 is the default's name
    {"rock.png:017", "rock.png", 17, false, "rock:17"},
    // Colons that are not suffixes stay in the file name.
    {"a:b.png", "a:b.png", 0, false, "a:b"},
    {"a:b.png:3", "a:b.png", 3, false, "a:b:3"},
    {"maps:1/rock.png", "maps:1/rock.png", 0, false, "rock"},
    {"rock.png:", "rock.png:", 0, false, "rock"},  // stem of "rock.png:" is "rock"
    {"rock.png:+1", "rock.png:+1", 0, false, "rock"},
    {"rock.png:-1", "rock.png:-1", 0, false, "rock"},
    {"rock.png:1.5", "rock.png:1.5", 0, false, "rock.png:1"},
    {"rock.png:Normalize", "rock.png:Normalize", 0, false, "rock"},
    {"normalize", "normalize", 0, false, "normalize"},
    // One channel, then one ':normalize', in that order: the next colon's text is the file's.
    {"x:1:0", "x:1", 0, false, "x:1"},
    {"x.png:1:2", "x.png:1", 2, false, "x:2"},
    {"x.png:normalize:2", "x.png:normalize", 2, false, "x:2"},
    {"x.png:normalize:normalize", "x.png:normalize", 0, true, "x:normalize"},
    {"x.png:1023", "x.png", 1023, false, "x:1023"},
};

void PrintTo(const EntryCase& c, std::ostream* os) {
    *os << '"' << c.text << '"';
}

class BenchMapEntry : public ::testing::TestWithParam<EntryCase> {};

TEST_P(BenchMapEntry, ReadsTheSuffixesFromTheRight) {
    const EntryCase& c = GetParam();
    const MapSource source = parseMapEntry(c.text);
    ASSERT_TRUE(source.file);
    EXPECT_EQ(source.file->string(), c.file);
    EXPECT_EQ(source.load.channel, c.channel);
    EXPECT_EQ(source.load.normalize, c.normalize);
    EXPECT_EQ(mapName(source), c.name);
}

// Each case named by its index and its text, letters and digits kept.
INSTANTIATE_TEST_SUITE_P(Entries, BenchMapEntry, ::testing::ValuesIn(kEntries),
                         [](const ::testing::TestParamInfo<EntryCase>& info) {
                             std::string name = std::to_string(info.index) + "_";
                             for (const char* c = info.param.text; *c; ++c)
                                 name += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
                             return name;
                         });

TEST(BenchMapEntryErrors, EmptyFileNamesAndChannelsNoMapHasAreRefused) {
    const struct {
        const char* text;
        const char* message;
    } cases[] = {
        {"", "an empty file name"},
        {":1", "an empty file name"},
        {":normalize", "an empty file name"},
        {":2:normalize", "an empty file name"},
        {"x.png:1024", "channel 1024 is beyond the 1024 channels"},
        // Far beyond an int: refused, not wrapped round to a small channel.
        {"x.png:99999999999999999999", "channel 99999999999999999999 is beyond"},
        {"x.png:4294967296:normalize", "channel 4294967296 is beyond"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        try {
            parseMapEntry(c.text);
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
        }
    }
}

TEST(BenchMapEntryNames, TheBundledMapGoesByItsFileStem) {
    MapSource bundled;
    EXPECT_EQ(mapName(bundled), "cobbles");
    bundled.load.channel = 1;
    bundled.load.normalize = true;
    EXPECT_EQ(mapName(bundled), "cobbles:1:normalize");
}

}  // namespace
