// Draws microrelief with the multilevel method: the base surface's bounding box is the
// proxy geometry, and each of its fragments traces its own ray (shaders/relief.frag).
// One renderer is one relief: its base, height scale, model and method. The map it draws
// (gl/ReliefMap.h) and the programs (gl/ReliefPrograms.h) are shared: with every renderer
// given the same ReliefMap or ReliefPrograms. Draws into whatever framebuffer is bound
// (see draw).
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/core/base/ReliefExtent.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/scene/Method.h"
#include "microrelief/core/scene/ModelTransform.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/gl/AlbedoTexture.h"
#include "microrelief/gl/Objects.h"
#include "microrelief/gl/PyramidBuilder.h"
#include "microrelief/gl/ReliefMap.h"
#include "microrelief/gl/ReliefPrograms.h"
#include "microrelief/gl/ReliefShader.h"
#include "microrelief/gl/ReliefTextures.h"

namespace microrelief {

// The part of the picture one draw covers, in GL window coordinates of the whole
// picture (origin at the bottom left): the bound framebuffer holds width x height
// pixels of it from (x, y). The default, width 0, is the whole picture.
struct PictureTile {
    int x = 0, y = 0;
    int width = 0, height = 0;
};

// What a renderer has built so far, for tests and tools that hold it to rebuilding only what
// changed: max pyramids built whole (apply with heights, heightsReplaced), programs compiled for
// it (not those another renderer sharing its ReliefPrograms compiled first), albedo
// textures uploaded.
struct RebuildCounts {
    int pyramids = 0;
    int programs = 0;
    int albedos = 0;
    bool operator==(const RebuildCounts&) const = default;
};

class ReliefRenderer {
public:
    // Its own programs, compiled from `shaderDir` (which holds relief_box.vert, relief.frag,
    // relief_parameters.glsl, pyramid/ and microrelief/); `method` is the program compiled
    // first. Throws Error(Runtime) when it does not compile.
    ReliefRenderer(const GL& gl, const std::filesystem::path& shaderDir,
                   const MethodSettings& method = {});
    // The programs of `programs`, shared with the other renderers of its context: a
    // configuration one of them compiled is not compiled again.
    explicit ReliefRenderer(std::shared_ptr<ReliefPrograms> programs,
                            const MethodSettings& method = {});

    // A relief as a whole (core/scene/Scene.h). needsHeights: whether apply() needs the
    // relief's heights, because no pyramid was built for a relief yet, or the one built is
    // of other heights, addressing or tiles (samePyramid with the relief applied last).
    bool needsHeights(const ReliefDesc& relief) const;
    // Applies `relief`, rebuilding only what it changes (rebuilds() counts). With `heights`
    // (its map, named `source` in messages) a map of them is built (ReliefMap::upload):
    // the max pyramid laid over the relief's base (wrapped in u on a curved base), which
    // bounds the surface either last level makes of it, the map repeated relief.tiles times,
    // uploaded with the samples; `build` says where the pyramid is made (the CPU, the GPU, or
    // the GPU where that works: gl/ReliefMap.h holds the policy; a tiled map's on the CPU),
    // and setPaging whether the map is read through pages. Without heights, the map built is
    // kept, and must serve the relief's addressing and tiles (else Error(Runtime)). Then the
    // base, the last level, the height scale and the model. The albedo and an animation are
    // the caller's: they need files, a time. Throws Error(BadInput) naming `source` for a
    // map past GL_MAX_TEXTURE_SIZE (not paged), and for a method that does not run on the
    // relief's base or tiles; nothing changes then.
    void apply(const ReliefDesc& relief, const HeightMap* heights = nullptr,
               const std::string& source = {}, PyramidBuild build = PyramidBuild::Cpu);
    // A relief and the method that is to trace it, together: the pair is checked first (the
    // method runs on the relief's base and tiles, core/scene/Method.h), so that neither the
    // method held for the last relief (a cone on the plane, before a cylinder) nor the
    // relief held for the last method (a cylinder, before a cone on the plane) refuses the
    // other. Then as apply() above and setMethod(); where either throws, the method held
    // stays.
    void apply(const ReliefDesc& relief, const MethodSettings& method,
               const HeightMap* heights = nullptr, const std::string& source = {},
               PyramidBuild build = PyramidBuild::Cpu);
    // Both for heights the caller shares: read through pages, the pages keep them rather
    // than a copy (a map past GL_MAX_TEXTURE_SIZE: 1.6 GB at 20000 x 20000); null heights
    // keep the map built.
    void apply(const ReliefDesc& relief, std::shared_ptr<const HeightMap> heights,
               const std::string& source = {}, PyramidBuild build = PyramidBuild::Cpu);
    void apply(const ReliefDesc& relief, const MethodSettings& method,
               std::shared_ptr<const HeightMap> heights, const std::string& source = {},
               PyramidBuild build = PyramidBuild::Cpu);
    // `relief` drawn over `map`, which the caller built of the relief's heights
    // (ReliefMap::upload; fromPages for a pyramid file, read through pages whatever
    // setPaging says) and may share with other renderers of its context:
    // nothing of the map is built again but what this renderer's method reads and the map
    // lacks (ReliefMap::prepareFor). The map's addressing must be the relief's (u wrapping
    // on a curved base, the tiles): else Error(Runtime), and nothing changes. Then the
    // base, the last level, the height scale and the model, as apply() with heights.
    void apply(const ReliefDesc& relief, std::shared_ptr<ReliefMap> map);
    // The map drawn (null before a map is set), for another renderer to share.
    const std::shared_ptr<ReliefMap>& map() const { return map_; }

