// Which frames of a camera path one process renders: --frames A-B (a range of the path)
// and --shard I/N (one of N processes that share it), I and N also from a Slurm job
// array (--shard slurm).
#pragma once

#include <cstdlib>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace microrelief {

// Frames first..last of the path, both included, numbered from 0; no `last`: to the end.
struct FrameRange {
    int first = 0;
    std::optional<int> last;
};

// "A-B", "A-" (from A to the end) or "A" (frame A alone). Throws Error(BadInput).
FrameRange parseFrameRange(const std::string& text);

// Shard `index` of `count`: the k-th frame of the range (k from 0) belongs to shard
// k mod count. Interleaved rather than in blocks: along a turntable or a fly-through
// the time per frame changes slowly (grazing views, close-ups), so blocks would give
// one shard all the slow frames, while interleaving spreads them evenly; and the
// frames done so far, whichever shards have run, cover the whole path.
struct Shard {
    int index = 0, count = 1;
};

using EnvironmentLookup = std::function<const char*(const char*)>;

// "I/N" with 0 <= I < N, or "slurm": I and N of this task of a Slurm job array,
//   I = (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN) / SLURM_ARRAY_TASK_STEP,
//   N = SLURM_ARRAY_TASK_COUNT,
// so that --array=1-8 or --array=0-30:2 work as well as --array=0-7. TASK_ID and
// TASK_COUNT must be set (else the task is no array task); TASK_MIN and TASK_STEP,
// which Slurm always sets, default to 0 and 1 for runs by hand. An array that is not
// one range (--array=1,4,6) is refused. Throws Error(BadInput) naming the variable.
Shard parseShard(const std::string& text, const EnvironmentLookup& environment = std::getenv);

// The frames of a path of `frameCount` frames that the range and the shard select,
// ascending. Throws Error(BadInput) when the range reaches past the path.
std::vector<int> selectFrames(int frameCount, const FrameRange& range, const Shard& shard);

}  // namespace microrelief
