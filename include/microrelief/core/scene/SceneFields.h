// The fields of a scene (core/scene/Scene.h) that messages may name as {field} (core/Error.h),
// apart from the scene itself so that the error type needs nothing but the standard library
// (the WebAssembly pyramid of microrelief-three compiles it alone).
#pragma once

#include <string>
#include <vector>

namespace microrelief {

// Every member path of ReliefDesc and ViewDesc that a check concerns, and "size" (width
// and height together). A program names each (microrelief-render: a flag; tests/batch
// checks it has one for all but map.samples).
const std::vector<std::string>& sceneFields();
bool isSceneField(const std::string& path);

}  // namespace microrelief
