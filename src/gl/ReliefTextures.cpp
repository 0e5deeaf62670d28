#include "microrelief/gl/ReliefTextures.h"

#include "microrelief/core/Error.h"
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

MaxPyramid buildPyramid(const HeightMap& map, const std::string& source,
                        const MapAddressing& addressing, Interpolation interpolation) {
    try {
        return MaxPyramid(map, addressing, interpolation);
    } catch (const std::bad_alloc&) {
        throwRuntime(source + ": not enough memory for the max pyramid of its " +
                     std::to_string(map.width) + "x" + std::to_string(map.height) + " samples");
    }
}

void uploadLevel(const GL& gl, int level, int width, int height, const float* data) {
    gl.TexImage2D(GL_TEXTURE_2D, level, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, data);
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

}  // namespace

ReliefTextures::ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source,
                               bool wrapU, Interpolation interpolation, glm::ivec2 tiles)
    : wrapU_(wrapU), interpolation_(interpolation) {
    checkTextureSize(gl, map, source);
    shape_.tiles = tiles;
    // On the GPU from here on; only its shape is kept.
    upload(gl, map, buildPyramid(map, source, {wrapU, tiles.x, tiles.y}, interpolation));
}

ReliefTextures::ReliefTextures(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid,
                               Interpolation interpolation)
    : wrapU_(pyramid.wrapsU()), interpolation_(interpolation) {
    shape_.tiles = {pyramid.addressing().tilesX, pyramid.addressing().tilesY};
    checkTextureSize(gl, map, "the map");
    upload(gl, map, pyramid);
}

void ReliefTextures::upload(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid) {
    shape_.size = glm::ivec2(map.width, map.height) * shape_.tiles;
    shape_.pyramidSize = {pyramid.levelWidth(0), pyramid.levelHeight(0)};
    shape_.levelCount = pyramid.levelCount();
    shape_.maxHeight = pyramid.texel(pyramid.levelCount() - 1, 0, 0);
    samples_ = gl::Texture::create(gl);
    windows_ = gl::Texture::create(gl);
    aligned_ = gl::Texture::create(gl);

    const gl::StateGuard saved(gl);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (bool windows : {false, true}) {
        gl.BindTexture(GL_TEXTURE_2D, (windows ? windows_ : aligned_).id());
        for (int level = 0; level < pyramid.levelCount(); ++level) {
            uploadLevel(
                gl, level, pyramid.levelWidth(level), pyramid.levelHeight(level),
                (windows ? pyramid.windowLevelData(level) : pyramid.levelData(level)).data());
        }
        setSamplerState(gl, GL_NEAREST_MIPMAP_NEAREST, pyramid.levelCount() - 1);
    }
    gl.BindTexture(GL_TEXTURE_2D, samples_.id());
    uploadLevel(gl, 0, map.width, map.height, map.samples.data());
    const bool tiled = shape_.tiles != glm::ivec2(1, 1);
    setSamplerState(gl, GL_NEAREST, 0, wrapU_ || tiled, tiled);
}

}  // namespace microrelief
