// The scene flags' bindings: for each row of the table of scene fields that has a flag
// (core/scene/SceneFields.h), how the programs register the flag on a command line, turn
// its text into the scene's member and write the member back as the flag's exact text.
// SceneFlags (SceneOptions.h) registers, parses and echoes them all in one loop over this
// table, in its order (--help's); renderCommandLine echoes them in the same loop.
//
// A plain setting's binding is one line of SceneBindings.cpp, made by its kind: a number
// or a whole number (number), a switch (toggle), a word from a list (word), a vector of
// three (vector). The fields read specially (the map file, the albedo, the base and its
// sizes, the tiles, the animation and its time, the size, the model, the two lights) have
// codecs of their own there and go through the same loop. Every row with a flag has one
// binding and every binding a row with a flag: SceneFlags stops a program that starts
// without (a programming error; tests/batch: SceneBindings).
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "microrelief/core/scene/Georeference.h"
#include "microrelief/core/scene/SceneFields.h"
#include "microrelief/gl/HeadlessRender.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace microrelief {

// A binding's state in one parse: the flag's text until apply() reads it.
struct FlagSlot {
    std::string text;                          // seeded with the field's own text
    std::optional<double> number;              // --time's value (CLI11 reads it)
    std::map<std::string, std::string> sizes;  // --base's: its sizes' text, by field
    CLI::Option* option = nullptr;             // as registered: count() says it was given
};
// The slots of one parse, by path.
using FlagSlots = std::map<std::string_view, FlagSlot>;

// The command line renderCommandLine writes, flag by flag.
struct CommandEcho {
    std::string line;
    // " --flag value", the value quoted for a POSIX shell; a switch has none.
    void spaced(std::string_view field, const std::string& value);
    // " --flag=value": a leading minus must not read as a flag in any parser.
    void joined(std::string_view field, const std::string& value);
};

// Which of SceneFlags' two groups registers a flag (addMapAndCamera, addShading).
enum class FlagGroup { MapAndCamera, Shading };

struct SceneBinding {
    std::string_view path;  // its row's (core/scene/SceneFields.h)
    FlagGroup group = FlagGroup::MapAndCamera;
    // Before the parse: the slot's text from the scene's member (the default --help shows,
    // and what a parse that does not give the flag reads back). Null: the flag is read
    // into the member itself.
    std::function<void(const RenderJob&, FlagSlot&)> seed;
    // Registers the flag, named `flag` with `help` (its row's); returns its option.
    std::function<CLI::Option*(CLI::App&, RenderJob&, FlagSlot&, const std::string& flag,
                               const std::string& help)>
        add;
    // After the parse, in the table's order: the slot's text into the member. Throws
    // Error(BadInput) naming the flag; the rules between flags read the other slots. Null:
    // CLI11 has written the member.
    std::function<void(RenderJob&, const FlagSlot&, const FlagSlots&)> apply;
    // The member on a command line, where it is not left to its default.
    std::function<void(const RenderJob&, const GeoreferenceFit&, CommandEcho&)> echo;
    // Given on the command line: kept over a georeferenced map's own (GeoreferenceFit).
    bool GeoreferenceFit::*keep = nullptr;
    // Registered and read only by the programs that draw colours (SceneFlags' withAlbedo).
    bool albedoOnly = false;
    // Echoed just before that path's binding rather than in its place (--tile before --base,
    // the order the echo has always had).
    std::string_view echoedBefore;
    // Read just after that path's binding rather than in its place: where two flags are
    // wrong at once, the one reported is the one it has always been (--base before
    // --interpolation, the lights and --shadows before --size, --view before --method,
    // --model last).
    std::string_view parsedAfter;
};

// The bindings, in --help's order: each group's flags as SceneFlags registers them.
std::span<const SceneBinding> sceneBindings();

// What does not match between `rows` and `bindings`, one line each: a row with a flag and
// no binding, a binding without a row that has a flag, a path bound twice, an echo or a
// read placed by a path that has no binding. Empty: they match.
std::vector<std::string> sceneBindingGaps(std::span<const SceneField> rows,
                                          std::span<const SceneBinding> bindings);

}  // namespace microrelief
