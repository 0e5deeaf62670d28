// The table of base surfaces (core/base/BaseType.h). Each row is written in its base's own
// file, beside the BaseSurface it makes; a new base is a line here.
#include <algorithm>
#include <cctype>

#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/SceneFields.h"

namespace microrelief {

BaseType planeBaseType();      // core/base/PlaneSurface.cpp
BaseType cylinderBaseType();   // core/base/CylinderSurface.cpp
BaseType ellipsoidBaseType();  // core/base/EllipsoidSurface.cpp
BaseType sphereBaseType();     // core/base/EllipsoidSurface.cpp

const std::vector<BaseType>& baseTypes() {
    static const std::vector<BaseType> table = {planeBaseType(), cylinderBaseType(),
                                                ellipsoidBaseType(), sphereBaseType()};
    return table;
}

const BaseType& baseType(const BaseShape& shape) {
    const BaseType* general = nullptr;
    for (const BaseType& type : baseTypes()) {
        if (type.kind != shape.kind) continue;
        if (type.names == nullptr) {
            if (general == nullptr) general = &type;
        } else if (type.names(shape)) {
            return type;  // a name for some shapes of the kind goes before the kind's own
        }
    }
    // A kind no row has is a programming error (validateBaseShape refuses it as input).
    if (general == nullptr)
        throwRuntime("BaseShape of kind " + std::to_string(static_cast<int>(shape.kind)) +
                     ", which the table of bases does not hold");
    return *general;
}

const BaseType& baseType(std::string_view name) {
    std::vector<std::string> names;
    for (const BaseType& type : baseTypes()) {
        if (type.name == name) return type;
        names.emplace_back(type.name);
    }
    throwBadInput("unknown {base} '" + std::string(name) + "' (expected " + joinWords(names, " or ") +
                  ")");
}

std::unique_ptr<BaseSurface> BaseSurface::make(const BaseShape& shape, int mapWidth, int mapHeight,
                                               double heightScale, double maxHeight) {
    return baseType(shape).makeSurface(shape, mapWidth, mapHeight, heightScale, maxHeight);
}

std::vector<std::string> baseSizeFields() {
    std::vector<std::string> fields;
    for (const BaseType& type : baseTypes())
        for (const BaseSize& size : type.sizes)
            if (std::find(fields.begin(), fields.end(), size.field) == fields.end())
                fields.push_back(size.field);
    return fields;
}

// core/scene/SceneFields.h's, here beside the sizes it names: a row's flag, or a size's
// from its field, for the sizes this table has and no other field of their form.
std::string sceneFieldFlag(std::string_view path) {
    if (const SceneField* field = findSceneField(path)) return std::string(field->flag);
    const std::vector<std::string> sizes = baseSizeFields();
    if (std::find(sizes.begin(), sizes.end(), path) == sizes.end()) return {};
    std::string flag = "--";
    for (char c : path.substr(path.find('.') + 1)) {
        if (std::isupper(static_cast<unsigned char>(c))) {
            flag += '-';
            c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        }
        flag += c;
    }
    return flag;
}

}  // namespace microrelief
