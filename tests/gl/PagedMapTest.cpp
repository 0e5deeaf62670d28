// Maps read through pages (gl/PagedPyramid.h, shaders/paged_map.glsl): the
// picture of a paged map is the picture of the same map in whole textures, bit for bit,
// whatever the page size, the levels paged and the memory budget (which only changes how
// many draws it takes); a map past GL_MAX_TEXTURE_SIZE agrees with the exact CPU reference.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "GlTestBackend.h"
#include "SweepCases.h"
#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/heightmap/PyramidPages.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/gl/PagedPyramid.h"
#include "microrelief/gl/ReliefRenderer.h"
#include "microrelief/io/PyramidFile.h"

using namespace microrelief;

namespace {

class PagedMap : public test::GlTest {
protected:
    // `job` of `map` in whole textures and through pages with `paging` (Mode::Always).
    static HeadlessResult renderWhole(const HeightMap& map, const RenderJob& job) {
        HeadlessRenderer renderer(test::glContext(), job.method);
        renderer.setHeights(job, map, "whole");
        return renderer.render(job);
    }
    static HeadlessResult renderPaged(const HeightMap& map, const RenderJob& job,
                                      PagingSettings paging) {
        paging.mode = PagingSettings::Mode::Always;
        HeadlessRenderer renderer(test::glContext(), job.method);
        renderer.setPaging(paging);
        renderer.setHeights(job, map, "paged");
        return renderer.render(job);
    }
    static void expectSamePicture(const HeadlessResult& paged, const HeadlessResult& whole,
                                  const std::string& what) {
        EXPECT_EQ(paged.frame.color, whole.frame.color) << what;
        EXPECT_EQ(paged.frame.position, whole.frame.position) << what;
        EXPECT_EQ(paged.frame.stats, whole.frame.stats) << what;
        EXPECT_EQ(paged.frame.shadow, whole.frame.shadow) << what;
    }
    static std::size_t hits(const RenderedFrame& frame) {
        std::size_t n = 0;
        for (std::size_t p = 3; p < frame.position.size(); p += 4) n += frame.position[p] > 0.5f;
        return n;
    }
};

std::shared_ptr<const PyramidPages> inMemory(const HeightMap& map) {
    return std::make_shared<PyramidInMemory>(std::make_shared<const HeightMap>(map), false, "test");
}

// Small pages and a small resident side, so that the samples and several window levels
// are paged; a budget that holds every page.
PagingSettings smallPages() {
    PagingSettings paging;
    paging.pageSide = 16;
    paging.residentSide = 16;
    return paging;
}

TEST_F(PagedMap, PagedPictureIsTheWholeTexturePictureBitForBit) {
    const HeightMap map = synth::cobbles(150, 110, 3);
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        for (const BaseKind base : {BaseKind::Plane, BaseKind::Cylinder}) {
            RenderJob job;
            job.base.kind = base;
            job.interpolation = interpolation;
            job.camera = test::orbitCamera(30.0, 25.0, 1.5, {0.0, 0.02, 0.0});
            job.width = 96;
            job.height = 72;
            job.shading.shadows = ShadowMode::Soft;
            const std::string what =
                std::string(baseName(job.base)) + ", " + interpolationName(interpolation);
            const HeadlessResult whole = renderWhole(map, job);
            const HeadlessResult paged = renderPaged(map, job, smallPages());
            expectSamePicture(paged, whole, what);
            EXPECT_GT(hits(whole.frame), 96u * 72 / 4) << what << ": the relief fills the picture";
            EXPECT_GT(paged.paging.draws, 1) << what << ": the first draw found no page resident";
            EXPECT_GT(paged.paging.pagesLoaded, 0u) << what;
            EXPECT_EQ(paged.paging.splits, 0) << what << ": the budget holds every page";
        }
    }
}

