// The library's table of scene fields (core/scene/SceneFields.h) against the programs'
// flags (app/shared/SceneOptions): each row's flag is registered with its row's --help
// line, and the default a row states (docs/cli.md's table shows it) is the one the flag
// takes, wherever --help shows one.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <string>

#include "SceneOptions.h"
#include "microrelief/core/scene/SceneFields.h"

namespace microrelief {
namespace {

TEST(SceneFieldTable, EveryFlagIsARowsWithItsHelpAndDefault) {
    SceneOptions options;
    SceneFlags flags(options);
    CLI::App app;
    flags.addMapAndCamera(app);
    flags.addShading(app);
    int defaultsCompared = 0;
    for (const SceneField& field : sceneFieldTable()) {
        if (field.flag.empty()) continue;  // a library user's only (map.samples)
        SCOPED_TRACE(std::string(field.path));
        const CLI::Option* option = app.get_option_no_throw(std::string(field.flag));
        ASSERT_NE(option, nullptr) << field.flag << " is not registered";
        EXPECT_EQ(flagName(std::string(field.path)), field.flag);
        // --base's line goes on with the table of bases' names.
        EXPECT_EQ(option->get_description().substr(0, field.help.size()), field.help);
        const std::string shown = option->get_default_str();
        if (shown.empty()) continue;
        EXPECT_EQ(shown, field.defaultText) << field.flag << "'s default";
        ++defaultsCompared;
    }
    // At least channel, height-scale, interpolation, base, eye, target, up, fovy, size,
    // shadows, light-size, method, steps, pixel-error, view, background: a table that lost
    // them would compare none (a new setting whose --help shows its default adds one).
    EXPECT_GE(defaultsCompared, 16);
}

// A row's page key (web/scene.js's URL key) is its flag's name, or the page has none.
TEST(SceneFieldTable, PageKeysAreTheFlagsNames) {
    for (const SceneField& field : sceneFieldTable()) {
        if (field.urlKey.empty()) continue;
        EXPECT_EQ("--" + std::string(field.urlKey), field.flag) << field.path;
    }
}

}  // namespace
}  // namespace microrelief
