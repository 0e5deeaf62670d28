#include "render/HeadlessRender.h"

#include <algorithm>
#include <cmath>

#include "core/DataPaths.h"
#include "core/Error.h"

namespace microrelief {

namespace {

void checkHeightScale(float heightScale) {
    if (!(heightScale > 0.0f) || !std::isfinite(heightScale)) {
        throwBadInput("--height-scale must be a positive number");
    }
}

}  // namespace

HeadlessRenderer::HeadlessRenderer(GlContext& context, const MethodSettings& method)
    : context_(context) {
    context_.makeCurrent();
    renderer_.emplace(context_.gl(), shaderDirectory(), method);
}

void HeadlessRenderer::setHeightMap(const HeightMap& map, const std::string& source,
                                    const BaseShape& base, Interpolation interpolation) {
    context_.makeCurrent();
    renderer_->setHeightMap(map, source, base, interpolation);
    source_ = source;
    mapWidth_ = map.width;
    mapHeight_ = map.height;
    maxHeight_ = map.maxValue();
}

HeadlessResult HeadlessRenderer::render(const RenderJob& job) {
    checkHeightScale(job.heightScale);
    if (mapWidth_ == 0) throwRuntime("HeadlessRenderer::render: no height map");
    context_.makeCurrent();
    const GL& gl = context_.gl();
    // Another size or curved base of the map's addressing; between the plane and a curved
    // base the pyramid is built anew (setHeightMap).
    if (job.base != renderer_->base()) renderer_->setBase(job.base);
    if (job.interpolation != renderer_->interpolation())
        throwRuntime("HeadlessRenderer::render: the map was set for another interpolation");
    renderer_->setMethod(job.method);  // compiled once per method, then looked up
    if (heightScale_ != job.heightScale) {
        renderer_->setHeightScale(job.heightScale);
        heightScale_ = job.heightScale;
    }
    const CameraFrame camera = resolveCamera(
        job.camera, job.width, job.height,
        sceneRadius(reliefExtent(mapWidth_, mapHeight_, maxHeight_, job.heightScale, job.base)));

    if (!target_ || target_->width() != job.width || target_->height() != job.height) {
        target_.reset();
        target_.emplace(gl, job.width, job.height);
    }
    target_->clear(job.background);
    renderer_->draw(camera, job.shading);
    gl.Finish();
    HeadlessResult result{target_->read(), camera};
    const GLenum error = gl.GetError();
    if (error != GL_NO_ERROR)
        throwRuntime("GL error " + gl::enumHex(error) + " while rendering " + source_);
    return result;
}

HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job) {
    checkHeightScale(job.heightScale);
    // GL objects live in this scope and die before the context does.
    HeadlessRenderer renderer(context, job.method);
    renderer.setHeightMap(map, source, job.base, job.interpolation);
    return renderer.render(job);
}

}  // namespace microrelief
