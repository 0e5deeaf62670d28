#include "Report.h"

#include "Timing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "SceneOptions.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"
#include "microrelief/io/AtomicFile.h"

namespace microrelief::bench {

// Text files get the same whole-or-nothing treatment as images (io/AtomicFile.h).
void writeTextAtomically(const std::filesystem::path& file, const std::string& text) {
    writeFileAtomically(file, text);
}

std::string csvQuote(const std::string& text) {
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string csvField(const std::string& text) {
    return text.find_first_of(",\"\r\n") == std::string::npos ? text : csvQuote(text);
}

std::string portableFileName(const std::string& name) {
    std::string portable;
    for (const char c : name) {
        const bool control = static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
        portable +=
            control || std::string_view("<>:\"/\\|?*").find(c) != std::string_view::npos ? '-' : c;
    }
    return portable;
}

std::string markdownText(const std::string& text) {
    std::string out;
    for (const char c : printable(text)) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

std::string gnuplotString(const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
    return out + "'";
}

std::string fixed(double value, int digits) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
    return buffer;
}

namespace {

// A peer reaches the multilevel method's accuracy when neither of its figures is worse
// by more than 0.01 percentage points: a handful of pixels at these sizes (7 of 65 536
// at 256 x 256), the rays that graze an edge, where float and double may differ.
constexpr double kEqualAccuracyMarginPct = 0.01;

// Whether a method traces the side walls and the bottom face; the others are measured on
// the top surface only (issue 5), against the multilevel method on the same pixels.
bool tracesTheSolid(const std::string& method) {
    return methodTracesTheSolid(parseMethod(method));
}

// A markdown table's header: the leading columns, then a column a peer, marked "(top)"
// where it is measured on the top surface only.
void peerTableHeader(std::ostream& md, const std::vector<std::string>& leading,
                     const std::vector<std::string>& peers) {
    md << '|';
    for (const std::string& column : leading) md << ' ' << column << " |";
    for (const std::string& p : peers)
        md << ' ' << p << (tracesTheSolid(p) ? "" : " (top)") << " |";
    md << "\n|";
    for (std::size_t k = 0; k < leading.size() + peers.size(); ++k) md << "---|";
    md << '\n';
}

bool reaches(const Measurement& peer, const Measurement& multilevel) {
    if (!tracesTheSolid(peer.method)) {
        return peer.topCoverageMismatchPct <=
                   multilevel.topCoverageMismatchPct + kEqualAccuracyMarginPct &&
               peer.topOffHalfTexelPct <= multilevel.topOffHalfTexelPct + kEqualAccuracyMarginPct;
    }
    return peer.coverageMismatchPct <= multilevel.coverageMismatchPct + kEqualAccuracyMarginPct &&
           peer.offHalfTexelPct <= multilevel.offHalfTexelPct + kEqualAccuracyMarginPct;
}

using Key = std::tuple<std::string, int, int>;  // map, size, view

Key keyOf(const Measurement& r) {
    return {r.map, r.mapSize, r.viewDegrees};
}

// What the tables' times are, as bench.md's first line says.
std::string clockDescription(Clock clock) {
    switch (clock) {
        case Clock::Cpu:
            return "the process's CPU time to glFinish, every thread (the rasteriser's "
                   "included; on a CPU rasteriser the GL timer query misses its work)";
        case Clock::Wall:
            return "the wall time to glFinish";
        default:
            return "GL_TIME_ELAPSED timer queries";
    }
}

std::string clockLabel(Clock clock) {
    switch (clock) {
        case Clock::Cpu:
            return "frame time, process CPU time (ms)";
        case Clock::Wall:
            return "frame time, wall clock (ms)";
        default:
            return "GPU time per frame (ms)";
    }
}

const Measurement* find(const std::vector<Measurement>& rows, const Key& key,
                        const std::string& method, const std::string& param) {
    for (const Measurement& r : rows) {
        if (Key{r.map, r.mapSize, r.viewDegrees} == key && r.method == method && r.param == param)
            return &r;
    }
    return nullptr;
}

// The cheapest-to-reach setting: the smallest budget (rows are in increasing budget order).
const Measurement* equalAccuracy(const std::vector<Measurement>& rows, const Key& key,
                                 const std::string& method, const Measurement& multilevel) {
    for (const Measurement& r : rows) {
        if (Key{r.map, r.mapSize, r.viewDegrees} == key && r.method == method &&
            reaches(r, multilevel))
            return &r;
    }
    return nullptr;
}

std::vector<Key> keys(const std::vector<Measurement>& rows) {
    std::vector<Key> out;
    for (const Measurement& r : rows) {
        const Key k{r.map, r.mapSize, r.viewDegrees};
        if (std::find(out.begin(), out.end(), k) == out.end()) out.push_back(k);
    }
    return out;
}

std::vector<std::string> methods(const std::vector<Measurement>& rows) {
    std::vector<std::string> out;
    for (const Measurement& r : rows) {
        if (std::find(out.begin(), out.end(), r.method) == out.end()) out.push_back(r.method);
    }
    return out;
}

// Issue 11's figures for the curved bases: the multilevel method on the column and the
// sphere beside the plane, the same map and view; its fetches against 2 (log2 N + 1);
// the growth from 256 to the largest map beside the plane's; what pom and relief get
// wrong at their largest budget.
std::string curvedSection(const std::vector<Measurement>& rows, Clock clock) {
    std::vector<std::string> curved;
    for (const Measurement& r : rows) {
        if (r.base != "plane" && r.interpolation == "bilinear" &&
            r.map.rfind(kResampledRelief + "-", 0) == 0 &&
            std::find(curved.begin(), curved.end(), r.map) == curved.end())
            curved.push_back(r.map);
    }
    if (curved.empty()) return "";
    std::ostringstream md;
    md << "\nCurved bases, multilevel method exact, beside the plane for the same map and view "
          "(hit %: pixels the relief covers; per hit pixel: the time over the hit pixels, against "
          "the plane's, target <= 2; fetches target: 2 (log2 N + 1)); pom and relief at their "
          "largest budget, on the pixels whose rays come in through the shell:\n\n";
    md << "| map | size | view | ms | plane ms | hit % (plane) | per hit pixel vs plane | "
          "fetches (target) | pom off % / mismatch % | relief off % / mismatch % |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n";
    const auto largest = [&](const Key& key, const std::string& method) {
        const Measurement* best = nullptr;
        for (const Measurement& r : rows) {
            if (Key{r.map, r.mapSize, r.viewDegrees} == key && r.method == method &&
                (!best || std::stoi(r.param) > std::stoi(best->param)))
                best = &r;
        }
        return best;
    };
    for (const Key& key : keys(rows)) {
        if (std::find(curved.begin(), curved.end(), std::get<0>(key)) == curved.end()) continue;
        const Measurement* ml = find(rows, key, "multilevel", "exact");
        const Measurement* plane = find(
            rows, Key{kResampledRelief, std::get<1>(key), std::get<2>(key)}, "multilevel", "exact");
        if (!ml) continue;
        const double perHit =
            plane && ml->hitPct > 0.0 && plane->hitPct > 0.0
                ? (frameMs(*ml, clock) / ml->hitPct) / (frameMs(*plane, clock) / plane->hitPct)
                : 0.0;
        md << "| " << markdownText(std::get<0>(key)) << " | " << std::get<1>(key) << " | "
           << std::get<2>(key) << "° | " << fixed(frameMs(*ml, clock), 2) << " | "
           << (plane ? fixed(frameMs(*plane, clock), 2) : "-") << " | " << fixed(ml->hitPct, 0)
           << " (" << (plane ? fixed(plane->hitPct, 0) : "-") << ") | "
           << (perHit > 0.0 ? fixed(perHit, 2) + "x" : "-") << " | " << fixed(ml->fetchesMean, 1)
           << " (" << fixed(2.0 * (std::log2(ml->mapSize) + 1.0), 0) << ") |";
        for (const char* peer : {"pom", "relief"}) {
            const Measurement* p = largest(key, peer);
            if (p) {
                md << ' ' << p->param << ": " << fixed(p->topOffHalfTexelPct, 2) << " / "
                   << fixed(p->topCoverageMismatchPct, 2) << " |";
            } else {
                md << " - |";
            }
        }
        md << '\n';
    }
    // Growth with the map's size at the view nearest 45 degrees, against the plane's.
    for (const std::string& name : curved) {
        std::map<int, const Measurement*> exact, flat;
        int view = -1;
        for (const Measurement& r : rows) {
            if (r.map == name && (view < 0 || std::abs(r.viewDegrees - 45) < std::abs(view - 45)))
                view = r.viewDegrees;
        }
        for (const Measurement& r : rows) {
            if (r.method != "multilevel" || r.param != "exact" || r.viewDegrees != view) continue;
            if (r.map == name) exact[r.mapSize] = &r;
            if (r.map == kResampledRelief) flat[r.mapSize] = &r;
        }
        if (!exact.count(256) || exact.size() < 2) continue;
        const int big = exact.rbegin()->first;
        md << "- " << markdownText(name) << ": time at " << big << " / time at 256, " << view
           << "°: " << fixed(frameMs(*exact[big], clock) / frameMs(*exact[256], clock), 2);
        if (flat.count(256) && flat.count(big))
            md << " (the plane's: "
               << fixed(frameMs(*flat[big], clock) / frameMs(*flat[256], clock), 2)
               << "; target: no worse)";
        md << ".\n";
    }
    return md.str();
}

// Issue 12's figures: the biquadratic last level beside the bilinear one for the same map,
// base and view, with the exact methods; targets: time <= 1.5x, fetches <= 1.2x.
std::string biquadraticSection(const std::vector<Measurement>& rows, Clock clock) {
    const std::string suffix = "-biquadratic";
    std::ostringstream md;
    bool any = false;
    for (const Key& key : keys(rows)) {
        const std::string& name = std::get<0>(key);
        if (name.size() <= suffix.size() ||
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const Key bilinear{name.substr(0, name.size() - suffix.size()), std::get<1>(key),
                           std::get<2>(key)};
        for (const auto& [method, param] :
             {std::pair<std::string, std::string>{"multilevel", "exact"},
              {"maxmip", "exact"},
              {"cone", "exact"}}) {
            const Measurement* q = find(rows, key, method, param);
            const Measurement* l = find(rows, bilinear, method, param);
            if (!q || !l) continue;
            if (!any) {
                md << "\nBiquadratic last level beside the bilinear one, the same map, base and "
                      "view (targets: time <= 1.5x, fetches <= 1.2x); traversal: of the "
                      "fetches, the reads of the bounds (the pyramid, the same for both "
                      "levels; cone's map, whose apexes the biquadratic level raises), the "
                      "rest the last level's:\n\n"
                      "| map | size | view | method | ms | bilinear ms | time | fetches | "
                      "bilinear fetches | fetches ratio | traversal | bilinear traversal | "
                      "mismatch % | off % |\n"
                      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
                any = true;
            }
            md << "| " << markdownText(name) << " | " << std::get<1>(key) << " | "
               << std::get<2>(key) << "° | " << method << " | " << fixed(frameMs(*q, clock), 2)
               << " | " << fixed(frameMs(*l, clock), 2) << " | "
               << fixed(frameMs(*q, clock) / frameMs(*l, clock), 2) << "x | "
               << fixed(q->fetchesMean, 1) << " | " << fixed(l->fetchesMean, 1) << " | "
               << fixed(l->fetchesMean > 0.0 ? q->fetchesMean / l->fetchesMean : 0.0, 2) << "x | "
               << fixed(q->boundFetchesMean, 1) << " | " << fixed(l->boundFetchesMean, 1) << " | "
               << fixed(q->coverageMismatchPct, 3) << " | " << fixed(q->offHalfTexelPct, 3)
               << " |\n";
        }
    }
    return md.str();
}

// Equal-time accuracy: for each peer, its most accurate setting within the
// multilevel method's exact time.
std::string equalTimeSection(const std::vector<Measurement>& rows, Clock clock,
                             const std::vector<std::string>& peers) {
    std::ostringstream md;
    md << "\nEqual-time accuracy: for each peer, of its settings whose time is within the "
          "multilevel method's, the most accurate (the fewest hit/miss disagreements plus hits "
          "off by more than half a texel, then the smallest p99 error): its setting, hit/miss "
          "%, off % and p99 error in texels (over the hits), and its time. *none*: every "
          "setting takes longer (its cheapest in brackets). Peers marked *(top)* on the pixels "
          "whose rays come in through the top face.\n\n";
    peerTableHeader(
        md, {"map", "size", "view", "multilevel ms", "hit/miss %", "off %", "p99 texels"}, peers);
    for (const Key& key : keys(rows)) {
        const Measurement* ml = find(rows, key, "multilevel", "exact");
        if (!ml || ml->interpolation != "bilinear") continue;
        md << "| " << markdownText(std::get<0>(key)) << " | " << std::get<1>(key) << " | "
           << std::get<2>(key) << "° | " << fixed(frameMs(*ml, clock), 2) << " | "
           << fixed(ml->coverageMismatchPct, 3) << " | " << fixed(ml->offHalfTexelPct, 3) << " | "
           << fixed(ml->p99ErrorTexels, 2) << " |";
        for (const std::string& p : peers) {
            const bool top = !tracesTheSolid(p);
            if (const Measurement* pick = equalTime(rows, p, *ml, clock)) {
                const PeerAccuracy a = peerAccuracy(*pick, top);
                md << ' ' << pick->param << ": " << fixed(a.mismatchPct, 3) << " / "
                   << fixed(a.offPct, 3) << " / " << fixed(a.p99Texels, 2) << " ("
                   << fixed(frameMs(*pick, clock), 2) << " ms) |";
                continue;
            }
            const Measurement* cheapest = nullptr;
            for (const Measurement& r : rows) {
                if (keyOf(r) == key && r.method == p &&
                    (!cheapest || frameMs(r, clock) < frameMs(*cheapest, clock)))
                    cheapest = &r;
            }
            md << (cheapest ? " none (" + cheapest->param + ": " +
                                  fixed(frameMs(*cheapest, clock), 2) + " ms) |"
                            : std::string(" - |"));
        }
        md << '\n';
    }
    return md.str();
}

// Figures to hold against published ones: throughput and fetches beside each
// time (every setting), the traversal's reads of its bounds beside the total.
std::string throughputSection(const std::vector<Measurement>& rows, Clock clock) {
    std::ostringstream md;
    md << "\nThroughput and fetches: each method's first (exact, or fewest steps) and the "
          "equal-accuracy or largest setting; Mpix/s: the whole picture over the frame's time; "
          "fetches: mean texture reads a pixel in the relief's box, of them the traversal's "
          "reads of its bounds (max pyramid or cone map), the rest the samples' (the last "
          "level, the surface).\n\n"
          "| map | size | view | method | setting | ms | Mpix/s | fetches | bounds | samples |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Key& key : keys(rows)) {
        const Measurement* ml = find(rows, key, "multilevel", "exact");
        for (const std::string& method : methods(rows)) {
            const Measurement *first = nullptr, *last = nullptr;
            for (const Measurement& r : rows) {
                if (keyOf(r) != key || r.method != method) continue;
                if (!first) first = &r;
                last = &r;
            }
            if (!first) continue;
            const Measurement* eq = ml ? equalAccuracy(rows, key, method, *ml) : nullptr;
            const Measurement* second = method == "multilevel" ? first : eq ? eq : last;
            for (const Measurement* r : {first, second}) {
                md << "| " << markdownText(std::get<0>(key)) << " | " << std::get<1>(key) << " | "
                   << std::get<2>(key) << "° | " << method << " | " << r->param << " | "
                   << fixed(frameMs(*r, clock), 2) << " | "
                   << fixed(megapixelsPerSecond(*r, clock), 2) << " | " << fixed(r->fetchesMean, 1)
                   << " | " << fixed(r->boundFetchesMean, 1) << " | "
                   << fixed(r->fetchesMean - r->boundFetchesMean, 1) << " |\n";
                if (second == first) break;
            }
        }
    }
    return md.str();
}

// The coarse pass (issue 52): the multilevel method's exact frame with each tile size
// measured, beside the single pass on the same map and view.
std::string coarseSection(const std::vector<Measurement>& rows, Clock clock) {
    std::ostringstream md;
    for (const Key& key : keys(rows)) {
        const Measurement* exact = find(rows, key, "multilevel", "exact");
        if (!exact) continue;
        for (const Measurement& r : rows) {
            if (keyOf(r) != key || r.method != "multilevel" ||
                r.param.rfind("exact+coarse", 0) != 0)
                continue;
            if (md.tellp() == 0) {
                md << "\nThe coarse pass (`--coarse-tiles`): the multilevel method's exact frame "
                      "with a pass over T x T tiles of pixels that starts each pixel's walk where "
                      "its tile's rays may first meet the relief, beside the single pass; its "
                      "time over the single pass's (paired rounds), fetches a pixel in the box "
                      "(the pass's own reads among them), and its accuracy (the same as the "
                      "single pass's but for float rounding).\n\n"
                      "| map | size | view | single ms | fetches | tile | ms | over single | "
                      "fetches (pass) | off % (single) |\n"
                      "|---|---|---|---|---|---|---|---|---|---|\n";
            }
            const Spread ratio = timeRatio(r, *exact, clock);
            md << "| " << markdownText(std::get<0>(key)) << " | " << std::get<1>(key) << " | "
               << std::get<2>(key) << "° | " << fixed(frameMs(*exact, clock), 2) << " | "
               << fixed(exact->fetchesMean, 1) << " | " << r.param.substr(12) << " | "
               << fixed(frameMs(r, clock), 2) << " | " << fixed(ratio.median, 2) << "x +-"
               << fixed(ratio.halfIqrPercent(), 0) << " % | " << fixed(r.fetchesMean, 1) << " ("
               << fixed(r.coarseFetchesMean, 1) << ") | " << fixed(r.offHalfTexelPct, 3) << " ("
               << fixed(exact->offHalfTexelPct, 3) << ") |\n";
        }
    }
    return md.str();
}

// Costs: GPU bytes a map texel and the build of each method's bounds, per map.
std::string costSection(const std::vector<Measurement>& rows) {
    std::ostringstream md;
    md << "\nMemory and preprocessing: the GPU textures each method reads (the samples, R32F, "
          "and its bounds: the multilevel method's overlapping windows and maxmip's quadtree, "
          "R16F mip chains; cone's and rcsm's cone maps, RG16F), bytes a map texel; and the "
          "time to build its bounds, wall ms to glFinish (gpu: median of three builds, or the "
          "first where it took a second or more; cpu: "
          "one build, read-back and upload included; -: nothing to build), cone's map on the "
          "GPU and on the CPU.\n\n"
          "| map | size | method | bytes / texel | preprocessing ms |\n|---|---|---|---|---|\n";
    std::vector<std::tuple<std::string, int, std::string>> seen;
    for (const Measurement& r : rows) {
        const auto id = std::make_tuple(r.map, r.mapSize, r.method);
        if (std::find(seen.begin(), seen.end(), id) != seen.end()) continue;
        seen.push_back(id);
        md << "| " << markdownText(r.map) << " | " << r.mapSize << " | " << r.method << " | "
           << fixed(r.bytesPerTexel, 2) << " | "
           << (r.preprocessWhere == "-" ? std::string("-")
                                        : fixed(r.preprocessMs, 1) + " (" + r.preprocessWhere + ")")
           << (r.preprocessWhere == "gpu" && r.cpuPreprocessMs >= 0.0
                   ? ", " + fixed(r.cpuPreprocessMs, 1) + " (cpu)"
                   : std::string())
           << " |\n";
    }
    return md.str();
}

// The Pareto plots: for each map and size, a panel per view, every method's settings as
// points of time against error, joined in the order of their settings. Error: % of the
// pixels a method is measured on whose hit/miss disagrees with the exact reference plus %
// of hits off by more than half a texel (PeerAccuracy::wrongPct), drawn at 0.001 where
// it is 0 (a log axis). Adds the pictures' names to `outputs`; the data beside them.
std::string paretoScript(const std::filesystem::path& folder, const std::vector<Measurement>& rows,
                         Clock clock, std::vector<std::string>& outputs) {
    constexpr double kZeroDrawnAt = 1e-3;
    // A colour and a point type per method, the same in every panel and picture (gnuplot's
    // own cycle repeats after eight).
    const std::vector<std::string> all = methods(rows);
    const auto methodIndex = [&](const std::string& method) {
        return static_cast<std::size_t>(std::find(all.begin(), all.end(), method) - all.begin());
    };
    const std::vector<std::string> colours{"#9400d3", "#009e73", "#56b4e9", "#e69f00", "#f0e442",
                                           "#0072b2", "#e51e10", "#000000", "#d55e00", "#808080"};
    std::vector<std::pair<std::string, int>> maps;
    for (const Measurement& r : rows) {
        if (r.interpolation != "bilinear") continue;
        if (std::find(maps.begin(), maps.end(), std::make_pair(r.map, r.mapSize)) == maps.end())
            maps.emplace_back(r.map, r.mapSize);
    }
    std::ostringstream script;
    std::set<std::string> stems;  // each plot its own file, whatever the maps' names
    for (const auto& [map, size] : maps) {
        std::vector<int> views;
        for (const Measurement& r : rows) {
            if (r.map == map && r.mapSize == size &&
                std::find(views.begin(), views.end(), r.viewDegrees) == views.end())
                views.push_back(r.viewDegrees);
        }
        std::string stem = "pareto-" + portableFileName(map) + "-" + std::to_string(size);
        for (int k = 2; !stems.insert(stem).second; ++k)
            stem = "pareto-" + portableFileName(map) + "-" + std::to_string(size) + "-" +
                   std::to_string(k);
        std::ostringstream data;
        int block = 0;
        std::vector<std::vector<std::pair<int, std::string>>> panels;  // (block, method)
        for (int view : views) {
            panels.emplace_back();
            for (const std::string& method : methods(rows)) {
                std::ostringstream points;
                for (const Measurement& r : rows) {
                    if (r.map != map || r.mapSize != size || r.viewDegrees != view ||
                        r.method != method)
                        continue;
                    const PeerAccuracy a = peerAccuracy(r, !tracesTheSolid(method));
                    points << frameMs(r, clock) << ' ' << std::max(a.wrongPct(), kZeroDrawnAt)
                           << " \"" << r.param << "\"\n";
                }
                if (points.str().empty()) continue;
                data << points.str() << "\n\n";
                panels.back().emplace_back(block++, method);
            }
        }
        writeTextAtomically(folder / (stem + ".txt"), data.str());
        outputs.push_back(stem + ".png");
        script << "set terminal pngcairo size " << 520 * views.size() << ",520 noenhanced\n"
               << "set output " << gnuplotString((folder / (stem + ".png.part")).string()) << "\n"
               << "unset logscale\nset logscale xy\nset key inside top right font ',9'\n"
               << "set grid\nset yrange [" << 0.5 * kZeroDrawnAt << ":200]\n"
               << "set xlabel '" << clockLabel(clock)
               << "'\nset ylabel '% wrong: hit/miss + hits off > 1/2 texel (0 drawn at "
               << kZeroDrawnAt << ")'\n"
               << "set multiplot layout 1," << views.size() << " title "
               << gnuplotString(printable(map) + " " + std::to_string(size) +
                                ": time against error, every setting")
               << "\n";
        for (std::size_t v = 0; v < views.size(); ++v) {
            script << "set title 'view " << views[v] << " deg'\nplot ";
            for (std::size_t k = 0; k < panels[v].size(); ++k) {
                script << (k ? ", " : "") << gnuplotString((folder / (stem + ".txt")).string())
                       << " index " << panels[v][k].first
                       << " using 1:2 with linespoints pointsize 1.2 pointtype "
                       << 1 + methodIndex(panels[v][k].second) << " lc rgb '"
                       << colours[methodIndex(panels[v][k].second) % colours.size()] << "' title '"
                       << panels[v][k].second << "'";
            }
            script << '\n';
        }
        script << "unset multiplot\nset autoscale y\n";
    }
    return script.str();
}

}  // namespace

Clock parseClock(const std::string& name) {
    for (Clock clock : {Clock::Auto, Clock::Timer, Clock::Wall, Clock::Cpu})
        if (name == clockName(clock)) return clock;
    throwBadInput("--clock: '" + name + "' is not one of auto, timer, wall, cpu");
}

const char* clockName(Clock clock) {
    switch (clock) {
        case Clock::Auto:
            return "auto";
        case Clock::Timer:
            return "timer";
        case Clock::Wall:
            return "wall";
        case Clock::Cpu:
            return "cpu";
    }
    return "auto";
}

Clock resolveClock(Clock clock, const std::string& renderer) {
    if (clock != Clock::Auto) return clock;
    return softwareRenderer(renderer) ? kSoftwareClock : Clock::Timer;
}

Clock clockOf(const RunInfo& info) {
    return resolveClock(info.clock, info.renderer);
}

double frameMs(const Measurement& r, Clock clock) {
    return clock == Clock::Cpu ? r.msCpuMedian : clock == Clock::Wall ? r.msWallMedian : r.msMedian;
}

const std::vector<double>& frameSeries(const Measurement& r, Clock clock) {
    return clock == Clock::Cpu ? r.cpuFrames : clock == Clock::Wall ? r.wallFrames : r.gpuFrames;
}

Spread timeRatio(const Measurement& r, const Measurement& base, Clock clock) {
    const std::vector<double>&a = frameSeries(r, clock), &b = frameSeries(base, clock);
    if (!a.empty() && a.size() == b.size()) return pairedRatio(a, b);
    const double ratio =
        frameMs(base, clock) > 0.0 ? frameMs(r, clock) / frameMs(base, clock) : 0.0;
    return {ratio, ratio, ratio};
}

PeerAccuracy peerAccuracy(const Measurement& r, bool topOnly) {
    if (topOnly) return {r.topCoverageMismatchPct, r.topOffHalfTexelPct, r.topP99ErrorTexels};
    return {r.coverageMismatchPct, r.offHalfTexelPct, r.p99ErrorTexels};
}

const Measurement* equalTime(const std::vector<Measurement>& rows, const std::string& method,
                             const Measurement& multilevel, Clock clock) {
    const bool top = !tracesTheSolid(method);
    const Measurement* best = nullptr;
    for (const Measurement& r : rows) {
        if (keyOf(r) != keyOf(multilevel) || r.method != method ||
            frameMs(r, clock) > frameMs(multilevel, clock))
            continue;
        if (!best) {
            best = &r;
            continue;
        }
        const PeerAccuracy a = peerAccuracy(r, top), b = peerAccuracy(*best, top);
        if (std::make_tuple(a.wrongPct(), a.p99Texels, frameMs(r, clock)) <
            std::make_tuple(b.wrongPct(), b.p99Texels, frameMs(*best, clock)))
            best = &r;
    }
    return best;
}

double megapixelsPerSecond(const Measurement& r, Clock clock) {
    const double ms = frameMs(r, clock);
    return ms > 0.0 ? static_cast<double>(r.width) * r.height / (ms * 1e3) : 0.0;
}

void writeCsv(const std::filesystem::path& file, const RunInfo& info,
              const std::vector<Measurement>& rows) {
    std::ostringstream out;
    // One literal per group of columns, each name whole.
    out << "method,param,map,base,map_size,view_deg,width,height,"
           "ms_median,ms_wall_median,fetches_mean,fetches_max,"
           "coverage_mismatch_pct,off_half_texel_pct,"
           "top_coverage_mismatch_pct,top_off_half_texel_pct,"
           "mean_error_px,p99_error_px,exhausted_px,hit_pct,interpolation,renderer,"
           "fetches_bounds_mean,p99_error_texels,top_p99_error_texels,mpix_per_s,"
           "bytes_per_texel,preprocess_ms,preprocess_where,preprocess_cpu_ms,"
           "ms_cpu_median,clock,ms_spread_pct,ratio_to_multilevel,ratio_spread_pct,"
           "coarse_fetches_mean\n";
    const Clock clock = clockOf(info);
    for (const Measurement& r : rows) {
        const Measurement* base = find(rows, keyOf(r), "multilevel", "exact");
        const Spread ratio = base ? timeRatio(r, *base, clock) : Spread{};
        out << r.method << ',' << r.param << ',' << csvField(r.map) << ',' << r.base << ','
            << r.mapSize << ',' << r.viewDegrees << ',' << r.width << ',' << r.height << ','
            << fixed(r.msMedian, 4) << ',' << fixed(r.msWallMedian, 4) << ','
            << fixed(r.fetchesMean, 2) << ',' << fixed(r.fetchesMax, 0) << ','
            << fixed(r.coverageMismatchPct, 4) << ',' << fixed(r.offHalfTexelPct, 4) << ','
            << fixed(r.topCoverageMismatchPct, 4) << ',' << fixed(r.topOffHalfTexelPct, 4) << ','
            << fixed(r.meanErrorPx, 3) << ',' << fixed(r.p99ErrorPx, 3) << ',' << r.exhausted << ','
            << fixed(r.hitPct, 2) << ',' << r.interpolation << ',' << csvQuote(info.renderer) << ','
            << fixed(r.boundFetchesMean, 2) << ',' << fixed(r.p99ErrorTexels, 3) << ','
            << fixed(r.topP99ErrorTexels, 3) << ',' << fixed(megapixelsPerSecond(r, clock), 3)
            << ',' << fixed(r.bytesPerTexel, 3) << ',' << fixed(r.preprocessMs, 2) << ','
            << r.preprocessWhere << ','
            << (r.cpuPreprocessMs >= 0.0 ? fixed(r.cpuPreprocessMs, 2) : std::string()) << ','
            << fixed(r.msCpuMedian, 4) << ',' << clockName(clock) << ','
            << fixed(spreadOf(frameSeries(r, clock)).halfIqrPercent(), 2) << ','
            << (base ? fixed(ratio.median, 4) : std::string()) << ','
            << (base ? fixed(ratio.halfIqrPercent(), 2) : std::string()) << ','
            << fixed(r.coarseFetchesMean, 2) << '\n';
    }
    writeTextAtomically(file, out.str());
}

std::string writeMarkdown(const std::filesystem::path& file, const RunInfo& info,
                          const std::vector<Measurement>& rows) {
    const Clock clock = clockOf(info);
    std::ostringstream md;
    md << "Run " << info.date << " on " << info.renderer << " (`" << info.command
       << "`). Times: " << clockDescription(clock)
       << ", in ms: the median of each setting's frames, every setting of a map and view timed "
          "in the same rounds, a frame each in turn. Ratios: the median over the rounds of the "
          "round's ratio, and beside it +- half the interquartile range of those ratios, in % "
          "of the median.\n\n";
    if (!info.notes.empty()) {
        md << "Not measured:\n\n";
        for (const std::string& line : info.notes) md << "- " << markdownText(line) << '\n';
        md << '\n';
    }
    if (std::none_of(rows.begin(), rows.end(),
                     [](const Measurement& r) { return r.method == "multilevel"; }))
        md << "The multilevel method was not measured (`--methods`): the comparisons below "
              "are against it, and stay empty.\n\n";
    md << "Equal-accuracy time: for each peer, the smallest setting whose accuracy against the "
          "exact CPU "
          "reference (% of pixels whose hit/miss disagrees, % of hits off by more than half a "
          "texel) is within "
          "0.01 percentage points of the multilevel method's, its time, and that time over the "
          "multilevel "
          "method's (above 1: the multilevel method is faster). *never*: no setting measured "
          "reaches it. Peers marked *(top)* know no side walls or bottom face: they are "
          "measured on the pixels whose rays come in through the top face, against the "
          "multilevel method's accuracy on the same pixels.\n\n";
    const std::vector<std::string> peers = [&] {
        std::vector<std::string> all = methods(rows);
        all.erase(std::remove(all.begin(), all.end(), "multilevel"), all.end());
        return all;
    }();
    peerTableHeader(
        md, {"map", "size", "view", "multilevel ms", "Mpix/s", "mismatch %", "off %", "fetches"},
        peers);
    for (const Key& key : keys(rows)) {
        const Measurement* ml = find(rows, key, "multilevel", "exact");
        // The biquadratic rows, without peers, have a table of their own.
        if (!ml || ml->interpolation != "bilinear") continue;
        md << "| " << markdownText(std::get<0>(key)) << " | " << std::get<1>(key) << " | "
           << std::get<2>(key) << "° | " << fixed(frameMs(*ml, clock), 2) << " | "
           << fixed(megapixelsPerSecond(*ml, clock), 2) << " | "
           << fixed(ml->coverageMismatchPct, 3) << " | " << fixed(ml->offHalfTexelPct, 3) << " | "
           << fixed(ml->fetchesMean, 1) << " |";
        for (const std::string& p : peers) {
            const Measurement* eq = equalAccuracy(rows, key, p, *ml);
            if (!eq) {
                md << " never |";
            } else {
                const Spread ratio = timeRatio(*eq, *ml, clock);
                md << ' ' << eq->param << ": " << fixed(frameMs(*eq, clock), 2) << " ms ("
                   << fixed(ratio.median, 2) << "x +-" << fixed(ratio.halfIqrPercent(), 0) << " %; "
                   << fixed(megapixelsPerSecond(*eq, clock), 2) << " Mpix/s, "
                   << fixed(eq->fetchesMean, 1) << " fetches) |";
            }
        }
        md << '\n';
    }

    md << equalTimeSection(rows, clock, peers);
    md << throughputSection(rows, clock);
    md << coarseSection(rows, clock);
    md << costSection(rows);

    md << "\nAccuracy-controlled level of detail (multilevel, `--pixel-error`): time and "
          "accuracy (off %: hits off by more than half a texel; px: the mean and the 99th "
          "percentile of a hit's distance from the exact one, in pixels at that "
          "distance).\n\n";
    md << "| map | size | view | exact ms | 1 px ms | 1 px off % | 1 px error px | 4 px ms | "
          "4 px off % | 4 px error px |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Key& key : keys(rows)) {
        const Measurement* e = find(rows, key, "multilevel", "exact");
        const Measurement* one = find(rows, key, "multilevel", "1px");
        const Measurement* four = find(rows, key, "multilevel", "4px");
        if (!e || !one || !four) continue;
        md << "| " << markdownText(std::get<0>(key)) << " | " << std::get<1>(key) << " | "
           << std::get<2>(key) << "° | " << fixed(frameMs(*e, clock), 2) << " | "
           << fixed(frameMs(*one, clock), 2) << " | " << fixed(one->offHalfTexelPct, 2) << " | "
           << fixed(one->meanErrorPx, 2) << " / " << fixed(one->p99ErrorPx, 1) << " | "
           << fixed(frameMs(*four, clock), 2) << " | " << fixed(four->offHalfTexelPct, 2) << " | "
           << fixed(four->meanErrorPx, 2) << " / " << fixed(four->p99ErrorPx, 1) << " |\n";
    }

    // The targets of issue 5, as measured (where the procedural relief was).
    std::ostringstream targets;
    std::map<int, const Measurement*> at45;
    int view45 = -1;
    for (const Measurement& r : rows) {
        if (r.method != "multilevel" || r.param != "exact" || r.map != kResampledRelief) continue;
        if (view45 < 0 || std::abs(r.viewDegrees - 45) < std::abs(view45 - 45))
            view45 = r.viewDegrees;
    }
    for (const Measurement& r : rows) {
        if (r.method == "multilevel" && r.param == "exact" && r.map == kResampledRelief &&
            r.viewDegrees == view45)
            at45[r.mapSize] = &r;
    }
    if (at45.count(256) && at45.size() > 1) {
        const Measurement& big = *at45.rbegin()->second;
        targets << "- Time at " << big.mapSize << " / time at 256, multilevel at " << view45
                << "°: " << fixed(frameMs(big, clock) / frameMs(*at45[256], clock), 2) << " exact";
        const Key bigKey{big.map, big.mapSize, big.viewDegrees};
        const Measurement* bigOne = find(rows, bigKey, "multilevel", "1px");
        const Measurement* smallOne =
            find(rows, Key{big.map, 256, big.viewDegrees}, "multilevel", "1px");
        if (bigOne && smallOne)
            targets << ", " << fixed(frameMs(*bigOne, clock) / frameMs(*smallOne, clock), 2)
                    << " with `--pixel-error 1`";
        targets << " (target <= 1.5).\n";
    }
    for (const auto& [size, r] : at45) {
        const double budget = 2.0 * (std::log2(size) + 1.0);
        targets << "- Mean fetches per pixel at " << size << ": " << fixed(r->fetchesMean, 1)
                << " (target <= " << fixed(budget, 0) << ").\n";
    }
    if (!targets.str().empty()) md << "\nTargets:\n\n" << targets.str();
    md << curvedSection(rows, clock);
    md << biquadraticSection(rows, clock);
    writeTextAtomically(file, md.str());
    return md.str();
}

bool writePlots(const std::filesystem::path& folder, const RunInfo& info,
                const std::vector<Measurement>& rows, std::string& why) {
    const Clock clock = clockOf(info);
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
        why = "gnuplot is not installed (apt-get install gnuplot-nox)";
        return false;
    }
    // One line per method on the resampled relief at the view nearest 45 degrees: the
    // multilevel method exact, each peer at its equal-accuracy setting where it has one,
    // else its largest budget.
    int view = -1;
    for (const Measurement& r : rows) {
        if (r.map == kResampledRelief &&
            (view < 0 || std::abs(r.viewDegrees - 45) < std::abs(view - 45)))
            view = r.viewDegrees;
    }
    std::ostringstream data;
    std::vector<std::string> names;
    for (const std::string& method : methods(rows)) {
        std::ostringstream block;
        int points = 0;
        for (const Key& key : keys(rows)) {
            if (std::get<0>(key) != kResampledRelief || std::get<2>(key) != view) continue;
            const Measurement* ml = find(rows, key, "multilevel", "exact");
            const Measurement* pick = nullptr;
            if (method == "multilevel") {
                pick = ml;
            } else if (ml) {
                pick = equalAccuracy(rows, key, method, *ml);
            }
            if (!pick) {  // largest budget measured
                for (const Measurement& r : rows) {
                    if (Key{r.map, r.mapSize, r.viewDegrees} == key && r.method == method)
                        pick = &r;
                }
            }
            if (!pick) continue;
            block << pick->mapSize << ' ' << frameMs(*pick, clock) << ' ' << pick->fetchesMean
                  << '\n';
            ++points;
        }
        if (points == 0) continue;
        data << block.str() << "\n\n";
        names.push_back(method);
    }
    writeTextAtomically(folder / "plot_data.txt", data.str());
    std::ostringstream script;
    script << "set terminal pngcairo size 800,500 noenhanced\nset logscale x 2\nset logscale "
              "y\nset key outside right\n"
              "set grid\nset xlabel 'map size (texels per side)'\n";
    std::vector<std::string> outputs;
    // Against the map's size only where the procedural relief was measured.
    for (const auto& [output, column, label] :
         {std::tuple<std::string, int, std::string>{"time_vs_size.png", 2, clockLabel(clock)},
          {"fetches_vs_size.png", 3, "texel fetches per pixel (mean)"}}) {
        if (names.empty()) break;
        outputs.push_back(output);
        script << "set output " << gnuplotString((folder / (output + ".part")).string())
               << "\nset ylabel '" << label << "'\nset title '"
               << "view " << view
               << " deg: multilevel exact; peers at equal accuracy, else their largest budget'\n"
               << "plot ";
        for (std::size_t k = 0; k < names.size(); ++k) {
            script << (k ? ", " : "") << gnuplotString((folder / "plot_data.txt").string())
                   << " index " << k << " using 1:" << column << " with linespoints title '"
                   << names[k] << "'";
        }
        script << '\n';
    }
    script << paretoScript(folder, rows, clock, outputs);
    writeTextAtomically(folder / "plots.gnuplot", script.str());
    const std::string command =
        "gnuplot " + shellQuote((folder / "plots.gnuplot").string()) + " 2>&1";
    if (std::system(command.c_str()) != 0) {
        why = "gnuplot failed on " + (folder / "plots.gnuplot").string();
        return false;
    }
    // gnuplot drew each picture beside its name; renamed whole into place.
    for (const std::string& output : outputs) {
        std::error_code ec;
        std::filesystem::rename(folder / (output + ".part"), folder / output, ec);
        if (ec) {
            why = "cannot rename " + (folder / (output + ".part")).string() + ": " + ec.message();
            return false;
        }
    }
    return true;
}

}  // namespace microrelief::bench
