#include "render/HeadlessRender.h"

#include <algorithm>
#include <cmath>

#include "core/DataPaths.h"
#include "core/Error.h"
#include "render/FloatLimits.h"

namespace microrelief {

HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job) {
    if (!(job.heightScale > 0.0f) || !std::isfinite(job.heightScale)) {
        throwBadInput("--height-scale must be a positive number");
    }
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
