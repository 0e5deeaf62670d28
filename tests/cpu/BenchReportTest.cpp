// microrelief-bench's equal-time pick and throughput (app/microrelief-bench/Report.h) on
// made-up measurements: which setting a peer is reported at, and on which pixels.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <sstream>

#include "Report.h"

using namespace microrelief::bench;

namespace {

Measurement row(const std::string& method, const std::string& param, double wallMs,
                double mismatchPct, double offPct, double p99Texels) {
    Measurement r;
    r.method = method;
    r.param = param;
    r.map = "relief";
    r.mapSize = 256;
    r.viewDegrees = 45;
    r.width = r.height = 256;
    r.msWallMedian = wallMs;
    r.msMedian = 100.0 - wallMs;  // the timer's order the other way round
    r.coverageMismatchPct = r.topCoverageMismatchPct = mismatchPct;
    r.offHalfTexelPct = r.topOffHalfTexelPct = offPct;
    r.p99ErrorTexels = r.topP99ErrorTexels = p99Texels;
    return r;
}

TEST(BenchReport, EqualTimePicksTheMostAccurateSettingWithinTheTime) {
    const Measurement multilevel = row("multilevel", "exact", 10.0, 0.0, 0.0, 0.0);
    const std::vector<Measurement> rows{
        multilevel,
        row("relief", "8", 5.0, 0.5, 10.0, 3.0),
        row("relief", "16", 9.0, 0.1, 1.0, 0.4),
        row("relief", "32", 10.0, 0.1, 2.0, 0.2),  // as fast as allowed, less accurate
        row("relief", "64", 12.0, 0.0, 0.0, 0.0),  // exact, but slower
        row("pom", "8", 11.0, 0.0, 0.1, 0.1),      // every setting slower
        row("steep", "8", 4.0, 0.0, 50.0, 2.0),    // ties on wrong %: the smaller p99
        row("steep", "16", 6.0, 0.0, 50.0, 1.0),
        row("steep", "32", 3.0, 0.0, 50.0, 1.0),  // and then the faster
        row("relief", "16", 1.0, 0.0, 0.0, 0.0),  // another map's
    };
    std::vector<Measurement> all = rows;
    all.back().map = "cobbles";

    const Measurement* relief = equalTime(all, "relief", multilevel, true);
    ASSERT_NE(relief, nullptr);
    EXPECT_EQ(relief->param, "16");
    EXPECT_EQ(relief->map, "relief");
    EXPECT_EQ(equalTime(all, "pom", multilevel, true), nullptr);
    const Measurement* steep = equalTime(all, "steep", multilevel, true);
    ASSERT_NE(steep, nullptr);
    EXPECT_EQ(steep->param, "32");
    // By the timer's times instead (100 - wall here, multilevel's 90 ms): relief 32 (90 ms)
    // and 64 (88 ms) are within it, and 64 is exact.
    const Measurement* byTimer = equalTime(all, "relief", multilevel, false);
    ASSERT_NE(byTimer, nullptr);
    EXPECT_EQ(byTimer->param, "64");
}

TEST(BenchReport, EqualTimeJudgesPeersWithoutWallsOnTheTopFacesPixels) {
    const Measurement multilevel = row("multilevel", "exact", 10.0, 0.0, 0.0, 0.0);
    // Over every pixel setting 8 looks better; over the top face's pixels (what relief is
    // measured on: it knows no side walls) setting 16 is.
    Measurement eight = row("relief", "8", 5.0, 0.1, 0.1, 0.1);
    eight.topOffHalfTexelPct = 5.0;
    Measurement sixteen = row("relief", "16", 6.0, 3.0, 3.0, 3.0);
    sixteen.topCoverageMismatchPct = 0.0;
    sixteen.topOffHalfTexelPct = 0.5;
    const std::vector<Measurement> rows{multilevel, eight, sixteen};
    const Measurement* pick = equalTime(rows, "relief", multilevel, true);
    ASSERT_NE(pick, nullptr);
    EXPECT_EQ(pick->param, "16");
    EXPECT_DOUBLE_EQ(peerAccuracy(*pick, true).wrongPct(), 0.5);
    EXPECT_DOUBLE_EQ(peerAccuracy(*pick, false).wrongPct(), 6.0);

    // cone traces the walls: judged over every pixel.
    Measurement coneA = eight, coneB = sixteen;
    coneA.method = coneB.method = "cone";
    const std::vector<Measurement> cones{multilevel, coneA, coneB};
    const Measurement* cone = equalTime(cones, "cone", multilevel, true);
    ASSERT_NE(cone, nullptr);
    EXPECT_EQ(cone->param, "8");
}

TEST(BenchReport, ThroughputIsThePictureOverTheFramesTime) {
    Measurement r = row("multilevel", "exact", 6.5536, 0.0, 0.0, 0.0);  // 65536 pixels
    EXPECT_DOUBLE_EQ(megapixelsPerSecond(r, true), 10.0);
    r.msMedian = 2 * 6.5536;
    EXPECT_DOUBLE_EQ(megapixelsPerSecond(r, false), 5.0);
    r.msWallMedian = 0.0;
    EXPECT_EQ(megapixelsPerSecond(r, true), 0.0);  // not measured: no figure, no division
}

}  // namespace

