// What a map read through pages (gl/PagedPyramid.h) is read from: its samples and the
// windows of its max pyramid (MaxPyramid.h, BoundPrecision::Half, untiled), level by level,
// a rectangle at a time, wherever they are kept. Two keep them: PyramidInMemory (a map and
// its pyramid, built whole) and io/PyramidFile.h (a tiled file on disk, built from rows in
// bounded memory by PyramidStream.h); both give the same texels, bit for bit.
//
// Page levels: 0 the samples (map units), 1 + k the windows of level k as MaxPyramid keeps
// them (bounds in map units on the half grid times 2^S, S = scaleExponent()).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/MaxPyramid.h"

namespace microrelief {

class PyramidPages {
public:
    virtual ~PyramidPages() = default;

    int mapWidth() const { return mapWidth_; }
    int mapHeight() const { return mapHeight_; }
    bool wrapsU() const { return wrapU_; }
    int scaleExponent() const { return scaleExponent_; }
    // The largest sample, and the top bound (MaxPyramid::maxHeight): it rounded up to the
    // half grid (pyramidTop).
    float largestSample() const { return largestSample_; }
    float maxHeight() const { return pyramidTop(largestSample_); }
    // 1 + the window levels (windowLevelSizes).
    int levelCount() const { return static_cast<int>(windowSizes_.size()) + 1; }
    // Level 0 (the samples) is W x H, as window level 0 is.
    glm::ivec2 levelSize(int level) const { return windowSizes_[level > 0 ? level - 1 : 0]; }

    // The texels of `rect` (inside level `level`) into `out`, row-major, rect.width() a row.
    // A file's reader throws Error(BadInput) naming the file for a page it finds corrupt.
    virtual void read(int level, const TexelRect& rect, float* out) const = 0;
    // The whole of a level.
    std::vector<float> readLevel(int level) const;

protected:
    PyramidPages(int mapWidth, int mapHeight, bool wrapU, float largestSample);

private:
    int mapWidth_, mapHeight_;
    bool wrapU_;
    float largestSample_;
    int scaleExponent_;
    std::vector<glm::ivec2> windowSizes_;
};

// A map and its pyramid's windows in memory (what paging reads; not the blocks a MaxPyramid
// keeps for its updates, as many bytes again).
class PyramidInMemory final : public PyramidPages {
public:
    // The windows of `map`'s pyramid (u wrapped when `wrapU`), built from its rows as a
    // pyramid file's are (PyramidStream.h: the same texels as MaxPyramid's, BoundPrecision::
    // Half, untiled), without the blocks whole; the map is shared, not copied. `source`
    // names the map in errors. Throws Error.
    PyramidInMemory(std::shared_ptr<const HeightMap> map, bool wrapU, const std::string& source);

    void read(int level, const TexelRect& rect, float* out) const override;
    const HeightMap& map() const { return *map_; }

private:
    struct Windows {
        std::vector<std::unique_ptr<float[]>> levels;  // window level k: its sizes' texels
        float largestSample = 0.0f;
    };
    static Windows streamWindows(const HeightMap& map, bool wrapU, const std::string& source);
    PyramidInMemory(std::shared_ptr<const HeightMap> map, bool wrapU, Windows windows);

    std::shared_ptr<const HeightMap> map_;
    std::vector<std::unique_ptr<float[]>> windows_;
};

}  // namespace microrelief
