// A map larger than one texture on the GPU (shaders/paged_map.glsl): its samples
// and the fine levels of its windows (core/heightmap/MaxPyramid.h) cut into square pages, as
// many resident as a memory budget holds, in one texture array (the pool); the coarse levels
// whole in one R16F texture; a page table and a wants buffer in shader storage. A draw reads
// a texel from its page where the page is resident and otherwise stands in for it with a
// bound above it, and records the page as wanted (takeWanted); the host loads what was
// wanted (load) and draws again, until a draw wants nothing: that picture is the one the
// whole map gives, bit for bit (gl/HeadlessRender.h draws so). Pages are cut from the
// samples and windows as PyramidPages keeps them (core/heightmap/PyramidPages.h: in memory,
// or in a pyramid file on disk, io/PyramidFile.h). A draw also records every resident page
// it reads, so the least recently used go first when the pool is full: the pages a view
// reads stay resident from one frame to the next while the pool holds them.
//
// GL 4.3 (shader storage in the fragment shader); the multilevel method only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <memory>

#include "microrelief/core/heightmap/PyramidPages.h"
#include "microrelief/gl/Gl.h"
#include "microrelief/gl/Objects.h"

namespace microrelief {

// When a map is paged, and how.
struct PagingSettings {
    // Never: a map larger than GL_MAX_TEXTURE_SIZE is refused (ReliefRenderer's default: a
    // paged map's picture is exact only when drawn until no page is wanted, which
    // HeadlessRenderer does and a single draw does not); Auto: such maps are paged (the
    // default of HeadlessRenderer and microrelief-render); Always: every map (the tests hold
    // the two paths to the same pictures with it).
    enum class Mode { Never, Auto, Always };
    Mode mode = Mode::Auto;
    // Texels a page side: a power of two, 16 to 4096. The pool is one texture array, a page
    // a layer: where the budget would hold more of the map's pages than the GL has layers
    // (GL_MAX_ARRAY_TEXTURE_LAYERS, 2048 on llvmpipe and NVIDIA: 512 MiB of 256^2 pages), the
    // side doubles until it does not (pageSide() says what was used).
    int pageSide = 256;
    // The pool's budget, bytes (--memory): pages of pageSide^2 R32F texels, at least one.
    std::size_t memoryBytes = std::size_t{512} << 20;
    // What the host calls the budget, for the errors that say to raise or lower it: the
    // command line's flag by default; a host whose setting has another name (an option's
    // key, a field of its own) gives that, so the message speaks of what its user sets.
    std::string budgetName = "--memory";
    // Window levels whose sides are at most this stay whole in one texture.
    int residentSide = 2048;
};

// Where the page table's parts lie, in 32-bit words (paged_map.glsl gets them as defines):
// the info words (the paged window levels L, S, log2 of the page side, the stamp the draws
// write to the use buffer for the pages they read), then four words a page level (its
// first entry, width, height, a spare; level 0 the samples, 1 + k window level k, up to
// 1 + L), then an entry a page.
struct PageTableLayout {
    static constexpr int kInfoAt = 0;
    static constexpr int kMaxPageLevels = 34;  // the samples and 33 window levels at most
    static constexpr int kLevelsAt = 4;
    static constexpr int kEntriesAt = kLevelsAt + 4 * kMaxPageLevels;
};

class PagedPyramid {
public:
    // Pages are cut from `pages` as they are wanted (a file's reader may throw then, for a
    // corrupt page). Throws Error(BadInput) naming `source` for settings out of range,
    // Error(Runtime) where the GL lacks what paging needs (GL 4.3).
    PagedPyramid(const GL& gl, std::shared_ptr<const PyramidPages> pages,
                 const PagingSettings& settings, const std::string& source);

    GLuint pool() const { return pool_.id(); }
    GLuint coarse() const { return coarse_.id(); }
    GLuint table() const { return table_.id(); }
    // The use buffer (paged_map.glsl): a word a page, the stamp of the last draw that read
    // or wanted it.
    GLuint wants() const { return wants_.id(); }

