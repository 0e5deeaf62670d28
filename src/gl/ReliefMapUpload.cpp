#include "microrelief/gl/ReliefMapUpload.h"

#include <utility>

#include "microrelief/core/Error.h"

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

}  // namespace microrelief
