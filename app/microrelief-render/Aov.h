// The --aov file (scene-and-cli.md, "Outputs"): OpenEXR, float, R, G, B the hit's world
// position and A 1 for a hit, 0 for a miss; with shadows on, a fifth channel `shadow`:
// how much of the (first) light reaches the hit, 1 lit, 0 shadowed, 0 on misses.
#pragma once

#include <filesystem>

#include "microrelief/io/ImageFile.h"
#include "microrelief/gl/RenderedFrame.h"

namespace microrelief {

void writeAov(ImageWriteBatch& batch, const std::filesystem::path& file, const RenderedFrame& frame,
              bool withShadow);

}  // namespace microrelief
