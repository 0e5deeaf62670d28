// Height maps from image files, through OpenImageIO (the microrelief::io component):
// the file's header checked before anything is allocated, the samples read as floats;
// and georeferenced elevation models (GeoTIFF, SRTM .hgt) through GDAL where the component
// was built with it (docs/terrain.md).
#pragma once

#include <filesystem>
#include <optional>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Georeference.h"

namespace microrelief {

// Reads any image OpenImageIO can read. Integer formats become [0, 1] by their type
// range, float formats stay as stored. Throws Error(BadInput) naming the file and the
// reason for a missing, unreadable or empty file, one that is not a regular file (a
// device or a FIFO, refused before OpenImageIO opens it), a size beyond
// kMaxHeightMapSide (from the header, before allocating), a PNG that libpng would
// refuse (src/io/PngCheck.h), a missing channel, or values that are not finite and
// >= 0 (suggesting --normalize where that would help); Error(Runtime) naming the file
// when memory runs out. A georeferenced map comes back as loadHeightMapFile reads it,
// without its georeference.
HeightMap loadHeightMap(const std::filesystem::path& file,
                        const HeightMapLoadOptions& options = {});

struct HeightMapFile {
    HeightMap map;
    std::optional<Georeference> georeference;  // where the file has one
};

// A georeferenced elevation model (a .tif or .tiff whose first directory holds a GeoTIFF
// grid, or an SRTM .hgt), read through GDAL: the samples as metres (the band's scale, offset
// and unit applied: metres, feet or US survey feet; a band without a unit is in metres), north
// up and east to the right (a grid whose rows and columns run along the axes, in any order
// and direction, permuted sample for sample as it is read), its nodata samples filled
// with the lowest valid height, [lowest, highest] mapped to [0, 1]; the georeference says
// what that was and how large a sample is (core/scene/Georeference.h). Every other file (a
// TIFF without a grid too, through OpenImageIO alone) as loadHeightMap reads it. Refuses,
// besides what loadHeightMap refuses: a DEM GDAL cannot read, one with no valid sample or a
// sample that is not a height, heights in another unit, a grid turned by another angle or
// sheared, a latitude/longitude grid reaching past a pole or round more than the globe, an
// .hgt file where the io component was built without GDAL.
HeightMapFile loadHeightMapFile(const std::filesystem::path& file,
                                const HeightMapLoadOptions& options = {});

// A map file's grid on the ground from its header alone, where it is an elevation model
// the io component reads (no sample read: the heights' range not known); empty for any
// other file. For what the grid decides before the map is read: the base a global grid
// goes on (core/scene/Georeference.h: fittedBase). Throws Error(BadInput) as
// loadHeightMapFile does for a DEM it cannot read.
std::optional<Georeference> readMapGrid(const std::filesystem::path& file);

// Whether the io component reads georeferenced maps (it was built with GDAL).
bool readsGeoreferencedMaps();

}  // namespace microrelief
