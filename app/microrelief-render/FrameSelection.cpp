#include "FrameSelection.h"

#include <charconv>
#include <climits>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

// A whole string as an integer in [low, high], or nothing.
std::optional<long long> parseInteger(const std::string& text, long long low, long long high) {
    long long value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec != std::errc() || ptr != end || value < low || value > high)
        return std::nullopt;
    return value;
}

}  // namespace

FrameRange parseFrameRange(const std::string& text) {
    const auto fail = [&] {
        throwBadInput("--frames expects A-B, A- or A with frame numbers from 0 and A <= B, got '" +
                      text + "'");
    };
    const std::size_t dash = text.find('-');
    FrameRange range;
    const auto first = parseInteger(text.substr(0, dash), 0, INT_MAX);
    if (!first) fail();
    range.first = static_cast<int>(*first);
    if (dash == std::string::npos) {
        range.last = range.first;
    } else if (dash + 1 < text.size()) {
        const auto last = parseInteger(text.substr(dash + 1), 0, INT_MAX);
        if (!last || *last < *first) fail();
        range.last = static_cast<int>(*last);
    }
    return range;
}

Shard parseShard(const std::string& text, const EnvironmentLookup& environment) {
    if (text != "slurm") {
        const std::size_t slash = text.find('/');
        const auto index = parseInteger(text.substr(0, slash), 0, INT_MAX);
        const auto count = slash == std::string::npos
                               ? std::nullopt
                               : parseInteger(text.substr(slash + 1), 1, INT_MAX);
        if (!index || !count || *index >= *count) {
            throwBadInput("--shard expects I/N with 0 <= I < N (or slurm), got '" + text + "'");
        }
        return {static_cast<int>(*index), static_cast<int>(*count)};
    }
    // A variable as an integer; `fallback` where it is not set, or an error when none.
    const auto variable = [&](const char* name, std::optional<long long> fallback,
                              long long low) -> long long {
        const char* value = environment(name);
        if (!value || !*value) {
            if (fallback) return *fallback;
            throwBadInput(std::string("--shard slurm: ") + name +
                          " is not set (not a task of a Slurm job array: sbatch --array=0-N)");
        }
        const auto parsed = parseInteger(value, low, INT_MAX);
        if (!parsed) {
            throwBadInput(std::string("--shard slurm: ") + name + "='" + value +
                          "' is not an integer >= " + std::to_string(low));
        }
        return *parsed;
    };
    const long long id = variable("SLURM_ARRAY_TASK_ID", std::nullopt, 0);
    const long long count = variable("SLURM_ARRAY_TASK_COUNT", std::nullopt, 1);
    const long long min = variable("SLURM_ARRAY_TASK_MIN", 0, 0);
    const long long step = variable("SLURM_ARRAY_TASK_STEP", 1, 1);
    const long long max = variable("SLURM_ARRAY_TASK_MAX", min + (count - 1) * step, 0);
    // The array as the environment gives it: a value this function filled in is said to
    // be one, not shown as if Slurm had set it.
    std::string array;
    for (const auto& [name, value] :
         {std::pair{"SLURM_ARRAY_TASK_MIN", min}, std::pair{"SLURM_ARRAY_TASK_MAX", max},
          std::pair{"SLURM_ARRAY_TASK_STEP", step}, std::pair{"SLURM_ARRAY_TASK_COUNT", count}}) {
        const char* given = environment(name);
        array += (array.empty() ? "" : "; ") + std::string(name) +
                 (given && *given ? "=" + std::to_string(value)
                                  : " unset, taken as " + std::to_string(value));
    }
    if (max < min || (max - min) % step != 0 || (max - min) / step + 1 != count) {
        throwBadInput("--shard slurm: the array is not one range A-B or A-B:S (" + array +
                      "); give --shard I/N yourself");
    }
    if (id < min || id > max || (id - min) % step != 0) {
        throwBadInput("--shard slurm: SLURM_ARRAY_TASK_ID=" + std::to_string(id) +
                      " is not a task of the array (" + array + ")");
    }
    return {static_cast<int>((id - min) / step), static_cast<int>(count)};
}

std::vector<int> selectFrames(int frameCount, const FrameRange& range, const Shard& shard) {
    const int last = range.last.value_or(frameCount - 1);
    if (range.first >= frameCount || last >= frameCount) {
        throwBadInput("--frames " + std::to_string(range.first) + "-" +
                      (range.last ? std::to_string(*range.last) : std::string()) +
                      ": the camera path has " + std::to_string(frameCount) + " frame" +
                      (frameCount == 1 ? "" : "s") + " (0-" + std::to_string(frameCount - 1) + ")");
    }
    std::vector<int> frames;
    for (long long k = shard.index; range.first + k <= last; k += shard.count)
        frames.push_back(static_cast<int>(range.first + k));
    return frames;
}

}  // namespace microrelief
