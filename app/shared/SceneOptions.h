// The flags that describe a view of a height map (scene-and-cli.md): the map, the camera
// and the shading. microrelief-render and microrelief-viewer register them through this
// one file, so the viewer's "copy as command" writes exactly what the renderer parses.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/heightmap/HeightMap.h"
#include "microrelief/render/HeadlessRender.h"

namespace CLI {
class App;
}

namespace microrelief {

struct SceneOptions {
    std::optional<std::filesystem::path> heightFile;  // empty: the bundled default map
    // The map's colours: a file, or none; unset: the bundled map's own colours with the
    // bundled map, none with any other.
    std::optional<std::filesystem::path> albedoFile;
    bool noAlbedo = false;  // --albedo none
    HeightMapLoadOptions load;
    RenderJob job;  // camera, size, height scale, shading, background
};

// Registers the flags on a CLI11 app and turns their text into the options after the
// parse. Two groups, so a program can place its own flags between them in --help.
class SceneFlags {
public:
    // The targets hold the defaults shown in --help and receive the parsed values; they
    // must outlive the parse.
    SceneFlags(std::optional<std::filesystem::path>& heightFile, HeightMapLoadOptions& load,
               RenderJob& job);
    explicit SceneFlags(SceneOptions& options)
        : SceneFlags(options.heightFile, options.load, options.job) {
        albedoFile_ = &options.albedoFile;
        noAlbedo_ = &options.noAlbedo;
    }

    // --height --channel --normalize --height-scale --interpolation --base --radius --length
    // --radii --tile --animate --time --eye --target --up --fovy --size --model
    void addMapAndCamera(CLI::App& app);
    // --light --light-position --shadows --light-size --method --steps --pixel-error --view
    // --background
    void addShading(CLI::App& app);

    // After app.parse(): validates and fills the targets. Throws Error(BadInput) with a
    // message naming the flag.
    void apply();

private:
    std::optional<std::filesystem::path>& heightFile_;
    HeightMapLoadOptions& load_;
    RenderJob& job_;
    std::string height_, eye_, target_, up_, size_, light_, method_, view_, background_;
    std::string lightPosition_, shadows_ = "off", albedo_;
    std::optional<std::filesystem::path>* albedoFile_ = nullptr;  // --albedo, where registered
    bool* noAlbedo_ = nullptr;
    std::string base_ = "plane", radii_, interpolation_ = "bilinear", model_, tile_;
    std::optional<double> radius_, length_, time_;
    std::string animate_;
};

// "a,b,c,..." -> exactly `count` finite numbers; throws Error(BadInput) naming `flag` and
// saying it expects `what`.
std::vector<double> parseNumberList(const std::string& flag, const std::string& text,
                                    std::size_t count, const std::string& what);
// --tile's "N,M": each a whole number from 1 to kMaxTiles (the whole map's side in float
// map coordinates stays exact to 2^-7 of a texel at 256 tiles of a 256 map: README,
// "Tiling"); throws Error(BadInput).
inline constexpr int kMaxTiles = 4096;
glm::ivec2 parseTiles(const std::string& text);
// "x,y,z" -> vector, for --eye and its kind; throws Error(BadInput) naming `flag`.
glm::dvec3 parseVectorFlag(const std::string& flag, const std::string& text);
// "WxH" -> width, height, each side from 1 to `maxSide`; throws Error(BadInput), for a
// side beyond `maxSide` with `limitReason` ("the most ...") in the message.
void parseSizeFlag(const std::string& text, int& width, int& height, int maxSide = 65536,
                   const std::string& limitReason = "");

// The shortest decimal text that reads back as exactly `value` ("0.1", "-2.5e-07").
std::string exactNumber(double value);
// "x,y,z" with exactNumber() components.
std::string exactVector(const glm::dvec3& v);

// The albedo file `options` render with: --albedo's, or the bundled map's own with the
// bundled map and no --albedo (unless --animate waves or ripples replaces its heights);
// none for --albedo none or another map without one.
std::optional<std::filesystem::path> albedoPath(const SceneOptions& options);

// The microrelief-render command line (without --out) that renders `options` again, every
// value written exactly: `program --height FILE --height-scale 0.1 --eye x,y,z ...`.
// Arguments are quoted for a POSIX shell where they need it.
std::string renderCommandLine(const SceneOptions& options,
                              const std::string& program = "microrelief-render");

// `text` quoted for a POSIX shell, unchanged when it needs no quoting.
std::string shellQuote(const std::string& text);

}  // namespace microrelief