// A map is named by its file, which may hold what CSV and gnuplot take as syntax: a plain
// name is written as it is, one with a comma, quote or line break quoted with the quote
// doubled (RFC 4180); gnuplot's strings double a single quote.
TEST(BenchReport, NamesAreQuotedWhereTheyHoldSyntax) {
    EXPECT_EQ(csvField("rock:1"), "rock:1");
    EXPECT_EQ(csvField("rock,wall"), "\"rock,wall\"");
    EXPECT_EQ(csvField("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
    EXPECT_EQ(gnuplotString("rock:1 256"), "'rock:1 256'");
    EXPECT_EQ(gnuplotString("it's"), "'it''s'");
    // In a plot's file name: what Windows' file systems refuse, as '-'.
    EXPECT_EQ(portableFileName("rock:1"), "rock-1");
    EXPECT_EQ(portableFileName("a<b>c\"d/e\\f|g?h*i\tj"), "a-b-c-d-e-f-g-h-i-j");
    EXPECT_EQ(portableFileName("it's x,y"), "it's x,y");
}

// A map named with a '|' or a line break (its file's name) keeps bench.md's tables whole
// (issue 47): the '|' escaped, the line break written as "\n"; every row of a table has as
// many cells as its header.
TEST(BenchReport, MarkdownTablesKeepTheirCellsWhateverTheMapsAreCalled) {
    EXPECT_EQ(markdownText("rock"), "rock");
    EXPECT_EQ(markdownText("a|b"), "a\\|b");
    EXPECT_EQ(markdownText("two\nlines|x"), "two\\nlines\\|x");
    std::vector<Measurement> rows;
    for (const std::string map : {"a|b", "two\nlines", "plain"}) {
        for (const char* param : {"exact", "1px", "4px"}) {
            Measurement r = row("multilevel", param, 10.0, 0.0, 0.0, 0.0);
            r.map = map;
            rows.push_back(r);
        }
        Measurement peer = row("maxmip", "64", 5.0, 0.0, 0.0, 0.0);
        peer.map = map;
        rows.push_back(peer);
    }
    const auto file =
        std::filesystem::temp_directory_path() / ("bench-md-" + std::to_string(::getpid()) + ".md");
    const std::string md =
        writeMarkdown(file, RunInfo{"llvmpipe", "2026-12-06", "bench", {}}, rows);
    std::filesystem::remove(file);
    // A row's cells: its '|' not escaped, less one (a row starts and ends with one).
    const auto cells = [](const std::string& line) {
        int bars = 0;
        for (std::size_t k = 0; k < line.size(); ++k)
            bars += line[k] == '|' && (k == 0 || line[k - 1] != '\\');
        return bars - 1;
    };
    std::istringstream lines(md);
    int header = -1, tableRows = 0;
    for (std::string line; std::getline(lines, line);) {
        if (line.empty() || line[0] != '|') {
            header = -1;
            continue;
        }
        if (header < 0) {
            header = cells(line);
            continue;
        }
        EXPECT_EQ(cells(line), header) << line;
        ++tableRows;
    }
    EXPECT_GT(tableRows, 6);
    EXPECT_NE(md.find("| a\\|b |"), std::string::npos) << md;
    EXPECT_NE(md.find("| two\\nlines |"), std::string::npos) << md;
}