// A map the caller shares (a camera path's, the viewer's) is kept by the pages, not copied,
// through each way a program sets one; the picture is the same as from the map copied.
TEST_F(PagedMap, PagesKeepASharedMapRatherThanACopy) {
    const auto map = std::make_shared<const HeightMap>(synth::cobbles(150, 110, 3));
    RenderJob job;
    job.camera = test::orbitCamera(30.0, 25.0, 1.5, {0.0, 0.02, 0.0});
    job.width = 64;
    job.height = 48;
    PagingSettings paging = smallPages();
    paging.mode = PagingSettings::Mode::Always;
    const HeadlessResult copied = renderPaged(*map, job, smallPages());
    {
        HeadlessRenderer renderer(test::glContext(), job.method);
        renderer.setPaging(paging);
        renderer.setHeights(job, map, "shared");
        EXPECT_EQ(map.use_count(), 2) << "setHeights: the pages hold the caller's map";
        expectSamePicture(renderer.render(job), copied, "setHeights");
        EXPECT_THROW(renderer.setHeights(job, std::shared_ptr<const HeightMap>(), "none"), Error);
        EXPECT_THROW(
            renderHeadless(test::glContext(), std::shared_ptr<const HeightMap>(), "none", job),
            Error);
    }
    EXPECT_EQ(map.use_count(), 1) << "the renderer let it go";
    {
        ReliefRenderer renderer(gl(), shaderDirectory());
        renderer.setPaging(paging);
        renderer.apply(job, map, "shared");
        EXPECT_EQ(map.use_count(), 2) << "ReliefRenderer::apply";
        renderer.apply(job, job.method, map, "shared");
        EXPECT_EQ(map.use_count(), 2) << "ReliefRenderer::apply with a method";
        renderer.apply(job, map.get(), "copied");
        EXPECT_EQ(map.use_count(), 1) << "a map not shared is copied";
    }
}

// A view from above at an angle, `width` x `height` pixels.
RenderJob obliqueView(int width, int height) {
    RenderJob job;
    job.camera = test::orbitCamera(40.0, -30.0, 1.4, {0.0, 0.02, 0.0});
    job.width = width;
    job.height = height;
    return job;
}

TEST_F(PagedMap, TinyBudgetEvictsAndStillConvergesToTheSamePicture) {
    const HeightMap map = synth::cobbles(150, 110, 4);
    const RenderJob job = obliqueView(80, 60);
    const HeadlessResult whole = renderWhole(map, job);
    PagingSettings paging = smallPages();
    paging.memoryBytes = 12 * 16 * 16 * 4;  // 12 pages of the map's 100 or so
    const HeadlessResult paged = renderPaged(map, job, paging);
    expectSamePicture(paged, whole, "12 pages");
    EXPECT_GT(paged.paging.splits, 0) << "the picture's pages cannot all be resident at once";
    EXPECT_LE(paged.paging.pagesResident, 12);
    EXPECT_GT(paged.paging.pagesLoaded, 12u) << "pages were evicted and loaded again";
}

// A pyramid file (io/PyramidFile.h), built a band of rows at a time, draws the picture of
// the map in memory, bit for bit, under a budget of a few pages; a page corrupted on disk
// is refused when a draw wants it, naming the file, never drawn.
TEST_F(PagedMap, APyramidFileDrawsTheMapsPictureAndRefusesACorruptPage) {
    const HeightMap map = synth::cobbles(150, 110, 6);
    test::ScratchDir scratch;
    const std::filesystem::path file = scratch / "cobbles.mrpyr";
    MapRows rows;
    rows.width = map.width;
    rows.height = map.height;
    rows.read = [&](int y0, int y1, float* out) {
        std::copy(map.samples.begin() + static_cast<std::ptrdiff_t>(y0) * map.width,
                  map.samples.begin() + static_cast<std::ptrdiff_t>(y1) * map.width, out);
    };
    writePyramidFile(file, rows, false, "cobbles", "cobbles", 16);
    const RenderJob job = obliqueView(80, 60);
    PagingSettings paging = smallPages();
    paging.memoryBytes = 12 * 16 * 16 * 4;
    const auto drawFile = [&] {
        HeadlessRenderer renderer(test::glContext(), job.method);
        renderer.setPaging(paging);
        renderer.setPyramidPages(PyramidFile::open(file), file.string());
        return renderer.render(job);
    };
    const HeadlessResult fromFile = drawFile();
    expectSamePicture(fromFile, renderWhole(map, job), "from the file");
    EXPECT_GT(fromFile.paging.splits, 0) << "12 pages cannot hold the picture's at once";
    EXPECT_GT(hits(fromFile.frame), 80u * 60 / 4);

    // Every page of the samples corrupted: the first draw wants one.
    std::vector<std::uint8_t> bytes = test::readBytes(file);
    const auto pages = PyramidFile::open(file)->pageCount();
    const std::size_t pageBytes = 16 * 16 * 4, dataOffset = bytes.size() - pages * pageBytes;
    for (std::size_t page = 0; page < 10 * 7; ++page)
        bytes[dataOffset + page * pageBytes + 7] ^= 0x10;
    test::writeBytes(file, bytes);
    try {
        (void)drawFile();
        FAIL() << "a corrupt page was drawn";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find(file.string() + ": page "), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("is corrupt"), std::string::npos) << e.what();
    }
}