    glm::ivec2 tiles() const { return map_ ? map_->tiles() : glm::ivec2(1, 1); }
    // When apply() reads heights through pages (gl/PagedPyramid.h), and how: by default
    // never (Mode::Never: a map larger than GL_MAX_TEXTURE_SIZE is refused), since a paged
    // map's draw is exact only when repeated until its pager wants nothing
    // (PagedPyramid::takeWanted, load), as HeadlessRenderer repeats it. For the next
    // map built; its budget and page side for ReliefMap::fromPages too.
    void setPaging(const PagingSettings& paging) { paging_ = paging; }
    const PagingSettings& paging() const { return paging_; }
    // The pager of the map set, where it is paged; else null.
    PagedPyramid* pager() { return map_ ? map_->pager() : nullptr; }
    bool paged() const { return map_ && map_->paged(); }

    // A map that changes on the GPU (sculpting, animation). The map's textures, for a pass
    // of the caller's that draws into the samples (null before a map is set).
    ReliefTextures* textures() { return map_ ? &map_->textures() : nullptr; }
    const ReliefTextures* textures() const { return map_ ? &map_->textures() : nullptr; }
    // After the caller changed the samples inside `changed` (map texels): the map's
    // pyramids brought up to date (ReliefMap::heightsChanged), what the method reads built
    // again, and the box fitted to the map's new maximum (other renderers drawing the map
    // fit theirs at their next draw). heightsReplaced: every sample changed, the pyramids
    // built anew.
    void heightsChanged(const std::vector<TexelRect>& changed);
    void heightsReplaced();
    // The surface's maximum, map units: the pyramid's top texel.
    float maxHeight() const { return map_ ? map_->maxHeight() : 0.0f; }
    // The GPU pyramid builder this renderer uses (its ReliefPrograms'), made on first use.
    PyramidBuilder& pyramidBuilder() { return programs_->pyramidBuilder(); }
    const std::shared_ptr<ReliefPrograms>& programs() const { return programs_; }
    // The base and the last level applied last.
    const BaseShape& base() const { return base_; }
    Interpolation interpolation() const { return interpolation_; }

    // The surface's colour from `albedo` over the map's (u, v) (core/image/Albedo.h), or, with
    // nothing, the shading's one colour. Throws Error(BadInput) naming `source` for a
    // texture larger than the GL takes, keeping the one it had.
    void setAlbedo(const AlbedoImage* albedo, const std::string& source = "the albedo");
    bool hasAlbedo() const { return albedo_.has_value(); }

    // Where the relief sits in the world (apply's relief.model; the identity: where the
    // spec puts it).
    const ModelTransform& model() const { return model_; }
    // The depth convention of the caller's projection and framebuffer (the default:
    // OpenGL's [-1, 1] clip depth, a standard depth test).
    void setDepthConvention(const DepthConvention& depth) { depth_ = depth; }
    const DepthConvention& depthConvention() const { return depth_; }

    // Recompiles the current program from the files; on failure throws and keeps the
    // previous program. Other programs compiled before are dropped (they may be stale),
    // for every renderer sharing its ReliefPrograms.
    void reloadShaders();

