#include "microrelief/gl/HeadlessRender.h"

#include <algorithm>
#include <array>
#include <functional>

#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/core/scene/FloatLimits.h"

namespace microrelief {

HeadlessRenderer::HeadlessRenderer(GlContext& context, const MethodSettings& method)
    : context_(context) {
    context_.makeCurrent();
    renderer_.emplace(context_.gl(), shaderDirectory(), method);
    renderer_->setPaging(PagingSettings{});  // Auto: it draws a paged map until it is exact
}

void HeadlessRenderer::setPyramidPages(std::shared_ptr<const PyramidPages> pages,
                                       const std::string& source, const BaseShape& base,
                                       Interpolation interpolation) {
    if (!pages) throwRuntime("HeadlessRenderer::setPyramidPages: no pages");
    validateBaseShape(base);
    if (base.wrapsU() != pages->wrapsU()) {
        throwBadInput(source + ": its pyramid was built for " +
                      (pages->wrapsU() ? "a curved base" : "the plane") + ", not this base");
    }
    ReliefDesc relief;
    relief.base = base;
    relief.interpolation = interpolation;
    upload([&] {
        renderer_->apply(relief, ReliefMap::fromPages(renderer_->programs(), std::move(pages),
                                                      source, renderer_->paging()));
    });
    fromPages_ = true;  // of no relief's heights: any relief set with heights builds its own
}

void HeadlessRenderer::setHeights(const RenderJob& job, const HeightMap& map,
                                  const std::string& source) {
    // With the job's method: the last job's may not run on this relief's base or tiles.
    upload([&] { renderer_->apply(job, job.method, &map, source, kBuild); });
}

void HeadlessRenderer::setHeights(const RenderJob& job, std::shared_ptr<const HeightMap> map,
                                  const std::string& source) {
    if (!map) throwRuntime("HeadlessRenderer::setHeights: no map");
    // Shared: a map read through pages keeps this one rather than a copy.
    upload([&] { renderer_->apply(job, job.method, map, source, kBuild); });
}

void HeadlessRenderer::upload(const std::function<void()>& set) {
    context_.makeCurrent();
    set();
    fromPages_ = false;
    if (animated_) animated_->forgetMap();
}

std::size_t HeadlessRenderer::gpuBytes() const {
    return renderer_->textures() ? renderer_->textures()->gpuBytes(context_.gl()) : 0;
}

bool HeadlessRenderer::needsHeights(const ReliefDesc& relief) const {
    return fromPages_ || renderer_->needsHeights(relief);
}

void HeadlessRenderer::setAlbedo(const AlbedoImage* albedo, const std::string& source) {
    context_.makeCurrent();
    renderer_->setAlbedo(albedo, source);
}

HeadlessResult HeadlessRenderer::render(const RenderJob& job) {
    // The door: the scene as a whole (core/scene/Scene.h), once, before any GL work.
    throwIfInvalid(validateScene(job, job));
    if (job.onMesh) return renderMesh(job);  // src/gl/HeadlessMesh.cpp
    const ReliefMap* map = renderer_->map().get();
    if (!map) throwRuntime("HeadlessRenderer::render: no height map");
    {
        // Before any GL work: the float range and precision the shader needs.
        const CameraFrame frame = resolveCamera(job.camera, job.width, job.height, 1.0);
        checkFloatLimits({map->size().x, map->size().y, map->highestSample()}, job.heightScale,
                         job.base, job.model, job.camera, frame, map->source());
    }
    context_.makeCurrent();
    const GL& gl = context_.gl();
    gl::refuseEarlierError(gl, "rendering " + map->source());
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
    }
    if (!job.animation.empty()) {
        if (!animated_ || animated_->name() != job.animation)
            animated_ = std::make_unique<AnimatedHeights>(gl, shaderDirectory(), job.animation);
        animated_->evaluate(*renderer_, job.time);
    }
    // Against the map's highest sample as uploaded, or its pyramid's top once edited
    // (ReliefMap::highestSample: an animation's heights are written on the GPU).
    const CameraFrame camera = renderer_->resolveCamera(job.camera, job.width, job.height);

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

    HeadlessResult result{{}, camera, std::nullopt, {}};
    const std::size_t loadedBefore = renderer_->pager() ? renderer_->pager()->pagesLoaded() : 0;
    allocateFrame(result.frame, job, camera.eye);  // ReliefRenderer::draw traces relative to it
    quartersReversed_ = !quartersReversed_;  // drawTile's quarters, the other way this frame
    for (int y = 0; y < job.height; y += tile) {
        for (int x = 0; x < job.width; x += tile) {
            const PictureTile part{x, y, std::min(tile, job.width - x),
                                   std::min(tile, job.height - y)};
            drawTile(job, camera, part, result);
        }
    }
    if (!job.animation.empty()) result.animatedMap = renderer_->textures()->readSamples(gl);
    if (const PagedPyramid* pager = renderer_->pager()) {
        result.paging.pagesLoaded = pager->pagesLoaded() - loadedBefore;
        result.paging.pagesResident = pager->residentCount();
    }
    gl.Finish();
    const GLenum error = gl.GetError();
    if (error != GL_NO_ERROR)
        throwRuntime("GL error " + gl::enumHex(error) + " while rendering " + map->source());
    return result;
}