// The error names the budget as the host calls it (PagingSettings::budgetName): the command
// line's flag by default, a host's own name where it gives one.
TEST_F(PagedMap, BudgetBelowWhatOneRayNeedsIsRefused) {
    const HeightMap map = synth::cobbles(150, 110, 4);
    const RenderJob job = obliqueView(16, 12);
    PagingSettings paging = smallPages();
    paging.memoryBytes = 16 * 16 * 4;  // one page
    for (const std::string name : {"", "memoryBudgetMiB"}) {
        if (!name.empty()) paging.budgetName = name;
        const std::string said =
            "raise the memory budget (" + (name.empty() ? "--memory" : name) + ")";
        try {
            (void)renderPaged(map, job, paging);
            FAIL() << "a one-page budget drew a picture";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            EXPECT_NE(std::string(e.what()).find(said), std::string::npos) << e.what();
            if (!name.empty()) {
                EXPECT_EQ(std::string(e.what()).find("--memory"), std::string::npos) << e.what();
            }
        }
    }
    // Less than a page: refused at once, naming the budget as the host calls it.
    paging.memoryBytes = 100;
    try {
        (void)renderPaged(map, job, paging);
        FAIL() << "a budget of less than a page drew a picture";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("a memory budget of 100 bytes holds no page"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("(memoryBudgetMiB)"), std::string::npos) << e.what();
    }
}

// The pool is one texture array: a budget of more pages than the GL has layers grows the
// pages (here 16^2 to 32^2) rather than leaving the budget unused (it was capped at 2048
// layers: 512 MiB of 256^2 pages, whatever --memory said), and the picture is the same.
TEST_F(PagedMap, ABudgetPastTheGlsLayersGrowsThePages) {
    GLint maxLayers = 0;
    gl().GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    ASSERT_GE(maxLayers, 256);  // GL 4.3's minimum is 2048
    // At 32^2 more pages than layers: the samples alone have (W / 32) x (H / 32).
    const int side = 32 * static_cast<int>(std::ceil(std::sqrt(maxLayers + 64.0)));
    const HeightMap map = synth::cobbles(side, side, 5);
    PagingSettings settings = smallPages();
    settings.memoryBytes = std::size_t{4} * maxLayers * (16 * 16 * 4);  // 4 x the layers at 16^2
    const PagedPyramid pager(gl(), inMemory(map), settings, "map");
    EXPECT_EQ(pager.pageSide(), 32);
    EXPECT_EQ(pager.capacity(), maxLayers) << "the whole budget: maxLayers pages of 32^2";
    EXPECT_EQ(gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));

    const RenderJob job = obliqueView(48, 36);
    expectSamePicture(renderPaged(map, job, settings), renderWhole(map, job), "pages grown");

    // A map whose pages all fit the layers keeps the side asked, whatever the budget: the
    // other tests' 16^2 pages under the default 512 MiB.
    const HeightMap small = synth::cobbles(150, 110, 5);
    const PagedPyramid kept(gl(), inMemory(small), smallPages(), "small");
    EXPECT_EQ(kept.pageSide(), 16);
}

