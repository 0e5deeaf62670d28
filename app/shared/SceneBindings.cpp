#include "SceneBindings.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdlib>
#include <limits>
#include <set>
#include <type_traits>

#include "SceneOptions.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/FloatLimits.h"
#include "microrelief/core/scene/Scene.h"

namespace microrelief {

namespace {

template <class T>
std::string toChars(T value, int precision = -1) {
    char text[64];
    const auto end = precision < 0 ? std::to_chars(text, text + sizeof text, value).ptr
                                   : std::to_chars(text, text + sizeof text, value,
                                                   std::chars_format::general, precision)
                                         .ptr;
    return std::string(text, end);
}

// The shortest text that reads back as `value` both through std::stod (our vectors)
// and through CLI11 (strtold, then a cast: a second rounding that could in principle
// move a shortest text to the neighbouring value); else max_digits10 digits. A whole
// number as std::to_string writes it.
template <class T>
std::string exactText(T value) {
    if constexpr (std::is_integral_v<T>) {
        return std::to_string(value);
    } else {
        const std::string shortest = toChars(value);
        const bool exact = static_cast<T>(std::strtold(shortest.c_str(), nullptr)) == value &&
                           static_cast<T>(std::strtod(shortest.c_str(), nullptr)) == value;
        return exact ? shortest : toChars(value, std::numeric_limits<T>::max_digits10);
    }
}

template <class T>
std::string exactVectorText(const glm::vec<3, T>& v) {
    return exactText(v.x) + ',' + exactText(v.y) + ',' + exactText(v.z);
}

// A base size's numbers as its flag takes them, exactly: "0.3", or "0.5,0.35,0.4".
std::string sizeText(const BaseSize& size, const BaseShape& shape) {
    double numbers[3] = {};
    size.read(shape, numbers);
    std::string text;
    for (int i = 0; i < size.count; ++i) text += (i ? "," : "") + exactText(numbers[i]);
    return text;
}

// The --base flags into a shape: the named base's defaults, each size flag given only where
// that base has the size, each number positive and finite.
BaseShape parseBase(const std::string& name, const std::map<std::string, std::string>& sizes) {
    const BaseType& type = baseType(name);
    BaseShape shape = type.defaults;
    for (const auto& entry : sizes) {
        const std::string& field = entry.first;  // named, not bound: lambdas capture it
        const std::string& text = entry.second;
        if (text.empty()) continue;
        const std::string flagText = flagName(field);
        const auto size = std::find_if(type.sizes.begin(), type.sizes.end(),
                                       [&](const BaseSize& s) { return s.field == field; });
        if (size == type.sizes.end()) throwBadInput(flagText + " does not apply to --base " + name);
        std::vector<double> numbers;
        if (size->count == 3) {
            const glm::dvec3 v = parseVectorFlag(flagText, text);
            numbers = {v.x, v.y, v.z};
        } else {
            numbers = parseNumberList(flagText, text, 1, "a number");
        }
        for (double number : numbers)
            if (!(number > 0.0)) throwBadInput(flagText + " must be a positive finite number");
        size->write(shape, numbers.data());
    }
    validateBaseShape(shape);
    return shape;
}

// ---- The kinds of a plain setting ----
//
// `access` is the member, as a lambda that takes a RenderJob, const or not, and returns a
// reference to it: MEMBER(path) writes one from the path itself, so a binding cannot name
// one field and write another.
// clang-format off
#define MEMBER(path) #path, [](auto& job) -> auto& { return job.path; }
// clang-format on

// When a plain setting is echoed: unless it has its default (the command stays short and
// runs on renderers older than the flag), or always.
using EchoWhen = bool (*)(const RenderJob&);
constexpr EchoWhen kUnlessDefault = nullptr;
bool always(const RenderJob&) {
    return true;
}

const RenderJob& defaults() {
    static const RenderJob job;
    return job;
}

template <class Access>
bool echoed(const RenderJob& job, Access access, EchoWhen when) {
    return when ? when(job) : !(access(job) == access(defaults()));
}

// A number or a whole number: CLI11 reads it into the member (its messages: "--fovy: 'x' is
// not a value it takes"); --help shows the member's default; echoed "--flag N".
template <class Access>
SceneBinding number(std::string_view path, Access access, EchoWhen when = kUnlessDefault) {
    SceneBinding b;
    b.path = path;
    b.add = [access](CLI::App& app, RenderJob& job, FlagSlot&, const std::string& flag,
                     const std::string& help) {
        return app.add_option(flag, access(job), help)->capture_default_str();
    };
    b.echo = [path, access, when](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (echoed(job, access, when)) out.spaced(path, exactText(access(job)));
    };
    return b;
}

// A switch: given, the member is true; echoed "--flag" where it is.
template <class Access>
SceneBinding toggle(std::string_view path, Access access) {
    SceneBinding b;
    b.path = path;
    b.add = [access](CLI::App& app, RenderJob& job, FlagSlot&, const std::string& flag,
                     const std::string& help) { return app.add_flag(flag, access(job), help); };
    b.echo = [path, access](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (access(job)) out.spaced(path, "");
    };
    return b;
}

// A word from a list: `name` writes the member's, `parse` reads one (throwing
// Error(BadInput) that names the field and the words it takes).
template <class Access, class Name, class Parse>
SceneBinding word(std::string_view path, Access access, Name name, Parse parse,
                  EchoWhen when = kUnlessDefault) {
    SceneBinding b;
    b.path = path;
    b.seed = [access, name](const RenderJob& job, FlagSlot& slot) {
        slot.text = name(access(job));
    };
    b.add = [](CLI::App& app, RenderJob&, FlagSlot& slot, const std::string& flag,
               const std::string& help) {
        return app.add_option(flag, slot.text, help)->capture_default_str();
    };
    b.apply = [access, parse](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        access(job) = parse(slot.text);
    };
    b.echo = [path, access, name, when](const RenderJob& job, const GeoreferenceFit&,
                                        CommandEcho& out) {
        if (echoed(job, access, when)) out.spaced(path, name(access(job)));
    };
    return b;
}

// How a vector reads: what the message says it expects, each component within `limit`
// (parseVectorFlag), and how it is echoed.
struct VectorText {
    const char* expected = "three numbers x,y,z";
    double limit = kMaxWorldCoordinate;
    bool joined = true;  // "--flag=x,y,z": a leading minus
};

// Three numbers x,y,z into a glm vector of float or double.
template <class Access>
SceneBinding vector(std::string_view path, Access access, VectorText text = {},
                    EchoWhen when = always) {
    SceneBinding b;
    b.path = path;
    b.seed = [access](const RenderJob& job, FlagSlot& slot) {
        slot.text = exactVectorText(access(job));
    };
    b.add = [](CLI::App& app, RenderJob&, FlagSlot& slot, const std::string& flag,
               const std::string& help) {
        return app.add_option(flag, slot.text, help)->capture_default_str();
    };
    b.apply = [path, access, text](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        using Vector = std::remove_reference_t<decltype(access(job))>;
        access(job) = Vector(
            parseVectorFlag(flagName(std::string(path)), slot.text, text.expected, text.limit));
    };
    b.echo = [path, access, text, when](const RenderJob& job, const GeoreferenceFit&,
                                        CommandEcho& out) {
        if (!echoed(job, access, when)) return;
        if (text.joined)
            out.joined(path, exactVectorText(access(job)));
        else
            out.spaced(path, exactVectorText(access(job)));
    };
    return b;
}

// A flag whose text the slot holds, registered without a default to show (a file, a list).
CLI::Option* addText(CLI::App& app, RenderJob&, FlagSlot& slot, const std::string& flag,
                     const std::string& help) {
    return app.add_option(flag, slot.text, help);
}

// ---- The fields read specially ----

SceneBinding mapFile() {
    SceneBinding b;
    b.path = "map.file";
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        if (job.map.file) slot.text = job.map.file->string();
    };
    b.add = addText;
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        if (!slot.text.empty()) job.map.file = slot.text;
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (job.map.file) out.spaced("map.file", job.map.file->string());
    };
    return b;
}

