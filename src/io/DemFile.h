// Georeferenced elevation models through GDAL (io/HeightMapFile.h: loadHeightMapFile).
// Private to microrelief::io; compiled where the component is built with GDAL.
#pragma once

#include <filesystem>

#include "microrelief/io/HeightMapFile.h"

namespace microrelief {

// Whether a TIFF's first image directory holds a GeoTIFF grid tag (ModelPixelScale,
// ModelTiepoint or ModelTransformation): read from its header and that directory alone,
// without GDAL; false for a file that is not a TIFF or is cut short there (OpenImageIO then
// reads it as an image and says what is wrong).
bool hasGeoTiffGrid(const std::filesystem::path& file);

// The file (a GeoTIFF, an SRTM .hgt) as loadHeightMapFile reads a DEM; refuses one GDAL
// cannot read or that has no grid on the ground. The file is a regular one (checked by the
// caller).
HeightMapFile loadDem(const std::filesystem::path& file, const HeightMapLoadOptions& options);

}  // namespace microrelief
