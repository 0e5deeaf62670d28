#include "microrelief/gl/ReliefTextures.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "microrelief/core/Error.h"
#include "microrelief/gl/PyramidBuilder.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/peers/ConeMap.h"
#include "microrelief/peers/MaxMipPyramid.h"

namespace microrelief {

namespace {

void checkTextureSize(const GL& gl, const HeightMap& map, const std::string& source) {
    GLint maxSize = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (map.width > maxSize || map.height > maxSize) {
        throwBadInput(source + ": " + std::to_string(map.width) + "x" + std::to_string(map.height) +
                      " is larger than this GPU's GL_MAX_TEXTURE_SIZE (" + std::to_string(maxSize) +
                      ")");
    }
}

MaxPyramid buildPyramid(const HeightMap& map, const std::string& source,
                        const MapAddressing& addressing) {
    try {
        return MaxPyramid(map, addressing, BoundPrecision::Half);
    } catch (const std::bad_alloc&) {
        throwRuntime(source + ": not enough memory for the max pyramid of its " +
                     std::to_string(map.width) + "x" + std::to_string(map.height) + " samples");
    }
}

// The samples of a curved base repeat in S, so that a patch's textureGather at the seam
// reads column W - 1 and column 0 (bilinear_patch.glsl); a tiled map's repeat in both, so
// that a gather across a seam between tiles reads the next tile; everything else clamps.
void setSamplerState(const GL& gl, GLint minFilter, int maxLevel, bool repeatS = false,
                     bool repeatT = false) {
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minFilter);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, repeatS ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, repeatT ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, maxLevel);
}

// A pyramid texture of R16F levels of `sizes`, empty.
gl::Texture allocatePyramid(const GL& gl, const std::vector<glm::ivec2>& sizes) {
    gl::Texture texture = gl::Texture::create(gl);
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    for (int level = 0; level < static_cast<int>(sizes.size()); ++level) {
        gl.TexImage2D(GL_TEXTURE_2D, level, GL_R16F, sizes[level].x, sizes[level].y, 0, GL_RED,
                      GL_HALF_FLOAT, nullptr);
    }
    setSamplerState(gl, GL_NEAREST_MIPMAP_NEAREST, static_cast<int>(sizes.size()) - 1);
    return texture;
}

// A pyramid level (the bounds as MaxPyramid keeps them) into the bound texture, as halves.
void uploadHalves(const GL& gl, int level, const glm::ivec2& size, const std::vector<float>& bounds,
                  int scaleExponent) {
    const std::vector<std::uint16_t> halves = storedHalves(bounds, scaleExponent);
    gl.TexSubImage2D(GL_TEXTURE_2D, level, 0, 0, size.x, size.y, GL_RED, GL_HALF_FLOAT,
                     halves.data());
}

}  // namespace

std::vector<std::uint16_t> storedHalves(const std::vector<float>& bounds, int scaleExponent) {
    // Each bound / 2^S is on the half grid (MaxPyramid.h: storedBound): its bits exactly
    // (peers/ConeMap.h's halfBits), which no driver's conversion can round.
    std::vector<std::uint16_t> halves(bounds.size());
    for (std::size_t k = 0; k < bounds.size(); ++k)
        halves[k] = halfBits(std::ldexp(bounds[k], -scaleExponent));
    return halves;
}

ReliefTextures::ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source,
                               bool wrapU, bool withMaxMip, glm::ivec2 tiles)
    : wrapU_(wrapU) {
    checkTextureSize(gl, map, source);
    shape_.tiles = tiles;
    // On the GPU from here on; only its shape is kept.
    upload(gl, map, buildPyramid(map, source, {wrapU, tiles.x, tiles.y}),
           withMaxMip);
}

ReliefTextures::ReliefTextures(const GL& gl, std::shared_ptr<const HeightMap> map,
                               const std::string& source, bool wrapU, const PagingSettings& paging)
    : ReliefTextures(gl, keptInMemory(std::move(map), source, wrapU), source, paging) {}

