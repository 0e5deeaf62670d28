// A height map: W x H samples h(i, j) >= 0, row-major with row 0 the first row of the
// image file (v = 0). Sample (i, j) sits at the texel centre u = (i + 0.5) / W,
// v = (j + 0.5) / H; between centres the surface is the bilinear interpolation of the
// samples, clamped to the edge outside them (scene-and-cli.md, "Height map to surface").
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "microrelief/core/Error.h"

namespace microrelief {

// The last level of detail (paper, section II: "bi-linear or bi-quadratic interpolation
// of elevation values"; scene-and-cli.md, "Interpolation"): the bilinear interpolation of
// the samples, or the uniform quadratic B-spline whose control points are the samples
// (smooth, C1; it does not in general pass through them).
enum class Interpolation { Bilinear = 0, Biquadratic = 1 };

// "bilinear", "biquadratic"; throws Error(BadInput) naming --interpolation.
Interpolation parseInterpolation(const std::string& name);
const char* interpolationName(Interpolation interpolation);

// The uniform quadratic B-spline's weights at f in [-1/2, 1/2] (the position in a texel
// square from its sample, X - i - 1/2) of the samples i - 1, i, i + 1.
inline void quadraticWeights(double f, double w[3]) {
    w[0] = 0.5 * (0.5 - f) * (0.5 - f);
    w[1] = 0.75 - f * f;
    w[2] = 0.5 * (0.5 + f) * (0.5 + f);
}

// How a map's samples are addressed (scene-and-cli.md): clamped to the edge beyond the
// map, u wrapped round a curved base, and the map repeated tilesX x tilesY times
// (--tile): then its samples are those of the larger image made by repeating it, and
// indices run over that image (i in [0, tilesX W)).
struct MapAddressing {
    bool wrapU = false;
    int tilesX = 1, tilesY = 1;

    bool tiled() const { return tilesX > 1 || tilesY > 1; }
    bool operator==(const MapAddressing&) const = default;
};

struct HeightMap {
    int width = 0;
    int height = 0;
    std::vector<float> samples;  // width * height values, row-major

    HeightMap() = default;
    HeightMap(int w, int h, float fill = 0.0f)
        : width(w), height(h), samples(static_cast<std::size_t>(w) * h, fill) {}

    bool empty() const { return samples.empty(); }

    float& at(int i, int j) { return samples[static_cast<std::size_t>(j) * width + i]; }
    float at(int i, int j) const { return samples[static_cast<std::size_t>(j) * width + i]; }

    // The sample with its indices clamped to the map: the CLAMP_TO_EDGE rule.
    float clamped(int i, int j) const;
    // The sample with i wrapped around the map (a curved base's periodic u) and j clamped.
    float wrapped(int i, int j) const;
    // clamped() or wrapped(): how a base surface addresses its map.
    float sample(int i, int j, bool wrapU) const { return wrapU ? wrapped(i, j) : clamped(i, j); }
    // Sample (i, j) of the map as `addressing` has it (i, j over the tiled whole).
    float sample(int i, int j, const MapAddressing& addressing) const;

    // h(X, Y) in texel space (X = u W, Y = v H): the bilinear surface of the spec, with
    // column W - 1 joined to column 0 when `wrapU` (a curved base).
    double surface(double x, double y, bool wrapU = false) const;
    // The same for either interpolation: the biquadratic one sums the 3 x 3 samples around
    // the texel square holding (X, Y), clamped or wrapped as sample() has it.
    double surface(double x, double y, bool wrapU, Interpolation interpolation) const;
    // The same over the tiled whole (x in [0, tilesX W]).
    double surface(double x, double y, const MapAddressing& addressing,
                   Interpolation interpolation) const;

