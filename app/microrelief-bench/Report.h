// microrelief-bench's outputs: the CSV (one row per measurement), a Markdown summary
// with the equal-accuracy comparison and the targets, and gnuplot plots.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "Benchmark.h"
#include "Timing.h"

namespace microrelief::bench {

// The clock the tables, ratios and plots read (--clock): the GL timer query's, the wall
// clock's to glFinish, or the process's CPU time to glFinish (Timing.h). Auto: the timer
// query on a GPU; on a CPU rasteriser (softwareRenderer), whose timer query misses the
// deferred rasterisation, kSoftwareClock.
enum class Clock { Auto, Timer, Wall, Cpu };
// The clock of a CPU rasteriser's tables: its CPU time, which other processes on the
// machine's cores hardly move, where they move its wall time by up to 3x. On 2 shared cores
// (load 2 to 12) each ratio to the multilevel method varied by at most 7 % over nine runs
// on it, and by up to 47 % over five on the wall clock, both paired round by round
// (docs/perf/2026-12-07-steady-ratios.md).
inline constexpr Clock kSoftwareClock = Clock::Cpu;
Clock parseClock(const std::string& name);  // auto, timer, wall, cpu; Error(BadInput) else
const char* clockName(Clock clock);
Clock resolveClock(Clock clock, const std::string& renderer);

struct RunInfo {
    std::string renderer;            // GL_RENDERER
    std::string date;                // ISO date of the run
    std::string command;             // how it was run
    std::vector<std::string> notes;  // what was asked for and not measured, a line each
    Clock clock = Clock::Auto;       // what the tables read (resolveClock)
};
Clock clockOf(const RunInfo& info);

// A row's median frame time and its frames in round order, on `clock` (not Auto).
double frameMs(const Measurement& r, Clock clock);
const std::vector<double>& frameSeries(const Measurement& r, Clock clock);

// The ratio the tables give, `r`'s time over `base`'s (the multilevel method's exact, the
// same map, size and view): the median and quartiles of the rounds' ratios where both were
// timed in the same rounds (Timing.h: pairedRatio), else the ratio of their medians.
Spread timeRatio(const Measurement& r, const Measurement& base, Clock clock);

// `name` as a part of a file name any file system takes: each of < > : " / \ | ? * and
// each control character as '-' ("rock:1" -> "rock-1"; the Pareto plots' names).
std::string portableFileName(const std::string& name);

// `text` into `file`, whole or not at all (a temporary beside it, renamed).
void writeTextAtomically(const std::filesystem::path& file, const std::string& text);
// A CSV field in quotes, a quote inside doubled.
std::string csvQuote(const std::string& text);
// A CSV field as it is where it holds no comma, quote or line break, else csvQuote'd (a map
// named by its file may hold any of them).
std::string csvField(const std::string& text);
// `text` (a map's name, a note naming one) as Markdown shows it in a table cell or a list
// item: a line break or other control character written as its escape ("\n",
// core/Text.h: printable) and '|' as "\|", so that a map named "a|b" or with a line
// break in its name keeps the row whole.
std::string markdownText(const std::string& text);
// A gnuplot string in single quotes, a quote inside doubled: a file or map name as written.
std::string gnuplotString(const std::string& text);
// A number with `digits` decimals.
std::string fixed(double value, int digits);

// A peer's figures on the pixels it is measured on: every pixel for the methods that trace
// the side walls and the bottom face, those whose rays come in through the top face for
// the others (the multilevel method's on the same pixels to hold them against).
struct PeerAccuracy {
    double mismatchPct = 0.0, offPct = 0.0, p99Texels = 0.0;
    // What the equal-time pick minimises: hit/miss disagreements (% of pixels) plus hits
    // off by more than half a texel (% of hits).
    double wrongPct() const { return mismatchPct + offPct; }
};
PeerAccuracy peerAccuracy(const Measurement& r, bool topOnly);

// Equal-time accuracy: of `method`'s settings on `multilevel`'s map, size and view, those
// whose time on `clock` is within the multilevel method's exact time, the most accurate:
// the fewest wrong (wrongPct), then the smallest p99 error, then the faster. Null where
// every setting takes longer.
const Measurement* equalTime(const std::vector<Measurement>& rows, const std::string& method,
                             const Measurement& multilevel, Clock clock);

// Pixels a second: the whole picture over the frame's time on `clock` (as frame rates at
// a resolution are quoted; on the CPU clock, per second of the CPU's work), millions.
double megapixelsPerSecond(const Measurement& r, Clock clock);

// Rewrites the whole CSV atomically (called after every measurement, so a long run
// that is interrupted keeps what it measured).
void writeCsv(const std::filesystem::path& file, const RunInfo& info,
              const std::vector<Measurement>& rows);

// The summary table; returns the Markdown text it wrote.
std::string writeMarkdown(const std::filesystem::path& file, const RunInfo& info,
                          const std::vector<Measurement>& rows);

// time_vs_size.png and fetches_vs_size.png in `folder`, and a Pareto plot of time against
// error for each map and size, pareto-MAP-SIZE.png (every method's settings, a panel per
// view; MAP as portableFileName writes it, a second map written alike gets -2), if gnuplot
// is installed; returns false (and says why) otherwise. Each picture is
// written whole or not at all.
bool writePlots(const std::filesystem::path& folder, const RunInfo& info,
                const std::vector<Measurement>& rows, std::string& why);

}  // namespace microrelief::bench