// An image file, or "none"; not given, the default (the bundled map's own colours).
SceneBinding albedo() {
    SceneBinding b;
    b.path = "albedo";
    b.albedoOnly = true;
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        if (job.albedo.kind == AlbedoSource::Kind::File) slot.text = job.albedo.file.string();
        if (job.albedo.kind == AlbedoSource::Kind::None) slot.text = "none";
    };
    b.add = addText;
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        if (slot.text.empty()) return;
        job.albedo = slot.text == "none" ? AlbedoSource{AlbedoSource::Kind::None, {}}
                                         : AlbedoSource{AlbedoSource::Kind::File, slot.text};
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (job.albedo.kind == AlbedoSource::Kind::File)
            out.spaced("albedo", job.albedo.file.string());
        if (job.albedo.kind == AlbedoSource::Kind::None) out.spaced("albedo", "none");
    };
    return b;
}

// The mesh base's name for --base (ReliefDesc::onMesh): no row of the table of bases.
constexpr const char* kMeshBase = "mesh";

// --base and each base size's flag (the table of bases' fields: core/base/BaseType.h), and
// `mesh`, the mesh base, which has no sizes (its file is --mesh's).
SceneBinding base() {
    SceneBinding b;
    b.path = "base";
    b.keep = &GeoreferenceFit::keepBase;
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        slot.text = job.onMesh ? kMeshBase : baseName(job.base);
        for (const BaseSize& size : baseType(job.base).sizes)
            slot.sizes[size.field] = sizeText(size, job.base);
    };
    b.add = [](CLI::App& app, RenderJob&, FlagSlot& slot, const std::string& flag,
               const std::string& help) {
        std::string bases = help;
        for (const BaseType& type : baseTypes())
            bases += std::string(&type == &baseTypes().front() ? " " : ", ") + type.name + " (" +
                     type.summary + ")";
        bases += std::string(", ") + kMeshBase + " (the triangle mesh of " + flagName("mesh.file") +
                 "; microrelief-render only so far)";
        CLI::Option* option = app.add_option(flag, slot.text, bases)->capture_default_str();
        for (const std::string& field : baseSizeFields()) {
            // "Radius of the cylinder (default 0.3) or the sphere (default 0.5), world units"
            std::string text;
            int count = 1;
            for (const BaseType& type : baseTypes()) {
                for (const BaseSize& size : type.sizes) {
                    if (size.field != field) continue;
                    count = size.count;  // the same in every row (tests/batch: SceneFlags)
                    if (text.empty())
                        text = std::string(size.label) + (size.count == 3 ? " x,y,z" : "") +
                               " of the ";
                    else
                        text += " or the ";
                    text +=
                        std::string(type.name) + " (default " + sizeText(size, type.defaults) + ")";
                }
            }
            app.add_option(flagName(field), slot.sizes[field], text + ", world units")
                ->type_name(count == 1 ? "FLOAT" : "X,Y,Z");
        }
        return option;
    };
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        job.onMesh = slot.text == kMeshBase;
        std::vector<std::string> names;
        for (const BaseType& type : baseTypes()) names.emplace_back(type.name);
        names.emplace_back(kMeshBase);
        if (std::find(names.begin(), names.end(), slot.text) == names.end())
            throwBadInput("unknown " + flagName("base") + " '" + slot.text + "' (expected " +
                          joinWords(names, " or ") + ")");
        if (!job.onMesh) {
            job.base = parseBase(slot.text, slot.sizes);
            return;
        }
        for (const auto& [field, text] : slot.sizes)
            if (!text.empty())
                throwBadInput(flagName(field) + " does not apply to --base " + kMeshBase);
        job.base = BaseShape{};  // not drawn: the plane's defaults (core/scene/Scene.h)
    };
    // The default base goes without saying, but where it was chosen over a georeferenced
    // map's own (a global grid's ellipsoid).
    b.echo = [](const RenderJob& job, const GeoreferenceFit& fit, CommandEcho& out) {
        if (job.onMesh) {
            out.spaced("base", kMeshBase);
            return;
        }
        const BaseType& type = baseType(job.base);
        if (&type == &baseType(BaseShape{}) && !fit.keepBase) return;
        out.spaced("base", type.name);
        for (const BaseSize& size : type.sizes) {
            if (size.count == 1)
                out.spaced(size.field, sizeText(size, job.base));
            else
                out.joined(size.field, sizeText(size, job.base));
        }
    };
    return b;
}

