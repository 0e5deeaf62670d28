#include "microrelief/gl/ReliefRenderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "microrelief/core/Error.h"
#include "microrelief/gl/ReliefMap.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/StateGuard.h"

namespace microrelief {

ReliefRenderer::ReliefRenderer(const GL& gl, const std::filesystem::path& shaderDir,
                               const MethodSettings& method)
    : ReliefRenderer(std::make_shared<ReliefPrograms>(gl, shaderDir), method) {}

ReliefRenderer::ReliefRenderer(std::shared_ptr<ReliefPrograms> programs,
                               const MethodSettings& method)
    : gl_(programs->gl()), programs_(std::move(programs)), method_(method) {
    program(configFor(method_, countFetches_, base_.kind, interpolation_, true, ShadowMode::Off,
                      false, tiled(), paged()));
    parameterBuffer_ = gl::Buffer::create(gl_);
    boxArray_ = gl::VertexArray::create(gl_);
    boxVertices_ = gl::Buffer::create(gl_);
    boxIndices_ = gl::Buffer::create(gl_);
}

namespace {
// What a paged map's draw binds beyond StateGuard's (gl/PagedPyramid.h): the pool on its
// unit, the page table and the wants on their storage bindings; restored after.
class PagedBindings {
public:
    PagedBindings(const GL& gl, const PagedPyramid& paged) : gl_(gl) {
        gl.GetIntegerv(GL_ACTIVE_TEXTURE, &active_);
        gl.ActiveTexture(GL_TEXTURE0 + ReliefShader::kPagePoolUnit);
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &pool_);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, paged.pool());
        gl.ActiveTexture(static_cast<GLenum>(active_));
        gl.GetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, ReliefShader::kPageTableBinding,
                         &table_);
        gl.GetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, ReliefShader::kPageWantsBinding,
                         &wants_);
        gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &generic_);
        gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, ReliefShader::kPageTableBinding, paged.table());
        gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, ReliefShader::kPageWantsBinding, paged.wants());
    }
    ~PagedBindings() {
        gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, ReliefShader::kPageTableBinding,
                           static_cast<GLuint>(table_));
        gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, ReliefShader::kPageWantsBinding,
                           static_cast<GLuint>(wants_));
        gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(generic_));
        gl_.GetIntegerv(GL_ACTIVE_TEXTURE, &active_);
        gl_.ActiveTexture(GL_TEXTURE0 + ReliefShader::kPagePoolUnit);
        gl_.BindTexture(GL_TEXTURE_2D_ARRAY, static_cast<GLuint>(pool_));
        gl_.ActiveTexture(static_cast<GLenum>(active_));
    }
    PagedBindings(const PagedBindings&) = delete;
    PagedBindings& operator=(const PagedBindings&) = delete;

private:
    const GL& gl_;
    GLint active_ = GL_TEXTURE0, pool_ = 0, table_ = 0, wants_ = 0, generic_ = 0;
};

// A map read through pages is the multilevel method's alone, and is not tiled.
void checkPagedMap(Method method, glm::ivec2 tiles, const std::string& source) {
    if (method != Method::Multilevel) {
        throwBadInput(source +
                      ": read through pages (larger than the GL's textures, or "
                      "paging asked for), which only the multilevel method reads, not " +
                      std::string(methodName(method)));
    }
    if (tiles != glm::ivec2(1, 1))
        throwBadInput(source + ": a map read through pages is not tiled");
}

}  // namespace

ReliefShaderConfig ReliefRenderer::configFor(const MethodSettings& settings, bool countFetches,
                                             BaseKind base, Interpolation interpolation,
                                             bool frontFaces, ShadowMode shadows, bool albedoMap,
                                             bool tiled, bool paged) const {
    // A front face lies on the ray before its hit, a back face after it: the depth written
    // is at least the face's (front) or at most (back) under a standard depth test, the
    // other way round under reversed-Z.
    const bool greater = frontFaces != depth_.reversed;
    // Shadows are the exact methods' (a second trace through the multilevel tracer).
    if (!methodTracesTheSolid(settings.method)) shadows = ShadowMode::Off;
    return {settings.method,
            base,
            interpolation,
            countFetches,
            greater ? DepthLayout::Greater : DepthLayout::Less,
            shadows,
            albedoMap,
            tiled,
            paged,
            glsl330_ && !paged};
}

