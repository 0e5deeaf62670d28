// microrelief-bench's equal-time pick and throughput (app/microrelief-bench/Report.h) on
// made-up measurements: which setting a peer is reported at, and on which pixels; the
// order in which settings are timed, the medians, spreads and ratios of their frames
// (Timing.h), and the CSV's columns for them.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
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

    const Measurement* relief = equalTime(all, "relief", multilevel, Clock::Wall);
    ASSERT_NE(relief, nullptr);
    EXPECT_EQ(relief->param, "16");
    EXPECT_EQ(relief->map, "relief");
    EXPECT_EQ(equalTime(all, "pom", multilevel, Clock::Wall), nullptr);
    const Measurement* steep = equalTime(all, "steep", multilevel, Clock::Wall);
    ASSERT_NE(steep, nullptr);
    EXPECT_EQ(steep->param, "32");
    // By the timer's times instead (100 - wall here, multilevel's 90 ms): relief 32 (90 ms)
    // and 64 (88 ms) are within it, and 64 is exact.
    const Measurement* byTimer = equalTime(all, "relief", multilevel, Clock::Timer);
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
    const Measurement* pick = equalTime(rows, "relief", multilevel, Clock::Wall);
    ASSERT_NE(pick, nullptr);
    EXPECT_EQ(pick->param, "16");
    EXPECT_DOUBLE_EQ(peerAccuracy(*pick, true).wrongPct(), 0.5);
    EXPECT_DOUBLE_EQ(peerAccuracy(*pick, false).wrongPct(), 6.0);

    // cone traces the walls: judged over every pixel.
    Measurement coneA = eight, coneB = sixteen;
    coneA.method = coneB.method = "cone";
    const std::vector<Measurement> cones{multilevel, coneA, coneB};
    const Measurement* cone = equalTime(cones, "cone", multilevel, Clock::Wall);
    ASSERT_NE(cone, nullptr);
    EXPECT_EQ(cone->param, "8");
}

