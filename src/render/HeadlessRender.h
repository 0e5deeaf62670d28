// One picture, start to finish, in an offscreen framebuffer of the given context: the
// path that microrelief-render and the GL tests share.
#pragma once

#include <string>

#include "context/GlContext.h"
#include "heightmap/HeightMap.h"
#include "render/Camera.h"
#include "render/OffscreenTarget.h"
#include "render/ReliefRenderer.h"

namespace microrelief {

struct RenderJob {
    Camera camera;
    int width = 1280, height = 720;
    float heightScale = 0.1f;
    BaseShape base;  // the surface the map is laid over (--base, --radius, --length, --radii)
    ShadingOptions shading;
    MethodSettings method;
    glm::vec3 background{0.11f, 0.12f, 0.14f};  // linear RGB
};

struct HeadlessResult {
    RenderedFrame frame;
    CameraFrame camera;  // the rays the picture was traced with
};

// `source` names the map in error messages. Throws Error.
HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job);

}  // namespace microrelief
