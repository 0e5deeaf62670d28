#include "microrelief/gl/ReliefTextures.h"

#include "microrelief/core/Error.h"
#include "microrelief/gl/PyramidBuilder.h"
#include "microrelief/gl/StateGuard.h"

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

MaxPyramid buildPyramid(const HeightMap& map, const std::string& source, bool wrapU,
                        Interpolation interpolation) {
    try {
        return MaxPyramid(map, wrapU, interpolation);
    } catch (const std::bad_alloc&) {
        throwRuntime(source + ": not enough memory for the max pyramid of its " +
                     std::to_string(map.width) + "x" + std::to_string(map.height) + " samples");
    }
}

void uploadLevel(const GL& gl, int level, int width, int height, const float* data) {
    gl.TexImage2D(GL_TEXTURE_2D, level, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, data);
}

// The samples of a curved base repeat in S, so that a patch's textureGather at the seam
// reads column W - 1 and column 0 (bilinear_patch.glsl); everything else clamps.
void setSamplerState(const GL& gl, GLint minFilter, int maxLevel, bool repeatS = false) {
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minFilter);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, repeatS ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, maxLevel);
}

}  // namespace

ReliefTextures::ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source,
                               bool wrapU, Interpolation interpolation)
    : wrapU_(wrapU), interpolation_(interpolation) {
    checkTextureSize(gl, map, source);
    // On the GPU from here on; only its shape is kept.
    upload(gl, map, buildPyramid(map, source, wrapU, interpolation));
}

ReliefTextures::ReliefTextures(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid,
                               Interpolation interpolation)
    : wrapU_(pyramid.wrapsU()), interpolation_(interpolation) {
    checkTextureSize(gl, map, "the map");
    upload(gl, map, pyramid);
}

ReliefTextures::ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source,
                               bool wrapU, Interpolation interpolation, PyramidBuilder& builder)
    : wrapU_(wrapU), interpolation_(interpolation) {
    checkTextureSize(gl, map, source);
    allocate(gl, map, static_cast<int>(pyramidLevelSizes(map.width, map.height).size()));
    builder.build(*this);
}

void ReliefTextures::allocate(const GL& gl, const HeightMap& map, int levelCount) {
    shape_.size = {map.width, map.height};
    levelSizes_ = pyramidLevelSizes(map.width, map.height);
    shape_.pyramidSize = levelSizes_.front();
    shape_.levelCount = levelCount;
    samples_ = gl::Texture::create(gl);
    windows_ = gl::Texture::create(gl);
    aligned_ = gl::Texture::create(gl);

    const gl::StateGuard saved(gl);  // unit 0's binding and the active unit among it
    gl.ActiveTexture(GL_TEXTURE0);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (const gl::Texture* pyramid : {&aligned_, &windows_}) {
        gl.BindTexture(GL_TEXTURE_2D, pyramid->id());
        for (int level = 0; level < levelCount; ++level)
            uploadLevel(gl, level, levelSizes_[level].x, levelSizes_[level].y, nullptr);
        setSamplerState(gl, GL_NEAREST_MIPMAP_NEAREST, levelCount - 1);
    }
    gl.BindTexture(GL_TEXTURE_2D, samples_.id());
    uploadLevel(gl, 0, map.width, map.height, map.samples.data());
    setSamplerState(gl, GL_NEAREST, 0, wrapU_);
}

void ReliefTextures::upload(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid) {
    allocate(gl, map, pyramid.levelCount());
    shape_.maxHeight = pyramid.texel(pyramid.levelCount() - 1, 0, 0);
    const gl::StateGuard saved(gl);  // unit 0's binding and the active unit among it
    gl.ActiveTexture(GL_TEXTURE0);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (bool windows : {false, true}) {
        gl.BindTexture(GL_TEXTURE_2D, (windows ? windows_ : aligned_).id());
        for (int level = 0; level < pyramid.levelCount(); ++level) {
            gl.TexSubImage2D(
                GL_TEXTURE_2D, level, 0, 0, pyramid.levelWidth(level), pyramid.levelHeight(level),
                GL_RED, GL_FLOAT,
                (windows ? pyramid.windowLevelData(level) : pyramid.levelData(level)).data());
        }
    }
}

std::size_t ReliefTextures::gpuBytes() const {
    std::size_t texels = static_cast<std::size_t>(shape_.size.x) * shape_.size.y;
    for (const glm::ivec2 size : levelSizes_)
        texels += 2 * static_cast<std::size_t>(size.x) * size.y;  // aligned and windows
    return texels * sizeof(float);
}

void ReliefTextures::writeSamples(const GL& gl, const TexelRect& rect, const float* values) {
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

std::vector<float> readTextureRect(const GL& gl, GLuint texture, int level, const TexelRect& rect) {
    std::vector<float> values(static_cast<std::size_t>(rect.width()) * rect.height());
    const gl::PassGuard saved(gl);
    const gl::Framebuffer framebuffer = gl::Framebuffer::create(gl);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer.id());
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture,
                            level);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(rect.x0, rect.y0, rect.width(), rect.height(), GL_RED, GL_FLOAT, values.data());
    return values;
}

std::vector<float> ReliefTextures::readSamples(const GL& gl, const TexelRect& rect) const {
    return readTextureRect(gl, samples_.id(), 0, rect);
}

HeightMap ReliefTextures::readSamples(const GL& gl) const {
    HeightMap map(shape_.size.x, shape_.size.y);
    map.samples = readTextureLevel(gl, samples_.id(), 0, map.width, map.height);
    return map;
}

std::vector<float> ReliefTextures::readAlignedLevel(const GL& gl, int level) const {
    return readTextureLevel(gl, aligned_.id(), level, levelSizes_[level].x, levelSizes_[level].y);
}

std::vector<float> ReliefTextures::readWindowLevel(const GL& gl, int level) const {
    return readTextureLevel(gl, windows_.id(), level, levelSizes_[level].x, levelSizes_[level].y);
}

}  // namespace microrelief