    // Chooses the tracing method; each configuration (ReliefShaderConfig) is compiled once
    // and kept. Step counts and the pixel error are uniforms. `countFetches` selects the
    // instrumented variant that writes texel reads to the statistics output. On a
    // compile failure throws and keeps the method that works.
    void setMethod(const MethodSettings& settings, bool countFetches = false);
    const MethodSettings& method() const { return method_; }

    // Compiles the shaders as GLSL 3.30 even where the context is newer (4.00 otherwise:
    // one textureGather a bilinear cell where 3.30 reads its four samples one by one), the
    // path an engine in a GL 3.3 context takes; for tests and the benchmark's A/B. Paged
    // maps stay on 4.30. On a compile failure throws and keeps the dialect that works.
    void setGlsl330(bool on);
    bool glsl330() const { return glsl330_; }

    // The coarse pass (issue 52, docs/api.md): before the relief's draw, one fragment per
    // tileSize x tileSize tile of pixels walks the frustum of the tile's rays through the
    // max pyramid (shaders/coarse_start.frag) to the first distance where any of them may
    // meet the solid, and each pixel's walk starts there instead of at the box: the same
    // picture (exact, pixelError 0: positions equal to float rounding), fewer reads per
    // pixel where rays cross much empty space. For the multilevel method on the plane, a
    // map not paged; any other draw is the single pass. 0, the default, turns it off.
    // Throws Error(BadInput) for a size outside 0 and 2 to 64.
    void setCoarsePass(int tileSize);
    int coarsePass() const { return coarseTile_; }
    // Whether the last draw ran the coarse pass; its texture (RGBA32F, a texel per tile: x
    // the start, coarse_start.glsl's MR_COARSE_KEEP, MR_COARSE_MISS or a t; y the pyramid
    // texels the tile read) and the texels used, ceil(width / T) x ceil(height / T), for
    // tests and tools.
    bool coarsePassDrawn() const { return coarseDrawn_; }
    GLuint coarseStartTexture() const { return coarseTexture_.id(); }
    glm::ivec2 coarseStartSize() const { return coarseSize_; }

    // Draws the picture `camera` describes, or the tile of it given, into the bound
    // framebuffer: relief.frag's colour to draw buffer 0 and, where the framebuffer's
    // draw buffers take them, the hit position, statistics and shadow to 1 to 3
    // (OffscreenTarget has all four; a framebuffer with the colour alone drops the rest).
    // The hit position is the world's less camera.eye: the draw traces relative to the
    // eye, the eye subtracted in double, so a relief far from the world's origin is as
    // exact as one at it (core/scene/FloatLimits.h; RenderedFrame::positionOrigin).
    // The colour is linear, for an sRGB target with GL_FRAMEBUFFER_SRGB on (gl::SrgbWrites,
    // gl/StateGuard.h): with it off the linear values are stored as they are and the
    // picture comes out dark. The same rays
    // whole or in tiles, so a picture drawn in tiles is the one drawn whole, pixel for
    // pixel. GL state: the draw sets what it needs (program, vertex array, the uniform
    // buffer at binding 0, textures on units 0 to 2, face culling and winding, the depth test
    // and its function, depth clamping, the viewport) and restores each as it found it
    // (gl/StateGuard.h). The depth mask stays the caller's: with it off nothing is written.
    // Before any map (apply) it throws Error(Runtime) rather than draw nothing.
    void draw(const CameraFrame& camera, const ShadingOptions& shading,
              const PictureTile& tile = {});

    // The picture `view` describes, as draw() above draws it: the view's method set
    // (setMethod), its camera resolved against this relief (resolveCamera), its shading.
    // The background is the caller's (clear the framebuffer first). Returns the camera
    // drawn, whose rays the hit positions are of. The view is checked first, alone and with
    // the relief applied (core/scene/Scene.h: ViewDesc::validate, validateTogether): a view
    // the description refuses throws Error(BadInput) with its message, and nothing changes.
    CameraFrame draw(const ViewDesc& view, const PictureTile& tile = {});
    // `camera` resolved for a width x height picture of this relief: an automatic distance
    // and clip range from the relief's extent (its map's size and highest sample, its base
    // and height scale) placed by its model, as every program resolves one. Throws
    // Error(Runtime) before a map is set.
    CameraFrame resolveCamera(const Camera& camera, int width, int height) const;

