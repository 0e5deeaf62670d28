// The map's data on the GPU, as the relief shaders read it (docs/engine.md, "Textures"):
// the samples, R32F with nearest filtering, clamped (repeating in s on a curved base, whose
// u wraps, and in both directions tiled: relief_map.glsl's MICRORELIEF_TILING); the
// overlapping windows the multilevel method reads (core/heightmap/MaxPyramid.h), an R16F mip
// chain of GL's own sizes of W x H down to 1 x 1, its bounds divided by 2^S; and, only
// where the maxmip peer runs, the aligned levels of its quadtree, R16F as well, padded to
// powers of two. Nearest-mipmap-nearest, clamped. With them, the numbers mr_ReliefMap
// (relief_map.glsl) holds about them. About 6.7 bytes a map texel with the windows alone
// (4 the samples, 2.67 the windows), whatever the size. A tiled map's textures hold one
// tile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/gl/Objects.h"
#include "microrelief/gl/PagedPyramid.h"
#include "microrelief/peers/ConeMap.h"

namespace microrelief {

// mr_ReliefMap's members, in the order of its constructor.
struct ReliefMapShape {
    glm::ivec2 size{0};         // W, H of the whole map: N W, M H tiled N x M
    glm::ivec2 pyramidSize{0};  // the finest pyramid level's size
    int levelCount = 0;         // levels down to 1 x 1
    float maxHeight = 0.0f;     // the pyramid's top texel: the surface's max, map units
    glm::ivec2 tiles{1, 1};     // N, M: the textures hold one tile
};

class PyramidBuilder;

// Where a map's max pyramids are built: on the CPU (MaxPyramid, then uploaded), on the
// GPU from the uploaded samples (gl/PyramidBuilder.h), or on the GPU where its build works
// and else on the CPU (gl/ReliefMap.h says which errors fall back). The texels are
// the same.
enum class PyramidBuild { Cpu, Gpu, GpuElseCpu };

class ReliefTextures {
public:
    // Builds the max pyramid of `map` (wrapped in u when `wrapU`: a curved base), which
    // bounds the surface either last level makes of it (core/heightmap/MaxPyramid.h), and
    // uploads it with the samples; the aligned levels
    // too when `withMaxMip`. Throws Error(BadInput) naming `source` when the map exceeds
    // GL_MAX_TEXTURE_SIZE, Error(Runtime) when memory runs out. The GL state it changes
    // (texture bindings, unpack alignment) is restored.
    ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source, bool wrapU,
                   bool withMaxMip = false, glm::ivec2 tiles = {1, 1});
    // The same from a pyramid the caller built of `map` (BoundPrecision::Half, what the
    // textures hold; tiled as its addressing has it).
    ReliefTextures(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid,
                   bool withMaxMip = false);
    // The same with the pyramids built on the GPU by `builder` (gl/PyramidBuilder.h): the
    // same texels, from the samples once they are on the GPU. Untiled: the builder's
    // passes bound each texel square within the one map.
    ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source, bool wrapU,
                   PyramidBuilder& builder, bool withMaxMip = false);

    // A map read through pages (gl/PagedPyramid.h), any size the CPU holds: its pyramid
    // built on the CPU, the samples and the fine windows paged in as draws want them, the
    // coarse windows resident. Only the multilevel method reads it: no aligned pyramid,
    // no cone maps, no edits (those throw Error(Runtime)).
    // `map` is shared with the pages (not copied: such a map is large).
    ReliefTextures(const GL& gl, std::shared_ptr<const HeightMap> map, const std::string& source,
                   bool wrapU, const PagingSettings& paging);
    // The same from a pyramid kept elsewhere (a pyramid file: io/PyramidFile.h), which may be
    // larger than memory: nothing of it is read until a draw wants it but the coarse levels.
    ReliefTextures(const GL& gl, std::shared_ptr<const PyramidPages> pages,
                   const std::string& source, const PagingSettings& paging);
    // The pager of a paged map; null for one in whole textures.
    PagedPyramid* paged() { return paged_.get(); }
    const PagedPyramid* paged() const { return paged_.get(); }

    // The samples (a paged map: a 1 x 1 texture the shader never reads) and the windows (a
    // paged map: its coarse levels, the first of them its level 0).
    GLuint samples() const { return samples_.id(); }
    GLuint windowPyramid() const { return paged_ ? paged_->coarse() : windows_.id(); }
    // The aligned pyramid, or 0 where none was made (addMaxMipPyramid makes it).
    GLuint maxPyramid() const { return aligned_.id(); }
    bool hasMaxMipPyramid() const { return static_cast<bool>(aligned_); }
    // The aligned pyramid for the maxmip peer, built on the GPU from the samples.
    void addMaxMipPyramid(const GL& gl, PyramidBuilder& builder);

    // The cone maps of the cone-stepping peers (peers/ConeMap.h), RG16F, linear filtering
    // (rcsm reads its map filtered, cone with texelFetch), clamped: the conservative map
    // for cone, the relaxed one for rcsm, each built when first asked for and kept until
    // the samples change (dropConeMaps). Only where one of these methods runs. With
    // `builder` the conservative map is built on the GPU (PyramidBuilder::buildConeMap);
    // without, and the relaxed map always, on the CPU from the samples the GPU holds (read
    // back). The GL state it changes is restored.
    enum class ConeKind { Conservative = 0, Relaxed = 1 };
    void addConeMap(const GL& gl, ConeKind kind, PyramidBuilder* builder = nullptr);
    void dropConeMaps() {
        for (gl::Texture& t : cones_) t.reset();
    }
    void dropConeMap(ConeKind kind) { cones_[static_cast<int>(kind)].reset(); }
    bool hasConeMaps() const { return cones_[0] || cones_[1]; }
    // 0 where that map was not made.
    GLuint coneMap(ConeKind kind) const { return cones_[static_cast<int>(kind)].id(); }
    // A cone map as the GPU holds it, read back (the halves as floats).
    ConeMap readConeMap(const GL& gl, ConeKind kind) const;

    // The multilevel method's mr_ReliefMap (the windows: pyramidSize W x H, their levels;
    // size the whole, N W x M H tiled N x M).
    ReliefMapShape shape() const {
        ReliefMapShape whole = shape_;
        whole.size *= whole.tiles;
        return whole;
    }
    // maxmip's: the aligned pyramid's size (W, H rounded up to powers of two) and levels.
    ReliefMapShape maxMipShape() const;
    bool wrapsU() const { return wrapU_; }
    glm::ivec2 tiles() const { return shape_.tiles; }
    // S: the pyramids hold bound / 2^S (MaxPyramid.h: pyramidScaleExponent of maxHeight;
    // the shaders derive it from mr_ReliefMap's maxHeight the same way).
    int scaleExponent() const { return scaleExponent_; }
    // What the textures take in GPU memory, bytes: the samples and every level of the
    // pyramids, as the GL reports their sizes and formats.
    std::size_t gpuBytes(const GL& gl) const;
    // The windows' level sizes, finest first (windowLevelSizes).
    const std::vector<glm::ivec2>& levelSizes() const { return levelSizes_; }

    // The samples inside `rect` (map texels) replaced by `values`, rect.width() a row, row
    // 0 first: an edit from the host. The pyramids are the caller's to bring up to date
    // (PyramidBuilder::update). The GL state it changes is restored.
    void writeSamples(const GL& gl, const TexelRect& rect, const float* values);
    // The pyramids built again on the CPU from the samples the GPU holds (read back), for
    // a tiled map, whose bounds the GPU builder does not make. The GL state it changes is
    // restored.
    void rebuildFromSamples(const GL& gl);
    // What the GPU holds, read back (through a framebuffer, as GL ES has it): the samples
    // as a map, a level of the aligned or the overlapping pyramid as the bounds it stands
    // for (the halves times 2^S), row 0 first.
    HeightMap readSamples(const GL& gl) const;
    // The samples inside `rect`, rect.width() a row, row 0 first.
    std::vector<float> readSamples(const GL& gl, const TexelRect& rect) const;
    std::vector<float> readAlignedLevel(const GL& gl, int level) const;
    std::vector<float> readWindowLevel(const GL& gl, int level) const;