void ReliefRenderer::reloadShaders() {
    const ReliefShaderConfig config = configFor(method_, countFetches_, base_.kind, interpolation_,
                                                true, ShadowMode::Off, false, tiled(), paged());
    programs_->reload(config);  // throws before anything changes
    ++rebuilds_.programs;
}

ReliefShader& ReliefRenderer::program(const ReliefShaderConfig& config) {
    bool compiled = false;
    ReliefShader& shader = programs_->program(config, &compiled);  // one lookup a draw
    if (compiled) ++rebuilds_.programs;
    return shader;
}

void ReliefRenderer::setGlsl330(bool on) {
    const bool before = glsl330_;
    glsl330_ = on;
    try {
        setMethod(method_, countFetches_);  // compiles it now: a failure throws here
    } catch (...) {
        glsl330_ = before;
        throw;
    }
}

void ReliefRenderer::setMethod(const MethodSettings& settings, bool countFetches) {
    if (paged()) checkPagedMap(settings.method, tiles(), "the map");
    checkMethodSupportsBase(settings.method, base_);
    checkMethodSupportsTiles(settings.method, tiles());
    program(configFor(settings, countFetches, base_.kind, interpolation_, true, ShadowMode::Off,
                      false, tiled(), paged()));  // may throw
    // The aligned pyramid and the cone maps are made only for the peers that read them.
    if (map_) map_->prepareFor(settings.method);
    method_ = settings;
    countFetches_ = countFetches;
}

bool ReliefRenderer::needsHeights(const ReliefDesc& relief) const {
    return !applied_ || !map_ || !samePyramid(*applied_, relief);
}

void ReliefRenderer::apply(const ReliefDesc& relief, const HeightMap* heights,
                           const std::string& source, PyramidBuild build) {
    applyOf(relief, heights, nullptr, source, build);
}

void ReliefRenderer::apply(const ReliefDesc& relief, std::shared_ptr<const HeightMap> heights,
                           const std::string& source, PyramidBuild build) {
    const HeightMap* map = heights.get();
    applyOf(relief, map, std::move(heights), source, build);
}

void ReliefRenderer::applyOf(const ReliefDesc& relief, const HeightMap* heights,
                             std::shared_ptr<const HeightMap> shared, const std::string& source,
                             PyramidBuild build) {
    if (heights) {
        setHeightMapOf(*heights, std::move(shared), source, relief.base, relief.interpolation,
                       build, relief.tiles);
        applied_ = relief;
    } else {
        if (!map_) throwRuntime("ReliefRenderer::apply: no heights yet");
        if (relief.tiles != tiles())
            throwRuntime("ReliefRenderer::apply: the map was set for other tiles");
        if (relief.base.wrapsU() != map_->wrapsU()) {
            throwRuntime(
                "ReliefRenderer::apply: between the plane and a curved base the map must be "
                "uploaded again (apply with its heights)");
        }
        validateBaseShape(relief.base);
        checkMethodSupportsBase(method_.method, relief.base);
        // The program of the base and last level together, so that nothing has changed
        // when it throws, and no program of one without the other is compiled.
        program(configFor(method_, countFetches_, relief.base.kind, relief.interpolation, true,
                          ShadowMode::Off, false, tiled(), paged()));
        base_ = relief.base;
        interpolation_ = relief.interpolation;
        if (applied_ && samePyramid(*applied_, relief)) applied_ = relief;
    }
    setHeightScale(relief.heightScale);  // the box, fitted to the base and the scale
    model_ = relief.model;
}

void ReliefRenderer::apply(const ReliefDesc& relief, const MethodSettings& method,
                           const HeightMap* heights, const std::string& source,
                           PyramidBuild build) {
    applyOf(relief, method, heights, nullptr, source, build);
}

void ReliefRenderer::apply(const ReliefDesc& relief, const MethodSettings& method,
                           std::shared_ptr<const HeightMap> heights, const std::string& source,
                           PyramidBuild build) {
    const HeightMap* map = heights.get();
    applyOf(relief, method, map, std::move(heights), source, build);
}