// A GL error that a caller left pending is said as theirs, not taken for the pool's
// allocation failing (gl::refuseEarlierError, as HeadlessRenderer::render says it).
TEST_F(PagedMap, AnEarlierGlErrorIsNotThePools) {
    const HeightMap small = synth::cobbles(40, 30, 4);
    gl().Enable(0x7fff);  // no capability: GL_INVALID_ENUM, left pending
    try {
        const PagedPyramid pager(gl(), inMemory(small), smallPages(), "small");
        ADD_FAILURE() << "a page pool allocated over a pending GL error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Runtime);
        EXPECT_EQ(std::string(e.what()),
                  "GL error 0x0500 left by an earlier call on this context, before allocating "
                  "the page pool for small");
    }
    EXPECT_EQ(gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(PagedMap, OnlyTheMultilevelMethodReadsPages) {
    const HeightMap map = synth::cobbles(40, 30, 4);
    RenderJob job;
    job.width = job.height = 8;
    job.method.method = Method::MaxMip;
    PagingSettings paging = smallPages();
    paging.mode = PagingSettings::Mode::Always;
    HeadlessRenderer renderer(test::glContext(), job.method);
    renderer.setPaging(paging);
    try {
        renderer.setHeights(job, map, "small.png");
        FAIL() << "maxmip took a paged map";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("small.png"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("maxmip"), std::string::npos) << e.what();
    }
}

// ReliefRenderer alone draws once: a map past the texture limit is refused there, as
// before paging, and paged only where asked for (HeadlessRenderer draws until exact).
TEST_F(PagedMap, ASingleDrawRendererRefusesAMapPastTheTextureLimit) {
    GLint maxSize = 0;
    gl().GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const HeightMap wide(maxSize + 1, 2, 0.5f);
    ReliefRenderer renderer(gl(), shaderDirectory());
    try {
        renderer.apply(ReliefDesc{}, &wide, "wide.png");
        FAIL() << "a single-draw renderer paged the map";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("GL_MAX_TEXTURE_SIZE"), std::string::npos) << e.what();
    }
    EXPECT_EQ(renderer.pager(), nullptr);
    renderer.setPaging(PagingSettings{});  // Auto
    renderer.apply(ReliefDesc{}, &wide, "wide.png");
    EXPECT_NE(renderer.pager(), nullptr);
}

// The map is wider than any texture the GL makes (llvmpipe's and most GPUs' limit is
// 16384), and larger than the budget several times over: 20000 x 1500 samples, 120 MB of
// floats, through 16 MiB of pages. Rough everywhere (a sum of sines with no period in the
// map), seen along its length at a low angle, so that rays run far across it.
TEST_F(PagedMap, MapPastTheTextureLimitMatchesTheReference) {
    GLint maxSize = 0;
    gl().GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int width = 20000, height = 1500;
    if (width <= maxSize) GTEST_SKIP() << "GL_MAX_TEXTURE_SIZE " << maxSize << " holds the map";
    HeightMap map(width, height);
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            const double x = i, y = j;
            map.samples[static_cast<std::size_t>(j) * width + i] = static_cast<float>(
                0.5 + 0.2 * std::sin(x * 0.0031 + 0.7 * std::sin(y * 0.0023)) +
                0.15 * std::sin(y * 0.013 - x * 0.004) + 0.1 * std::sin((x + 2.3 * y) * 0.11) +
                0.05 * std::sin(x * 0.9) * std::cos(y * 0.7));
        }
    }
    RenderJob job;
    job.camera = test::orbitCamera(14.0, 4.0, 0.12, {0.3, 0.0, 0.0});
    job.width = 64;
    job.height = 48;
    job.heightScale = 0.02f;
    PagingSettings paging;  // Auto: the size pages it
    paging.memoryBytes = std::size_t{16} << 20;
    HeadlessRenderer renderer(test::glContext(), job.method);
    renderer.setPaging(paging);
    renderer.setHeights(job, map, "20000x1500");
    const HeadlessResult r = renderer.render(job);
    const test::Accuracy a = test::compareWithReference(r.frame, r.camera, map, job.heightScale);
    std::printf("    %s; %d draws, %zu pages loaded, %d resident, %d splits\n", a.summary().c_str(),
                r.paging.draws, r.paging.pagesLoaded, r.paging.pagesResident, r.paging.splits);
    EXPECT_GT(r.paging.pagesLoaded, 0u) << "the map was paged";
    EXPECT_LE(static_cast<std::size_t>(r.paging.pagesResident) * 256 * 256 * 4, paging.memoryBytes);
    EXPECT_GT(hits(r.frame), 64u * 48 / 2) << "the terrain fills the picture";
    EXPECT_LE(a.coverageMismatchPercent(), test::kMaxCoverageMismatchPercent) << a.summary();
    EXPECT_LE(a.offHalfTexelPercent(), test::kMaxOffHalfTexelPercent) << a.summary();
    EXPECT_EQ(a.exhausted, 0u) << a.summary();
}