std::shared_ptr<const PyramidPages> ReliefTextures::keptInMemory(
    std::shared_ptr<const HeightMap> map, const std::string& source, bool wrapU) {
    const int width = map->width, height = map->height;
    try {
        return std::make_shared<PyramidInMemory>(std::move(map), wrapU, source);
    } catch (const std::bad_alloc&) {
        throwRuntime(source + ": not enough memory to keep its " + std::to_string(width) + "x" +
                     std::to_string(height) + " pyramid for paging");
    }
}

ReliefTextures::ReliefTextures(const GL& gl, std::shared_ptr<const PyramidPages> pages,
                               const std::string& source, const PagingSettings& paging)
    : wrapU_(pages->wrapsU()) {
    shape_.size = {pages->mapWidth(), pages->mapHeight()};
    levelSizes_ = windowLevelSizes(pages->mapWidth(), pages->mapHeight());
    shape_.pyramidSize = levelSizes_.front();
    shape_.levelCount = static_cast<int>(levelSizes_.size());
    shape_.maxHeight = pages->maxHeight();
    scaleExponent_ = pages->scaleExponent();
    paged_ = std::make_unique<PagedPyramid>(gl, std::move(pages), paging, source);
    const gl::StateGuard saved(gl);
    gl.ActiveTexture(GL_TEXTURE0);
    samples_ = gl::Texture::create(gl);
    gl.BindTexture(GL_TEXTURE_2D, samples_.id());
    const float zero = 0.0f;
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, 1, 1, 0, GL_RED, GL_FLOAT, &zero);
    setSamplerState(gl, GL_NEAREST, 0);
}

void ReliefTextures::refuseIfPaged(const char* what) const {
    if (paged_) throwRuntime(std::string(what) + " is not made for a map read through pages");
}

ReliefTextures::ReliefTextures(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid,
                               bool withMaxMip)
    : wrapU_(pyramid.wrapsU()) {
    shape_.tiles = {pyramid.addressing().tilesX, pyramid.addressing().tilesY};
    checkTextureSize(gl, map, "the map");
    if (pyramid.precision() != BoundPrecision::Half)
        throwRuntime("ReliefTextures: the GPU holds a pyramid of BoundPrecision::Half");
    upload(gl, map, pyramid, withMaxMip);
}

ReliefTextures::ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source,
                               bool wrapU, PyramidBuilder& builder, bool withMaxMip)
    : wrapU_(wrapU) {
    checkTextureSize(gl, map, source);
    allocate(gl, map);
    if (withMaxMip) allocateAligned(gl);
    // S from the samples at hand (the top is their largest, rounded up), so the build
    // fits at once; the builder checks it against the top it reads back.
    scaleExponent_ = pyramidScaleExponent(
        storedBound(map.maxValue(), BoundPrecision::Half, pyramidScaleExponent(map.maxValue())));
    builder.build(*this);
}

void ReliefTextures::allocate(const GL& gl, const HeightMap& map) {
    shape_.size = {map.width, map.height};
    levelSizes_ = windowLevelSizes(map.width, map.height);
    shape_.pyramidSize = levelSizes_.front();
    shape_.levelCount = static_cast<int>(levelSizes_.size());
    const gl::StateGuard saved(gl);  // unit 0's binding and the active unit among it
    gl.ActiveTexture(GL_TEXTURE0);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    windows_ = allocatePyramid(gl, levelSizes_);
    samples_ = gl::Texture::create(gl);
    gl.BindTexture(GL_TEXTURE_2D, samples_.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, map.width, map.height, 0, GL_RED, GL_FLOAT,
                  map.samples.data());
    const bool tiled = shape_.tiles != glm::ivec2(1, 1);
    setSamplerState(gl, GL_NEAREST, 0, wrapU_ || tiled, tiled);
}

void ReliefTextures::allocateAligned(const GL& gl) {
    const gl::StateGuard saved(gl);
    gl.ActiveTexture(GL_TEXTURE0);
    aligned_ = allocatePyramid(gl, maxMipLevelSizes(shape_.size.x, shape_.size.y));
}

void ReliefTextures::addMaxMipPyramid(const GL& gl, PyramidBuilder& builder) {
    if (aligned_) return;
    refuseIfPaged("maxmip's aligned pyramid");
    allocateAligned(gl);
    builder.buildAligned(*this);
}

