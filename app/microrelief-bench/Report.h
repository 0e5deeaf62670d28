// microrelief-bench's outputs: the CSV (one row per measurement), a Markdown summary
// with the equal-accuracy comparison and the targets, and gnuplot plots.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "Benchmark.h"

namespace microrelief::bench {

struct RunInfo {
    std::string renderer;  // GL_RENDERER
    std::string date;      // ISO date of the run
    std::string command;   // how it was run
};

// `text` into `file`, whole or not at all (a temporary beside it, renamed).
void writeTextAtomically(const std::filesystem::path& file, const std::string& text);
// A CSV field in quotes; a number with `digits` decimals.
std::string csvQuote(const std::string& text);
std::string fixed(double value, int digits);

// Rewrites the whole CSV atomically (called after every measurement, so a long run
// that is interrupted keeps what it measured).
void writeCsv(const std::filesystem::path& file, const RunInfo& info,
              const std::vector<Measurement>& rows);

// The summary table; returns the Markdown text it wrote.
std::string writeMarkdown(const std::filesystem::path& file, const RunInfo& info,
                          const std::vector<Measurement>& rows);

// time_vs_size.png and fetches_vs_size.png in `folder`, if gnuplot is installed;
// returns false (and says why) otherwise.
bool writePlots(const std::filesystem::path& folder, const RunInfo& info,
                const std::vector<Measurement>& rows, std::string& why);

}  // namespace microrelief::bench
