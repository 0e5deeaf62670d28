#include "microrelief/core/scene/SceneFields.h"

#include <algorithm>
#include <cctype>
#include <string_view>

namespace microrelief {

const std::vector<std::string>& sceneFields() {
    static const std::vector<std::string> fields = {"map.file",
                                                    "map.samples",
                                                    "map.load.channel",
                                                    "map.load.normalize",
                                                    "albedo",
                                                    "base",
                                                    "interpolation",
                                                    "tiles",
                                                    "heightScale",
                                                    "model",
                                                    "animation",
                                                    "time",
                                                    "camera.eye",
                                                    "camera.target",
                                                    "camera.up",
                                                    "camera.fovyDegrees",
                                                    "size",
                                                    "method",
                                                    "method.steps",
                                                    "method.pixelError",
                                                    "shading.lightDirection",
                                                    "shading.lightPosition",
                                                    "shading.shadows",
                                                    "shading.lightSizeDegrees",
                                                    "shading.view",
                                                    "background"};
    return fields;
}

bool isSceneField(const std::string& path) {
    const auto& fields = sceneFields();
    return std::find(fields.begin(), fields.end(), path) != fields.end() || isBaseSizeField(path);
}

bool isBaseSizeField(const std::string& path) {
    constexpr std::string_view prefix = "base.";
    return path.size() > prefix.size() && path.starts_with(prefix) &&
           std::all_of(path.begin() + prefix.size(), path.end(),
                       [](char c) { return std::isalnum(static_cast<unsigned char>(c)); });
}

}  // namespace microrelief
