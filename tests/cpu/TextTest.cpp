// Text for one-line messages (core/Text.h).
#include <gtest/gtest.h>

#include "microrelief/core/Text.h"

using namespace microrelief;

TEST(Text, JoinWordsReadsAsASentencesList) {
    EXPECT_EQ(joinWords({}, " or "), "");
    EXPECT_EQ(joinWords({"plane"}, " or "), "plane");
    EXPECT_EQ(joinWords({"plane", "cylinder"}, " or "), "plane or cylinder");
    EXPECT_EQ(joinWords({"a", "b", "c", "d"}, " and "), "a, b, c and d");
}
