// microrelief-render --pyramid-cache: maps drawn from their pyramid files (io/PyramidFile.h),
// for a single picture and for camera paths alike.
#pragma once

#include <filesystem>
#include <memory>

#include "Options.h"
#include "microrelief/io/PyramidFile.h"

namespace microrelief {

// The pyramid file of `map` in --pyramid-cache's folder, read with `load` for a base that
// wraps in u or not: opened, or built first (a line, then the percentage on a terminal, on
// stderr unless --quiet). Throws Error.
std::shared_ptr<const PyramidFile> openPyramidCache(const RenderOptions& options,
                                                    const std::filesystem::path& map,
                                                    const HeightMapLoadOptions& load, bool wrapU);

// What a map drawn from its pyramid file is not: drawn by another method than the
// multilevel one (the only one that reads pages), repeated (--tile) or replaced by an
// animated field (--animate). Throws Error(BadInput) naming the flag.
void checkDrawnFromPyramidFile(const RenderJob& job);

}  // namespace microrelief