    float maxValue() const;
    float minValue() const;
};

// The map with its rows in the opposite order: row j of the result is row H - 1 - j of
// `map`. The mesh base's texture coordinates are OpenGL's, (0, 0) the image's bottom-left
// corner (docs/bases.md, "The mesh"), while a HeightMap's row 0 is the image's first, top,
// row: the mesh's classes (MeshReference, MeshTracer, MeshProxy, gl::MeshRelief) address a
// map's row j at v = (j + 1/2) / H, so an image's map is handed to them reversed.
HeightMap rowsReversed(const HeightMap& map);

// The largest map side loadHeightMap (io/HeightMapFile.h) accepts, checked from the file's
// header before any sample is read or allocated: 16384, the GL_MAX_TEXTURE_SIZE of llvmpipe and of
// most desktop GPUs (and the least that OpenGL 4.1 and later guarantee), so that a map's samples
// take at most 1 GiB (its pyramid 0.67 GiB more on the GPU) before a GL context exists. The
// renderer checks the GPU's own, possibly lower, limit when it uploads.
inline constexpr int kMaxHeightMapSide = 16384;
// The largest side microrelief-render loads: maps past the GL's texture size are read through
// pages (gl/PagedPyramid.h), their samples and pyramid held in memory (about
// kPagedBytesPerSample a sample), so the sample count is bounded by the machine's memory too
// (HeightMapLoadOptions::maxSamples). 16: the samples (4 bytes, shared by the program and
// its pages), the pyramid's windows that pages read (5.3; PyramidInMemory), and room for
// what a program holds beside them: microrelief-render's single picture, a turntable and the
// viewer each peaked at 11 bytes a sample on a 20000 x 20000 map (4.4 GB, 2026-12-05).
inline constexpr int kMaxPagedHeightMapSide = 65536;
inline constexpr std::size_t kPagedBytesPerSample = 16;
// More channels than any height map needs; OpenImageIO reads whole pixels, so this
// bounds what it holds per scanline.
inline constexpr int kMaxHeightMapChannels = 1024;

struct HeightMapLoadOptions {
    int channel = 0;                  // --channel: which image channel holds the heights
    bool normalize = false;           // --normalize: map [min, max] to [0, 1]
    int maxSide = kMaxHeightMapSide;  // larger maps are refused from the header
    // More samples than this are refused from the header too (MapOverMemory); 0: no
    // bound beyond maxSide.
    std::size_t maxSamples = 0;
};

// The refusal of a map over HeightMapLoadOptions::maxSamples, an Error(BadInput) of its
// own type, so that a program that can draw such a map another way says so
// (microrelief-render: --pyramid-cache, which never holds the map whole).
class MapOverMemory : public Error {
public:
    explicit MapOverMemory(const std::string& message) : Error(ErrorKind::BadInput, message) {}
};

// The larger image made by repeating `tile` tilesX x tilesY times: what a tiled map is
// (MapAddressing). Throws Error(BadInput) beyond `maxSamples` samples.
HeightMap repeatMap(const HeightMap& tile, int tilesX, int tilesY,
                    std::size_t maxSamples = std::size_t(1) << 26);

// The checks and normalisation loadHeightMap applies after reading; `source` names the
// map in messages. Exposed for maps built in memory.
void prepareHeights(HeightMap& map, const HeightMapLoadOptions& options, const std::string& source);

// A map copied from samples the caller holds (an engine's own image, a texture read
// back): `width` x `height` values, row j starting `rowStrideBytes * j` bytes after
// `samples` (at least a row's bytes: width * sizeof the sample), row 0 at v = 0. 16-bit
// samples become [0, 1] by 65535, as the loader reads them. Then prepareHeights, with
// `options.normalize`. Throws Error(BadInput) naming `source` for an empty or oversized
// size (options.maxSide), a null pointer, a stride shorter than a row, or samples
// prepareHeights refuses.
HeightMap heightMapFromSamples(const float* samples, int width, int height,
                               std::size_t rowStrideBytes, const HeightMapLoadOptions& options = {},
                               const std::string& source = "samples");
HeightMap heightMapFromSamples(const std::uint16_t* samples, int width, int height,
                               std::size_t rowStrideBytes, const HeightMapLoadOptions& options = {},
                               const std::string& source = "samples");

}  // namespace microrelief
