// One picture, start to finish, in an offscreen framebuffer of the given context: the
// path that microrelief-render and the GL tests share. HeadlessRenderer draws many
// pictures in one context (microrelief-render's camera paths) along the same path.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "microrelief/gl/GlContext.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/base/ReliefExtent.h"
#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/gl/AnimatedHeights.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/scene/ModelTransform.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefRenderer.h"
#include "microrelief/core/scene/Scene.h"

namespace microrelief {

// Pictures larger than kDefaultTileSide (or the GL's limits) are drawn in tiles of it.
inline constexpr int kDefaultTileSide = 4096;

// A picture to render: the relief (what it is and where it lies) and the view of it
// (core/scene/Scene.h). The heights themselves are HeadlessRenderer's (setHeights), or
// renderHeadless's argument.
struct RenderJob : ReliefDesc, ViewDesc {};

// How a picture of a map read through pages (gl/PagedPyramid.h) was drawn.
struct PagingReport {
    int draws = 0;                // draws of tiles, each again until none wanted a page
    int splits = 0;               // tiles drawn in quarters: the pool held too few pages
    std::size_t pagesLoaded = 0;  // for this picture
    int pagesResident = 0;        // after it
};

struct HeadlessResult {
    RenderedFrame frame;
    CameraFrame camera;  // the rays the picture was traced with
    // With an animation, the heights it traced (read back from the GPU): the map to hold
    // the picture to.
    std::optional<HeightMap> animatedMap;
    PagingReport paging;  // all 0 for a map in whole textures
};

namespace gl {
class MeshRelief;
}

// Pictures of one map at a time, keeping what they share from one to the next: the
// programs (each method compiled once), the map's textures and max pyramid (built
// again only by setHeights or setPyramidPages) and the framebuffer (made again only for another size).
// Its GL objects belong to `context`: it must not outlive it.
class HeadlessRenderer {
public:
    // Compiles `method`'s program first. Throws Error.
    explicit HeadlessRenderer(GlContext& context, const MethodSettings& method = {});

    // The map of the relief of `job`, with its method (ReliefRenderer::apply): `map` holds
    // the heights its map source names (loaded by the caller), `source` names it in error
    // messages. Its pyramid is built on the GPU (gl/PyramidBuilder.h; on the CPU where the
    // GL cannot render into R16F, and for a tiled map, whose bounds the GPU builder does not
    // make). A job may then take another size of that base, another curved base or last
    // level; between the plane and a curved base, or for other tiles, set the map again.
    // needsHeights says whether another relief needs heights of its own: no map yet, or one
    // set for another pyramid (core/scene/Scene.h: samePyramid; after setPyramidPages,
    // always). A caller loads maps only when it does.
    void setHeights(const RenderJob& job, const HeightMap& map, const std::string& source);
    // The same for a map the caller shares: read through pages, the pages keep it rather
    // than a copy (a camera path over a map past GL_MAX_TEXTURE_SIZE).
    void setHeights(const RenderJob& job, std::shared_ptr<const HeightMap> map,
                    const std::string& source);
    // A map whose samples and pyramid `pages` keeps (a pyramid file, io/PyramidFile.h;
    // ReliefMap::fromPages): read through pages, laid over `base` (Error(BadInput) naming
    // `source` where the pyramid was built for other addressing).
    void setPyramidPages(std::shared_ptr<const PyramidPages> pages, const std::string& source,
                         const BaseShape& base = {},
                         Interpolation interpolation = Interpolation::Bilinear);
    bool needsHeights(const ReliefDesc& relief) const;
    // What has been built so far (gl/ReliefRenderer.h): render() of another job builds
    // only what the job changed.
    const RebuildCounts& rebuilds() const { return renderer_->rebuilds(); }
    // The map's colours (core/image/Albedo.h), or none (the shading's one colour). Throws Error.
    void setAlbedo(const AlbedoImage* albedo, const std::string& source);
    // The mesh base's triangles and map (ReliefDesc::onMesh; io/ReliefFiles.h loads both),
    // which render() draws a job on the mesh base over with gl::MeshRelief (src/gl/
    // HeadlessMesh.cpp); `source` names them in messages. The map's textures and the proxy
    // are built at the first such render and kept while the mesh, the map, the height
    // scale, the last level, the light's direction, the colour and the view stay the same
    // (a camera path's frames).
    void setMesh(std::shared_ptr<const TriangleMesh> mesh, std::shared_ptr<const HeightMap> map,
                 const std::string& source);
    // Renders `job` of the current map (of setMesh's mesh and map, on the mesh base). The
    // scene is checked as a whole first (validateScene: Error(BadInput) with its first
    // refusal, before any GL work). Throws Error.
    HeadlessResult render(const RenderJob& job);
    // When setHeights reads a map through pages (ReliefRenderer::setPaging;
    // by default Auto: maps larger than GL_MAX_TEXTURE_SIZE).
    void setPaging(const PagingSettings& paging) { renderer_->setPaging(paging); }
    // The largest tile a picture is drawn in, pixels a side (kDefaultTileSide; the GL's
    // limits cap it): a smaller one holds less memory at once. Any side draws the same
    // picture, bit for bit.
    void setMaxTileSide(int side) { maxTileSide_ = side > 0 ? side : kDefaultTileSide; }
    // Pictures from the instrumented variant (ReliefRenderer::setMethod's countFetches):
    // each pixel's texel reads in its statistics output. For measurement only.
    void setCountFetches(bool count) { renderer_->setMethod(renderer_->method(), count); }
    // The GL memory the map's textures (and pages, pool and tables) take, bytes.
    std::size_t gpuBytes() const;

private:
    // Its maps' pyramids: on the GPU, or on the CPU where the GPU's build fails for a reason
    // other than the map (gl/ReliefMap.h).
    static constexpr PyramidBuild kBuild = PyramidBuild::GpuElseCpu;
    // The map set on the renderer by `set` (with kBuild); the map's facts are its
    // (ReliefMap: size, highest sample, name).
    void upload(const std::function<void()>& set);