    int maxIterations() const { return map_ ? map_->traversalBudget() : 0; }
    const RebuildCounts& rebuilds() const { return rebuilds_; }

private:
    ReliefShaderConfig configFor(const MethodSettings& settings, bool countFetches, BaseKind base,
                                 Interpolation interpolation, bool frontFaces, ShadowMode shadows,
                                 bool albedoMap, bool tiled, bool paged) const;
    bool tiled() const { return tiles() != glm::ivec2(1, 1); }
    // Whether this draw runs the coarse pass (setCoarsePass), and the pass itself into
    // coarseTexture_ for the picture tile `t` (after which the relief's draw reads it).
    bool coarsePassApplies() const;
    void drawCoarsePass(const ReliefParameters& values, const PictureTile& t);
    // A map of `map` built (ReliefMap::upload) and drawn with `base` and `interpolation`;
    // `shared`, where not null, is `map`, shared by the caller.
    void setHeightMapOf(const HeightMap& map, std::shared_ptr<const HeightMap> shared,
                        const std::string& source, const BaseShape& base,
                        Interpolation interpolation, PyramidBuild build, glm::ivec2 tiles);
    // apply's work, as setHeightMapOf's: `shared`, where not null, is `heights`.
    void applyOf(const ReliefDesc& relief, const HeightMap* heights,
                 std::shared_ptr<const HeightMap> shared, const std::string& source,
                 PyramidBuild build);
    void applyOf(const ReliefDesc& relief, const MethodSettings& method, const HeightMap* heights,
                 std::shared_ptr<const HeightMap> shared, const std::string& source,
                 PyramidBuild build);
    // The program for the configuration, compiled on first use (counted in rebuilds_);
    // throws and changes nothing on failure.
    ReliefShader& program(const ReliefShaderConfig& config);
    // The relief's height scale (apply's relief.heightScale), the box fitted to it.
    void setHeightScale(float scale);
    // `map` drawn from now on, with `base` and `interpolation`, what the method reads
    // prepared first (may throw: then nothing changed), the box fitted.
    void useMap(std::shared_ptr<ReliefMap> map, const BaseShape& base,
                Interpolation interpolation);
    // Whether the eye lies outside the proxy box (with a margin): then its front faces
    // are drawn, else its back faces.
    bool eyeOutsideBox(const glm::dvec3& eye) const;
    ReliefParameters parameters(const CameraFrame& camera, const ShadingOptions& shading,
                                const PictureTile& tile) const;
    void uploadBox();

    const GL& gl_;
    std::shared_ptr<ReliefPrograms> programs_;  // the context's, maybe shared
    std::shared_ptr<ReliefMap> map_;            // maybe shared; none yet
    std::optional<AlbedoTexture> albedo_;
    gl::Buffer parameterBuffer_;              // MicroreliefParameters
    gl::VertexArray boxArray_;
    gl::Buffer boxVertices_;
    gl::Buffer boxIndices_;
    glm::dvec3 boxMin_{0.0}, boxMax_{0.0};  // the proxy box drawn, object space
    std::uint64_t boxGeneration_ = 0;       // the map's generation() the box was fitted for
    float heightScale_ = 0.1f;
    MethodSettings method_;
    bool countFetches_ = false;
    bool glsl330_ = false;
    BaseShape base_;
    Interpolation interpolation_ = Interpolation::Bilinear;  // the surface it bounds
    ModelTransform model_;
    DepthConvention depth_;
    RebuildCounts rebuilds_;
    PagingSettings paging_{PagingSettings::Mode::Never};
    std::optional<ReliefDesc> applied_;  // the relief whose heights the pyramid is of (apply)
    // The coarse pass: its tile size (0: off), its program (compiled for coarseProgramKey_:
    // tile size, tiled map, GLSL 3.30), its texture (coarseCapacity_ texels allocated) and
    // framebuffer.
    int coarseTile_ = 0;
    bool coarseDrawn_ = false;
    gl::Program coarseProgram_;
    std::tuple<int, bool, bool> coarseProgramKey_{0, false, false};
    gl::Texture coarseTexture_;
    gl::Framebuffer coarseFramebuffer_;
    glm::ivec2 coarseCapacity_{0, 0}, coarseSize_{0, 0};
};

}  // namespace microrelief