void HeadlessRenderer::allocateFrame(RenderedFrame& frame, const RenderJob& job,
                                     const glm::dvec3& positionOrigin) {
    try {
        const std::size_t count = static_cast<std::size_t>(job.width) * job.height * 4;
        frame.width = job.width;
        frame.height = job.height;
        frame.positionOrigin = positionOrigin;
        frame.color.resize(count);
        frame.position.resize(count);
        frame.stats.resize(count);
        frame.shadow.resize(count / 4);
    } catch (const std::bad_alloc&) {
        throwRuntime("not enough memory for a " + std::to_string(job.width) + "x" +
                     std::to_string(job.height) + " picture (" +
                     std::to_string(kFrameBytesPerPixel) + " bytes a pixel)");
    }
}

void HeadlessRenderer::drawTile(const RenderJob& job, const CameraFrame& camera,
                                const PictureTile& part, HeadlessResult& result) {
    PagedPyramid* pager = renderer_->pager();
    std::vector<int> kept;  // the pages this tile's draws have wanted: not evicted for it
    for (;;) {
        target_->clear(job.background);
        {
            const gl::SrgbWrites srgb(context_.gl());  // the relief's linear colour, encoded
            renderer_->draw(camera, job.shading, part);
        }
        if (!pager) break;
        // A paged map (gl/PagedPyramid.h): drawn again with what the draw wanted loaded,
        // until a draw wants nothing, which read every texel from its page: the picture
        // the whole map gives. Each draw either ends or loads a page it lacked, and keeps
        // what it loaded, so it ends, when the pool holds what the tile needs at once;
        // where it does not, the tile is drawn in quarters. The pages the draw read from
        // the pool are kept for its load too: evicting one would only make the next draw
        // want it again (tests/gl/PagedMapTest.cpp's 512^2 cobbles in 32 x 32 pixels,
        // reading 948 pages, under a budget of 940: without it, 110 draws and 973 pages
        // loaded a frame after the first; with it, 8 draws and 24 pages; the tile is
        // quartered at once rather than after a page or two a draw).
        ++result.paging.draws;
        const std::vector<int> wanted = pager->takeWanted();
        if (wanted.empty()) break;
        if (!pager->loadKeepingRead(wanted, kept)) {
            if (part.width == 1 && part.height == 1) {
                throwBadInput(renderer_->map()->source() +
                              ": one pixel's ray needs more pages than the memory "
                              "budget holds (" +
                              std::to_string(pager->capacity()) + " pages of " +
                              std::to_string(pager->pageSide()) +
                              "^2 texels): raise the memory budget (" +
                              renderer_->paging().budgetName + ")");
            }
            ++result.paging.splits;
            const int w0 = (part.width + 1) / 2, h0 = (part.height + 1) / 2;
            std::array<PictureTile, 4> quarters = {
                PictureTile{part.x, part.y, w0, h0},
                PictureTile{part.x + w0, part.y, part.width - w0, h0},
                PictureTile{part.x, part.y + h0, w0, part.height - h0},
                PictureTile{part.x + w0, part.y + h0, part.width - w0, part.height - h0}};
            // Every other frame in the opposite order: the same order every frame is least
            // recently used eviction's worst case, each quarter evicting what the next one
            // needs; reversed, a frame starts with the pages the last one ended with.
            if (quartersReversed_) std::reverse(quarters.begin(), quarters.end());
            for (const PictureTile& quarter : quarters) {
                if (quarter.width > 0 && quarter.height > 0) drawTile(job, camera, quarter, result);
            }
            return;
        }
        kept.insert(kept.end(), wanted.begin(), wanted.end());
    }
    target_->readInto(result.frame, part.x, part.y, part.width, part.height);
}

namespace {

// renderHeadless's work, `set` giving the renderer the map.
HeadlessResult renderMap(GlContext& context, const HeightMap& map, const std::string& source,
                         const RenderJob& job, const AlbedoImage* albedo,
                         const PagingSettings& paging,
                         const std::function<void(HeadlessRenderer&)>& set) {
    // Refused before the pyramid is built; render checks the scene again.
    throwIfInvalid(validateScene(job, job));
    checkFloatLimits({map.width * job.tiles.x, map.height * job.tiles.y, map.maxValue()},
                     job.heightScale, job.base, job.model, job.camera,
                     resolveCamera(job.camera, job.width, job.height, 1.0), source);
    // GL objects live in this scope and die before the context does.
    HeadlessRenderer renderer(context, job.method);
    renderer.setPaging(paging);
    set(renderer);
    if (albedo) renderer.setAlbedo(albedo, source + " (albedo)");
    return renderer.render(job);
}

}  // namespace

HeadlessResult renderHeadless(GlContext& context, const HeightMap& map, const std::string& source,
                              const RenderJob& job, const AlbedoImage* albedo,
                              const PagingSettings& paging) {
    return renderMap(context, map, source, job, albedo, paging,
                     [&](HeadlessRenderer& renderer) { renderer.setHeights(job, map, source); });
}

HeadlessResult renderHeadless(GlContext& context, std::shared_ptr<const HeightMap> map,
                              const std::string& source, const RenderJob& job,
                              const AlbedoImage* albedo, const PagingSettings& paging) {
    if (!map) throwRuntime("renderHeadless: no map");
    return renderMap(context, *map, source, job, albedo, paging,
                     [&](HeadlessRenderer& renderer) { renderer.setHeights(job, map, source); });
}

}  // namespace microrelief
