// A height map's GPU resources (ReliefMap), built once and drawn by any number of reliefs
// of its context, and where they come from, decided in one place: read through pages (a
// map past the GL's textures, or paging asked for), the max pyramid built on the GPU from
// the uploaded samples (gl/PyramidBuilder.h), or built on the CPU and uploaded (a tiled
// map's always: the GPU builder bounds texel squares within one map). The texels are the
// same whichever builds them. ReliefRenderer and every host that keeps its own textures
// call these rather than choosing a ReliefTextures constructor themselves.
//
// microrelief-three splits its resources the same way (one ReliefMap, many Relief meshes):
// a map's textures, its pyramid and the cone maps a peer reads are the map's; the base, the
// height scale, the model and the method are each relief's (ReliefRenderer::apply).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/PyramidPages.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/core/scene/Method.h"
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

    // The settings whose addressing is `relief`'s (u wrapping on a curved base, its tiles),
    // the rest as above: what a map drawn by `relief` must be built with.
    static MapUploadSettings of(const ReliefDesc& relief) {
        MapUploadSettings settings;
        settings.wrapU = relief.base.wrapsU();
        settings.tiles = relief.tiles;
        return settings;
    }
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

// One map's GPU resources, shared by the reliefs that draw it (std::shared_ptr: the last
// relief or host holding it frees them). Its addressing (u wrapping for a curved base, the
// tiles) is fixed when it is built: a relief drawn over it must have the same
// (ReliefRenderer::apply checks). Its GL objects belong to its programs' context: it must
// not outlive it. Not thread-safe, as the context is not.
class ReliefMap {
public:
    // `heights`' resources as `settings` say (uploadReliefMap: the policy), the GPU's work
    // done with `programs`' pyramid builder. `shared`, where not null, is `heights` shared by
    // the caller: pages keep it rather than a copy (another map there is Error(Runtime)).
    // Throws as uploadReliefMap does.
    static std::shared_ptr<ReliefMap> upload(std::shared_ptr<ReliefPrograms> programs,
                                             const HeightMap& heights,
                                             std::shared_ptr<const HeightMap> shared,
                                             const std::string& source,
                                             const MapUploadSettings& settings);
    // A map whose samples and pyramid `pages` keeps (a pyramid file, io/PyramidFile.h): read
    // through pages under `paging`'s budget and page side, untiled, its addressing the
    // pages'.
    static std::shared_ptr<ReliefMap> fromPages(std::shared_ptr<ReliefPrograms> programs,
                                                std::shared_ptr<const PyramidPages> pages,
                                                const std::string& source,
                                                const PagingSettings& paging);
    ReliefMap(const ReliefMap&) = delete;
    ReliefMap& operator=(const ReliefMap&) = delete;

    // The textures, for a pass of the caller's that reads them or draws into the samples
    // (then heightsChanged).
    ReliefTextures& textures() { return textures_; }
    const ReliefTextures& textures() const { return textures_; }
    // The map as messages name it.
    const std::string& source() const { return source_; }
    bool wrapsU() const { return textures_.wrapsU(); }
    glm::ivec2 tiles() const { return textures_.tiles(); }
    bool paged() const { return textures_.paged() != nullptr; }
    PagedPyramid* pager() { return textures_.paged(); }
    // The surface's maximum, map units: the pyramid's top texel (a bound, rounded up to a
    // half's precision).
    float maxHeight() const { return textures_.shape().maxHeight; }
    // The map's facts a camera and the float checks are resolved with (core/scene/
    // FloatLimits.h, sceneRadius), held here alone: the whole's size in texels (tiles
    // included), and its highest sample: exactly as uploaded (the heights' maxValue, a
    // pyramid file's largestSample); after an edit on the GPU, whose samples nothing reads
    // back, the pyramid's top (maxHeight).
    glm::ivec2 size() const { return textures_.shape().size; }
    float highestSample() const { return highestSample_; }
    // The most segments a ray's traversal may visit on a map of this size (the whole, tiles
    // included: core/trace/MultilevelTracer.h's traversalBudget).
    int traversalBudget() const { return traversalBudget_; }

    // What `method` reads beyond the samples and the windows, built where it is missing:
    // the aligned pyramid for maxmip, the conservative cone map for cone (on the GPU), the
    // relaxed one for rcsm (on the CPU). Built once, whichever relief asks first; kept
    // until the heights change. A paged map reads the windows alone (nothing is built).
    void prepareFor(Method method);

    // After the caller changed the samples inside `changed` (map texels): the pyramids
    // brought up to date on the GPU over those texels only (a tiled map's built again on
    // the CPU from the samples read back: the GPU builder bounds one map, not tiles), the
    // cone maps dropped (built again when next asked for). heightsReplaced: every sample
    // changed, the pyramids built anew. Each moves generation() on. Throws Error(Runtime) for
    // a paged map (not edited on the GPU).
    void heightsChanged(const std::vector<TexelRect>& changed);
    void heightsReplaced();
    // Counts the changes of the heights: a relief drawing the map fits its proxy box to the
    // map's maximum again when the count it fitted for has moved (another relief, or the
    // host, edited the map).
    std::uint64_t generation() const { return generation_; }

private:
    ReliefMap(std::shared_ptr<ReliefPrograms> programs, ReliefTextures textures,
              std::string source, float highestSample);
    void refuseIfPaged() const;

    std::shared_ptr<ReliefPrograms> programs_;  // its context's: the GL and the builder
    ReliefTextures textures_;
    std::string source_;
    int traversalBudget_ = 0;
    float highestSample_ = 0.0f;
    std::uint64_t generation_ = 0;
};

}  // namespace microrelief
