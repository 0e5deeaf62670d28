// Georeferenced elevation models through GDAL (io/HeightMapFile.h: loadHeightMapFile).
// Private to microrelief::io; compiled where the component is built with GDAL.
#pragma once

#include <filesystem>
#include <functional>

#include "microrelief/core/heightmap/PyramidStream.h"
#include "microrelief/io/HeightMapFile.h"

namespace microrelief {

// Whether a TIFF's first image directory holds a GeoTIFF grid tag (ModelPixelScale,
// ModelTiepoint or ModelTransformation): read from its header and that directory alone,
// without GDAL; false for a file that is not a TIFF or is cut short there (OpenImageIO then
// reads it as an image and says what is wrong).
bool hasGeoTiffGrid(const std::filesystem::path& file);

// Whether `file` is read as an elevation model (the caller has checked it is a regular
// file): an .hgt file always, a .tif or .tiff where its first directory holds a GeoTIFF grid.
bool isElevationModelFile(const std::filesystem::path& file);

// An elevation model's rows as loadHeightMapFile reads its samples (metres, north up, nodata
// filled with the lowest valid height, [lowest, highest] to [0, 1]) and its georeference.
// Reads the whole file once at once (the heights' range and the nodata count, a block of
// rows at a time) and keeps it open for the rows, read a block at a time again: never held
// whole. Refuses (Error(BadInput) naming the file) what loadHeightMapFile refuses of a DEM.
struct DemRows {
    MapRows rows;
    Georeference georeference;
    GroundPlacement placement;
};
// `firstPass` (may be empty) is told the rows of that first pass read so far, out of the
// map's height.
DemRows demRows(const std::filesystem::path& file, const HeightMapLoadOptions& options,
                const std::function<void(long long done, long long total)>& firstPass = {});

// An elevation model's grid from its header alone (no sample read): the georeference's
// grid fields (geographic, global, the ellipsoid's axes, the samples' ground size, the
// coordinate system), its heights' range not known. Refuses what demRows refuses of the
// header.
Georeference demGrid(const std::filesystem::path& file);

// The file (a GeoTIFF, an SRTM .hgt) as loadHeightMapFile reads a DEM: demRows, read whole.
HeightMapFile loadDem(const std::filesystem::path& file, const HeightMapLoadOptions& options);

// saveElevationModel (io/HeightMapFile.h), through GDAL.
void writeDem(const std::filesystem::path& file, const HeightMap& map, const Georeference& geo,
              const GroundPlacement& placement);

}  // namespace microrelief