// --mesh FILE: the mesh base's triangles (io/MeshFile.h reads them), echoed after --base mesh.
SceneBinding meshFile() {
    SceneBinding b;
    b.path = "mesh.file";
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        if (job.mesh.file) slot.text = job.mesh.file->string();
    };
    b.add = addText;
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        if (!slot.text.empty()) job.mesh.file = slot.text;
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (job.mesh.file) out.spaced("mesh.file", job.mesh.file->string());
    };
    return b;
}

std::string tilesText(glm::ivec2 tiles) {
    return std::to_string(tiles.x) + "," + std::to_string(tiles.y);
}

SceneBinding tiles() {
    SceneBinding b;
    b.path = "tiles";
    b.echoedBefore = "base";
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        if (job.tiles != glm::ivec2(1, 1)) slot.text = tilesText(job.tiles);
    };
    b.add = addText;
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        if (!slot.text.empty()) job.tiles = parseTiles(slot.text);
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (job.tiles != glm::ivec2(1, 1)) out.spaced("tiles", tilesText(job.tiles));
    };
    return b;
}

SceneBinding animation() {
    SceneBinding b;
    b.path = "animation";
    b.seed = [](const RenderJob& job, FlagSlot& slot) { slot.text = job.animation; };
    b.add = addText;
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        if (!slot.text.empty()) job.animation = slot.text;
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (!job.animation.empty()) out.spaced("animation", job.animation);
    };
    return b;
}

