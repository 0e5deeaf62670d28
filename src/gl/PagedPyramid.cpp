#include "microrelief/gl/PagedPyramid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <tuple>
#include <utility>

#include "microrelief/core/Error.h"
#include "microrelief/gl/ReliefTextures.h"
#include "microrelief/gl/StateGuard.h"

namespace microrelief {

namespace {

// The bindings the pager's uploads change beyond StateGuard's: unit 0's texture array and
// the copy-write buffer, restored after.
class PagerBindings {
public:
    explicit PagerBindings(const GL& gl) : gl_(gl), state_(gl) {
        gl.GetIntegerv(GL_COPY_WRITE_BUFFER, &copyWrite_);  // its binding (GL 3.1 names it so)
        gl.ActiveTexture(GL_TEXTURE0);
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &array_);
    }
    ~PagerBindings() {
        gl_.ActiveTexture(GL_TEXTURE0);
        gl_.BindTexture(GL_TEXTURE_2D_ARRAY, static_cast<GLuint>(array_));
        gl_.BindBuffer(GL_COPY_WRITE_BUFFER, static_cast<GLuint>(copyWrite_));
    }
    PagerBindings(const PagerBindings&) = delete;
    PagerBindings& operator=(const PagerBindings&) = delete;

private:
    const GL& gl_;
    gl::StateGuard state_;
    GLint array_ = 0, copyWrite_ = 0;
};

bool hasGl43(const GL& gl) {
    GLint major = 0, minor = 0;
    gl.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl.GetIntegerv(GL_MINOR_VERSION, &minor);
    return major > 4 || (major == 4 && minor >= 3);
}

}  // namespace

