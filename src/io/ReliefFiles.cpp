#include "microrelief/io/ReliefFiles.h"

#include <utility>

#include "microrelief/core/DataPaths.h"
#include "microrelief/io/AlbedoFile.h"
#include "microrelief/io/MeshFile.h"

namespace microrelief {

std::filesystem::path heightMapPath(const MapSource& map) {
    return map.file ? *map.file : defaultHeightMapPath();
}

std::filesystem::path heightMapPath(const ReliefDesc& relief) {
    return heightMapPath(relief.map);
}

std::optional<std::filesystem::path> albedoPath(const ReliefDesc& relief) {
    switch (relief.albedo.kind) {
        case AlbedoSource::Kind::None:
            return std::nullopt;
        case AlbedoSource::Kind::File:
            return relief.albedo.file;
        case AlbedoSource::Kind::Default:
            break;
    }
    if (bundledColoursFit(relief)) return defaultAlbedoPath();
    return std::nullopt;
}

bool bundledColoursFit(const ReliefDesc& relief) {
    // The bundled map's colours go with its stones: not with a field that replaces them, nor
    // yet on the mesh base (gl/MeshRelief.h draws one colour).
    return relief.map.bundled() && !relief.onMesh &&
           (relief.animation.empty() || animatedFieldShowsTheMap(relief.animation));
}

bool albedoOffered(const ReliefDesc& relief) {
    return !relief.albedo.file.empty() || bundledColoursFit(relief);
}

std::shared_ptr<HeightMap> ReliefFiles::takeHeights() {
    std::shared_ptr<HeightMap> own;
    if (read_ && read_ == heights)
        own = std::move(read_);  // the samples read here, handed over
    else if (heights)
        own = std::make_shared<HeightMap>(*heights);
    read_.reset();
    heights.reset();
    return own;
}

ReliefFiles loadReliefFiles(const ReliefDesc& relief, ReliefParts parts) {
    ReliefFiles files;
    if (parts != ReliefParts::Albedo) {
        if (relief.map.samples) {
            files.heights = relief.map.samples;
        } else {
            files.heightFile = heightMapPath(relief);
            HeightMapFile read = loadHeightMapFile(*files.heightFile, relief.map.load);
            files.read_ = std::make_shared<HeightMap>(std::move(read.map));
            files.heights = files.read_;
            files.georeference = std::move(read.georeference);
            files.placement = std::move(read.placement);
        }
        if (relief.onMesh) {
            if (relief.mesh.triangles) {
                files.mesh = relief.mesh.triangles;
            } else if (relief.mesh.file) {
                files.meshFile = *relief.mesh.file;
                files.mesh = std::make_shared<const TriangleMesh>(loadMeshFile(*files.meshFile));
            }
        }
    }
    if (parts != ReliefParts::Heights) {
        files.albedoFile = albedoPath(relief);
        if (files.albedoFile) files.albedo = loadAlbedo(*files.albedoFile);
    }
    return files;
}

}  // namespace microrelief
