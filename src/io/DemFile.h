// Georeferenced elevation models through GDAL (io/HeightMapFile.h: loadHeightMapFile).
// Private to microrelief::io; compiled where the component is built with GDAL.
#pragma once

#include <filesystem>
#include <optional>

#include "microrelief/io/HeightMapFile.h"

namespace microrelief {

// The file as loadHeightMapFile reads a DEM. Unless `demOnly` (a format that is never an
// image: .hgt, .asc, .dem), nothing for a file GDAL cannot open or that has no grid on the
// ground: a TIFF that is an image, which OpenImageIO then reads (and says what is wrong
// with). The file is a regular one (checked by the caller).
std::optional<HeightMapFile> loadDem(const std::filesystem::path& file,
                                     const HeightMapLoadOptions& options, bool demOnly);

}  // namespace microrelief
