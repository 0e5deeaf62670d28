// The table of base surfaces (core/base/BaseType.h), built from its rows' data as
// variants.glsl writes it (glsl::kBaseRows, generated) and each kind's geometry, written in
// the kind's own file beside its BaseSurface. A new row of a kind the table has is a line in
// variants.glsl; a new kind, its MR_BASE_* there and its geometry function in its own file
// (kKinds below is generated from the MR_BASE_* list).
#include <algorithm>
#include <cctype>
#include <string_view>

#include "microrelief/core/Error.h"
#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/SceneFields.h"

namespace microrelief {

// Each kind's geometry, `<name>Geometry()` in core/base/<Name>Surface.cpp for MR_BASE_<NAME>
// (planeGeometry() in PlaneSurface.cpp ...), declared here for every MR_BASE_* of
// variants.glsl: a kind whose file does not define it fails to link, naming the function.
#define MICRORELIEF_DECLARE_GEOMETRY(Name, name, value) BaseType name##Geometry();
MICRORELIEF_GLSL_BASE_KIND_MEMBERS(MICRORELIEF_DECLARE_GEOMETRY)
#undef MICRORELIEF_DECLARE_GEOMETRY

// A member of BaseShape that a size sets, by the name variants.glsl's //@size lines give it,
// and how many numbers it holds.
struct BaseShapeMember {
    std::string_view name;
    int width;
    double (*get)(const BaseShape& shape, int i);
    void (*set)(BaseShape& shape, int i, double value);
};

namespace {

// The members a size may set: a base whose sizes are a member BaseShape has not yet adds
// it to BaseShape and here.
constexpr BaseShapeMember kShapeMembers[] = {
    {"radius", 1, [](const BaseShape& b, int) { return b.radius; },
     [](BaseShape& b, int, double value) { b.radius = value; }},
    {"length", 1, [](const BaseShape& b, int) { return b.length; },
     [](BaseShape& b, int, double value) { b.length = value; }},
    {"radii", 3, [](const BaseShape& b, int i) { return b.radii[i]; },
     [](BaseShape& b, int i, double value) { b.radii[i] = value; }},
};

constexpr const BaseShapeMember* shapeMember(std::string_view name) {
    for (const BaseShapeMember& member : kShapeMembers)
        if (member.name == name) return &member;
    return nullptr;
}

// Every size of the rows sets a member above, of the width the row says.
constexpr bool everySizeHasItsMember() {
    for (const glsl::BaseRow& row : glsl::kBaseRows) {
        for (int k = 0; k < row.sizeCount; ++k) {
            const BaseShapeMember* member = shapeMember(row.sizes[k].member);
            if (member == nullptr || member->width != row.sizes[k].memberWidth) return false;
        }
    }
    return true;
}
static_assert(
    everySizeHasItsMember(),
    "a //@size line of variants.glsl sets a member of BaseShape that kShapeMembers has not "
    "(or one of another width)");

// Each kind's geometry, by its value (MICRORELIEF_BASE), every MR_BASE_* in order.
constexpr struct {
    BaseKind kind;
    BaseType (*geometry)();
} kKinds[] = {
#define MICRORELIEF_KIND_GEOMETRY(Name, name, value) {BaseKind::Name, name##Geometry},
    MICRORELIEF_GLSL_BASE_KIND_MEMBERS(MICRORELIEF_KIND_GEOMETRY)
#undef MICRORELIEF_KIND_GEOMETRY
};

// The shape of `type`'s kind whose sizes are the row's defaults (or its example), every
// other member BaseShape's default.
BaseShape shapeOf(const BaseType& type, const glsl::BaseRow& row, bool example) {
    BaseShape shape;
    shape.kind = type.kind;
    for (int k = 0; k < row.sizeCount; ++k) {
        const glsl::BaseSizeRow& size = row.sizes[k];
        type.sizes[static_cast<std::size_t>(k)].write(shape,
                                                      example ? size.example : size.defaults);
    }
    return shape;
}

// Row `row` of variants.glsl's: its data, and its kind's geometry.
BaseType typeOf(const glsl::BaseRow& row) {
    BaseType type = kKinds[row.kind].geometry();  // row.kind is an MR_BASE_*: in kKinds
    type.name = row.name;
    type.summary = row.summary;
    for (int k = 0; k < row.sizeCount; ++k) {
        const glsl::BaseSizeRow& size = row.sizes[k];
        type.sizes.push_back({size.field, size.label, size.count, shapeMember(size.member)});
        // One number for a member of more: the row has only the shapes whose are equal.
        if (size.count < size.memberWidth) type.names = true;
    }
    type.defaults = shapeOf(type, row, false);
    type.example = shapeOf(type, row, true);
    return type;
}

}  // namespace

void BaseSize::read(const BaseShape& shape, double* numbers) const {
    for (int i = 0; i < count; ++i) numbers[i] = member->get(shape, i);
}

void BaseSize::write(BaseShape& shape, const double* numbers) const {
    for (int i = 0; i < member->width; ++i) member->set(shape, i, numbers[count == 1 ? 0 : i]);
}

bool BaseType::takes(const BaseShape& shape) const {
    for (const BaseSize& size : sizes) {
        if (size.count != 1) continue;
        for (int i = 1; i < size.member->width; ++i)
            if (size.member->get(shape, i) != size.member->get(shape, 0)) return false;
    }
    return true;
}

const std::vector<BaseType>& baseTypes() {
    static const std::vector<BaseType> table = [] {
        std::vector<BaseType> rows;
        for (const glsl::BaseRow& row : glsl::kBaseRows) rows.push_back(typeOf(row));
        return rows;
    }();
    return table;
}

const BaseType& baseType(const BaseShape& shape) {
    const BaseType* general = nullptr;
    for (const BaseType& type : baseTypes()) {
        if (type.kind != shape.kind) continue;
        if (!type.names) {
            if (general == nullptr) general = &type;
        } else if (type.takes(shape)) {
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
    throwBadInput("unknown {base} '" + std::string(name) + "' (expected " +
                  joinWords(names, " or ") + ")");
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