void ReliefRenderer::applyOf(const ReliefDesc& relief, const MethodSettings& method,
                             const HeightMap* heights, std::shared_ptr<const HeightMap> shared,
                             const std::string& source, PyramidBuild build) {
    checkMethodSupportsBase(method.method, relief.base);
    checkMethodSupportsTiles(method.method, relief.tiles);
    // The held method gives way to the new one where it cannot trace the relief: apply()
    // then compiles the new pair's program and, with heights, builds what the new method
    // reads; setMethod() adds what it reads to a pyramid kept.
    const MethodSettings held = method_;
    if (!methodRunsOnBase(held.method, relief.base) ||
        (relief.tiles != glm::ivec2(1, 1) && !methodTakesTiles(held.method)))
        method_ = method;
    try {
        applyOf(relief, heights, std::move(shared), source, build);
    } catch (...) {
        method_ = held;
        throw;
    }
    setMethod(method, countFetches_);
}

void ReliefRenderer::setHeightMapOf(const HeightMap& map, std::shared_ptr<const HeightMap> shared,
                                    const std::string& source, const BaseShape& base,
                                    Interpolation interpolation, PyramidBuild build,
                                    glm::ivec2 tiles) {
    validateBaseShape(base);
    checkMethodSupportsBase(method_.method, base);
    checkMethodSupportsTiles(method_.method, tiles);
    if (tiles.x < 1 || tiles.y < 1) throwBadInput("{tiles}: counts must be at least 1");
    // Both throw before anything changes: the program is compiled (or looked up) first,
    // the textures are made before the old ones go.
    const bool paging = readsThroughPages(gl_, map, paging_);
    if (paging) checkPagedMap(method_.method, tiles, source);
    program(configFor(method_, countFetches_, base.kind, interpolation, true, ShadowMode::Off,
                      false, tiles != glm::ivec2(1, 1), paging));
    const MapUploadSettings upload{.wrapU = base.wrapsU(),
                                   .tiles = tiles,
                                   .withMaxMip = methodHas(method_.method, MethodTrait::MaxPyramid),
                                   .build = build,
                                   .paging = paging_};
    useMap(ReliefMap::upload(programs_, map, std::move(shared), source, upload), base,
           interpolation);
    ++rebuilds_.pyramids;
    applied_.reset();  // of heights no relief named; apply() names them
}

void ReliefRenderer::apply(const ReliefDesc& relief, std::shared_ptr<ReliefMap> map) {
    if (!map) throwRuntime("ReliefRenderer::apply: no map");
    if (map->wrapsU() != relief.base.wrapsU()) {
        throwRuntime("ReliefRenderer::apply: " + map->source() + " was built for " +
                     (map->wrapsU() ? "a curved base" : "the plane") + ", not this relief's base");
    }
    if (map->tiles() != relief.tiles) {
        throwRuntime("ReliefRenderer::apply: " + map->source() +
                     " was built for other tiles than this relief's");
    }
    validateBaseShape(relief.base);
    checkMethodSupportsBase(method_.method, relief.base);
    checkMethodSupportsTiles(method_.method, relief.tiles);
    if (map->paged()) checkPagedMap(method_.method, relief.tiles, map->source());
    // Throw before anything changes: the program first, then what the method reads.
    program(configFor(method_, countFetches_, relief.base.kind, relief.interpolation, true,
                      ShadowMode::Off, false, relief.tiles != glm::ivec2(1, 1), map->paged()));
    map->prepareFor(method_.method);
    heightScale_ = relief.heightScale;
    useMap(std::move(map), relief.base, relief.interpolation);
    applied_ = relief;  // the caller built the map of the relief's heights
    model_ = relief.model;
}

void ReliefRenderer::useMap(std::shared_ptr<ReliefMap> map, const BaseShape& base,
                            Interpolation interpolation) {
    map->prepareFor(method_.method);
    map_ = std::move(map);
    base_ = base;
    interpolation_ = interpolation;
    uploadBox();
}

void ReliefRenderer::setAlbedo(const AlbedoImage* albedo, const std::string& source) {
    if (!albedo) {
        albedo_.reset();
        return;
    }
    albedo_.emplace(AlbedoTexture(gl_, *albedo, source));  // made before the old one goes
    ++rebuilds_.albedos;
}