PagedPyramid::PagedPyramid(const GL& gl, std::shared_ptr<const PyramidPages> pages,
                           const PagingSettings& settings, const std::string& source)
    : gl_(gl), source_(std::move(pages)) {
    if (!hasGl43(gl))
        throwRuntime(source + ": a map read through pages needs OpenGL 4.3 (shader storage)");
    const int requested = settings.pageSide;
    if (requested < 16 || requested > 4096 ||
        !std::has_single_bit(static_cast<unsigned>(requested)))
        throwBadInput("the page side " + std::to_string(requested) +
                      " is not a power of two from 16 to 4096");
    // The page levels: the samples, then the windows down to the first whose sides are at
    // most residentSide (L), which with the coarser ones lies whole in one texture.
    const std::vector<glm::ivec2> sizes =
        windowLevelSizes(source_->mapWidth(), source_->mapHeight());
    pagedLevels_ = 0;
    while (pagedLevels_ + 1 < static_cast<int>(sizes.size()) &&
           glm::any(glm::greaterThan(sizes[pagedLevels_], glm::ivec2(settings.residentSide))))
        ++pagedLevels_;
    if (2 + pagedLevels_ > PageTableLayout::kMaxPageLevels)
        throwBadInput(source + ": too many pyramid levels to page");
    // Pages of 2^shift a side the map has: level 0 (the samples) and window levels
    // 0 .. L - 1 have W x H, then the windows' sizes.
    const auto pageCount = [&](int shift) {
        std::size_t count = 0;
        for (int level = 0; level <= pagedLevels_; ++level) {
            const glm::ivec2 across = (sizes[std::max(level - 1, 0)] + (1 << shift) - 1) >> shift;
            count += static_cast<std::size_t>(across.x) * across.y;
        }
        return count;
    };

    // The pool is one texture array, a page a layer: where the budget would hold more of
    // the map's pages than the GL has layers (GL_MAX_ARRAY_TEXTURE_LAYERS, 2048 on llvmpipe
    // and current NVIDIA drivers: 512 MiB of 256^2 pages), the pages grow, so that the
    // budget is used; where all the map's pages fit the layers, they keep the side asked.
    shift_ = std::countr_zero(static_cast<unsigned>(requested));
    GLint maxLayers = 0;
    gl.GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    maxLayers = std::max(maxLayers, 1);
    while (shift_ < 12 && std::min(settings.memoryBytes / (std::size_t{4} << (2 * shift_)),
                                   pageCount(shift_)) > static_cast<std::size_t>(maxLayers))
        ++shift_;
    const int side = 1 << shift_;
    const std::size_t pageBytes = std::size_t{4} << (2 * shift_);
    if (settings.memoryBytes < pageBytes) {
        throwBadInput(source + ": a memory budget of " + std::to_string(settings.memoryBytes) +
                      " bytes holds no page of " + std::to_string(side) + " x " +
                      std::to_string(side) + " texels (" + std::to_string(pageBytes) +
                      " bytes): raise the memory budget (" + settings.budgetName + ")");
    }

    std::vector<std::uint32_t> words(PageTableLayout::kEntriesAt, 0u);
    words[PageTableLayout::kInfoAt] = static_cast<std::uint32_t>(pagedLevels_);
    words[PageTableLayout::kInfoAt + 1] = static_cast<std::uint32_t>(source_->scaleExponent());
    words[PageTableLayout::kInfoAt + 2] = static_cast<std::uint32_t>(shift_);
    words[PageTableLayout::kInfoAt + 3] = stamp_;  // the use buffer starts at 0: no stamp
    for (int level = 0; level <= pagedLevels_ + 1; ++level) {
        // Level 0 (the samples) has window level 0's size, W x H.
        const glm::ivec2 size = sizes[std::max(level - 1, 0)];
        const int at = PageTableLayout::kLevelsAt + 4 * level;
        words[at] = static_cast<std::uint32_t>(pages_.size());
        words[at + 1] = static_cast<std::uint32_t>(size.x);
        words[at + 2] = static_cast<std::uint32_t>(size.y);
        if (level > pagedLevels_) continue;  // level L's size only: it is not paged
        const glm::ivec2 across = (size + side - 1) >> shift_;
        for (int y = 0; y < across.y; ++y)
            for (int x = 0; x < across.x; ++x) pages_.push_back({level, glm::ivec2(x, y) * side});
    }
    words.resize(words.size() + pages_.size(), 0u);

    const std::size_t layers = std::min(
        {settings.memoryBytes / pageBytes, pages_.size(), static_cast<std::size_t>(maxLayers)});
    for (int layer = static_cast<int>(layers) - 1; layer >= 0; --layer)
        freeLayers_.push_back(layer);

    const PagerBindings saved(gl);
    gl::refuseEarlierError(gl, "allocating the page pool for " + source);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    pool_ = gl::Texture::create(gl);
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, pool_.id());
    gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, side, side, static_cast<GLsizei>(layers), 0,
                  GL_RED, GL_FLOAT, nullptr);
    // A GL may refuse one texture this large (llvmpipe's limit is 1 GiB a texture): said
    // here, where the budget can be named, not as a later draw's GL error.
    if (const GLenum error = gl.GetError(); error == GL_OUT_OF_MEMORY) {
        throwBadInput(source + ": the GL cannot allocate a page pool of " +
                      std::to_string((layers * pageBytes) >> 20) + " MiB (" +
                      std::to_string(layers) + " pages of " + std::to_string(side) + " x " +
                      std::to_string(side) + " texels): lower the memory budget (" +
                      settings.budgetName + ")");
    } else if (error != GL_NO_ERROR) {
        throwRuntime("GL error " + gl::enumHex(error) + " allocating the page pool for " + source);
    }
    for (GLenum name : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER})
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, name, GL_NEAREST);
    for (GLenum name : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T})
        gl.TexParameteri(GL_TEXTURE_2D_ARRAY, name, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);

    // The coarse levels L and on, as ReliefTextures holds the windows: halves of bound / 2^S.
    coarse_ = gl::Texture::create(gl);
    gl.BindTexture(GL_TEXTURE_2D, coarse_.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 2);
    const int coarseLevels = static_cast<int>(sizes.size()) - pagedLevels_;
    for (int k = 0; k < coarseLevels; ++k) {
        const glm::ivec2 size = sizes[pagedLevels_ + k];
        const std::vector<std::uint16_t> halves =
            storedHalves(source_->readLevel(1 + pagedLevels_ + k), source_->scaleExponent());
        gl.TexImage2D(GL_TEXTURE_2D, k, GL_R16F, size.x, size.y, 0, GL_RED, GL_HALF_FLOAT,
                      halves.data());
    }
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, coarseLevels - 1);

    table_ = gl::Buffer::create(gl);
    gl.BindBuffer(GL_COPY_WRITE_BUFFER, table_.id());
    gl.BufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(words.size() * 4), words.data(),
                  GL_DYNAMIC_DRAW);
    wants_ = gl::Buffer::create(gl);
    const std::vector<std::uint32_t> none(pages_.size(), 0u);
    gl.BindBuffer(GL_COPY_WRITE_BUFFER, wants_.id());
    gl.BufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(none.size() * 4), none.data(),
                  GL_DYNAMIC_READ);
}