    int pageSide() const { return 1 << shift_; }
    int pagedLevels() const { return pagedLevels_; }  // L: window levels 0 .. L - 1 are paged
    int pageCount() const { return static_cast<int>(pages_.size()); }
    int capacity() const { return static_cast<int>(freeLayers_.size() + residentCount_); }
    int residentCount() const { return residentCount_; }
    std::size_t pagesLoaded() const { return pagesLoaded_; }
    std::size_t pagesEvicted() const { return pagesEvicted_; }
    const PyramidPages& pages() const { return *source_; }
    // The pool, the coarse texture and the two buffers, bytes.
    std::size_t gpuBytes() const;

    // The pages the draws since the last call wanted and found absent, in the entries'
    // order; the pages they read (resident or wanted) count as used now (for load's
    // order), those read resident are readByLastDraws() until the next call. Waits for the
    // draws (a buffer read).
    std::vector<int> takeWanted();
    // The pages the draws before the last takeWanted read from the pool, in the entries'
    // order: a host that keeps them (load's `keep`) never evicts what the next draw reads.
    const std::vector<int>& readByLastDraws() const { return read_; }
    // Loads `pages` (ids from takeWanted) that are absent, each into a free layer or the
    // layer of the least recently used resident page outside `keep` (which may hold any
    // ids, `pages` among them; of pages last used at once, the finer level goes first: a
    // coarse page is read by more rays). Returns false, loading nothing, when they do not
    // all fit beside `keep`.
    bool load(const std::vector<int>& pages, const std::vector<int>& keep);
    // The hosts' rule (HeadlessRenderer's tiles, the viewer's frames): load with the pages
    // the last draws read kept too (readByLastDraws), besides `keep`. Least recently used
    // order alone evicts them last, but where the pool is short it evicts them still, and
    // the next draw wants them again; kept, the load fails instead (a host then draws in
    // parts, or loads less: loadWhatFitsKeepingRead).
    bool loadKeepingRead(const std::vector<int>& pages, const std::vector<int>& keep);
    // loadKeepingRead of the longest run of `pages` from the first that fits beside `keep`
    // and the pages the last draws read; returns its length (0: none fits, nothing loaded).
    // For a host that cannot draw a view in parts (the viewer): it loads what fits and
    // draws again, never at the cost of a page its last draw read.
    std::size_t loadWhatFitsKeepingRead(const std::vector<int>& pages,
                                        const std::vector<int>& keep);
    bool resident(int page) const { return pages_[page].layer >= 0; }

private:
    struct Page {
        int level = 0;           // page level: 0 the samples, 1 + k window level k
        glm::ivec2 origin;       // its first texel
        int layer = -1;          // the pool layer, -1 absent
        std::uint64_t used = 0;  // when last read, wanted or loaded (clock_)
    };
    std::vector<float> pageTexels(const Page& page) const;
    void setEntry(int page, std::uint32_t entry);

    const GL& gl_;
    std::shared_ptr<const PyramidPages> source_;
    int shift_ = 8;
    int pagedLevels_ = 0;
    std::vector<Page> pages_;
    std::vector<int> freeLayers_;
    int residentCount_ = 0;
    std::uint64_t clock_ = 0;  // takeWanted's calls
    // What the draws write to the use buffer for a page they read (the table's info word
    // 3): 1 to kLastStamp, changed by each takeWanted; the top bit marks a page wanted.
    static constexpr std::uint32_t kWantedBit = 0x80000000u, kLastStamp = kWantedBit - 1;
    std::uint32_t stamp_ = 1;
    std::vector<int> read_;
    std::size_t pagesLoaded_ = 0, pagesEvicted_ = 0;
    gl::Texture pool_, coarse_;
    gl::Buffer table_, wants_;
};

}  // namespace microrelief