    // The picture's arrays at the job's size, positions relative to `positionOrigin`;
    // Error(Runtime) where memory runs out.
    static void allocateFrame(RenderedFrame& frame, const RenderJob& job,
                              const glm::dvec3& positionOrigin);
    // render() of a job on the mesh base, in tiles as render() draws a picture.
    HeadlessResult renderMesh(const RenderJob& job);
    // One tile of the picture into `result`; a paged map's drawn until it is exact.
    void drawTile(const RenderJob& job, const CameraFrame& camera, const PictureTile& part,
                  HeadlessResult& result);

    GlContext& context_;
    std::optional<ReliefRenderer> renderer_;
    std::optional<OffscreenTarget> target_;
    std::unique_ptr<AnimatedHeights> animated_;
    bool fromPages_ = false;  // the map set is a pyramid file's (setPyramidPages)
    // Whether drawTile draws a tile too large for the page pool in its quarters last to
    // first: every other frame (render() turns it), so that a camera path's frames do not
    // cycle through the quarters in one order, least recently used eviction's worst case.
    bool quartersReversed_ = false;
    // setMesh's, and the MeshRelief drawn last (src/gl/HeadlessMesh.cpp; shared: deleted as
    // made there, where it is complete).
    struct MeshState;
    std::shared_ptr<MeshState> mesh_;
    int maxTileSide_ = kDefaultTileSide;
};

// The box the mesh base's shell lies in (ReliefExtent: min, max, topHeight = s H): the
// mesh's vertices' box grown by s H on every side, `top` H >= every height of the map (the
// pyramid's top: gl::MeshRelief::top, or the map's largest sample, which bounds every
// bilinear and biquadratic value). Why it holds: a point of the shell is X(b, t) =
// B(b) + s t D(b) with B(b) a convex combination of the vertices (in their box),
// D(b) = sum b_i N_i of length at most sum b_i |N_i| = 1 (unit normals, b_i >= 0, sum 1) and
// 0 <= t <= H, so |X - B| <= s H and each coordinate lies within s H of the box.
ReliefExtent meshShellExtent(const TriangleMesh& mesh, double heightScale, double top);
// What the mesh base's checks and `-v` tell of a mesh: its vertices' box and that box's
// diagonal, the largest |coordinate| of a vertex (`reach`), and the median over its
// triangles of sqrt(2 area) (a grid quad's side: the scale of its detail), all in the
// mesh's units.
struct MeshSize {
    glm::dvec3 low{0.0}, high{0.0};
    double diagonal = 0.0, reach = 0.0, medianTriangle = 0.0;
};
MeshSize meshSize(const TriangleMesh& mesh);
// Throws Error(BadInput), one line naming `source` (the mesh) and the limit, where the
// shader's float arithmetic cannot trace the mesh base exactly (src/gl/HeadlessMesh.cpp
// says how each was measured): the shell s H (`heightScale` times the map's largest
// height) more than 16 times the vertices' box diagonal or less than 2^-64 of it; a vertex
// farther than kMaxWorldPosition from the origin (core/scene/FloatLimits.h).
// HeadlessRenderer::render checks it before drawing a job on the mesh base.
void checkMeshFloatLimits(const TriangleMesh& mesh, const HeightMap& map, double heightScale,
                          const std::string& source);
// The same with the map's largest height `top` (a camera path checks each frame's map from
// its facts, not held in memory).
void checkMeshFloatLimits(const TriangleMesh& mesh, double top, double heightScale,
                          const std::string& source);
// The camera a picture of the mesh base takes where the user gives none: `camera` with its
// target, where not `targetGiven`, at the centre of `shell` (meshShellExtent), and its eye,
// where not `eyeGiven`, along the default camera's direction (Camera{}: from above, to the
// front right) from the target, at the distance where the shell's bounding sphere (about its
// centre, radius half its box's diagonal) fills the narrower of the picture's two fields of
// view (width x height pixels, camera.fovyDegrees): the whole shell in the picture, as the
// default camera has the unit plane and the curved bases in it. `up` and the field of view
// stay as given.
Camera meshCamera(Camera camera, bool eyeGiven, bool targetGiven, const ReliefExtent& shell,
                  int width, int height);

// `source` names the map in error messages; `paging`: when and how the map is read through
// pages (by default, past GL_MAX_TEXTURE_SIZE). Throws Error.
HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job, const AlbedoImage* albedo = nullptr,
                              const PagingSettings& paging = {});
// The same for a map the caller shares, which a map read through pages keeps rather than a
// copy of it (microrelief-render's, which it holds the picture to afterwards).
HeadlessResult renderHeadless(GlContext& context, std::shared_ptr<const HeightMap> map,
                              const std::string& source, const RenderJob& job,
                              const AlbedoImage* albedo = nullptr,
                              const PagingSettings& paging = {});

}  // namespace microrelief
