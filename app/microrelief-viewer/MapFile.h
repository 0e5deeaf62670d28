// Saving an edited map (the viewer's sculpting): a 16-bit PNG, as maps are usually stored
// (heights 0 to 1 by 65535, rounded to the nearest level), a float OpenEXR, the samples
// exactly, or, for a map that came from an elevation model, a GeoTIFF DEM of metres over
// the same grid on the ground (io/HeightMapFile.h: saveElevationModel); written whole or not
// at all (io/AtomicFile.h), so a save that fails leaves the file that was there untouched.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/ReliefFiles.h"

namespace microrelief {

// Where a map came from an elevation model: its georeference (the metres its [0, 1] stand
// for) and where it lies, which a GeoTIFF save keeps.
struct MapGround {
    Georeference georeference;
    GroundPlacement placement;
};
// The ground of a loaded map (io/ReliefFiles.h): a DEM's; none for an image.
std::optional<MapGround> mapGround(const ReliefFiles& loaded);

// Throws Error(BadInput) naming the file unless its extension is .png, .exr, .tif or .tiff
// (any case).
void checkMapExtension(const std::filesystem::path& file);
// checkMapExtension, and a .tif or .tiff only for a map with a ground (a GeoTIFF is a DEM's
// save; any other map is saved as .png or .exr): Error(BadInput) naming the file.
void checkMapSave(const std::filesystem::path& file, const std::optional<MapGround>& ground);

// Writes `map` to `file`: .png 16 bits, .exr 32-bit float, one channel; .tif or .tiff a
// GeoTIFF DEM over `ground` (metres, its geotransform and coordinate system). Returns a
// warning, one line naming the file, where the file keeps less than the map had: a DEM's
// map saved as .png or .exr keeps its [0, 1] samples but not where they lie nor their metres
// (save as .tif to keep them); empty otherwise. Throws Error(BadInput) for what
// checkMapSave refuses or, for a PNG, a height above 1 (which the PNG cannot hold: save as
// .exr), before anything is written; Error(Runtime) when the write fails.
std::string saveHeightMap(const HeightMap& map, const std::filesystem::path& file,
                          const std::optional<MapGround>& ground = std::nullopt);

}  // namespace microrelief
