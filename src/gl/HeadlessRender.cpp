#include "microrelief/gl/HeadlessRender.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/core/scene/FloatLimits.h"

namespace microrelief {

namespace {

void checkHeightScale(float heightScale) {
    if (!(heightScale > 0.0f) || !std::isfinite(heightScale)) {
        throwBadInput("{heightScale} must be a positive number");
    }
}

}  // namespace

void checkPictureSize(int width, int height) {
    const double pixels = static_cast<double>(width) * height;
    if (width <= 0 || height <= 0 || width > kMaxPictureSide || height > kMaxPictureSide ||
        pixels > static_cast<double>(kMaxPicturePixels)) {
        throwBadInput("{size} " + std::to_string(width) + "x" + std::to_string(height) +
                      " is outside the pictures this program renders: sides up to " +
                      std::to_string(kMaxPictureSide) + ", at most " +
                      std::to_string(kMaxPicturePixels) + " pixels (16384 x 16384; " +
                      std::to_string(kFrameBytesPerPixel) + " bytes a pixel in memory)");
    }
}

HeadlessRenderer::HeadlessRenderer(GlContext& context, const MethodSettings& method)
    : context_(context) {
    context_.makeCurrent();
    renderer_.emplace(context_.gl(), shaderDirectory(), method);
}

void HeadlessRenderer::setHeightMap(const HeightMap& map, const std::string& source,
                                    const BaseShape& base, Interpolation interpolation,
                                    glm::ivec2 tiles) {
    upload(map, source, tiles, [&](PyramidBuild build) {
        renderer_->setHeightMap(map, source, base, interpolation, build, tiles);
    });
}

void HeadlessRenderer::setHeights(const RenderJob& job, const HeightMap& map,
                                  const std::string& source) {
    // With the job's method: the last job's may not run on this relief's base or tiles.
    upload(map, source, job.tiles,
           [&](PyramidBuild build) { renderer_->apply(job, job.method, &map, source, build); });
}

void HeadlessRenderer::upload(const HeightMap& map, const std::string& source, glm::ivec2 tiles,
                              const std::function<void(PyramidBuild)>& build) {
    context_.makeCurrent();
    try {
        build(PyramidBuild::Gpu);
    } catch (const Error& e) {
        if (e.kind() == ErrorKind::BadInput) throw;  // the map's fault, not the GL's
        build(PyramidBuild::Cpu);
    }
    if (animated_) animated_->forgetMap();
    source_ = source;
    mapWidth_ = map.width * tiles.x;  // the whole, tiles included
    mapHeight_ = map.height * tiles.y;
    maxHeight_ = map.maxValue();
}

bool HeadlessRenderer::needsHeights(const ReliefDesc& relief) const {
    return renderer_->needsHeights(relief);
}

void HeadlessRenderer::setAlbedo(const AlbedoImage* albedo, const std::string& source) {
    context_.makeCurrent();
    renderer_->setAlbedo(albedo, source);
}

HeadlessResult HeadlessRenderer::render(const RenderJob& job) {
    checkHeightScale(job.heightScale);
    checkPictureSize(job.width, job.height);
    if (mapWidth_ == 0) throwRuntime("HeadlessRenderer::render: no height map");
    {
        // Before any GL work: the float range and precision the shader needs.
        const CameraFrame frame = resolveCamera(job.camera, job.width, job.height, 1.0);
        checkFloatLimits({mapWidth_, mapHeight_, maxHeight_}, job.heightScale, job.base, job.model,
                         job.camera, frame, source_);
    }
    context_.makeCurrent();
    const GL& gl = context_.gl();
    if (!job.animation.empty() && job.tiles != glm::ivec2(1, 1)) {
        // The animated field is written on the GPU, whose pyramid builder bounds one map.
        throwBadInput("{animation} and {tiles}: an animated height field does not tile");
    }
    // Another size or curved base of the map's addressing, another last level, scale or
    // model, on the pyramid built; between the plane and a curved base, or for other
    // tiles, the map is set again first (setHeights).
    renderer_->apply(job, job.method);  // each program compiled once, then looked up
    if (animated_ && animated_->evaluated() && animated_->name() != job.animation) {
        animated_->restore(*renderer_);  // another field, or the map's own heights again
        maxHeight_ = renderer_->maxHeight();
    }
    if (!job.animation.empty()) {
        if (!animated_ || animated_->name() != job.animation)
            animated_ = std::make_unique<AnimatedHeights>(gl, shaderDirectory(), job.animation);
        animated_->evaluate(*renderer_, job.time);
        maxHeight_ = renderer_->maxHeight();
    }
    const CameraFrame camera = resolveCamera(
        job.camera, job.width, job.height,
        sceneRadius(reliefExtent(mapWidth_, mapHeight_, maxHeight_, job.heightScale, job.base),
                    job.model.objectToWorld()));

    // Tiles no larger than the GL's viewport and renderbuffer limits, and kDefaultTileSide
    // (a 4096 x 4096 target holds 640 MB of attachments; llvmpipe fails to complete one of
    // 16384 x 16384). Each tile casts the whole picture's rays (ReliefRenderer::draw).
    // The colour attachments are textures: GL_MAX_TEXTURE_SIZE bounds them too.
    GLint maxRenderbuffer = 0, maxTexture = 0, maxViewport[2] = {0, 0};
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int tile = std::min({maxTileSide_,
                               static_cast<int>(maxRenderbuffer), static_cast<int>(maxTexture),
                               static_cast<int>(maxViewport[0]), static_cast<int>(maxViewport[1])});
    if (tile < 1) throwRuntime("the GL reports no usable framebuffer size (a failed query)");
    const int targetWidth = std::min(tile, job.width), targetHeight = std::min(tile, job.height);
    if (!target_ || target_->width() != targetWidth || target_->height() != targetHeight) {
        target_.reset();
        target_.emplace(gl, targetWidth, targetHeight);
    }

    HeadlessResult result{{}, camera, std::nullopt};
    RenderedFrame& frame = result.frame;
    try {
        const std::size_t count = static_cast<std::size_t>(job.width) * job.height * 4;
        frame.width = job.width;
        frame.height = job.height;
        frame.color.resize(count);
        frame.position.resize(count);
        frame.stats.resize(count);
        frame.shadow.resize(count / 4);
    } catch (const std::bad_alloc&) {
        throwRuntime("not enough memory for a " + std::to_string(job.width) + "x" +
                     std::to_string(job.height) + " picture (" +
                     std::to_string(kFrameBytesPerPixel) + " bytes a pixel)");
    }
    for (int y = 0; y < job.height; y += tile) {
        for (int x = 0; x < job.width; x += tile) {
            const PictureTile part{x, y, std::min(tile, job.width - x),
                                   std::min(tile, job.height - y)};
            target_->clear(job.background);
            {
                const gl::SrgbWrites srgb(gl);  // the relief's linear colour, encoded
                renderer_->draw(camera, job.shading, part);
            }
            target_->readInto(frame, part.x, part.y, part.width, part.height);
        }
    }
    if (!job.animation.empty()) result.animatedMap = renderer_->textures()->readSamples(gl);
    gl.Finish();
    const GLenum error = gl.GetError();
    if (error != GL_NO_ERROR)
        throwRuntime("GL error " + gl::enumHex(error) + " while rendering " + source_);
    return result;
}

HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job, const AlbedoImage* albedo) {
    // Refused before the pyramid is built; render checks them again.
    checkHeightScale(job.heightScale);
    checkPictureSize(job.width, job.height);
    checkFloatLimits({map.width * job.tiles.x, map.height * job.tiles.y, map.maxValue()},
                     job.heightScale, job.base, job.model, job.camera,
                     resolveCamera(job.camera, job.width, job.height, 1.0), source);
    // GL objects live in this scope and die before the context does.
    HeadlessRenderer renderer(context, job.method);
    renderer.setHeightMap(map, source, job.base, job.interpolation, job.tiles);
    if (albedo) renderer.setAlbedo(albedo, source + " (albedo)");
    return renderer.render(job);
}

}  // namespace microrelief
