#include "BatchRender.h"

#include "Aov.h"

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <tuple>

#include "CameraPath.h"
#include "EyeInside.h"
#include "FramePattern.h"
#include "Manifest.h"
#include "MeshNotes.h"
#include "Progress.h"
#include "PyramidCache.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"
#include "microrelief/core/scene/FloatLimits.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/io/MeshFile.h"
#include "microrelief/io/ReliefFiles.h"

namespace microrelief {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct FrameFiles {
    int frame = 0;
    std::filesystem::path out;
    std::optional<std::filesystem::path> aov;
};

// The files of every selected frame, checked before anything is drawn: patterns that
// name one file for two frames, unknown formats, folders in the way.
std::vector<FrameFiles> frameFiles(const RenderOptions& o, std::size_t pathLength,
                                   const std::vector<int>& frames) {
    const FramePattern out(o.out.string(), "--out");
    const std::optional<FramePattern> aov =
        o.aov ? std::optional<FramePattern>(FramePattern(o.aov->string(), "--aov")) : std::nullopt;
    if (pathLength > 1 && !out.uses("frame")) {
        throwBadInput("--out " + out.text() +
                      ": no {frame} in the name, so every frame would overwrite the last (e.g. "
                      "out/view-{frame:04d}.png)");
    }
    if (aov && pathLength > 1 && !aov->uses("frame")) {
        throwBadInput("--aov " + aov->text() +
                      ": no {frame} in the name, so every frame would overwrite the last (e.g. "
                      "out/view-{frame:04d}.exr)");
    }
    std::vector<FrameFiles> files;
    std::map<std::filesystem::path, int> owner;  // file -> frame, to find names given twice
    for (const int frame : frames) {
        FrameFiles f{frame, out.expand("frame", frame), std::nullopt};
        if (aov) f.aov = aov->expand("frame", frame);
        if (files.empty()) {
            if (f.aov) checkAovExtension(*f.aov);
            checkOutputTargets(f.aov ? std::vector{f.out, *f.aov} : std::vector{f.out});
        }
        for (const auto* file : {&f.out, f.aov ? &*f.aov : nullptr}) {
            if (!file) continue;
            const auto [at, fresh] = owner.emplace(file->lexically_normal(), frame);
            if (!fresh) {
                throwBadInput(file->string() + ": the name of two outputs (frames " +
                              std::to_string(at->second) + " and " + std::to_string(frame) + ")");
            }
            checkReplaceable(*file);  // a folder, FIFO or device: refused before any frame
        }
        files.push_back(std::move(f));
    }
    return files;
}

// Every map and albedo file a selected frame reads (io/ReliefFiles.h: heightMapPath,
// albedoPath) is there, before anything is drawn (what is in it is checked when it is loaded).
void checkMapFiles(const CameraPath& path, const std::vector<int>& frames) {
    std::set<std::filesystem::path> checked;
    for (const int k : frames) {
        const PathFrame frame = path.frame(k);
        const std::optional<std::filesystem::path> mapFile = heightMapPath(frame.scene.job),
                                                   albedoFile = albedoPath(frame.scene.job);
        for (const auto* file : {&mapFile, &albedoFile}) {
            if (!*file || !checked.insert(**file).second) continue;
            std::error_code ec;
            const auto status = std::filesystem::status(**file, ec);
            if (!std::filesystem::exists(status))
                throwBadInput(frame.origin + ": " + (*file)->string() + ": no such file");
            if (!std::filesystem::is_regular_file(status))
                throwBadInput(frame.origin + ": " + (*file)->string() + ": not a regular file");
        }
    }
}

std::filesystem::path manifestFile(const RenderOptions& o) {
    const Shard shard = o.batch.shard.value_or(Shard{});
    const std::string text =
        o.batch.manifest ? *o.batch.manifest
                         : (FramePattern(o.out.string(), "--out").fixedFolder() /
                            (o.batch.shard ? "manifest-{shard}-of-{shards}.csv" : "manifest.csv"))
                               .string();
    return FramePattern(text, "--manifest", {"shard", "shards"})
        .expand({{"shard", shard.index}, {"shards", shard.count}});
}

// Before anything is read or written: the manifest is no frame's file, and no file the run
// writes (frames, AOVs, the manifest) is one it reads (the camera file, each selected
// frame's map and albedo), through a link or not.
void checkFilesWritten(const RenderOptions& o, const CameraPath& path,
                       const std::vector<FrameFiles>& files,
                       const std::filesystem::path& manifest) {
    for (const FrameFiles& f : files) {
        if (manifest.lexically_normal() == f.out.lexically_normal() ||
            (f.aov && manifest.lexically_normal() == f.aov->lexically_normal()))
            throwBadInput(manifest.string() + ": given for the manifest and an output");
    }
    std::vector<NamedFile> read;
    if (o.batch.cameras) read.push_back({*o.batch.cameras, "--cameras"});
    std::set<std::filesystem::path> seen;
    for (const FrameFiles& f : files) {
        const PathFrame frame = path.frame(f.frame);
        for (NamedFile& file :
             filesRead(frame.scene.job, o.batch.cameras ? frame.origin + ": " : "")) {
            if (seen.insert(file.file).second) read.push_back(std::move(file));
        }
    }
    std::vector<NamedFile> written{{manifest, "--manifest"}};
    for (const FrameFiles& f : files) {
        written.push_back({f.out, "--out"});
        if (f.aov) written.push_back({*f.aov, "--aov"});
    }
    checkOutputsAreNotInputs(written, read);
}

// Removes the temporary files that a killed run left beside this run's outputs; those
// of other frames and of running processes stay.
int removeAbandonedTemporaries(const std::vector<FrameFiles>& files) {
    std::set<std::filesystem::path> outputs, folders;
    for (const FrameFiles& f : files) {
        for (const auto* file : {&f.out, f.aov ? &*f.aov : nullptr}) {
            if (!file) continue;
            outputs.insert(file->lexically_normal());
            folders.insert(file->parent_path());
        }
    }
    int removed = 0;
    for (const auto& folder : folders) {
        std::error_code ec;
        const std::filesystem::path listed = folder.empty() ? "." : folder;
        for (auto it = std::filesystem::directory_iterator(listed, ec);
             !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
            const auto target = abandonedTemporaryTarget(folder / it->path().filename());
            if (!target || outputs.count(target->lexically_normal()) == 0) continue;
            std::error_code ignored;
            removed += std::filesystem::remove(it->path(), ignored);
        }
    }
    return removed;
}

std::string plural(int n, const std::string& noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// A file as an earlier run left it, whole: checked, not trusted. This program renames
// files into place only when they are on disk, but a file there may come from a version
// that did not, a disk that lost what it said it had, or another program.
bool complete(const std::filesystem::path& file, BatchProgress& progress) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return false;
    const std::optional<std::string> defect = imageFileDefect(file);
    if (defect) {
        progress.clear();
        logWarning(file.string() + ": not a whole image (" + *defect + "); drawing it again");
    }
    return !defect;
}

// The map a frame draws, as the check before the first frame loads it and bounds its extent:
// file, load options, whether its pyramid wraps in u and the tiles (what core/scene/Scene.h's
// samePyramid compares, as a key that orders; the renderer itself asks needsHeights), and
// whether the base given is kept over a georeferenced map's (a global grid goes on the
// ellipsoid unless a --base is given: fittedBase), so that one key is one drawn base.
using MapKey = std::tuple<std::filesystem::path, int, bool, bool, int, int, bool>;

// Whether two keys name the same samples (file and load options), whatever they are drawn on.
bool sameSamples(const MapKey& a, const MapKey& b) {
    return std::get<0>(a) == std::get<0>(b) && std::get<1>(a) == std::get<1>(b) &&
           std::get<2>(a) == std::get<2>(b);
}

MapKey mapKey(const SceneOptions& scene) {
    return {heightMapPath(scene.job),
            scene.job.map.load.channel,
            scene.job.map.load.normalize,
            scene.job.base.wrapsU(),
            scene.job.tiles.x,
            scene.job.tiles.y,
            scene.georeference.keepBase};
}

// A map as loaded for a frame, kept from the check before the first frame to the first
// frame that draws it (no second load where the whole path draws one map).
struct LoadedMap {
    MapKey key;
    std::shared_ptr<const HeightMap> map;
};

// What the frames need of each map they draw: its size and largest height (the float
// limits), its georeference (a frame's scene over it: SceneOptions.h, sceneOverMap); with
// --pyramid-cache, that the frames draw it from its pyramid file (opened again when a frame
// needs it: a path of a thousand maps holds one open at a time).
struct MapFacts {
    MapExtent extent;
    std::optional<Georeference> georeference;
    bool fromPyramidFile = false;
};

struct CheckedFrames {
    std::map<MapKey, MapFacts> maps;
    std::optional<LoadedMap> last;  // the last map loaded
};

// The name of a frame's mesh in messages: its file.
std::string meshName(const RenderJob& job) {
    return job.mesh.file ? job.mesh.file->string() : std::string("the mesh");
}

// A frame's scene over its map: a georeferenced map's true proportions where the frame's
// flags let.
RenderJob frameJob(const PathFrame& frame, const MapFacts& facts) {
    // The mesh base: no fit, the mesh's units are its file's (as its single picture).
    if (frame.scene.job.onMesh) return frame.scene.job;
    return sceneOverMap(frame.scene.job, frame.scene.georeference, facts.extent.width,
                        facts.extent.height, facts.georeference,
                        heightMapPath(frame.scene.job).string());
}

// The facts of a frame's map, the first time a frame draws it: with --pyramid-cache from its
// pyramid file (opened, built where missing, and closed again), else from the map loaded
// whole, which `last` keeps for the first frame that draws it.
MapFacts readMapFacts(const RenderOptions& o, const PathFrame& frame, const MapKey& key,
                      std::optional<LoadedMap>& last) {
    if (o.pyramidCache) {
        const std::shared_ptr<const PyramidFile> pages =
            openPyramidCache(o, std::get<0>(key), frame.scene.job.map.load,
                             drawnBase(frame.scene, std::get<0>(key)).wrapsU());
        const MapExtent extent{pages->mapWidth(), pages->mapHeight(), pages->largestSample()};
        return MapFacts{extent, pages->georeference(), true};
    }
    ReliefFiles loaded =
        loadFilesOrPointToCache(frame.scene.job, o.compareReference, ReliefParts::Heights);
    const HeightMap& map = *loaded.heights;
    MapFacts facts{{map.width, map.height, map.maxValue()}, loaded.georeference, false};
    last = LoadedMap{key, std::move(loaded.heights)};
    return facts;
}

// What a map's facts tell the user, once a map: an exaggeration its grid leaves unused and,
// unless --quiet, what its georeference gave.
void reportMapFacts(const RenderOptions& o, const PathFrame& frame, const MapKey& key,
                    const MapFacts& facts) {
    if (frame.scene.job.onMesh) return;  // no georeference fit on the mesh base (frameJob)
    if (const std::string unused = exaggerationUnused(std::get<0>(key).string(),
                                                      frame.scene.georeference, facts.georeference);
        !unused.empty())
        logWarning(unused);
    if (facts.georeference && !o.quiet)
        std::printf("microrelief-render: %s\n",
                    georeferenceSummary(std::get<0>(key).string(), *facts.georeference,
                                        frameJob(frame, facts), frame.scene.georeference)
                        .c_str());
}

// Every selected frame, checked before the first is drawn, its errors naming its row: the
// maps it draws load (each once) and, with its camera, stay within what the shader's
// float arithmetic holds (core/scene/FloatLimits.h); its albedo loads. An animated frame's
// heights are known once evaluated: its limits are checked when it is drawn. Unless
// `quiet`, a line says what each georeferenced map's grid gave. With --pyramid-cache each
// map's pyramid file is opened (built where missing) in place of the map: never read whole.
CheckedFrames checkFrames(const RenderOptions& o, const CameraPath& path,
                          const std::vector<int>& frames) {
    CheckedFrames checked;
    std::set<std::filesystem::path> albedos;
    // The meshes' -v lines said (mesh, height scale, the map's top): each once, its sizes
    // (a sort of the triangles) not computed again per frame.
    std::set<std::tuple<std::string, double, double>> described;
    for (const int k : frames) {
        const PathFrame frame = path.frame(k);
        try {
            const MapKey key = mapKey(frame.scene);
            auto facts = checked.maps.find(key);
            if (facts == checked.maps.end()) {
                checked.last.reset();
                facts = checked.maps.emplace(key, readMapFacts(o, frame, key, checked.last)).first;
                reportMapFacts(o, frame, key, facts->second);
            }
            const RenderJob job = frameJob(frame, facts->second);
            checkPictureSize(job.width, job.height);
            if (o.pyramidCache) checkDrawnFromPyramidFile(job, o.compareReference);
            if (job.onMesh) {
                // The mesh's own limits (the map's largest height from its facts); the
                // camera's positions were checked with the path (CameraPath.h).
                checkMeshFloatLimits(*job.mesh.triangles, facts->second.extent.maxHeight,
                                     job.heightScale, meshName(job));
                // -v's size of the mesh against its shell, as the single picture says it:
                // once for each mesh and height scale of the path.
                const double top = facts->second.extent.maxHeight;
                if (o.verbose && described.emplace(meshName(job), job.heightScale, top).second)
                    logInfo(meshSizeLine(meshName(job), *job.mesh.triangles, job.heightScale, top));
            } else if (job.animation.empty()) {
                const MapExtent& map = facts->second.extent;
                checkFloatLimits({map.width * job.tiles.x, map.height * job.tiles.y, map.maxHeight},
                                 job.heightScale, job.base, job.model, job.camera,
                                 resolveCamera(job.camera, job.width, job.height, 1.0),
                                 std::get<0>(key).string());
            }
            if (const auto albedo = albedoPath(job); albedo && albedos.insert(*albedo).second)
                (void)loadReliefFiles(job, ReliefParts::Albedo);  // what is in it: finite
        } catch (const Error& e) {
            throw e.after(frame.origin + ": ");
        }
    }
    return checked;
}

// The meshes of a path's frames on the mesh base (ReliefDesc::onMesh): each file named
// and the triangles read from it, once.
using PathMeshes = std::vector<std::pair<std::string, std::shared_ptr<const TriangleMesh>>>;

// A frame's mesh: read once a file (kept in `meshes`) and held in the frame's scene
// (MeshSource::triangles: no frame reads its file again, and the renderer keeps its proxy
// from frame to frame: HeadlessRenderer::setMesh). Errors name the frame's row, where
// `fromRow` (a command line's file is named by its own flag).
void holdMesh(PathFrame& frame, PathMeshes& meshes, bool fromRow) {
    MeshSource& source = frame.scene.job.mesh;
    if (!frame.scene.job.onMesh || source.triangles) return;
    const std::string name = meshName(frame.scene.job);
    for (const auto& [file, mesh] : meshes) {
        if (file == name) {
            source.triangles = mesh;
            return;
        }
    }
    try {
        source.triangles = std::make_shared<const TriangleMesh>(loadMeshFile(*source.file));
    } catch (const Error& e) {
        if (!fromRow) throw;
        throw e.after(frame.origin + ": ");
    }
    meshes.emplace_back(name, source.triangles);
}

// The path with its frames' meshes held (holdMesh), once the plan's files are checked: a
// camera file's selected rows each hold their own. A turntable on the mesh base turns the
// camera the single picture takes: where --eye or --target is not given, the one framing
// the mesh's shell (gl/HeadlessRender.h: meshCamera, at the command line's picture size),
// for which the map is read too, even where --skip-existing finds every frame done (the
// manifest's rows name each frame's camera).
CameraPath pathWithMeshes(const RenderOptions& o, std::vector<PathFrame> rows,
                          const std::vector<int>& frames, PathMeshes& meshes) {
    if (o.batch.cameras) {
        for (const int k : frames) holdMesh(rows.at(static_cast<std::size_t>(k)), meshes, true);
        return CameraPath(std::move(rows));
    }
    PathFrame line{o.scene, "", "the command line"};
    if (!line.scene.job.onMesh) return CameraPath::turntable(o.scene, o.batch.turntable);
    holdMesh(line, meshes, false);
    RenderJob& job = line.scene.job;
    if (!(o.eyeGiven && o.targetGiven)) {
        const std::shared_ptr<const HeightMap> map =
            loadFilesOrPointToCache(job, o.compareReference, ReliefParts::Heights).heights;
        // Before the camera frames it, as the single picture (the line names the mesh).
        checkMeshFloatLimits(*job.mesh.triangles, *map, job.heightScale, meshName(job));
        job.camera = meshCamera(job.camera, o.eyeGiven, o.targetGiven,
                                meshShellExtent(*job.mesh.triangles, job.heightScale,
                                                map->maxValue()),
                                job.width, job.height);
        if (o.verbose)
            logInfo("the camera framing the mesh, the turntable's frame 0: " +
                    cameraFlags(job.camera));
    }
    return CameraPath::turntable(line.scene, o.batch.turntable);
}

// The stages of a run, in the order runBatch calls them. Each says what it hands the next.

// Stage 1, the plan: the path (frames made one at a time as they are drawn: a path of a
// million views holds none), the frames the --frames range and the --shard select, their
// files and the manifest's, all checked before anything is read or written.
struct BatchPlan {
    CameraPath path;
    Shard shard;
    std::vector<int> frames;
    std::vector<FrameFiles> files;
    std::filesystem::path manifest;
    PathMeshes meshes;  // of the selected frames on the mesh base
};

BatchPlan planBatch(const RenderOptions& o) {
    std::vector<PathFrame> rows;
    if (o.batch.cameras) rows = readCameraFile(*o.batch.cameras, o.scene);
    CameraPath path = o.batch.cameras ? CameraPath(rows)
                                      : CameraPath::turntable(o.scene, o.batch.turntable);
    const Shard shard = o.batch.shard.value_or(Shard{});
    std::vector<int> frames = selectFrames(path.size(), o.batch.frames, shard);
    std::vector<FrameFiles> files = frameFiles(o, path.size(), frames);
    std::filesystem::path manifest = manifestFile(o);
    checkFilesWritten(o, path, files, manifest);
    PathMeshes meshes;
    path = pathWithMeshes(o, std::move(rows), frames, meshes);
    return {std::move(path),     shard,
            std::move(frames),   std::move(files),
            std::move(manifest), std::move(meshes)};
}

// Stage 2, --skip-existing: which of the plan's frames have whole files already (done, by
// the plan's index), and the frames left to draw. Nothing of a done frame's is read: no map
// loaded, no pyramid file opened or built, no cache folder made.
struct FramesToDraw {
    std::vector<bool> done;
    std::vector<int> frames;
};

FramesToDraw framesToDraw(const RenderOptions& o, const std::vector<FrameFiles>& files,
                          BatchProgress& progress) {
    FramesToDraw left{std::vector<bool>(files.size(), false), {}};
    for (std::size_t k = 0; k < files.size(); ++k) {
        const FrameFiles& f = files[k];
        left.done[k] = o.batch.skipExisting && complete(f.out, progress) &&
                       (!f.aov || complete(*f.aov, progress));
        if (!left.done[k]) left.frames.push_back(f.frame);
    }
    return left;
}

// Stage 3, the frames to draw checked before the first is drawn: their map and albedo files
// are there, then checkFrames. Hands on each map's facts and the last map it loaded.
CheckedFrames checkFramesToDraw(const RenderOptions& o, const CameraPath& path,
                                const std::vector<int>& frames) {
    checkMapFiles(path, frames);
    CheckedFrames checked = checkFrames(o, path, frames);
    if (o.lightSizeGiven && !path.anySoftShadows()) logWarning(lightSizeUnused());
    return checked;
}

// Stage 4, before the first frame is written: the temporaries a killed run left beside
// this run's outputs go (the manifest is opened before, by the caller).
void removeTemporariesOfAKilledRun(const std::vector<FrameFiles>& files) {
    if (const int removed = removeAbandonedTemporaries(files); removed > 0)
        logInfo("removed " + std::to_string(removed) + " temporary file(s) of a killed run");
}

// Stage 5's renderer: the context and renderer, made for the first frame drawn, and the map
// and albedo set on it, changed only for a frame that draws another. Hands each frame's
// picture back, and keeps the counts the summary gives (maps loaded, eyes inside the solid).
class FrameRenderer {
public:
    FrameRenderer(const RenderOptions& o, CheckedFrames& checked) : o_(o), checked_(checked) {}

