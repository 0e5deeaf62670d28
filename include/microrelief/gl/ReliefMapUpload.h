// Where a map's textures come from, decided in one place: read through pages (a map past
// the GL's textures, or paging asked for), the max pyramid built on the GPU from the
// uploaded samples (gl/PyramidBuilder.h), or built on the CPU and uploaded (a tiled map's
// always: the GPU builder bounds texel squares within one map). The texels are the same
// whichever builds them. ReliefRenderer and every host that keeps its own textures call
// these rather than choosing a ReliefTextures constructor themselves.
#pragma once

#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/gl/Objects.h"
#include "microrelief/gl/PagedPyramid.h"
#include "microrelief/gl/ReliefPrograms.h"
#include "microrelief/gl/ReliefTextures.h"

namespace microrelief {

struct MapUploadSettings {
    bool wrapU = false;      // a curved base's addressing: u wraps
    glm::ivec2 tiles{1, 1};  // the map repeated N x M times; the textures hold one tile
    bool withMaxMip = false;  // the aligned pyramid too, for the maxmip peer
    PyramidBuild build = PyramidBuild::GpuElseCpu;
    // When the map is read through pages (never, by default: a single draw of a paged map is
    // not exact, gl/PagedPyramid.h).
    PagingSettings paging{PagingSettings::Mode::Never};
};

// Whether `map` is read through pages under `paging`: always, never, or (Mode::Auto) where
// a side exceeds GL_MAX_TEXTURE_SIZE. Decided before a program is chosen: a paged map's
// programs differ.
bool readsThroughPages(const GL& gl, const HeightMap& map, const PagingSettings& paging);

// `map`'s textures as `settings` say, their GPU work done with `programs`' pyramid builder.
// `shared`, where not null, is `map` shared by the caller: pages keep it rather than a copy.
// A map read through pages takes no tiles and no aligned pyramid (Error(BadInput) naming
// `source`). PyramidBuild::GpuElseCpu builds on the CPU where the GPU's build throws for a
// reason other than the map (Error(Runtime): a GL that cannot render into R16F); bad input
// throws as it is. Throws Error(BadInput) naming `source` for a map past the GL's limits.
ReliefTextures uploadReliefMap(ReliefPrograms& programs, const HeightMap& map,
                               std::shared_ptr<const HeightMap> shared, const std::string& source,
                               const MapUploadSettings& settings);

}  // namespace microrelief
