// The files a relief's description names, and what they hold: the one place where the
// rules live that turn a ReliefDesc (core/scene/Scene.h) into its resources. The map is
// the relief's own file or the bundled default (share/microrelief/assets/cobbles.png); the
// colours are the relief's albedo file, none, or by default the bundled map's own colours,
// which go only with the bundled map's stones. Every program (microrelief-render, its camera
// paths, the viewer, microrelief-bench's maps) and an engine reading a scene resolve files
// here rather than by hand.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>

#include "microrelief/core/image/Albedo.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/io/HeightMapFile.h"

namespace microrelief {

// The height map file `map` names: its own, or the bundled default map where it names none
// (a list of maps, such as microrelief-bench's, resolves each entry here). `relief`'s: its
// map's.
std::filesystem::path heightMapPath(const MapSource& map);
std::filesystem::path heightMapPath(const ReliefDesc& relief);
// The albedo file `relief` draws with: its own, or the bundled map's with the bundled map
// (unless an animated field, waves or ripples, replaces its heights); none for
// AlbedoSource::Kind::None or another map without one.
std::optional<std::filesystem::path> albedoPath(const ReliefDesc& relief);
// Whether the bundled map's colours go with `relief`'s heights: the bundled map, unless an
// animated field replaces them (albedoPath's rule for AlbedoSource::Kind::Default).
bool bundledColoursFit(const ReliefDesc& relief);
// Whether `relief` has colours to turn on, whatever albedo.kind says now: a file of its
// own (kept while turned off), or the bundled map's (bundledColoursFit).
bool albedoOffered(const ReliefDesc& relief);

// What loadReliefFiles reads: the map and its colours, or one of them where a host holds
// the other already (a camera path's frames change colours over one map; the viewer turns
// colours on and off over the map it holds, and opens another map under the same colours
// rule).
enum class ReliefParts { HeightsAndAlbedo, Heights, Albedo };

// What a relief's map and albedo hold.
struct ReliefFiles {
    // The file the heights were read from (heightMapPath); none where the description
    // holds its samples in memory (MapSource::samples) or the heights were not asked for.
    std::optional<std::filesystem::path> heightFile;
    std::shared_ptr<const HeightMap> heights;  // shared with the description's, or read
    std::optional<Georeference> georeference;  // a DEM's (io/HeightMapFile.h)
    std::optional<GroundPlacement> placement;  // a DEM's, with its georeference
    std::optional<std::filesystem::path> albedoFile;  // albedoPath, where asked for
    std::optional<AlbedoImage> albedo;                // its texels, where it names one
    // On the mesh base (ReliefDesc::onMesh), with the heights: the triangles, the
    // description's in memory or read from its file (meshFile; io/MeshFile.h).
    std::optional<std::filesystem::path> meshFile;
    std::shared_ptr<const TriangleMesh> mesh;

    // The heights for a host that edits them (the viewer's sculpting), `heights` left empty:
    // those read from the file handed over as they are (no copy: a copy of `heights` kept
    // from before sees the edits), the description's samples in memory copied (they are
    // shared, not the caller's to change).
    std::shared_ptr<HeightMap> takeHeights();

private:
    friend ReliefFiles loadReliefFiles(const ReliefDesc&, ReliefParts);
    std::shared_ptr<HeightMap> read_;  // `heights` as read from the file, before takeHeights
};

// Reads what `relief` names, as `parts` asks: the samples it holds, or its map file as
// relief.map.load says (loadHeightMapFile), and with them on the mesh base its triangles
// (loadMeshFile); the albedo where albedoPath names one (loadAlbedo). Throws as those do:
// one Error(BadInput) naming the file and the reason.
ReliefFiles loadReliefFiles(const ReliefDesc& relief,
                            ReliefParts parts = ReliefParts::HeightsAndAlbedo);

}  // namespace microrelief
