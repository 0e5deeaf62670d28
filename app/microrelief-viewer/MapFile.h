// Saving an edited map (the viewer's sculpting): a 16-bit PNG, as maps are usually stored
// (heights 0 to 1 by 65535, rounded to the nearest level), or a float OpenEXR, the
// samples exactly; written whole or not at all (io/ImageFile.h), so a save that fails
// leaves the file that was there untouched.
#pragma once

#include <filesystem>

#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief {

// Throws Error(BadInput) naming the file unless its extension is .png or .exr (any case).
void checkMapExtension(const std::filesystem::path& file);

// Writes `map` to `file` (.png: 16 bits, .exr: 32-bit float, one channel). Throws
// Error(BadInput) for another extension or, for a PNG, a height above 1 (which the PNG
// cannot hold: save as .exr), before anything is written; Error(Runtime) when the write
// fails.
void saveHeightMap(const HeightMap& map, const std::filesystem::path& file);

}  // namespace microrelief