void ReliefRenderer::heightsChanged(const std::vector<TexelRect>& changed) {
    if (!map_) return;
    map_->heightsChanged(changed);
    map_->prepareFor(method_.method);
    uploadBox();
}

void ReliefRenderer::heightsReplaced() {
    if (!map_) return;
    map_->heightsReplaced();
    map_->prepareFor(method_.method);
    ++rebuilds_.pyramids;
    uploadBox();
}

void ReliefRenderer::setHeightScale(float scale) {
    heightScale_ = scale;
    if (map_) uploadBox();
}

void ReliefRenderer::uploadBox() {
    // A small margin keeps every pixel whose ray meets the exact box inside the
    // rasterised proxy; the shader clips the ray to the exact shell itself.
    const ReliefMapShape shape = map_->textures().shape();
    const ReliefExtent extent =
        reliefExtent(shape.size.x, shape.size.y, shape.maxHeight, heightScale_, base_);
    boxGeneration_ = map_->generation();
    const glm::vec3 lo = glm::vec3(extent.min) - 1e-3f, hi = glm::vec3(extent.max) + 1e-3f;
    boxMin_ = lo;
    boxMax_ = hi;
    const std::array<float, 24> corners = {lo.x, lo.y, lo.z, hi.x, lo.y, lo.z, hi.x, lo.y,
                                           hi.z, lo.x, lo.y, hi.z, lo.x, hi.y, lo.z, hi.x,
                                           hi.y, lo.z, hi.x, hi.y, hi.z, lo.x, hi.y, hi.z};
    // Outward-facing counter-clockwise triangles, two per face.
    const std::array<GLushort, 36> indices = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                                              1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0};
    const gl::StateGuard saved(gl_);
    gl_.BindVertexArray(boxArray_.id());
    gl_.BindBuffer(GL_ARRAY_BUFFER, boxVertices_.id());
    gl_.BufferData(GL_ARRAY_BUFFER, sizeof(corners), corners.data(), GL_STATIC_DRAW);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, boxIndices_.id());
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof(indices), indices.data(), GL_STATIC_DRAW);
    gl_.EnableVertexAttribArray(0);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
}

bool ReliefRenderer::eyeOutsideBox(const glm::dvec3& eye) const {
    // Outside the drawn box grown by a margin: an eye just outside it may see its front
    // faces cut by the near plane (depth clamping keeps them), one inside must never get
    // front faces (none would cover the pixels around it). The margin is relative, far
    // above float rounding of the box and the model.
    const glm::dvec3 p = model_.pointToObject(eye);
    const glm::dvec3 margin = 1e-4 * (boxMax_ - boxMin_) + 1e-6;
    return glm::any(glm::lessThan(p, boxMin_ - margin)) ||
           glm::any(glm::greaterThan(p, boxMax_ + margin));
}

