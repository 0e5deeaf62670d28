// Height maps from image files, through OpenImageIO (the microrelief::io component):
// the file's header checked before anything is allocated, the samples read as floats.
#pragma once

#include <filesystem>

#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief {

// Reads any image OpenImageIO can read. Integer formats become [0, 1] by their type
// range, float formats stay as stored. Throws Error(BadInput) naming the file and the
// reason for a missing, unreadable or empty file, one that is not a regular file (a
// device or a FIFO, refused before OpenImageIO opens it), a size beyond
// kMaxHeightMapSide (from the header, before allocating), a PNG that libpng would
// refuse (src/io/PngCheck.h), a missing channel, or values that are not finite and
// >= 0 (suggesting --normalize where that would help); Error(Runtime) naming the file
// when memory runs out.
HeightMap loadHeightMap(const std::filesystem::path& file,
                        const HeightMapLoadOptions& options = {});

}  // namespace microrelief
