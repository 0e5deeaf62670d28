#include "microrelief/core/scene/SceneFields.h"

#include <algorithm>

namespace microrelief {

const std::vector<std::string>& sceneFields() {
    static const std::vector<std::string> fields = {
        "map.file", "map.samples", "map.load.channel", "map.load.normalize", "albedo", "base",
        "base.radius", "base.length", "base.radii", "interpolation", "tiles", "heightScale",
        "model", "animation", "time", "camera.eye", "camera.target", "camera.up",
        "camera.fovyDegrees", "size", "method", "method.steps", "method.pixelError",
        "shading.lightDirection", "shading.lightPosition", "shading.shadows",
        "shading.lightSizeDegrees", "shading.view", "background"};
    return fields;
}

bool isSceneField(const std::string& path) {
    const auto& fields = sceneFields();
    return std::find(fields.begin(), fields.end(), path) != fields.end();
}

}  // namespace microrelief