ReliefParameters ReliefRenderer::parameters(const CameraFrame& camera,
                                            const ShadingOptions& shading,
                                            const PictureTile& t) const {
    // A tile: the same clip space, scaled and shifted in x and y so that the tile fills
    // the viewport (rows z and w are untouched, so the depth is the whole picture's to
    // the bit); the shader adds the tile's origin to gl_FragCoord, so each pixel casts
    // the ray it casts in the whole picture.
    glm::dmat4 toTile(1.0);
    toTile[0][0] = static_cast<double>(camera.width) / t.width;
    toTile[1][1] = static_cast<double>(camera.height) / t.height;
    toTile[3][0] = static_cast<double>(camera.width - 2 * t.x - t.width) / t.width;
    toTile[3][1] = static_cast<double>(camera.height - 2 * t.y - t.height) / t.height;

    // Traced relative to the eye, as renderers of planets do: the shader's "world" is the
    // world moved by -eye, each transform that meets a world position composed with that
    // move here in double (the model's translation becomes the relief's offset from the
    // eye, the clip transform's the eye's own), so no float ever holds a coordinate of
    // the world's origin. The eye's point in the relief's frame is then the model's inverse
    // of the eye, rounded once (FloatLimits check 4 bounds it), however far from the
    // origin the two are: a relief at 9e5 is traced as one at 0. Hits come out relative
    // too (RenderedFrame::positionOrigin).
    const glm::dmat4 fromEye = glm::translate(glm::dmat4(1.0), camera.eye);
    const glm::dmat4 toEye = glm::translate(glm::dmat4(1.0), -camera.eye);
    ReliefParameters p;
    p.viewProjection = glm::mat4(toTile * camera.viewProjection * fromEye);
    p.objectToWorld = glm::mat4(toEye * model_.objectToWorld());
    p.worldToObject = glm::mat4(model_.worldToObject() * fromEye);
    p.eye = glm::vec3(0.0f);
    p.cameraRight = glm::vec3(camera.right);
    p.cameraUp = glm::vec3(camera.up);
    p.cameraForward = glm::vec3(camera.forward);
    p.pixelErrorTolerance = method_.pixelError;
    p.tMin = 0.0f;  // the rays' range: a picture's, the whole ray (MR_T_INFINITY)
    p.tMax = 3.4e38f;
    // The multilevel method reads the windows, maxmip its aligned quadtree: each its own
    // pyramid's size and levels.
    const ReliefTextures& textures = map_->textures();
    const ReliefMapShape shape = methodHas(method_.method, MethodTrait::MaxPyramid)
                                     ? textures.maxMipShape()
                                     : textures.shape();
    p.heightScale = heightScale_;
    p.reliefMaxHeight = shape.maxHeight;
    p.frameScale = glm::vec3(base_.frameScale());
    const ReliefExtent extent =
        reliefExtent(shape.size.x, shape.size.y, shape.maxHeight, heightScale_, base_);
    p.reliefBoxMin = glm::vec3(extent.min);
    p.reliefBoxMax = glm::vec3(extent.max);
    p.pyramidLevels = shape.levelCount;
    p.maxIterations = map_->traversalBudget();
    p.lightDirection = glm::normalize(shading.lightDirection);
    if (shading.lightPosition)
        p.lightPosition = glm::vec4(glm::vec3(*shading.lightPosition - camera.eye), 1.0f);
    p.albedoFinest = shading.albedoFinestLevel ? 1 : 0;
    p.reliefTiles = shape.tiles;
    p.lightTanRadius = static_cast<float>(
        std::tan(0.5 * glm::radians(static_cast<double>(shading.lightSizeDegrees))));
    p.debugView = static_cast<int>(shading.view);
    p.albedo = shading.albedo;
    p.methodSteps = method_.steps;
    p.methodMinSteps = method_.minSteps;
    p.methodRefineSteps = method_.refineSteps;
    p.reliefSize = glm::vec2(shape.size);
    p.pyramidSize = shape.pyramidSize;
    p.viewportSize = glm::vec2(camera.width, camera.height);
    p.tileOrigin = glm::vec2(t.x, t.y);
    p.depthZeroToOne = depth_.zeroToOne ? 1 : 0;
    return p;
}