gl::Texture& ReliefTextures::allocateConeMap(const GL& gl, ConeKind kind) {
    gl::Texture& texture = cones_[static_cast<int>(kind)];
    if (texture) return texture;
    const gl::StateGuard saved(gl);
    gl.ActiveTexture(GL_TEXTURE0);
    texture = gl::Texture::create(gl);
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RG16F, shape_.size.x, shape_.size.y, 0, GL_RG, GL_HALF_FLOAT,
                  nullptr);
    setSamplerState(gl, GL_LINEAR, 0);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return texture;
}

void ReliefTextures::addConeMap(const GL& gl, ConeKind kind, PyramidBuilder* builder) {
    if (cones_[static_cast<int>(kind)]) return;
    refuseIfPaged("a cone map");
    if (builder && kind == ConeKind::Conservative) {
        builder->buildConeMap(*this);
        return;
    }
    const HeightMap map = readSamples(gl);
    const ConeMap cones =
        kind == ConeKind::Conservative ? buildConservativeConeMap(map) : buildRelaxedConeMap(map);
    const std::vector<std::uint16_t> texels = coneMapHalfTexels(cones);
    const GLuint texture = allocateConeMap(gl, kind).id();
    const gl::StateGuard saved(gl);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.BindTexture(GL_TEXTURE_2D, texture);
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, map.width, map.height, GL_RG, GL_HALF_FLOAT,
                     texels.data());
}

ReliefMapShape ReliefTextures::maxMipShape() const {
    const std::vector<glm::ivec2> sizes = maxMipLevelSizes(shape_.size.x, shape_.size.y);
    return {shape_.size, sizes.front(), static_cast<int>(sizes.size()), shape_.maxHeight};
}

void ReliefTextures::upload(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid,
                            bool withMaxMip) {
    allocate(gl, map);
    if (withMaxMip) allocateAligned(gl);
    uploadPyramid(gl, pyramid);
}

void ReliefTextures::rebuildFromSamples(const GL& gl) {
    refuseIfPaged("an edit");
    const HeightMap map = readSamples(gl);
    uploadPyramid(gl, buildPyramid(map, "the edited map", {wrapU_, shape_.tiles.x, shape_.tiles.y}));
}

void ReliefTextures::uploadPyramid(const GL& gl, const MaxPyramid& pyramid) {
    shape_.maxHeight = pyramid.maxHeight();
    scaleExponent_ = pyramid.scaleExponent();
    const gl::StateGuard saved(gl);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 2);
    gl.BindTexture(GL_TEXTURE_2D, windows_.id());
    for (int level = 0; level < pyramid.windowLevelCount(); ++level)
        uploadHalves(gl, level, levelSizes_[level], pyramid.windowLevelData(level), scaleExponent_);
    if (!aligned_) return;
    const MaxMipPyramid maxMip(pyramid);  // maxmip's quadtree, from the same finest bounds
    gl.BindTexture(GL_TEXTURE_2D, aligned_.id());
    for (int level = 0; level < maxMip.levelCount(); ++level) {
        uploadHalves(gl, level, {maxMip.levelWidth(level), maxMip.levelHeight(level)},
                     maxMip.levelData(level), scaleExponent_);
    }
}

std::size_t ReliefTextures::gpuBytes(const GL& gl) const {
    std::size_t bytes = 0;
    for (const gl::Texture* texture : {&samples_, &windows_, &aligned_, &cones_[0], &cones_[1]})
        if (*texture) bytes += textureBytes(gl, texture->id());
    if (paged_) bytes += paged_->gpuBytes();
    return bytes;
}

std::size_t textureBytes(const GL& gl, GLuint texture) {
    // Asked of the GL, level by level: what it allocated, not what we meant it to.
    const gl::StateGuard saved(gl);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, texture);
    // Levels up to log2(GL_MAX_TEXTURE_SIZE) only: past it the query is GL_INVALID_VALUE
    // (a full chain of a map that wide ends there, and no level follows to answer 0).
    GLint maxTexture = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    const int lastLevel = std::bit_width(static_cast<unsigned>(std::max(maxTexture, 1))) - 1;
    std::size_t bytes = 0;
    for (int level = 0; level <= lastLevel; ++level) {
        GLint width = 0, height = 0, format = 0;
        gl.GetTexLevelParameteriv(GL_TEXTURE_2D, level, GL_TEXTURE_WIDTH, &width);
        if (width == 0) break;
        gl.GetTexLevelParameteriv(GL_TEXTURE_2D, level, GL_TEXTURE_HEIGHT, &height);
        gl.GetTexLevelParameteriv(GL_TEXTURE_2D, level, GL_TEXTURE_INTERNAL_FORMAT, &format);
        const std::size_t texelBytes = format == GL_R16F                         ? 2
                                       : format == GL_R32F || format == GL_RG16F ? 4
                                                                                 : 16;
        bytes += static_cast<std::size_t>(width) * height * texelBytes;
    }
    return bytes;
}