// The moment of an animation, only with one.
SceneBinding time() {
    SceneBinding b;
    b.path = "time";
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        if (!job.animation.empty()) slot.number = job.time;
    };
    b.add = [](CLI::App& app, RenderJob&, FlagSlot& slot, const std::string& flag,
               const std::string& help) { return app.add_option(flag, slot.number, help); };
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots& slots) {
        if (!slot.number) return;
        if (slots.at("animation").text.empty())
            throwBadInput(flagName("time") + " needs " + flagName("animation") + " NAME");
        job.time = *slot.number;
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (!job.animation.empty()) out.joined("time", exactNumber(job.time));
    };
    return b;
}

std::string sizeText(const RenderJob& job) {
    return std::to_string(job.width) + "x" + std::to_string(job.height);
}

SceneBinding size() {
    SceneBinding b;
    b.path = "size";
    b.seed = [](const RenderJob& job, FlagSlot& slot) { slot.text = sizeText(job); };
    b.add = [](CLI::App& app, RenderJob&, FlagSlot& slot, const std::string& flag,
               const std::string& help) {
        return app.add_option(flag, slot.text, help)->capture_default_str();
    };
    // Any side here; the scene states the limits, sides and pixels, in one message.
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        parseSizeFlag(slot.text, job.width, job.height, 1 << 30);
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        out.spaced("size", sizeText(job));
    };
    return b;
}

std::string modelText(const ModelTransform& model) {
    std::string rows;
    for (double value : model.rows()) rows += (rows.empty() ? "" : ",") + exactNumber(value);
    return rows;
}

SceneBinding model() {
    SceneBinding b;
    b.path = "model";
    b.keep = &GeoreferenceFit::keepModel;
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        if (!job.model.isIdentity()) slot.text = modelText(job.model);
    };
    b.add = addText;
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        if (slot.text.empty()) return;
        const std::vector<double> rows =
            parseNumberList(flagName("model"), slot.text, 12,
                            "12 numbers: a 3 x 4 matrix in rows, comma-separated");
        std::array<double, 12> m{};
        std::copy(rows.begin(), rows.end(), m.begin());
        job.model = ModelTransform::fromRows(m);
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (!job.model.isIdentity()) out.joined("model", modelText(job.model));
    };
    return b;
}