std::size_t PagedPyramid::gpuBytes() const {
    return static_cast<std::size_t>(capacity()) * (std::size_t{4} << (2 * shift_)) +
           textureBytes(gl_, coarse_.id()) + (PageTableLayout::kEntriesAt + 2 * pages_.size()) * 4;
}

std::vector<int> PagedPyramid::takeWanted() {
    // The draws' writes to the use buffer reach the read below only after a barrier.
    gl_.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> words(pages_.size(), 0u);
    const PagerBindings saved(gl_);
    gl_.BindBuffer(GL_COPY_WRITE_BUFFER, wants_.id());
    gl_.GetBufferSubData(GL_COPY_WRITE_BUFFER, 0, static_cast<GLsizeiptr>(words.size() * 4),
                         words.data());
    // Only the words of this stamp are the draws since the last call's: older stamps stay
    // in the buffer (nothing clears it), and are never this one until the stamps wrap,
    // where the buffer is cleared.
    ++clock_;
    std::vector<int> wanted;
    read_.clear();
    for (std::size_t page = 0; page < words.size(); ++page) {
        if ((words[page] & kLastStamp) != stamp_) continue;
        (words[page] & kWantedBit ? wanted : read_).push_back(static_cast<int>(page));
        pages_[page].used = clock_;
    }
    if (stamp_ == kLastStamp) {
        std::fill(words.begin(), words.end(), 0u);
        gl_.BufferSubData(GL_COPY_WRITE_BUFFER, 0, static_cast<GLsizeiptr>(words.size() * 4),
                          words.data());
        stamp_ = 0;
    }
    ++stamp_;
    gl_.BindBuffer(GL_COPY_WRITE_BUFFER, table_.id());
    gl_.BufferSubData(GL_COPY_WRITE_BUFFER, (PageTableLayout::kInfoAt + 3) * 4, 4, &stamp_);
    return wanted;
}

bool PagedPyramid::load(const std::vector<int>& pages, const std::vector<int>& keep) {
    const PagerBindings saved(gl_);
    std::vector<char> kept(pages_.size(), 0);
    for (int page : keep) kept[page] = 1;
    for (int page : pages) kept[page] = 1;
    std::vector<int> absent;
    for (int page : pages)
        if (pages_[page].layer < 0) absent.push_back(page);
    // Evictable: resident pages outside what is kept, least recently used first, and of
    // those used last at once the finer level first (a coarse page is read by more rays;
    // the ids break ties, so the order is the same every run).
    std::vector<int> evictable;
    if (absent.size() > freeLayers_.size()) {
        for (int page = 0; page < pageCount(); ++page)
            if (pages_[page].layer >= 0 && !kept[page]) evictable.push_back(page);
        if (absent.size() > freeLayers_.size() + evictable.size()) return false;
        const std::size_t needed = absent.size() - freeLayers_.size();
        std::partial_sort(evictable.begin(), evictable.begin() + static_cast<long>(needed),
                          evictable.end(), [&](int a, int b) {
                              return std::tie(pages_[a].used, pages_[a].level, a) <
                                     std::tie(pages_[b].used, pages_[b].level, b);
                          });
        for (std::size_t k = 0; k < needed; ++k) {
            Page& out = pages_[evictable[k]];
            freeLayers_.push_back(out.layer);
            out.layer = -1;
            setEntry(evictable[k], 0u);
            --residentCount_;
            ++pagesEvicted_;
        }
    }
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl_.BindTexture(GL_TEXTURE_2D_ARRAY, pool_.id());
    const int side = pageSide();
    for (int id : absent) {
        Page& page = pages_[id];
        page.layer = freeLayers_.back();
        freeLayers_.pop_back();
        const std::vector<float> texels = pageTexels(page);
        gl_.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, page.layer, side, side, 1, GL_RED, GL_FLOAT,
                          texels.data());
        setEntry(id, static_cast<std::uint32_t>(page.layer) + 1u);
        page.used = clock_;
        ++residentCount_;
        ++pagesLoaded_;
    }
    return true;
}

