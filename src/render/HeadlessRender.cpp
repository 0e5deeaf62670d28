#include "render/HeadlessRender.h"

#include <algorithm>
#include <cmath>

#include "core/DataPaths.h"
#include "core/Error.h"

namespace microrelief {

HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job) {
    if (!(job.heightScale > 0.0f) || !std::isfinite(job.heightScale)) {
        throwBadInput("--height-scale must be a positive number");
    }
    context.makeCurrent();
    const GL& gl = context.gl();
    // GL objects live in this scope and die before the context does.
    ReliefRenderer renderer(gl, shaderDirectory(), job.method);
    renderer.setHeightScale(job.heightScale);
    renderer.setHeightMap(map, source, job.base);
    const CameraFrame camera =
        resolveCamera(job.camera, job.width, job.height,
                      sceneRadius(reliefExtent(map, job.heightScale, job.base)));

    OffscreenTarget target(gl, job.width, job.height);
    target.clear(job.background);
    renderer.draw(camera, job.shading);
    gl.Finish();
    HeadlessResult result{target.read(), camera};
    const GLenum error = gl.GetError();
    if (error != GL_NO_ERROR)
        throwRuntime("GL error " + gl::enumHex(error) + " while rendering " + source);
    return result;
}

}  // namespace microrelief
