// How the viewer refines a view of a map read through pages (gl/PagedPyramid.h), without
// the GL: after each draw, the pages the draw wanted are loaded, at most kPagesPerFrame a
// frame, and the view is drawn again (generation() is part of what the picture depends
// on), until a draw wants none (the exact picture, as microrelief-render draws it) or the
// view needs more pages at once than the pool holds (then it stays drawn partly from
// coarser windows, which lie above the surface: coarse, never a hole). Pages loaded for the
// view being refined are kept for it, so it never loads a page twice; another view starts
// afresh. Each load also keeps the pages the last draw read (the viewer's Load is
// PagedPyramid::loadWhatFitsKeepingRead, HeadlessRenderer's rule): a frame of a moving view
// loads what it lacks only where it evicts nothing the frame before it read, so a slow orbit
// or a still view after one does not reload the pages it is drawn from.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace microrelief {

class PageRefiner {
public:
    // 64 MiB of 256^2 float pages: a view that wants thousands refines over frames, each
    // answering the mouse, instead of stalling.
    static constexpr std::size_t kPagesPerFrame = 256;
    // Loads the longest run of `pages` from the first that fits the pool beside `keep` (and
    // what the last draw read: PagedPyramid::loadWhatFitsKeepingRead); returns its length,
    // 0 where none fits.
    using Load =
        std::function<std::size_t(const std::vector<int>& pages, const std::vector<int>& keep)>;

    // After a draw that wanted `wanted` (PagedPyramid::takeWanted); `anotherView`: not the
    // view refined before. Returns true where the pool has just proved too small for the
    // view (once a view: the viewer says so).
    bool afterDraw(bool anotherView, const std::vector<int>& wanted, const Load& load);
    // The map is not read through pages: nothing wanted.
    void noPages();

    // Whether the last draw wanted pages (its picture is not the exact one).
    bool pagesWanted() const { return wanted_ > 0; }
    bool poolTooSmall() const { return poolTooSmall_; }
    // Whether the view is still being refined: --frames draws on until it is not.
    bool refining() const { return pagesWanted() && !poolTooSmall_; }
    // Counts the loads: the view is drawn again after each.
    int generation() const { return generation_; }
    // The pages kept for the view refined.
    const std::vector<int>& kept() const { return kept_; }
    // The panel's word on the view: exact, coarse in parts, or refining.
    std::string progress() const;

private:
    std::vector<int> kept_;
    std::size_t wanted_ = 0;
    int generation_ = 0;
    bool poolTooSmall_ = false;
};

}  // namespace microrelief
