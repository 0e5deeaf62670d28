#include "render/HeadlessRender.h"

#include <algorithm>
#include <cmath>

#include "core/DataPaths.h"
#include "core/Error.h"
#include "render/FloatLimits.h"

namespace microrelief {

void checkPictureSize(int width, int height) {
    const double pixels = static_cast<double>(width) * height;
    if (width <= 0 || height <= 0 || width > kMaxPictureSide || height > kMaxPictureSide ||
        pixels > static_cast<double>(kMaxPicturePixels)) {
        throwBadInput("--size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is outside the pictures this program renders: sides up to " +
                      std::to_string(kMaxPictureSide) + ", at most " +
                      std::to_string(kMaxPicturePixels) + " pixels (16384 x 16384; " +
                      std::to_string(kFrameBytesPerPixel) + " bytes a pixel in memory)");
    }
}

HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job) {
    if (!(job.heightScale > 0.0f) || !std::isfinite(job.heightScale)) {
        throwBadInput("--height-scale must be a positive number");
    }
    checkPictureSize(job.width, job.height);
    {
        // Before any GL work: the float range and precision the shader needs.
        const CameraFrame frame = resolveCamera(job.camera, job.width, job.height, 1.0);
        checkFloatLimits(map, job.heightScale, job.camera, frame, source);
    }
    context.makeCurrent();
    const GL& gl = context.gl();
    // GL objects live in this scope and die before the context does.
    ReliefRenderer renderer(gl, shaderDirectory(), job.method);
    renderer.setHeightScale(job.heightScale);
    renderer.setHeightMap(map, source);
    const CameraFrame camera = resolveCamera(job.camera, job.width, job.height,
                                             sceneRadius(reliefExtent(map, job.heightScale)));

    // Tiles no larger than the GL's viewport and renderbuffer limits, and kDefaultTileSide
    // (a 4096 x 4096 target holds 640 MB of attachments; llvmpipe fails to complete one of
    // 16384 x 16384). Each tile casts the whole picture's rays (ReliefRenderer::draw).
    GLint maxRenderbuffer = 0, maxViewport[2] = {0, 0};
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int tile = std::min({job.tileSide > 0 ? job.tileSide : kDefaultTileSide,
                               static_cast<int>(maxRenderbuffer), static_cast<int>(maxViewport[0]),
                               static_cast<int>(maxViewport[1])});
    OffscreenTarget target(gl, std::min(tile, job.width), std::min(tile, job.height));

    HeadlessResult result{{}, camera};
    RenderedFrame& frame = result.frame;
    try {
        const std::size_t count = static_cast<std::size_t>(job.width) * job.height * 4;
        frame.width = job.width;
        frame.height = job.height;
        frame.color.resize(count);
        frame.position.resize(count);
        frame.stats.resize(count);
    } catch (const std::bad_alloc&) {
        throwRuntime("not enough memory for a " + std::to_string(job.width) + "x" +
                     std::to_string(job.height) + " picture (" +
                     std::to_string(kFrameBytesPerPixel) + " bytes a pixel)");
    }
    for (int y = 0; y < job.height; y += tile) {
        for (int x = 0; x < job.width; x += tile) {
            const PictureTile part{x, y, std::min(tile, job.width - x),
                                   std::min(tile, job.height - y)};
            target.clear(job.background);
            renderer.draw(camera, job.shading, part);
            target.readInto(frame, part.x, part.y, part.width, part.height);
        }
    }
    gl.Finish();
    const GLenum error = gl.GetError();
    if (error != GL_NO_ERROR)
        throwRuntime("GL error " + gl::enumHex(error) + " while rendering " + source);
    return result;
}

}  // namespace microrelief
