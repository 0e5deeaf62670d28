// Where the viewer writes what a person asks for, without a window: a screenshot's name
// (out/viewer-STAMP.png, never over a file there) and where "Save map" writes an edited
// map by default (out/NAME-edited.exr, or .tif for a DEM's map, which keeps its ground).
#pragma once

#include <filesystem>
#include <string>

namespace microrelief {

// The local time as a screenshot's name carries it: YYYYmmdd-HHMMSS.
std::string localTimestamp();

// `folder`/viewer-`stamp`.png, or the first of viewer-`stamp`-2.png, -3.png, ... that is not
// there yet.
std::filesystem::path screenshotPath(const std::filesystem::path& folder, const std::string& stamp);

// out/STEM-edited.exr for `mapFile`, out/STEM-edited.tif where the map is a DEM's
// (`keepsGround`: MapFile.h, mapGround).
std::string editedMapPath(const std::filesystem::path& mapFile, bool keepsGround);

}  // namespace microrelief