    HeadlessResult render(const PathFrame& frame, const RenderJob& job, const MapKey& key,
                          const MapFacts& facts) {
        start(frame);
        setMap(job, key, facts);
        setAlbedo(job);
        HeadlessResult result = renderer_->render(job);
        noteEyeInside(frame, job, result);
        return result;
    }

    const GlContext* context() const { return context_.get(); }
    int mapsLoaded() const { return mapsLoaded_; }
    int eyeInside() const { return eyeInside_; }
    const std::string& firstEyeInside() const { return firstEyeInside_; }
    bool firstEyeInsideOnMesh() const { return firstEyeInsideOnMesh_; }

private:
    // The context and renderer, for the first frame drawn (none where every frame is skipped).
    void start(const PathFrame& frame) {
        if (context_) return;
        context_ = createHeadlessContext(o_.backend);
        if (o_.verbose)
            logInfo("GL: " + context_->renderer() + ", " + context_->version() + " via " +
                    context_->description());
        renderer_.emplace(*context_, frame.scene.job.method);
        renderer_->setPaging(o_.paging);
    }

    // A map is loaded and its pyramid built only for a frame whose relief has another
    // pyramid than the last (core/scene/Scene.h: samePyramid).
    void setMap(const RenderJob& job, const MapKey& key, const MapFacts& facts) {
        if (facts.fromPyramidFile) {
            // Pages stay resident from frame to frame while the map is the same (another
            // size of its base, last level or view is the job's own: render applies it).
            if (pagesSet_ != key) {
                renderer_->setPyramidPages(
                    openPyramidCache(o_, std::get<0>(key), job.map.load, job.base.wrapsU()),
                    std::get<0>(key).string(), job.base, job.interpolation);
                pagesSet_ = key;
                map_.reset();
                mapHeld_.reset();
                ++mapsLoaded_;
            }
        } else if (job.onMesh) {
            setMeshMap(job, key);
        } else if (renderer_->needsHeights(job)) {
            // The same samples for another pyramid (another base or tiles): the map held.
            // The check's map, where it has the same samples, is not read again either.
            std::optional<LoadedMap>& checkedMap = checked_.last;
            const bool held = map_ && mapHeld_ && sameSamples(*mapHeld_, key);
            const bool checkedHere = checkedMap && sameSamples(checkedMap->key, key);
            // Or the mesh frames' map (setMeshMap), where a path mixes the mesh and a base.
            const bool onTheMesh = meshMap_ && sameSamples(meshMap_->key, key);
            std::shared_ptr<const HeightMap> heights =
                held          ? map_
                : onTheMesh   ? meshMap_->map
                : checkedHere ? std::move(checkedMap->map)
                              : loadReliefFiles(job, ReliefParts::Heights).heights;
            checkedMap.reset();  // taken, or held already, or of another map: not kept
            if (!held) {
                map_.reset();  // the last map, kept now only by pages that setHeights lets go
                mapHeld_.reset();
                if (!onTheMesh) ++mapsLoaded_;
            }
            renderer_->setHeights(job, heights, std::get<0>(key).string());
            map_ = std::move(heights);
            mapHeld_ = key;
        }
    }

