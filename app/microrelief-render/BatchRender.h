// microrelief-render's camera paths: the frames of a --turntable or a --cameras file
// that the --frames range and the --shard select, drawn in one process (one context,
// each program compiled once, the map and its pyramid made once and again only when a
// row names another map), each frame's files written whole or not at all, a manifest
// row per frame, progress on a terminal.
#pragma once

#include "Options.h"

namespace microrelief {

// Exit status 0; throws Error (before any frame is written for a bad path, pattern
// or camera file).
int runBatch(const RenderOptions& options);

}  // namespace microrelief
