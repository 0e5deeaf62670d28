// The table of scene fields: one row for each field of a scene (core/scene/Scene.h) that
// messages may name as {field} (core/Error.h), with what the programs, the page and the
// documentation call it: microrelief-render's flag and --help line, the web page's URL key,
// the default and the range as docs/cli.md states them. A user-visible setting is one row
// here plus its use; the flags (app/shared/SceneOptions.cpp, through each row's binding in
// app/shared/SceneBindings.cpp, checked one to one), docs/cli.md's table of scene options
// (generated: tests/docs/scene_field_table.cpp) and the pages' keys (web/scene.js and
// examples/three/view.js, checked against the rows: ctest web.field_keys) come from it.
//
// Apart from the scene itself so that the error type needs nothing but the standard
// library (the WebAssembly pyramid of microrelief-three compiles it alone).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace microrelief {

// One row. Every text is plain, but `doc`, which is Markdown (docs/cli.md's cell).
struct SceneField {
    std::string_view path;         // what a message names: "shading.lightSizeDegrees"
    std::string_view flag;         // the programs' flag: "--light-size"; empty: none
    std::string_view valueName;    // the flag's value in docs/cli.md: "DEG"; empty: a switch
    std::string_view urlKey;       // web/scene.js's query key: "light-size"; empty: none
    std::string_view defaultText;  // the default as docs/cli.md writes it: "1"
    std::string_view range;        // the values taken, their unit: "degrees, from 0 to 90"
    std::string_view help;         // the flag's line in --help
    std::string_view doc;          // docs/cli.md's meaning, where it says more than help
};

// The rows, in docs/cli.md's order. The base's sizes are not rows: the table of bases
// holds them (core/base/BaseType.h: baseSizeFields(); sceneFieldFlag derives their flags).
std::span<const SceneField> sceneFieldTable();
// The row of `path`, or null.
const SceneField* findSceneField(std::string_view path);
// The flag that sets `path`: its row's, or a base size's from its field ("base.radius" is
// --radius, "base.minorRadius" would be --minor-radius); empty for a field no flag sets,
// such as one of a size's form that no base has. Defined in core/base/BaseTable.cpp, which
// holds the sizes (the WebAssembly builds compile SceneFields.cpp without it).
std::string sceneFieldFlag(std::string_view path);

// Every member path of ReliefDesc and ViewDesc that a check concerns (the table's paths),
// and "size" (width and height together), but the base's sizes. A program names each
// (microrelief-render: a flag; tests/batch checks it has one for all but map.samples).
const std::vector<std::string>& sceneFields();
// One of sceneFields(), or a base's size (isBaseSizeField).
bool isSceneField(const std::string& path);
// "base." and a name (letters and digits): a size of a base, as the table of bases has them
// (core/base/BaseType.h: baseSizeFields(); a test holds every one of them to this form).
bool isBaseSizeField(const std::string& path);

}  // namespace microrelief