private:
    friend class PyramidBuilder;  // writes S and maxHeight after a build or an update

    // `map` and its pyramid's windows (built on the CPU), kept for paging.
    static std::shared_ptr<const PyramidPages> keptInMemory(std::shared_ptr<const HeightMap> map,
                                                            const std::string& source, bool wrapU);

    void allocate(const GL& gl, const HeightMap& map);
    void allocateAligned(const GL& gl);
    // The cone map of `kind`, its RG16F level allocated and its sampling set where it was
    // not made yet.
    gl::Texture& allocateConeMap(const GL& gl, ConeKind kind);
    void upload(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid, bool withMaxMip);
    // The pyramid's levels into the allocated textures, its top and S into the shape.
    void uploadPyramid(const GL& gl, const MaxPyramid& pyramid);
    std::vector<float> readScaled(const GL& gl, GLuint texture, int level,
                                  const glm::ivec2& size) const;

    // A paged map's only texture is its stand-in samples_; the pager holds the rest.
    void refuseIfPaged(const char* what) const;

    gl::Texture samples_, windows_, aligned_;
    std::unique_ptr<PagedPyramid> paged_;
    gl::Texture cones_[2];  // by ConeKind
    ReliefMapShape shape_;  // size: one tile's, W x H (shape() has the whole's)
    std::vector<glm::ivec2> levelSizes_;
    int scaleExponent_ = 0;
    bool wrapU_ = false;
};

// Pyramid bounds (as MaxPyramid keeps them, BoundPrecision::Half) as the GPU holds them:
// bound / 2^S, the bits of a half, exactly (no driver's conversion rounds them).
std::vector<std::uint16_t> storedHalves(const std::vector<float>& bounds, int scaleExponent);

// What one 2D texture takes in GPU memory, bytes: every level, as the GL reports its size
// and format (R16F 2 a texel, R32F and RG16F 4, others counted as 16). The GL state it
// changes is restored.
std::size_t textureBytes(const GL& gl, GLuint texture);

// Level `level` (width x height) of a single-channel float texture (R32F, R16F), read back
// through a framebuffer as floats, row 0 first. The GL state it changes is restored.
std::vector<float> readTextureLevel(const GL& gl, GLuint texture, int level, int width, int height);
// The texels inside `rect` of that level, the same way.
std::vector<float> readTextureRect(const GL& gl, GLuint texture, int level, const TexelRect& rect);

}  // namespace microrelief
