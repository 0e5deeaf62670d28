#include "microrelief/core/scene/SceneFields.h"

#include <algorithm>
#include <cctype>

namespace microrelief {

namespace {

// The rows. `help` is what --help prints (tests/cli compare some of it); `doc` what
// docs/cli.md says, links relative to docs/. A default or a range that depends on the
// program (the viewer's smaller maps) is microrelief-render's.
constexpr SceneField kSceneFields[] = {
    {"map.file", "--height", "FILE", "", "bundled `cobbles.png`", "1 x 1 to 65536 x 65536 samples",
     "Height map image (any format OpenImageIO reads); default: the bundled map",
     "height map: any image OpenImageIO reads (PNG 8/16-bit, TIFF, EXR, JPEG, TGA, ...), the "
     "format by its extension (past the GL's `GL_MAX_TEXTURE_SIZE`, 16384 here, read through "
     "pages within `--memory`, and only as many samples as the memory available now holds at "
     "16 bytes each: [terrain.md](terrain.md#maps-larger-than-one-texture); with "
     "`--pyramid-cache`, any such map, never read whole)"},
    // The samples in memory: a library user's (ReliefDesc::map.samples), no program's.
    {"map.samples", "", "", "", "", "", "", ""},
    {"map.load.channel", "--channel", "N", "", "0", "a whole number >= 0",
     "Image channel holding the heights",
     "which channel holds the heights: 0 is a colour picture's red, whatever the others hold "
     "(a photograph's heights are rarely its red: convert it to grey first; a packed map's "
     "height is often alpha, 3)"},
    {"map.load.normalize", "--normalize", "", "", "off", "", "Map the map's [min, max] to [0, 1]",
     "map the map's [min, max] to [0, 1] (a constant map becomes 0)"},
    {"heightScale", "--height-scale", "S", "height-scale", "0.1", "> 0, world units",
     "World height of map value 1 (the map spans 1 unit); default for a georeferenced map: its "
     "true proportions",
     "world height of map value 1; the map's longer side spans 1 world unit. On a curved "
     "base: a fraction of the radius; on the mesh base: the mesh's units. A georeferenced "
     "map (DEM) without it: its true proportions"},
    {"interpolation", "--interpolation", "I", "interpolation", "bilinear",
     "`bilinear`, `biquadratic`",
     "The last level: bilinear, or biquadratic (the quadratic B-spline of the samples: smooth)",
     "the last level, the surface between the samples: `bilinear` (a patch per cell, a facet "
     "close up) or `biquadratic` (the quadratic B-spline of the samples: smooth; see "
     "[interpolation.md](interpolation.md))"},
    // --help appends the table of bases' names and summaries (core/base/BaseType.h).
    {"base", "--base", "B", "base", "plane", "`plane`, `cylinder`, `ellipsoid`, `sphere`, `mesh`",
     "Base surface the map is laid over (u wraps around a curved base's y axis):",
     "the base surface the map is laid over; its sizes are the rows below (see "
     "[bases.md](bases.md)); `mesh`: the triangle mesh of `--mesh` (microrelief-render only "
     "so far)"},
    // The mesh base's file (ReliefDesc::mesh; not a row of the table of bases).
    {"mesh.file", "--mesh", "FILE", "", "none",
     "OBJ, glTF 2.0 (`.gltf`, `.glb`); up to 524288 triangles",
     "With --base mesh: the triangle mesh the map is laid over (OBJ, glTF 2.0), with texture "
     "coordinates; --height-scale is then in its units (microrelief-render only so far)",
     "with `--base mesh`: the triangle mesh the map is laid over, with texture coordinates "
     "(OBJ, glTF 2.0; read as [bases.md](bases.md#the-mesh) says); `--height-scale` is then "
     "in the mesh's units (`-v` prints the mesh's box and the shell's thickness). "
     "microrelief-render only so far, and not yet with shadows, `--albedo FILE`, a method "
     "other than `multilevel`, `--pixel-error`, `--tile`, `--animate`, `--model`, "
     "`--light-position`, a `--view` other than `shaded` and `normal`, `--compare-reference` "
     "or `--pyramid-cache`"},
    {"tiles", "--tile", "N,M", "", "1,1", "each a whole number from 1 to 4096",
     "Repeat the map N,M times across the base (N around a curved base), as the N x M larger "
     "image made by repeating it (default 1,1)",
     "the map repeated N x M times across the base (N around a curved base): the N x M larger "
     "image made by repeating it"},
    {"animation", "--animate", "NAME", "", "none", "`waves`, `ripples`, `flood`",
     "An animated relief over the map's grid, evaluated on the GPU: waves, ripples, or flood "
     "(the map under rising and falling water)",
     "an animated relief over the map's grid, evaluated on the GPU: `waves` (travelling sine "
     "waves, seamless round a curved base), `ripples` (rings from the middle), `flood` (the "
     "map under water that rises and falls); see [dynamic-maps.md](dynamic-maps.md)"},
    {"time", "--time", "T", "", "0", "seconds, within +-1e9",
     "With --animate: the moment drawn, seconds (default 0)", "with `--animate`: the moment drawn"},
    {"camera.eye", "--eye", "x,y,z", "eye", "0.8,0.5,0.85", "world units, each within +-1e12",
     "Camera position x,y,z (world, y up)",
     "camera position (y up); `--eye=-1,2,3` and `--eye -1,2,3` both work"},
    {"camera.target", "--target", "x,y,z", "target", "0,-0.03,0", "world units, each within +-1e12",
     "Point the camera looks at, x,y,z", "point looked at"},
    {"camera.up", "--up", "x,y,z", "up", "0,1,0", "each within +-1e6, not zero",
     "Camera up direction x,y,z", "camera up"},
    {"camera.fovyDegrees", "--fovy", "DEG", "fovy", "45", "degrees, strictly between 0 and 180",
     "Vertical field of view in degrees", "vertical field of view"},
    {"size", "--size", "WxH", "size", "1280x720",
     "pixels: sides up to 65536, at most 16384 x 16384 in all", "Picture size WIDTHxHEIGHT",
     "picture size; beyond the GL's limits it is drawn in tiles"},
    {"model", "--model", "M", "", "identity", "12 numbers, an invertible matrix",
     "Where the relief sits in the world: a 3 x 4 affine matrix, 12 numbers in rows "
     "(m00,m01,m02,tx,m10,...,tz); default: the identity",
     "where the relief sits in the world: a 3 x 4 affine matrix in rows "
     "(`m00,m01,m02,tx,m10,m11,m12,ty,m20,m21,m22,tz`); any invertible one (rotated, scaled, "
     "sheared, mirrored, moved). The scene of [scene-and-cli.md](scene-and-cli.md) is the "
     "relief's object space"},
    {"shading.lightDirection", "--light", "x,y,z", "light", "-0.45,0.8,-0.35",
     "each within +-1e6, not zero", "Direction towards the light x,y,z (default -0.45,0.8,-0.35)",
     "direction towards the light"},
    {"shading.lightPosition", "--light-position", "x,y,z", "", "none",
     "world units, each within +-1e12",
     "A point light at x,y,z (world) instead of the directional light",
     "a point light there instead (world); not with `--light`"},
    {"shading.shadows", "--shadows", "S", "shadows", "off", "`off`, `hard`, `soft`",
     "Self-shadows: off, hard (exact: a second trace towards the light) or soft (an estimate "
     "for a round light of --light-size); multilevel, maxmip and cone",
     "self-shadows: `off`, `hard` (exact: a second trace towards the light), `soft` (an "
     "estimate for a round light of `--light-size`); the exact methods"},
    {"shading.lightSizeDegrees", "--light-size", "DEG", "light-size", "1",
     "degrees, strictly between 0 and 90",
     "Soft shadows: the light's angular diameter in degrees (the sun's is 0.53)",
     "soft shadows: the light's angular diameter (the sun's is 0.53)"},
    // The page's albedo takes `map` (the bundled map's colours) or `none`, no file.
    {"albedo", "--albedo", "FILE", "albedo",
     "the bundled map's colours with the bundled map, else none", "up to 16384 a side",
     "The map's colours: an image over its (u, v), any size (sRGB unless float), or none; "
     "default: the bundled map's own with the bundled map",
     "the map's colours: any image OpenImageIO reads (sRGB unless float), or `none`"},
    {"background", "--background", "r,g,b", "background", "0.11,0.12,0.14", "linear RGB, each >= 0",
     "Background colour r,g,b (linear, each >= 0; 1 is full, above it saturates an 8-bit "
     "picture)",
     "background colour (1 is full; above it saturates an 8-bit picture, an EXR keeps it)"},
    {"method", "--method", "M", "method", "multilevel",
     "`multilevel`, `maxmip`, `cone`, `rcsm`, `relief`, `pom`, `steep`, `offset`, `normal`",
     "How rays are traced: multilevel (the paper's method, exact), or a peer for comparison: "
     "normal, offset, steep, pom, relief, maxmip, cone (cone step mapping, exact), rcsm "
     "(relaxed cone stepping; cone and rcsm on an untiled plane)",
     "how rays are traced: `multilevel` (the paper's method, exact), or a peer for "
     "comparison: `cone` (cone step mapping, exact), `rcsm` (relaxed cone stepping) and the "
     "others (see [performance.md](performance.md)); on a curved base `multilevel`, "
     "`maxmip`, `pom` and `relief`; `cone` and `rcsm` on an untiled plane"},
    {"method.steps", "--steps", "N", "steps", "64", "1 to 65536",
     "Peers' quality knob: steep layers, pom samples at grazing angles, relief linear steps, "
     "rcsm relaxed cone steps (the same default; --steps 15 is the published setting), each "
     "then 8 binary steps for relief and rcsm",
     "the step-based peers' budget: `steep` layers, `pom` samples at grazing angles (a "
     "quarter of them, at least 4, looking straight down), `relief` linear steps, `rcsm` "
     "relaxed cone steps (the same default; the published setting is `--steps 15`), each "
     "then 8 binary steps for `relief` and `rcsm`"},
    {"method.pixelError", "--pixel-error", "E", "pixel-error", "0", "pixels, >= 0",
     "multilevel: stop at pyramid levels whose windows project to less than this many pixels "
     "(0: exact)",
     "multilevel: stop at pyramid levels whose windows (the max boxes read, two texels of the "
     "level wide) project to less than E pixels and take that box as the surface; 0 is exact"},
    {"shading.view", "--view", "NAME", "view", "shaded",
     "`shaded`, `iterations`, `level`, `normal`, `depth`, `position`",
     "What the picture shows: shaded, or a debug view of the method: iterations (segments "
     "visited, heat map), level (pyramid level where the ray stopped), normal, depth, position",
     "`shaded`, or a debug view: `iterations` (segments visited, heat map), `level` (pyramid "
     "level where the ray stopped), `normal`, `depth`, `position`"},
};

}  // namespace

std::span<const SceneField> sceneFieldTable() {
    return kSceneFields;
}

const SceneField* findSceneField(std::string_view path) {
    for (const SceneField& field : kSceneFields)
        if (field.path == path) return &field;
    return nullptr;
}

// sceneFieldFlag is core/base/BaseTable.cpp's: a size's flag needs the table of bases,
// which the WebAssembly builds that compile this file leave out.

const std::vector<std::string>& sceneFields() {
    static const std::vector<std::string> fields = [] {
        std::vector<std::string> paths;
        for (const SceneField& field : kSceneFields) paths.emplace_back(field.path);
        return paths;
    }();
    return fields;
}

bool isSceneField(const std::string& path) {
    return findSceneField(path) != nullptr || isBaseSizeField(path);
}

bool isBaseSizeField(const std::string& path) {
    constexpr std::string_view prefix = "base.";
    return path.size() > prefix.size() && path.starts_with(prefix) &&
           std::all_of(path.begin() + prefix.size(), path.end(),
                       [](char c) { return std::isalnum(static_cast<unsigned char>(c)); });
}

}  // namespace microrelief
