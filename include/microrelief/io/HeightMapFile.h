// Height maps from image files, through OpenImageIO (the microrelief::io component):
// the file's header checked before anything is allocated, the samples read as floats;
// and georeferenced elevation models (GeoTIFF, SRTM .hgt) through GDAL where the component
// was built with it (docs/terrain.md).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

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

// Where a DEM's map lies on the ground, as GDAL says it: the map's own geotransform, north
// up ({x0, dx, 0, y0, 0, -dy}: the corner of sample (i, j) at x0 + i dx, y0 - j dy), in the
// coordinate system `projectionWkt` (OGC WKT; empty where the file names none). What a map
// saved from it needs to lie where it came from (saveElevationModel).
struct GroundPlacement {
    std::array<double, 6> geotransform{};
    std::string projectionWkt;

    bool operator==(const GroundPlacement&) const = default;
};

struct HeightMapFile {
    HeightMap map;
    std::optional<Georeference> georeference;  // where the file has one
    std::optional<GroundPlacement> placement;  // a DEM's, with its georeference
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

// Writes `map`, a DEM's as loadHeightMapFile read it (or edited since), as a GeoTIFF
// elevation model where it came from: one Float32 band of metres, lowest + h (highest -
// lowest) for map value h (`geo`'s range; nodata samples stay at the lowest height they
// were filled with, and no nodata value is written), unit metres, over `placement`'s
// geotransform and coordinate system. Read back, it is the same map (to float rounding) at
// the same place. Written whole or not at all (io/AtomicFile.h). Throws Error(BadInput)
// naming the file for a DEM with no range (one height: map values other than 0 have no
// size in metres) whose map has any, and where the io component was built without GDAL;
// Error(Runtime) when the write fails.
void saveElevationModel(const std::filesystem::path& file, const HeightMap& map,
                        const Georeference& geo, const GroundPlacement& placement);

// Whether the io component reads georeferenced maps (it was built with GDAL).
bool readsGeoreferencedMaps();

}  // namespace microrelief
