// microrelief-render --pyramid-cache: maps drawn from their pyramid files (io/PyramidFile.h),
// for a single picture and for camera paths alike.
#pragma once

#include <filesystem>
#include <memory>

#include "Options.h"
#include "microrelief/io/PyramidFile.h"
#include "microrelief/io/ReliefFiles.h"

namespace microrelief {

// The pyramid file of `map` in --pyramid-cache's folder, read with `load` for a base that
// wraps in u or not: opened, or built first (a line, then the percentage on a terminal, on
// stderr unless --quiet). Throws Error.
std::shared_ptr<const PyramidFile> openPyramidCache(const RenderOptions& options,
                                                    const std::filesystem::path& map,
                                                    const HeightMapLoadOptions& load, bool wrapU);

// The base `map` is drawn on, known before the map is read: the scene's, or the ellipsoid a
// global latitude/longitude grid goes on (its header read: readMapGrid, fittedBase). The
// pyramid file is built for it and checked against it (checkDrawnFromPyramidFile).
BaseShape drawnBase(const SceneOptions& scene, const std::filesystem::path& map);

// Why `job` cannot be drawn from its map's pyramid file, naming the flag, or empty where it
// can: a map drawn so is not drawn by another method than the multilevel one (the only one
// that reads pages), repeated (--tile) or replaced by an animated field (--animate); with
// `compareReference`, its base is the plane (the reference over a pyramid file is the
// plane's).
std::string pyramidFileRefusal(const RenderJob& job, bool compareReference);
// Throws Error(BadInput) with pyramidFileRefusal's reason, if any.
void checkDrawnFromPyramidFile(const RenderJob& job, bool compareReference);

// loadReliefFiles (io/ReliefFiles.h: the map and the albedo `job` names, as `parts` asks),
// except that a map refused for this machine's memory (MapOverMemory) that --pyramid-cache
// would draw for `job` says so.
ReliefFiles loadFilesOrPointToCache(const RenderJob& job, bool compareReference,
                                    ReliefParts parts = ReliefParts::HeightsAndAlbedo);

}  // namespace microrelief