// The lights are checked in double, before they are stored in float (core/scene/Scene.h).
// One of the two: the point light, where there is one, else the direction (seeded only
// where it is not the default, so that a point light given over it is no second light).
SceneBinding lightDirection() {
    SceneBinding b;
    b.path = "shading.lightDirection";
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        if (!job.shading.lightPosition &&
            job.shading.lightDirection != ShadingOptions{}.lightDirection)
            slot.text = exactVectorText(job.shading.lightDirection);
    };
    b.add = addText;
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots&) {
        if (slot.text.empty()) return;
        const glm::dvec3 light = parseVectorFlag(flagName("shading.lightDirection"), slot.text);
        std::vector<FieldError> errors;
        checkDirection(errors, "shading.lightDirection", light);
        throwIfInvalid(errors);
        job.shading.lightDirection = glm::vec3(light);
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (!job.shading.lightPosition)
            out.joined("shading.lightDirection", exactVectorText(job.shading.lightDirection));
    };
    return b;
}

SceneBinding lightPosition() {
    SceneBinding b;
    b.path = "shading.lightPosition";
    b.seed = [](const RenderJob& job, FlagSlot& slot) {
        if (job.shading.lightPosition) slot.text = exactVectorText(*job.shading.lightPosition);
    };
    b.add = addText;
    b.apply = [](RenderJob& job, const FlagSlot& slot, const FlagSlots& slots) {
        if (slot.text.empty()) return;
        if (!slots.at("shading.lightDirection").text.empty())
            throwBadInput(flagName("shading.lightDirection") + " and " +
                          flagName("shading.lightPosition") + " are two lights: give one");
        const glm::dvec3 position = parseVectorFlag(flagName("shading.lightPosition"), slot.text,
                                                    "three numbers x,y,z", kMaxWorldPosition);
        std::vector<FieldError> errors;
        checkPoint(errors, "shading.lightPosition", position);
        throwIfInvalid(errors);
        job.shading.lightPosition = position;
    };
    b.echo = [](const RenderJob& job, const GeoreferenceFit&, CommandEcho& out) {
        if (job.shading.lightPosition)
            out.joined("shading.lightPosition", exactVectorText(*job.shading.lightPosition));
    };
    return b;
}

// The light size whenever it is not the default, shadows or not (a camera-file row that
// turns soft shadows on keeps the command line's), and always with soft shadows.
bool softOrChanged(const RenderJob& job) {
    return job.shading.shadows == ShadowMode::Soft ||
           job.shading.lightSizeDegrees != ShadingOptions{}.lightSizeDegrees;
}

// The step budget and what follows from it (MethodSettings::setSteps), for a budget in
// range (the scene refuses the rest, naming it).
SceneBinding steps() {
    SceneBinding b = number(MEMBER(method.steps));
    b.apply = [](RenderJob& job, const FlagSlot&, const FlagSlots&) {
        if (job.method.steps >= 1 && job.method.steps <= 65536)
            job.method.setSteps(job.method.steps);
    };
    return b;
}

// A binding whose flag, given, is kept over a georeferenced map's own (the member of
// GeoreferenceFit that says so).
SceneBinding kept(SceneBinding binding, bool GeoreferenceFit::*keep) {
    binding.keep = keep;
    return binding;
}

// A binding read just after `path`'s (SceneBinding::parsedAfter).
SceneBinding readAfter(std::string_view path, SceneBinding binding) {
    binding.parsedAfter = path;
    return binding;
}

