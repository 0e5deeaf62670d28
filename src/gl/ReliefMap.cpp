#include "microrelief/gl/ReliefMap.h"

#include <utility>

#include "microrelief/core/Error.h"
#include "microrelief/core/trace/MultilevelTracer.h"

namespace microrelief {

bool readsThroughPages(const GL& gl, const HeightMap& map, const PagingSettings& paging) {
    if (paging.mode != PagingSettings::Mode::Auto)
        return paging.mode == PagingSettings::Mode::Always;
    GLint maxSize = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    return map.width > maxSize || map.height > maxSize;
}

ReliefTextures uploadReliefMap(ReliefPrograms& programs, const HeightMap& map,
                               std::shared_ptr<const HeightMap> shared, const std::string& source,
                               const MapUploadSettings& settings) {
    const GL& gl = programs.gl();
    const bool untiled = settings.tiles == glm::ivec2(1, 1);
    if (readsThroughPages(gl, map, settings.paging)) {
        if (!untiled) throwBadInput(source + ": a map read through pages is not tiled");
        if (settings.withMaxMip)
            throwBadInput(source + ": a map read through pages has no aligned pyramid (maxmip)");
        // The pages keep the map: the caller's where it shares it, else a copy.
        if (!shared) shared = std::make_shared<const HeightMap>(map);
        return ReliefTextures(gl, std::move(shared), source, settings.wrapU, settings.paging);
    }
    if (settings.build != PyramidBuild::Cpu && untiled) {
        try {
            return ReliefTextures(gl, map, source, settings.wrapU, programs.pyramidBuilder(),
                                  settings.withMaxMip);
        } catch (const Error& e) {
            // The map's fault (past the GL's limits) is the same on the CPU; the GL's (no
            // R16F render target, a pass that did not compile) is not.
            if (e.kind() == ErrorKind::BadInput || settings.build == PyramidBuild::Gpu) throw;
        }
    }
    return ReliefTextures(gl, map, source, settings.wrapU, settings.withMaxMip, settings.tiles);
}

ReliefMap::ReliefMap(std::shared_ptr<ReliefPrograms> programs, ReliefTextures textures,
                     std::string source, float highestSample)
    : programs_(std::move(programs)),
      textures_(std::move(textures)),
      source_(std::move(source)),
      traversalBudget_(microrelief::traversalBudget(size().x, size().y)),
      highestSample_(highestSample) {}

std::shared_ptr<ReliefMap> ReliefMap::upload(std::shared_ptr<ReliefPrograms> programs,
                                             const HeightMap& heights,
                                             std::shared_ptr<const HeightMap> shared,
                                             const std::string& source,
                                             const MapUploadSettings& settings) {
    if (!programs) throwRuntime("ReliefMap::upload: no programs");
    if (shared && shared.get() != &heights)
        throwRuntime("ReliefMap::upload: `shared` is not `heights` (" + source + ")");
    ReliefTextures textures = uploadReliefMap(*programs, heights, std::move(shared), source, settings);
    // The constructor is private (maps are shared, never copied): make_shared cannot call it.
    return std::shared_ptr<ReliefMap>(
        new ReliefMap(std::move(programs), std::move(textures), source, heights.maxValue()));
}

std::shared_ptr<ReliefMap> ReliefMap::fromPages(std::shared_ptr<ReliefPrograms> programs,
                                                std::shared_ptr<const PyramidPages> pages,
                                                const std::string& source,
                                                const PagingSettings& paging) {
    if (!programs || !pages) throwRuntime("ReliefMap::fromPages: no programs or no pages");
    const float highest = pages->largestSample();
    ReliefTextures textures(programs->gl(), std::move(pages), source, paging);
    return std::shared_ptr<ReliefMap>(
        new ReliefMap(std::move(programs), std::move(textures), source, highest));
}

void ReliefMap::prepareFor(Method method) {
    if (paged()) return;  // the multilevel method's alone: nothing beyond the windows
    const GL& gl = programs_->gl();
    // What the method's row says it reads beyond the samples and the windows.
    if (methodHas(method, MethodTrait::MaxPyramid) && !textures_.hasMaxMipPyramid())
        textures_.addMaxMipPyramid(gl, programs_->pyramidBuilder());
    using Kind = ReliefTextures::ConeKind;
    if (methodHas(method, MethodTrait::ConeMap) && !textures_.coneMap(Kind::Conservative))
        textures_.addConeMap(gl, Kind::Conservative, &programs_->pyramidBuilder());
    if (methodHas(method, MethodTrait::RelaxedConeMap) && !textures_.coneMap(Kind::Relaxed))
        textures_.addConeMap(gl, Kind::Relaxed);
}

void ReliefMap::refuseIfPaged() const {
    if (paged()) throwRuntime(source_ + ": a map read through pages is not edited on the GPU");
}

void ReliefMap::heightsChanged(const std::vector<TexelRect>& changed) {
    refuseIfPaged();
    if (tiles() != glm::ivec2(1, 1)) {
        textures_.rebuildFromSamples(programs_->gl());  // the GPU builder bounds one map
    } else {
        programs_->pyramidBuilder().update(textures_, changed);
    }
    textures_.dropConeMaps();  // stale: built again when next asked for
    highestSample_ = maxHeight();
    ++generation_;
}

void ReliefMap::heightsReplaced() {
    refuseIfPaged();
    if (tiles() != glm::ivec2(1, 1)) {
        textures_.rebuildFromSamples(programs_->gl());
    } else {
        programs_->pyramidBuilder().build(textures_);
    }
    textures_.dropConeMaps();
    highestSample_ = maxHeight();
    ++generation_;
}

}  // namespace microrelief
