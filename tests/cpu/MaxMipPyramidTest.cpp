// maxmip's quadtree (peers/MaxMipPyramid.h): its power-of-two shape for any map, level 0
// the max pyramid's finest bounds padded with 0, each coarser texel the max of the two by
// two below it, so every texel bounds the finest squares it covers.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/peers/MaxMipPyramid.h"

using namespace microrelief;

TEST(MaxMipPyramid, LevelSizesArePaddedToPowersOfTwo) {
    const MaxMipPyramid p{MaxPyramid(HeightMap(300, 77))};
    // Padded to 512 x 128, then halved with GL's max(1, n >> k) down to 1 x 1.
    ASSERT_EQ(p.levelCount(), 10);
    EXPECT_EQ(p.levelWidth(0), 512);
    EXPECT_EQ(p.levelHeight(0), 128);
    EXPECT_EQ(p.levelWidth(7), 4);
    EXPECT_EQ(p.levelHeight(7), 1);
    EXPECT_EQ(p.levelWidth(9), 1);
    EXPECT_EQ(p.levelHeight(9), 1);
    EXPECT_EQ(maxMipLevelSizes(1, 1), std::vector<glm::ivec2>{glm::ivec2(1)});
    EXPECT_EQ(maxMipLevelSizes(2, 2).size(), 2u);
}

// Every texel of every level, against the finest bounds it covers, on maps of odd sizes
// in both precisions: level 0 the max pyramid's finest bound (0 in the padding), level k
// the max over its 2^k x 2^k finest squares that lie on the map, the top the largest bound.
TEST(MaxMipPyramid, EachTexelIsTheMaxOfTheFinestBoundsItCovers) {
    for (const BoundPrecision precision : {BoundPrecision::Float, BoundPrecision::Half}) {
        for (const auto& [w, h] : {std::pair{37, 23}, std::pair{1, 9}, std::pair{16, 16}}) {
            const HeightMap map = synth::whiteNoise(w, h, static_cast<std::uint32_t>(w + h));
            const MaxPyramid pyramid(map, false, precision);
            const MaxMipPyramid p(pyramid);
            const std::string what = std::to_string(w) + "x" + std::to_string(h);
            for (int k = 0; k < p.levelCount(); ++k) {
                for (int q = 0; q < p.levelHeight(k); ++q) {
                    for (int s = 0; s < p.levelWidth(k); ++s) {
                        float expected = 0.0f;
                        for (int j = q << k; j < std::min((q + 1) << k, h); ++j)
                            for (int i = s << k; i < std::min((s + 1) << k, w); ++i)
                                expected = std::max(expected, pyramid.block(0, i, j));
                        ASSERT_EQ(p.texel(k, s, q), expected)
                            << what << ", level " << k << " texel " << s << "," << q;
                    }
                }
            }
            EXPECT_EQ(p.texel(p.levelCount() - 1, 0, 0), pyramid.maxHeight()) << what;
            if (precision == BoundPrecision::Float) {
                EXPECT_EQ(p.texel(p.levelCount() - 1, 0, 0), map.maxValue()) << what;
            }
        }
    }
}