// The bindings, in --help's order: SceneFlags::addMapAndCamera's, then addShading's. A plain
// setting is one line here, by its kind.
std::vector<SceneBinding> makeBindings() {
    const VectorText position{"three numbers x,y,z", kMaxWorldPosition};
    const VectorText colour{"three numbers r,g,b", kMaxWorldCoordinate, false};
    // clang-format off
    const auto method = [](auto& job) -> auto& { return job.method.method; };
    std::vector<SceneBinding> mapAndCamera{
        mapFile(),
        albedo(),
        number(MEMBER(map.load.channel)),
        toggle(MEMBER(map.load.normalize)),
        kept(number(MEMBER(heightScale), always), &GeoreferenceFit::keepHeightScale),
        readAfter("base", word(MEMBER(interpolation), interpolationName, parseInterpolation)),
        base(),
        meshFile(),
        tiles(),
        animation(),
        time(),
        vector(MEMBER(camera.eye), position),
        vector(MEMBER(camera.target), position),
        vector(MEMBER(camera.up)),
        number(MEMBER(camera.fovyDegrees), always),
        readAfter("shading.shadows", size()),
        readAfter("background", model()),
    };
    std::vector<SceneBinding> shading{
        lightDirection(),
        lightPosition(),
        word(MEMBER(shading.shadows), shadowModeName, parseShadowMode),
        number(MEMBER(shading.lightSizeDegrees), softOrChanged),
        readAfter("shading.view", word("method", method, methodName, parseMethod, always)),
        steps(),
        number(MEMBER(method.pixelError)),
        word(MEMBER(shading.view), debugViewName, parseDebugView, always),
        vector(MEMBER(background), colour, kUnlessDefault),
    };
    // clang-format on
    for (SceneBinding& b : shading) {
        b.group = FlagGroup::Shading;
        mapAndCamera.push_back(std::move(b));
    }
    return mapAndCamera;
}

#undef MEMBER

}  // namespace

std::string exactNumber(double value) {
    return exactText(value);
}

std::string exactVector(const glm::dvec3& v) {
    return exactVectorText(v);
}

void CommandEcho::spaced(std::string_view field, const std::string& value) {
    line += " " + flagName(std::string(field)) + (value.empty() ? "" : " " + shellQuote(value));
}

void CommandEcho::joined(std::string_view field, const std::string& value) {
    line += " " + flagName(std::string(field)) + "=" + value;
}

std::span<const SceneBinding> sceneBindings() {
    static const std::vector<SceneBinding> bindings = makeBindings();
    return bindings;
}

std::vector<std::string> sceneBindingGaps(std::span<const SceneField> rows,
                                          std::span<const SceneBinding> bindings) {
    std::vector<std::string> gaps;
    std::set<std::string_view> bound;
    for (const SceneBinding& b : bindings) {
        const auto row = std::find_if(rows.begin(), rows.end(),
                                      [&](const SceneField& r) { return r.path == b.path; });
        if (row == rows.end() || row->flag.empty())
            gaps.push_back(std::string(b.path) + ": a binding without a row that has a flag");
        if (!bound.insert(b.path).second) gaps.push_back(std::string(b.path) + ": bound twice");
    }
    for (const SceneField& row : rows)
        if (!row.flag.empty() && !bound.count(row.path))
            gaps.push_back(std::string(row.path) + ": a row with the flag " +
                           std::string(row.flag) + " and no binding");
    for (const SceneBinding& b : bindings) {
        if (!b.echoedBefore.empty() && !bound.count(b.echoedBefore))
            gaps.push_back(std::string(b.path) + ": echoed before " + std::string(b.echoedBefore) +
                           ", which has no binding");
        if (!b.parsedAfter.empty() && !bound.count(b.parsedAfter))
            gaps.push_back(std::string(b.path) + ": read after " + std::string(b.parsedAfter) +
                           ", which has no binding");
    }
    // Each read after another comes back to one read in its place (no cycle).
    for (const SceneBinding& b : bindings) {
        std::string_view after = b.parsedAfter;
        for (std::size_t step = 0; !after.empty() && step < bindings.size(); ++step) {
            const auto next = std::find_if(bindings.begin(), bindings.end(),
                                           [&](const SceneBinding& o) { return o.path == after; });
            after = next == bindings.end() ? std::string_view() : next->parsedAfter;
        }
        if (!after.empty()) gaps.push_back(std::string(b.path) + ": read after itself");
    }
    return gaps;
}

}  // namespace microrelief
