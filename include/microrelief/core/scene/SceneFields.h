// The fields of a scene (core/scene/Scene.h) that messages may name as {field} (core/Error.h),
// apart from the scene itself so that the error type needs nothing but the standard library
// (the WebAssembly pyramid of microrelief-three compiles it alone).
#pragma once

#include <string>
#include <vector>

namespace microrelief {

// Every member path of ReliefDesc and ViewDesc that a check concerns, and "size" (width
// and height together), but the base's sizes. A program names each (microrelief-render: a
// flag; tests/batch checks it has one for all but map.samples).
const std::vector<std::string>& sceneFields();
// One of sceneFields(), or a base's size (isBaseSizeField).
bool isSceneField(const std::string& path);
// "base." and a name (letters and digits): a size of a base, as the table of bases has them
// (core/base/BaseType.h: baseSizeFields(); a test holds every one of them to this form).
bool isBaseSizeField(const std::string& path);

}  // namespace microrelief