    // The mesh base's map, held apart from `map_` (the other bases' pyramid, which a path
    // that mixes them keeps): loaded only for other samples than the last mesh frame's, and
    // not where the other bases' or the check's map has them. The renderer keeps the mesh's
    // relief while the mesh and the map are the same (the same pointers:
    // HeadlessRenderer::setMesh).
    void setMeshMap(const RenderJob& job, const MapKey& key) {
        std::optional<LoadedMap>& checkedMap = checked_.last;
        if (!meshMap_ || !sameSamples(meshMap_->key, key)) {
            const bool checkedHere = checkedMap && sameSamples(checkedMap->key, key);
            const bool heldHere = map_ && mapHeld_ && sameSamples(*mapHeld_, key);
            std::shared_ptr<const HeightMap> heights =
                heldHere      ? map_
                : checkedHere ? std::move(checkedMap->map)
                              : loadReliefFiles(job, ReliefParts::Heights).heights;
            if (!heldHere) ++mapsLoaded_;
            meshMap_ = LoadedMap{key, std::move(heights)};
        }
        checkedMap.reset();  // taken, or held already, or of another map: not kept
        renderer_->setMesh(job.mesh.triangles, meshMap_->map, meshName(job));
    }

    // The albedo, loaded again only where it is another file (or none) than the last frame's.
    void setAlbedo(const RenderJob& job) {
        if (albedoPath(job) == loadedAlbedo_) return;
        loadedAlbedo_.reset();
        const ReliefFiles colours = loadReliefFiles(job, ReliefParts::Albedo);
        renderer_->setAlbedo(colours.albedo ? &*colours.albedo : nullptr,
                             colours.albedoFile ? colours.albedoFile->string() : "");
        loadedAlbedo_ = colours.albedoFile;
    }

