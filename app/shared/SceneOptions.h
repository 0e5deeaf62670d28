// The flags that describe a view of a height map (scene-and-cli.md): the programs' names
// for the fields of the library's scene values (core/scene/Scene.h: ReliefDesc, ViewDesc).
// microrelief-render and microrelief-viewer register them through this one file, so the
// viewer's "copy as command" writes exactly what the renderer parses. Each flag's name and
// --help line is its field's row in the library's table of scene fields
// (core/scene/SceneFields.h), which also names the flag in every error the library reports
// about a field (flagName); how it is read and written back is its binding
// (SceneBindings.h), which SceneFlags and renderCommandLine go through in one loop.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "SceneBindings.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Georeference.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/io/AtomicFile.h"
#include "microrelief/io/ReliefFiles.h"

namespace CLI {
class App;
class Option;
}

namespace microrelief {

struct SceneOptions {
    RenderJob job;  // the relief (its map file, colours, base, ...) and the view of it
    // What a georeferenced map may set in `job` (core/scene/Georeference.h): --exaggeration,
    // and which of --height-scale, --model and --base were given (those are kept).
    GeoreferenceFit georeference;
};

// The flag that sets a scene field ("camera.eye" -> "--eye"); a field no flag sets is
// written as the field itself. What the programs print for {field} in the library's
// errors (core/Error.h).
std::string flagName(const std::string& field);

// Registers the flags on a CLI11 app and turns their text into the options after the
// parse. Two groups, so a program can place its own flags between them in --help.
class SceneFlags {
public:
    // The targets hold the defaults shown in --help and receive the parsed values; they
    // must outlive the parse.
    // `withAlbedo`: register --albedo too (the programs that draw colours).
    explicit SceneFlags(RenderJob& job, bool withAlbedo = false);
    explicit SceneFlags(SceneOptions& options) : SceneFlags(options.job, true) {
        fit_ = &options.georeference;
    }

    // --height --channel --normalize --height-scale --exaggeration (with SceneOptions)
    // --interpolation --base --radius --length --radii --mesh --tile --animate --time --eye
    // --target --up --fovy --size --model
    void addMapAndCamera(CLI::App& app);
    // --light --light-position --shadows --light-size --method --steps --pixel-error --view
    // --background
    void addShading(CLI::App& app);

    // After app.parse(): fills the job from the flags' text and validates it
    // (validateScene). Throws Error(BadInput) with a message naming the flag.
    void apply();

private:
    // Registers the group's flags, in the bindings' order.
    void add(CLI::App& app, FlagGroup group);

    RenderJob& job_;
    bool withAlbedo_;
    GeoreferenceFit* fit_ = nullptr;  // SceneOptions': --exaggeration and the flags given
    std::optional<double> exaggeration_;
    FlagSlots slots_;  // each binding's text, seeded from the job (SceneBindings.h)
};

// --memory MiB, both programs' (its default `mib` as given): the GPU memory for the pages of
// a map larger than the GL's textures (gl/PagedPyramid.h), which `drawn` says how such a
// map is drawn in that program ("drawn again until exact").
CLI::Option* addMemoryFlag(CLI::App& app, std::size_t& mib, const std::string& drawn);
// The load limits of a program that reads maps past the GL's textures through pages: sides
// to kMaxPagedHeightMapSide, samples as many as the memory available now holds with their
// pyramid (kPagedBytesPerSample a sample; core/Machine.h: availableMemoryBytes).
void allowPagedMaps(HeightMapLoadOptions& load);

// "a,b,c,..." -> exactly `count` finite numbers; throws Error(BadInput) naming `flag` and
// saying it expects `what`.
std::vector<double> parseNumberList(const std::string& flag, const std::string& text,
                                    std::size_t count, const std::string& what);
// --tile's "N,M": each a whole number from 1 to kMaxTiles (core/scene/Scene.h); throws
// Error(BadInput).
glm::ivec2 parseTiles(const std::string& text);
// "x,y,z" -> vector, for --eye and its kind, each component within `limit`
// (kMaxWorldPosition for a position); throws Error(BadInput) naming `flag`.
glm::dvec3 parseVectorFlag(const std::string& flag, const std::string& text,
                           const char* expected = "three numbers x,y,z",
                           double limit = kMaxWorldCoordinate);
// "WxH" -> width, height, each side from 1 to `maxSide`; throws Error(BadInput) naming
// `flag`, for a side beyond `maxSide` with `limitReason` ("the most ...") in the message.
void parseSizeFlag(const std::string& text, int& width, int& height, int maxSide = 65536,
                   const std::string& limitReason = "", const std::string& flag = "--size");

// The shortest decimal text that reads back as exactly `value` ("0.1", "-2.5e-07").
std::string exactNumber(double value);
// "x,y,z" with exactNumber() components.
std::string exactVector(const glm::dvec3& v);

// heightMapPath, albedoPath, bundledColoursFit, albedoOffered: io/ReliefFiles.h.
// The files drawing `relief` reads, named by their flags after `where` (a camera file's
// row: "cams.csv: line 4 (frame 2): "): the height map, the albedo, if any, and the mesh
// base's file. What no output of a run may be (io/AtomicFile.h: checkOutputsAreNotInputs).
std::vector<NamedFile> filesRead(const ReliefDesc& relief, const std::string& where = "");

// `job` over a W x H map read with the georeference `geo` (io/HeightMapFile.h:
// loadHeightMapFile): the true proportions where `fit` lets (core/scene/Georeference.h),
// checked again (validateScene; a height scale the fit made that is not a positive finite
// number is refused naming `source`, the map); `job` as given for a map without one.
RenderJob sceneOverMap(const RenderJob& job, const GeoreferenceFit& fit, int width, int height,
                       const std::optional<Georeference>& geo, const std::string& source);
// The warning for --exaggeration over a map with no georeference (it is drawn at
// --height-scale); empty where there is nothing to say.
std::string exaggerationUnused(const std::string& source, const GeoreferenceFit& fit,
                               const std::optional<Georeference>& geo);
// One line for the programs' progress: what the georeference gave and how it is drawn.
// "dem.tif: WGS 84 / UTM zone 33N, samples 30 x 30 m, heights 412 to 1830 m; drawn at its
// true proportions (height scale 0.0183)".
std::string georeferenceSummary(const std::string& file, const Georeference& geo,
                                const RenderJob& fitted, const GeoreferenceFit& fit);

// The microrelief-render command line (without --out) that renders `options` again, every
// value written exactly: `program --height FILE --height-scale 0.1 --eye x,y,z ...`.
// Arguments are quoted for a POSIX shell where they need it.
std::string renderCommandLine(const SceneOptions& options,
                              const std::string& program = "microrelief-render");

// `text` quoted for a POSIX shell, unchanged when it needs no quoting.
std::string shellQuote(const std::string& text);

}  // namespace microrelief