void ReliefTextures::writeSamples(const GL& gl, const TexelRect& rect, const float* values) {
    refuseIfPaged("an edit");
    const gl::StateGuard saved(gl);  // unit 0's binding and the active unit among it
    gl.ActiveTexture(GL_TEXTURE0);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.BindTexture(GL_TEXTURE_2D, samples_.id());
    gl.TexSubImage2D(GL_TEXTURE_2D, 0, rect.x0, rect.y0, rect.width(), rect.height(), GL_RED,
                     GL_FLOAT, values);
}

std::vector<float> readTextureLevel(const GL& gl, GLuint texture, int level, int width,
                                    int height) {
    return readTextureRect(gl, texture, level, {0, 0, width, height});
}

namespace {

// The texels inside `rect` of a float texture's level, `format` (GL_RED, GL_RG) read as
// floats through a framebuffer, row 0 first. The GL state it changes is restored.
std::vector<float> readFloats(const GL& gl, GLuint texture, int level, const TexelRect& rect,
                              GLenum format, int channels) {
    std::vector<float> values(static_cast<std::size_t>(rect.width()) * rect.height() * channels);
    const gl::PassGuard saved(gl);
    const gl::Framebuffer framebuffer = gl::Framebuffer::create(gl);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer.id());
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture,
                            level);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(rect.x0, rect.y0, rect.width(), rect.height(), format, GL_FLOAT, values.data());
    return values;
}

}  // namespace

std::vector<float> readTextureRect(const GL& gl, GLuint texture, int level, const TexelRect& rect) {
    return readFloats(gl, texture, level, rect, GL_RED, 1);
}

HeightMap ReliefTextures::readSamples(const GL& gl) const {
    HeightMap map(shape_.size.x, shape_.size.y);
    if (paged_) {
        map.samples = paged_->pages().readLevel(0);
        return map;
    }
    map.samples = readTextureLevel(gl, samples_.id(), 0, map.width, map.height);
    return map;
}

std::vector<float> ReliefTextures::readSamples(const GL& gl, const TexelRect& rect) const {
    refuseIfPaged("reading samples back");
    return readTextureRect(gl, samples_.id(), 0, rect);
}

std::vector<float> ReliefTextures::readScaled(const GL& gl, GLuint texture, int level,
                                              const glm::ivec2& size) const {
    std::vector<float> values = readTextureLevel(gl, texture, level, size.x, size.y);
    for (float& value : values) value = std::ldexp(value, scaleExponent_);
    return values;
}

std::vector<float> ReliefTextures::readAlignedLevel(const GL& gl, int level) const {
    const std::vector<glm::ivec2> sizes = maxMipLevelSizes(shape_.size.x, shape_.size.y);
    return readScaled(gl, aligned_.id(), level, sizes[level]);
}

std::vector<float> ReliefTextures::readWindowLevel(const GL& gl, int level) const {
    refuseIfPaged("reading windows back");
    return readScaled(gl, windows_.id(), level, levelSizes_[level]);
}

ConeMap ReliefTextures::readConeMap(const GL& gl, ConeKind kind) const {
    const int w = shape_.size.x, h = shape_.size.y;
    const std::vector<float> texels = readFloats(gl, coneMap(kind), 0, {0, 0, w, h}, GL_RG, 2);
    ConeMap cones{w, h, {}, {}};
    for (std::size_t k = 0; k < texels.size(); k += 2) {
        cones.apex.push_back(texels[k]);
        cones.ratio.push_back(texels[k + 1]);
    }
    return cones;
}

}  // namespace microrelief