void ReliefRenderer::draw(const CameraFrame& camera, const ShadingOptions& shading,
                          const PictureTile& tile) {
    if (!map_) throwRuntime("ReliefRenderer::draw: no map (apply a relief first)");
    // Another renderer drawing the map, or the host, may have edited it since this one
    // last looked: the box is fitted to its maximum now, and what the method reads is
    // built again where the edit dropped it.
    if (boxGeneration_ != map_->generation()) uploadBox();
    map_->prepareFor(method_.method);
    const PictureTile whole{0, 0, camera.width, camera.height};
    const PictureTile& t = tile.width > 0 ? tile : whole;
    // Front faces from outside the box, back faces from inside it: exactly one fragment
    // per pixel the box covers either way (it is convex), and the depth layout the
    // program promises holds for the faces drawn.
    const bool frontFaces = eyeOutsideBox(camera.eye);
    ReliefShaderConfig config =
        configFor(method_, countFetches_, base_.kind, interpolation_, frontFaces, shading.shadows,
                  albedo_.has_value(), tiled(), paged());
    const bool coarse = coarsePassApplies();
    if (coarse) config.coarseTile = coarseTile_;
    ReliefShader& shader = program(config);

    const gl::StateGuard saved(gl_);
    const ReliefParameters values = parameters(camera, shading, t);
    gl_.BindBuffer(GL_UNIFORM_BUFFER, parameterBuffer_.id());
    gl_.BufferData(GL_UNIFORM_BUFFER, sizeof values, &values, GL_STREAM_DRAW);
    coarseDrawn_ = false;
    // The coarse pass's unit is past StateGuard's: its binding is restored here.
    GLint activeUnit = 0, coarseUnitTexture = 0;
    if (coarse) {
        drawCoarsePass(values, t);
        gl_.GetIntegerv(GL_ACTIVE_TEXTURE, &activeUnit);
        gl_.ActiveTexture(GL_TEXTURE0 + ReliefShader::kCoarseStartUnit);
        gl_.GetIntegerv(GL_TEXTURE_BINDING_2D, &coarseUnitTexture);
        gl_.BindTexture(GL_TEXTURE_2D, coarseTexture_.id());
        gl_.ActiveTexture(static_cast<GLenum>(activeUnit));
        coarseDrawn_ = true;
    }
    shader.use();
    const ReliefTextures& textures = map_->textures();
    shader.bindParameters(parameterBuffer_.id())
        .bindMaxPyramid(textures.maxPyramid())
        .bindHeights(textures.samples())
        .bindWindowPyramid(textures.windowPyramid());
    if (albedo_) shader.bindAlbedo(albedo_->id());
    std::optional<PagedBindings> pagedBindings;
    if (const PagedPyramid* paged = textures.paged()) pagedBindings.emplace(gl_, *paged);
    if (methodHas(method_.method, MethodTrait::ConeMap))
        shader.bindConeMap(textures.coneMap(ReliefTextures::ConeKind::Conservative));
    if (methodHas(method_.method, MethodTrait::RelaxedConeMap))
        shader.bindConeMap(textures.coneMap(ReliefTextures::ConeKind::Relaxed));

    // Depth clamping keeps faces nearer than the near plane (an eye close to the box). A
    // model that mirrors (a negative determinant) turns the box's winding round.
    const bool mirrored = glm::determinant(glm::dmat3(model_.objectToWorld())) < 0.0;
    gl_.Enable(GL_CULL_FACE);
    gl_.FrontFace(GL_CCW);  // the box's outward faces wind counter-clockwise
    gl_.CullFace(frontFaces != mirrored ? GL_BACK : GL_FRONT);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(depth_.reversed ? GL_GREATER : GL_LESS);
    gl_.Enable(GL_DEPTH_CLAMP);
    gl_.Viewport(0, 0, t.width, t.height);
    gl_.BindVertexArray(boxArray_.id());
    gl_.DrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_SHORT, nullptr);
    if (coarse) {
        gl_.ActiveTexture(GL_TEXTURE0 + ReliefShader::kCoarseStartUnit);
        gl_.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(coarseUnitTexture));
        gl_.ActiveTexture(static_cast<GLenum>(activeUnit));
    }
}

void ReliefRenderer::setCoarsePass(int tileSize) {
    if (tileSize != 0 && (tileSize < 2 || tileSize > 64)) {
        throwBadInput("ReliefRenderer::setCoarsePass: a tile of " + std::to_string(tileSize) +
                      " pixels; 0 (off) or 2 to 64");
    }
    coarseTile_ = tileSize;
}

bool ReliefRenderer::coarsePassApplies() const {
    // The plane's frame is an affine image of the world (coarse_start.glsl's argument);
    // a paged map's reads are its pager's.
    return coarseTile_ > 0 && method_.method == Method::Multilevel &&
           base_.kind == BaseKind::Plane && !paged();
}