    // A map drawn from its pyramid file is not in memory to hold the eye to.
    void noteEyeInside(const PathFrame& frame, const RenderJob& job, const HeadlessResult& result) {
        const HeightMap* traced = result.animatedMap ? &*result.animatedMap
                                  : job.onMesh       ? meshMap_->map.get()
                                  : map_             ? map_.get()
                                                     : nullptr;
        // The mesh's classes take the map's rows reversed (HeightMap.h: rowsReversed).
        const bool inside =
            traced && (job.onMesh ? eyeInsideTheMeshSolid(*job.mesh.triangles,
                                                          rowsReversed(*traced), job)
                                  : eyeInsideTheSolid(*traced, job));
        if (inside && eyeInside_++ == 0) {
            firstEyeInside_ = frame.origin;
            firstEyeInsideOnMesh_ = job.onMesh;
        }
    }

    const RenderOptions& o_;
    CheckedFrames& checked_;
    std::unique_ptr<GlContext> context_;
    std::optional<HeadlessRenderer> renderer_;
    // The map drawn, for the eye's check (none from a file); shared with the renderer, whose
    // pages keep it rather than a copy where it reads it through pages.
    std::shared_ptr<const HeightMap> map_;
    std::optional<MapKey> mapHeld_;   // the key of the frame `map_` was loaded or set for
    std::optional<LoadedMap> meshMap_;  // the mesh base's map and its key (setMeshMap)
    std::optional<MapKey> pagesSet_;  // the map whose pyramid file the renderer reads
    // The albedo file set on the renderer (itself optional: none); unset before the first.
    std::optional<std::optional<std::filesystem::path>> loadedAlbedo_;
    int mapsLoaded_ = 0;
    int eyeInside_ = 0;  // frames whose eye lies inside the solid
    std::string firstEyeInside_;
    bool firstEyeInsideOnMesh_ = false;  // whether that frame's base is the mesh
};

// Stage 5's end for a frame: a warning for pixels that ran out of the iteration budget, then
// the picture (and its AOVs) written whole or not at all.
void writeFrame(const FrameFiles& f, const RenderJob& job, const RenderedFrame& pixels,
                BatchProgress& progress) {
    std::size_t exhausted = 0;
    for (std::size_t p = 3; p < pixels.stats.size(); p += 4) exhausted += pixels.stats[p] > 0.0f;
    if (exhausted > 0) {
        progress.clear();
        logWarning("frame " + std::to_string(f.frame) + ": " + std::to_string(exhausted) +
                   " pixel(s) ran out of the iteration budget (shown magenta)");
    }
    ImageWriteBatch batch;
    const std::vector<std::uint8_t> rgb = rgbFromRgba(pixels.color, pixels.width, pixels.height);
    batch.write(f.out, {pixels.width, pixels.height, 3, PixelType::UInt8, rgb.data(), {}});
    if (f.aov) writeAov(batch, *f.aov, pixels, job.shading.shadows != ShadowMode::Off);
    batch.commit();
}

// Stage 5, every frame of the plan in order: a skipped one gets its row, one to draw is drawn
// over its map (as the check found it) and written, then gets its row. A frame that fails
// gets a "failed" row and its error names its row where the row's data is at fault. Hands
// the summary the counts.
struct FrameCounts {
    int rendered = 0;
    int skipped = 0;
};

FrameCounts drawFrames(const BatchPlan& plan, const std::vector<bool>& done,
                       const CheckedFrames& checked, FrameRenderer& renderer,
                       ManifestWriter& manifest, BatchProgress& progress) {
    FrameCounts counts;
    for (std::size_t index = 0; index < plan.files.size(); ++index) {
        const FrameFiles& f = plan.files[index];
        const PathFrame frame = plan.path.frame(f.frame);
        const std::string camera =
            cameraFlags(frame.scene.job.camera) + (frame.flags.empty() ? "" : " " + frame.flags);
        if (done[index]) {
            manifest.append({f.frame, f.out.string(), camera, 0.0, "skipped"});
            ++counts.skipped;
            progress.frameDone(false, 0.0);
            continue;
        }
        const auto frameStart = Clock::now();
        try {
            const MapKey key = mapKey(frame.scene);
            const MapFacts& facts = checked.maps.at(key);
            const RenderJob job = frameJob(frame, facts);
            const HeadlessResult result = renderer.render(frame, job, key, facts);
            writeFrame(f, job, result.frame, progress);
        } catch (const Error& e) {
            progress.clear();
            try {
                manifest.append(
                    {f.frame, f.out.string(), camera, secondsSince(frameStart) * 1e3, "failed"});
            } catch (const Error&) {
                // The frame's own error is the one to report.
            }
            // The row's data at fault: say which row (a GL or disk failure is no row's).
            if (e.kind() == ErrorKind::BadInput) throw e.after(frame.origin + ": ");
            throw;
        }
        const double seconds = secondsSince(frameStart);
        manifest.append({f.frame, f.out.string(), camera, seconds * 1e3, "rendered"});
        ++counts.rendered;
        progress.frameDone(true, seconds);
    }
    return counts;
}

// Stage 6, after the last frame: the eyes inside the solid, then (unless --quiet) one line
// of what was drawn, to where, how fast, and from how many maps.
void reportRun(const RenderOptions& o, const BatchPlan& plan, const FrameCounts& counts,
               const FrameRenderer& renderer, Clock::time_point start) {
    for (const auto& [name, held] : plan.meshes) {
        // Once drawn, as the single picture warns; each mesh once.
        if (counts.rendered == 0) break;
        const TriangleMesh& mesh = *held;
        warnOfZeroUvArea(name, mesh);
    }
    if (renderer.eyeInside() > 0) {
        const bool onMesh = renderer.firstEyeInsideOnMesh();
        const std::string where = onMesh
                                      ? "in the shell between the mesh and the relief's top"
                                      : "under its surface";
        logWarning(plural(renderer.eyeInside(), "frame") + " of " +
                   std::to_string(plan.files.size()) + " drawn with the eye inside the relief's solid (" +
                   where + "; first: " + renderer.firstEyeInside() +
                   "): the pictures are undefined there; move the eye " +
                   (onMesh ? "out of the shell" : "above the surface"));
    }
    if (o.quiet) return;
    const double seconds = secondsSince(start);
    char timing[64];
    std::snprintf(timing, sizeof timing, "%.2f s, %.3g fps", seconds,
                  seconds > 0.0 ? counts.rendered / seconds : 0.0);
    std::string line =
        "microrelief-render: " + plural(static_cast<int>(plan.frames.size()), "frame") + " of " +
        std::to_string(plan.path.size()) + " (" +
        (o.batch.cameras ? o.batch.cameras->string() : "turntable");
    if (o.batch.shard)
        line +=
            ", shard " + std::to_string(plan.shard.index) + "/" + std::to_string(plan.shard.count);
    line += "): " + std::to_string(counts.rendered) + " rendered, " +
            std::to_string(counts.skipped) + " skipped, to " + o.out.string() +
            (o.aov ? " and " + o.aov->string() : "") + "; manifest " + plan.manifest.string() +
            "; " + timing + ", " + plural(renderer.mapsLoaded(), "map") + " loaded" +
            (renderer.context() ? ", " + renderer.context()->description() : "");
    std::printf("%s\n", line.c_str());
}

}  // namespace

int runBatch(const RenderOptions& o) {
    const auto start = Clock::now();
    const BatchPlan plan = planBatch(o);
    BatchProgress progress(static_cast<int>(plan.frames.size()),
                           !o.quiet && BatchProgress::stderrIsTerminal());
    const FramesToDraw left = framesToDraw(o, plan.files, progress);
    CheckedFrames checked = checkFramesToDraw(o, plan.path, left.frames);
    ManifestWriter manifest(plan.manifest);
    removeTemporariesOfAKilledRun(plan.files);
    FrameRenderer renderer(o, checked);
    const FrameCounts counts = drawFrames(plan, left.done, checked, renderer, manifest, progress);
    progress.finish();
    reportRun(o, plan, counts, renderer, start);
    return 0;
}

}  // namespace microrelief
