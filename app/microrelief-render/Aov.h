// The --aov file (scene-and-cli.md, "Outputs"): OpenEXR, float, R, G, B the hit's world
// position and A 1 for a hit, 0 for a miss; with shadows on, a fifth channel `shadow`:
// how much of the (first) light reaches the hit, 1 lit, 0 shadowed, 0 on misses.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/gl/RenderedFrame.h"
#include "microrelief/io/ImageFile.h"

namespace microrelief {

// Throws Error(BadInput) unless `file` is named as an OpenEXR file: ".exr" in any case, as
// --out's extension is read in any case (OpenImageIO's choice of format).
inline void checkAovExtension(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension != ".exr")
        throwBadInput(file.string() + ": the AOV must be an OpenEXR file (.exr)");
}

void writeAov(ImageWriteBatch& batch, const std::filesystem::path& file, const RenderedFrame& frame,
              bool withShadow);

}  // namespace microrelief