void ReliefRenderer::drawCoarsePass(const ReliefParameters& values, const PictureTile& t) {
    (void)values;  // in the parameter buffer already, which the pass reads as the draw does
    const std::tuple<int, bool, bool> key{coarseTile_, tiled(), glsl330_};
    if (!coarseProgram_ || coarseProgramKey_ != key) {
        GLint major = 0;
        gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
        const std::string version = major >= 4 && !glsl330_ ? "400 core" : "330 core";
        const std::vector<ShaderDefine> defines = {
            {"MICRORELIEF_BASE", std::to_string(static_cast<int>(BaseKind::Plane))},
            {"MICRORELIEF_TILING", tiled() ? "1" : "0"},
            {"MICRORELIEF_COARSE_TILE", std::to_string(coarseTile_)}};
        const std::filesystem::path& dir = programs_->shaderDir();
        const gl::Shader vertex = gl::compileShader(
            gl_, GL_VERTEX_SHADER, assembleShader(dir / "pyramid" / "pass.vert", version));
        const gl::Shader fragment = gl::compileShader(
            gl_, GL_FRAGMENT_SHADER, assembleShader(dir / "coarse_start.frag", version, defines));
        gl::Program linked = gl::linkProgram(gl_, vertex, fragment,
                                             "coarse pass (" + std::to_string(coarseTile_) + ")");
        GLint previous = 0;
        gl_.GetIntegerv(GL_CURRENT_PROGRAM, &previous);
        gl_.UseProgram(linked.id());
        gl_.Uniform1i(gl::uniform(gl_, linked, "windowPyramid"), ReliefShader::kWindowPyramidUnit);
        gl_.UseProgram(static_cast<GLuint>(previous));
        const GLuint block = gl_.GetUniformBlockIndex(linked.id(), "MicroreliefParameters");
        if (block == GL_INVALID_INDEX)
            throwRuntime("the coarse pass has no MicroreliefParameters block");
        gl_.UniformBlockBinding(linked.id(), block, ReliefShader::kParametersBinding);
        coarseProgram_ = std::move(linked);
        coarseProgramKey_ = key;
    }
    coarseSize_ = {(t.width + coarseTile_ - 1) / coarseTile_,
                   (t.height + coarseTile_ - 1) / coarseTile_};
    const gl::PassGuard pass(gl_);  // the caller's framebuffers and state back after the pass
    if (!coarseTexture_ || glm::any(glm::greaterThan(coarseSize_, coarseCapacity_))) {
        coarseCapacity_ = glm::max(coarseSize_, coarseCapacity_);
        coarseTexture_ = gl::Texture::create(gl_);
        gl_.ActiveTexture(GL_TEXTURE0);
        gl_.BindTexture(GL_TEXTURE_2D, coarseTexture_.id());
        gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, coarseCapacity_.x, coarseCapacity_.y, 0,
                       GL_RGBA, GL_FLOAT, nullptr);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        coarseFramebuffer_ = gl::Framebuffer::create(gl_);
        gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, coarseFramebuffer_.id());
        gl_.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                 coarseTexture_.id(), 0);
        if (gl_.CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throwRuntime("the coarse pass's framebuffer (RGBA32F) is not complete");
    }
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, coarseFramebuffer_.id());
    const GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl_.DrawBuffers(1, &buffer);
    gl_.Viewport(0, 0, coarseSize_.x, coarseSize_.y);
    gl_.UseProgram(coarseProgram_.id());
    gl_.BindBufferBase(GL_UNIFORM_BUFFER, ReliefShader::kParametersBinding, parameterBuffer_.id());
    gl_.ActiveTexture(GL_TEXTURE0 + ReliefShader::kWindowPyramidUnit);
    gl_.BindTexture(GL_TEXTURE_2D, map_->textures().windowPyramid());
    gl_.BindVertexArray(boxArray_.id());
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
}

CameraFrame ReliefRenderer::resolveCamera(const Camera& camera, int width, int height) const {
    if (!map_) throwRuntime("ReliefRenderer::resolveCamera: no map");
    const glm::ivec2 size = map_->size();
    const ReliefExtent extent =
        reliefExtent(size.x, size.y, map_->highestSample(), heightScale_, base_);
    return microrelief::resolveCamera(camera, width, height,
                                      sceneRadius(extent, model_.objectToWorld()),
                                      sceneCentre(model_.objectToWorld()));
}

CameraFrame ReliefRenderer::draw(const ViewDesc& view, const PictureTile& tile) {
    // The view checked at this door as HeadlessRenderer checks a scene at its own: its values,
    // then with the relief applied (the method on its base and tiles, shadows on a method
    // that traces the solid), before anything is drawn or set.
    std::vector<FieldError> errors = view.validate();
    ReliefDesc applied;
    applied.base = base_;
    applied.tiles = tiles();
    for (FieldError& e : validateTogether(applied, view)) errors.push_back(std::move(e));
    throwIfInvalid(errors);
    setMethod(view.method, countFetches_);  // a program compiled once, then looked up
    const CameraFrame camera = resolveCamera(view.camera, view.width, view.height);
    draw(camera, view.shading, tile);
    return camera;
}

}  // namespace microrelief