// A frame at the level of detail (method.pixelError 1) wants no more pages of the samples
// than its pixels can tell apart: a hit the level of detail stands in for takes its normal
// from the window level the walk stopped at (mr_lodSlope), not from the samples under it.
// The cobbles of 1024^2 at obliqueView in 64 x 64 (about 10 texels a pixel at the centre):
// 15 of the 256 sample pages wanted, by the pixels near the eye that walk to the leaves.
// Drawn under a budget below what the frame wants, its picture is still the whole
// textures', bit for bit. Seen red with the normal read from the samples (mr_setTopHitAt,
// as before): 239 of the 256 sample pages wanted, as many as the exact frame.
TEST_F(PagedMap, ALevelOfDetailFrameWantsNoPageFinerThanItsPixels) {
    const HeightMap map = synth::cobbles(1024, 1024, 7);
    RenderJob job = obliqueView(64, 64);
    job.method.pixelError = 1.0f;
    PagingSettings paging = smallPages();
    paging.mode = PagingSettings::Mode::Always;
    ReliefRenderer renderer(gl(), shaderDirectory());
    renderer.setPaging(paging);
    renderer.apply(job, job.method, &map, "cobbles");
    OffscreenTarget target(gl(), job.width, job.height);
    const CameraFrame camera = renderer.resolveCamera(job.camera, job.width, job.height);
    PagedPyramid& pager = *renderer.pager();
    // The pages lie in order by page level (0 the samples, 1 + k window level k), each
    // level's pages across its size (the samples' that of window level 0).
    const int side = pager.pageSide();
    const std::vector<glm::ivec2> sizes = windowLevelSizes(map.width, map.height);
    std::vector<int> firstOf{0};
    for (int level = 0; level <= pager.pagedLevels(); ++level) {
        const glm::ivec2 across = (sizes[std::max(level - 1, 0)] + side - 1) / side;
        firstOf.push_back(firstOf.back() + across.x * across.y);
    }
    ASSERT_EQ(firstOf.back(), pager.pageCount());
    const int samplePages = firstOf[1];
    int wantedSamples = 0;
    std::vector<int> kept;
    for (int draw = 0;; ++draw) {
        ASSERT_LT(draw, 10) << "the draws end once nothing is wanted";
        target.clear(glm::vec3(0.0f));
        renderer.draw(camera, ShadingOptions{});
        const std::vector<int> wanted = pager.takeWanted();
        if (wanted.empty()) break;
        for (int id : wanted) wantedSamples += id < samplePages;
        ASSERT_TRUE(pager.load(wanted, kept));
        kept.insert(kept.end(), wanted.begin(), wanted.end());
    }
    EXPECT_LE(wantedSamples, samplePages / 8)
        << "of " << samplePages << " sample pages, " << kept.size() << " pages in all";

    PagingSettings tight = smallPages();
    tight.memoryBytes = 128 * 16 * 16 * 4;  // 128 pages of 16^2: fewer than the frame wants
    const HeadlessResult paged = renderPaged(map, job, tight);
    expectSamePicture(paged, renderWhole(map, job), "1 px level of detail");
    EXPECT_GT(hits(paged.frame), 64u * 64 / 2) << "the relief fills the picture";
}