bool PagedPyramid::loadKeepingRead(const std::vector<int>& pages, const std::vector<int>& keep) {
    std::vector<int> kept = keep;
    kept.insert(kept.end(), read_.begin(), read_.end());
    return load(pages, kept);
}

std::size_t PagedPyramid::loadWhatFitsKeepingRead(const std::vector<int>& pages,
                                                  const std::vector<int>& keep) {
    // A layer for each page held: resident and kept or read, or taken from `pages` (absent:
    // a free layer or an evicted page's; resident: its own, no longer evictable). load
    // finds the layers for the pages taken, since they and those held are at most the pool.
    std::vector<char> held(pages_.size(), 0);
    int room = capacity();
    const std::vector<int>* const heldLists[] = {&keep, &read_};
    for (const std::vector<int>* list : heldLists) {
        for (int page : *list) {
            if (held[page] || pages_[page].layer < 0) continue;
            held[page] = 1;
            --room;
        }
    }
    std::size_t taken = 0;
    for (; taken < pages.size(); ++taken) {
        const int page = pages[taken];
        if (held[page]) continue;
        if (room == 0) break;
        held[page] = 1;
        --room;
    }
    if (taken == 0) return 0;
    const std::vector<int> some(pages.begin(), pages.begin() + static_cast<std::ptrdiff_t>(taken));
    if (!loadKeepingRead(some, keep)) throwRuntime("PagedPyramid: a load counted to fit did not");
    return taken;
}

std::vector<float> PagedPyramid::pageTexels(const Page& page) const {
    // Texels past the level's edge are never read (reads are clamped to the level); 0.
    const int side = pageSide();
    const glm::ivec2 size = source_->levelSize(page.level);
    const TexelRect rect{page.origin.x, page.origin.y, std::min(size.x, page.origin.x + side),
                         std::min(size.y, page.origin.y + side)};
    std::vector<float> texels(static_cast<std::size_t>(rect.width()) * rect.height());
    source_->read(page.level, rect, texels.data());
    // Windows as the coarse texture holds them (bound / 2^S, a half exactly).
    if (page.level > 0) {
        for (float& texel : texels) texel = std::ldexp(texel, -source_->scaleExponent());
    }
    if (rect.width() == side && rect.height() == side) return texels;
    std::vector<float> padded(static_cast<std::size_t>(side) * side, 0.0f);
    for (int y = 0; y < rect.height(); ++y) {
        std::copy_n(texels.begin() + static_cast<std::ptrdiff_t>(y) * rect.width(), rect.width(),
                    padded.begin() + static_cast<std::ptrdiff_t>(y) * side);
    }
    return padded;
}

void PagedPyramid::setEntry(int page, std::uint32_t entry) {
    gl_.BindBuffer(GL_COPY_WRITE_BUFFER, table_.id());
    gl_.BufferSubData(GL_COPY_WRITE_BUFFER,
                      static_cast<GLintptr>((PageTableLayout::kEntriesAt + page) * 4), 4, &entry);
}

}  // namespace microrelief
