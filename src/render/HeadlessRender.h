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

// The largest picture renderHeadless makes, refused up front beyond: sides up to 65536
// and at most 16384 x 16384 pixels, which the frame holds in memory at
// kFrameBytesPerPixel (colour, the position AOV and the statistics: 9.7 GiB at the
// limit). Larger than the GL's own limits, it is drawn in tiles of kDefaultTileSide.
inline constexpr int kMaxPictureSide = 65536;
inline constexpr long long kMaxPicturePixels = 16384LL * 16384;
inline constexpr int kFrameBytesPerPixel = 4 + 16 + 16;
inline constexpr int kDefaultTileSide = 4096;

struct RenderJob {
    Camera camera;
    int width = 1280, height = 720;
    float heightScale = 0.1f;
    ShadingOptions shading;
    MethodSettings method;
    glm::vec3 background{0.11f, 0.12f, 0.14f};  // linear RGB
    int tileSide = 0;  // 0: kDefaultTileSide (or the GL's limit, if lower); tests set less
};

struct HeadlessResult {
    RenderedFrame frame;
    CameraFrame camera;  // the rays the picture was traced with
};

// Throws Error(BadInput) for a picture size beyond the limits above.
void checkPictureSize(int width, int height);

// `source` names the map in error messages. Throws Error.
HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job);

}  // namespace microrelief