// Pages a view reads stay resident from frame to frame (least recently used go first,
// paged_map.glsl marking every page a draw reads): under a budget that holds what the
// frame reads but not every page its first draws wanted (finer pages under the coarse
// stand-ins, which the exact frame does not read), the first frame evicts, and the frames
// after it load nothing: one draw each, the whole textures' picture. The cobbles of 512^2
// in 32 x 32 at obliqueView, pages of 16^2 (2388): the frame reads 948 pages, its draws
// want 1062; the budget is 1/16 over the 948. Seen red with eviction by when a page was
// last wanted or loaded (the resident pages a draw read were never marked, so those loaded
// first, the coarse ones every ray reads, went first): 385 pages loaded by the second
// frame, in 27 draws (and at a budget of 950, 1011 pages every frame).
TEST_F(PagedMap, FramesOfAViewWhosePagesFitLoadNothingAfterTheFirst) {
    const HeightMap map = synth::cobbles(512, 512, 7);
    const RenderJob job = obliqueView(32, 32);
    PagingSettings paging = smallPages();
    paging.mode = PagingSettings::Mode::Always;
    // What the exact frame reads: a draw after the one that wanted nothing reads the same.
    // 2000 pages of 16^2, more than its draws want (the map's 2388 would pass the GL's
    // layers, 2048 at least, and grow the pages).
    std::size_t frameReads = 0;
    {
        paging.memoryBytes = 2000 * 16 * 16 * 4;
        ReliefRenderer renderer(gl(), shaderDirectory());
        renderer.setPaging(paging);
        renderer.apply(job, job.method, &map, "cobbles");
        OffscreenTarget target(gl(), job.width, job.height);
        const CameraFrame camera = renderer.resolveCamera(job.camera, job.width, job.height);
        PagedPyramid& pager = *renderer.pager();
        ASSERT_EQ(pager.pageSide(), 16);
        std::vector<int> kept;
        for (int draw = 0;; ++draw) {
            ASSERT_LT(draw, 10) << "the draws end once nothing is wanted";
            target.clear(glm::vec3(0.0f));
            renderer.draw(camera, ShadingOptions{});
            const std::vector<int> wanted = pager.takeWanted();
            if (wanted.empty()) break;
            ASSERT_TRUE(pager.load(wanted, kept));
            kept.insert(kept.end(), wanted.begin(), wanted.end());
        }
        frameReads = pager.readByLastDraws().size();
        EXPECT_GT(kept.size(), frameReads + frameReads / 16)
            << "the draws want more pages than the frame reads, past the budget below";
        EXPECT_LT(frameReads + frameReads / 16, static_cast<std::size_t>(pager.pageCount()));
    }
    paging.memoryBytes = (frameReads + frameReads / 16) * 16 * 16 * 4;
    const HeadlessResult whole = renderWhole(map, job);
    HeadlessRenderer renderer(test::glContext(), job.method);
    renderer.setPaging(paging);
    renderer.setHeights(job, map, "paged");
    const HeadlessResult first = renderer.render(job);
    expectSamePicture(first, whole, "the first frame");
    EXPECT_GT(first.paging.pagesLoaded, frameReads + frameReads / 16) << "the first frame evicts";
    for (int frame = 2; frame <= 3; ++frame) {
        const HeadlessResult next = renderer.render(job);
        const std::string what = "frame " + std::to_string(frame) + " of " +
                                 std::to_string(frameReads) + " pages read, a budget of " +
                                 std::to_string(frameReads + frameReads / 16);
        expectSamePicture(next, whole, what);
        EXPECT_EQ(next.paging.pagesLoaded, 0u) << what;
        EXPECT_EQ(next.paging.draws, 1) << what;
    }
}

// A view whose pages do not fit the pool: its tile is drawn in quarters, every frame. Drawn
// in one order every frame, least recently used eviction met its worst case (each quarter
// evicted what the next one needed: 380 pages a frame after the first, 64 x 64 pixels reading
// 1239 pages under a budget of 1100); HeadlessRenderer draws them the other way round every
// other frame, and a frame begins with the pages the last one ended with. The pictures are
// the whole textures' still.
TEST_F(PagedMap, FramesPastTheBudgetDrawTheirQuartersTheOtherWayRound) {
    const HeightMap map = synth::cobbles(512, 512, 7);
    const RenderJob job = obliqueView(64, 64);
    PagingSettings paging = smallPages();
    paging.mode = PagingSettings::Mode::Always;
    paging.memoryBytes = 1100 * 16 * 16 * 4;
    const HeadlessResult whole = renderWhole(map, job);
    HeadlessRenderer renderer(test::glContext(), job.method);
    renderer.setPaging(paging);
    renderer.setHeights(job, map, "paged");
    std::size_t later = 0;
    for (int frame = 1; frame <= 5; ++frame) {
        const HeadlessResult next = renderer.render(job);
        const std::string what = "frame " + std::to_string(frame);
        expectSamePicture(next, whole, what);
        EXPECT_GT(next.paging.splits, 0) << what << ": the view does not fit";
        if (frame > 1) later += next.paging.pagesLoaded;
        std::printf("[ paged   ] 64 x 64 under 1100 pages, %s: %zu pages loaded, %d draws\n",
                    what.c_str(), next.paging.pagesLoaded, next.paging.draws);
    }
    EXPECT_LT(later / 4, 250u) << "pages loaded a frame after the first";
}

}  // namespace