TEST(BenchReport, ThroughputIsThePictureOverTheFramesTime) {
    Measurement r = row("multilevel", "exact", 6.5536, 0.0, 0.0, 0.0);  // 65536 pixels
    EXPECT_DOUBLE_EQ(megapixelsPerSecond(r, Clock::Wall), 10.0);
    r.msMedian = 2 * 6.5536;
    EXPECT_DOUBLE_EQ(megapixelsPerSecond(r, Clock::Timer), 5.0);
    r.msWallMedian = 0.0;
    EXPECT_EQ(megapixelsPerSecond(r, Clock::Wall), 0.0);  // not measured: no figure, no division
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

// Issue 52's steady ratios: every setting of a map and view timed in the same rounds, a
// frame each, each round starting one setting later (no setting always first, none always
// after the same one). Seen red with the rotation dropped (every round 0, 1, 2).
TEST(BenchTiming, SettingsAreTimedInTurnEachRoundStartingOneLater) {
    EXPECT_EQ(interleavedOrder(3, 4),
              (std::vector<std::size_t>{0, 1, 2, 1, 2, 0, 2, 0, 1, 0, 1, 2}));
    EXPECT_EQ(interleavedOrder(1, 3), (std::vector<std::size_t>{0, 0, 0}));
    EXPECT_TRUE(interleavedOrder(0, 10).empty());
    EXPECT_TRUE(interleavedOrder(4, 0).empty());
}

// The median and the quartiles, linear between order statistics (numpy's default
// percentile); the spread beside a median is half the interquartile range over it. Seen
// red with the quartiles taken at the nearest rank.
TEST(BenchTiming, SpreadIsTheMedianAndHalfTheInterquartileRange) {
    const Spread even = spreadOf({4.0, 1.0, 3.0, 2.0});
    EXPECT_DOUBLE_EQ(even.median, 2.5);
    EXPECT_DOUBLE_EQ(even.low, 1.75);
    EXPECT_DOUBLE_EQ(even.high, 3.25);
    EXPECT_DOUBLE_EQ(even.halfIqrPercent(), 30.0);  // 1.5 / 2 over 2.5
    const Spread odd = spreadOf({5.0, 1.0, 3.0, 2.0, 4.0});
    EXPECT_DOUBLE_EQ(odd.median, 3.0);
    EXPECT_DOUBLE_EQ(odd.low, 2.0);
    EXPECT_DOUBLE_EQ(odd.high, 4.0);
    const Spread one = spreadOf({7.0});
    EXPECT_DOUBLE_EQ(one.median, 7.0);
    EXPECT_DOUBLE_EQ(one.halfIqrPercent(), 0.0);
    EXPECT_DOUBLE_EQ(spreadOf({}).halfIqrPercent(), 0.0);  // nothing timed: no division
    EXPECT_DOUBLE_EQ(median({4.0, 1.0, 3.0, 2.0}), even.median);
}

// A ratio of two settings timed in the same rounds is taken round by round: a round slowed
// tenfold (another process on the core) slows both of its frames and leaves the ratio.
// Seen red with the ratio of the two medians instead (0.3 in the second case, not 2).
TEST(BenchTiming, RatiosArePairedRoundByRound) {
    const std::vector<double> peer{2.0, 20.0, 3.0, 40.0}, multilevel{1.0, 10.0, 1.5, 20.0};
    const Spread paired = pairedRatio(peer, multilevel);
    EXPECT_DOUBLE_EQ(paired.median, 2.0);
    EXPECT_DOUBLE_EQ(paired.halfIqrPercent(), 0.0);
    // The rounds' ratios 2, 0.3 and 3: their median 2, where the medians' ratio is 3 / 10.
    const Spread mixed = pairedRatio({2.0, 3.0, 30.0}, {1.0, 10.0, 10.0});
    EXPECT_DOUBLE_EQ(mixed.median, 2.0);
    EXPECT_DOUBLE_EQ(mixed.low, 1.15);
    EXPECT_DOUBLE_EQ(mixed.high, 2.5);
    // A round whose base was not timed (0 ms) is left out, not divided by.
    EXPECT_DOUBLE_EQ(pairedRatio({2.0, 5.0}, {1.0, 0.0}).median, 2.0);
}

// The tables' clock: the timer query on a GPU, the software clock on llvmpipe (whose timer
// query misses the rasteriser), or what --clock names.
TEST(BenchTiming, TheTablesClockFollowsTheRenderer) {
    EXPECT_EQ(resolveClock(Clock::Auto, "llvmpipe (LLVM 15.0.6, 256 bits)"), kSoftwareClock);
    EXPECT_EQ(resolveClock(Clock::Auto, "NVIDIA H200/PCIe/SSE2"), Clock::Timer);
    EXPECT_EQ(resolveClock(Clock::Wall, "llvmpipe (LLVM 15.0.6, 256 bits)"), Clock::Wall);
    EXPECT_EQ(resolveClock(Clock::Cpu, "NVIDIA H200/PCIe/SSE2"), Clock::Cpu);
    for (Clock clock : {Clock::Auto, Clock::Timer, Clock::Wall, Clock::Cpu})
        EXPECT_EQ(parseClock(clockName(clock)), clock);
    EXPECT_THROW(parseClock("gpu"), microrelief::Error);
}

// bench.csv's columns for the steady ratios (appended: a reader by name finds the old ones
// where they were): the CPU-time median, the clock the tables read, the spread of that
// clock's frames, and each row's ratio to the multilevel method's exact time on the same
// map, size and view, paired round by round, with its spread; bench.md's equal-accuracy
// cell gives the same ratio. Seen red with the ratio taken on the wall clock's frames.
TEST(BenchReport, TheCsvHasEachRowsRatioAndSpreads) {
    Measurement ml = row("multilevel", "exact", 10.0, 0.0, 0.0, 0.0);
    ml.gpuFrames = {1.0, 1.0, 1.0, 1.0};
    ml.wallFrames = {10.0, 10.0, 10.0, 10.0};
    ml.cpuFrames = {4.0, 8.0, 4.0, 4.0};
    ml.msCpuMedian = 4.0;
    Measurement cone = row("cone", "exact", 15.0, 0.0, 0.0, 0.0);
    cone.gpuFrames = {1.0, 1.0, 1.0, 1.0};
    cone.wallFrames = {15.0, 15.0, 15.0, 15.0};
    cone.cpuFrames = {6.0, 12.0, 6.0, 8.0};  // ratios 1.5, 1.5, 1.5, 2
    cone.msCpuMedian = 7.0;
    Measurement elsewhere = cone;  // on a map with no multilevel row: no ratio
    elsewhere.map = "rock";
    const std::vector<Measurement> rows{ml, cone, elsewhere};
    const auto file = std::filesystem::temp_directory_path() /
                      ("bench-csv-" + std::to_string(::getpid()) + ".csv");
    const auto read = [&](const std::string& renderer, Clock clock) {
        writeCsv(file, RunInfo{renderer, "2026-12-07", "bench", {}, clock}, rows);
        std::ifstream in(file);
        std::vector<std::vector<std::string>> table;
        for (std::string line; std::getline(in, line);) {
            std::vector<std::string> fields;
            bool quoted = false;
            std::string field;
            for (char c : line) {
                if (c == '"') quoted = !quoted;
                if (c == ',' && !quoted) {
                    fields.push_back(field);
                    field.clear();
                } else {
                    field += c;
                }
            }
            fields.push_back(field);
            table.push_back(fields);
        }
        std::filesystem::remove(file);
        return table;
    };
    const auto csv = read("llvmpipe (LLVM 15.0.6, 256 bits)", Clock::Cpu);
    ASSERT_EQ(csv.size(), 4u);
    const auto column = [&](const std::string& name) {
        const auto at = std::find(csv[0].begin(), csv[0].end(), name);
        EXPECT_NE(at, csv[0].end()) << name;
        return static_cast<std::size_t>(at - csv[0].begin());
    };
    EXPECT_EQ(csv[0][0], "method");  // the old columns first, where they were
    EXPECT_EQ(csv[0][9], "ms_wall_median");
    const std::size_t cpu = column("ms_cpu_median"), clock = column("clock"),
                      spread = column("ms_spread_pct"), ratio = column("ratio_to_multilevel"),
                      ratioSpread = column("ratio_spread_pct");
    for (std::size_t k = 1; k < csv.size(); ++k) ASSERT_EQ(csv[k].size(), csv[0].size());
    EXPECT_EQ(csv[1][cpu], "4.0000");
    EXPECT_EQ(csv[1][clock], "cpu");
    EXPECT_EQ(csv[1][spread], "12.50");  // quartiles 4 and 5 about 4: 0.5 / 4
    EXPECT_EQ(csv[1][ratio], "1.0000");
    EXPECT_EQ(csv[2][ratio], "1.5000");
    EXPECT_EQ(csv[2][ratioSpread], "4.17");  // quartiles 1.5 and 1.625: 0.0625 / 1.5
    EXPECT_EQ(csv[3][ratio], "");
    EXPECT_EQ(csv[3][ratioSpread], "");
    // On a GPU the timer query's frames, all alike here.
    const auto gpu = read("NVIDIA H200/PCIe/SSE2", Clock::Auto);
    EXPECT_EQ(gpu[2][clock], "timer");
    EXPECT_EQ(gpu[2][ratio], "1.0000");
    EXPECT_EQ(gpu[2][ratioSpread], "0.00");

    const auto mdFile = std::filesystem::temp_directory_path() /
                        ("bench-ratio-" + std::to_string(::getpid()) + ".md");
    const std::string md =
        writeMarkdown(mdFile, RunInfo{"llvmpipe", "2026-12-07", "bench", {}, Clock::Cpu}, rows);
    std::filesystem::remove(mdFile);
    EXPECT_NE(md.find("| exact: 7.00 ms (1.50x +-4 %; "), std::string::npos) << md;
}
