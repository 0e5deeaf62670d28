// core_facts: what web/relief_core.js mirrors, as the C++ computes it, written as one JSON
// object on stdout for tests/web/relief_core_test.mjs (ctest web.core) to hold the
// browser's host core to: the table of bases (each row's name, kind, summary, sizes with
// their labels, defaults and refusals; for shapes of every row its name, frame, box and
// whether u wraps), the pyramids' level sizes, S and tops for floats at every binade's
// edges, and the traversal's budget. Floats are written as their bits, doubles with 17
// digits (each reads back as itself): the test compares exactly.
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <bit>

#include "microrelief/core/Error.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/base/ReliefExtent.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/scene/SceneFields.h"
#include "microrelief/core/trace/MultilevelTracer.h"
#include "microrelief/peers/MaxMipPyramid.h"

using namespace microrelief;

namespace {

std::string number(double x) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

std::string vec(const glm::dvec3& v) {
    return "[" + number(v.x) + "," + number(v.y) + "," + number(v.z) + "]";
}

std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

// A message with its fields named as the pages name them: a base size by its key (its flag
// without the dashes), "base" as itself.
std::string pagesMessage(const Error& e) {
    return e.message([](const std::string& field) {
        const std::string flag = sceneFieldFlag(field);
        return flag.empty() ? field : flag.substr(2);
    });
}

// The sizes of `shape` by its row's sizes: {"field": [numbers]}.
std::string sizesOf(const BaseType& type, const BaseShape& shape) {
    std::string out = "{";
    for (std::size_t k = 0; k < type.sizes.size(); ++k) {
        double numbers[3] = {};
        type.sizes[k].read(shape, numbers);
        out += (k ? "," : "") + quoted(type.sizes[k].field) + ":[";
        for (int i = 0; i < type.sizes[k].count; ++i) out += (i ? "," : "") + number(numbers[i]);
        out += "]";
    }
    return out + "}";
}

// `shape` as the pages would make it (its row's name and sizes) and what the C++ makes of it.
std::string shapeFacts(const BaseShape& shape) {
    const BaseType& type = baseType(shape);
    std::string out = "{\"name\":" + quoted(type.name) + ",\"sizes\":" + sizesOf(type, shape) +
                      ",\"wrapsU\":" + (shape.wrapsU() ? "true" : "false") +
                      ",\"frameScale\":" + vec(shape.frameScale()) + ",\"extents\":[";
    // Maps wider, taller and square; tops of 0, a fraction and more than the radius.
    const struct {
        int width, height;
        double maxHeight, heightScale;
    } cases[] = {{64, 64, 0.0, 0.1}, {300, 17, 0.75, 0.25}, {17, 300, 3.0, 0.9}, {1, 4097, 1.0, 1e-3}};
    for (std::size_t k = 0; k < std::size(cases); ++k) {
        const auto& c = cases[k];
        const ReliefExtent e = reliefExtent(c.width, c.height, c.maxHeight, c.heightScale, shape);
        out += std::string(k ? "," : "") + "{\"size\":[" + std::to_string(c.width) + "," +
               std::to_string(c.height) + "],\"maxHeight\":" + number(c.maxHeight) +
               ",\"heightScale\":" + number(c.heightScale) + ",\"min\":" + vec(e.min) +
               ",\"max\":" + vec(e.max) + ",\"top\":" + number(e.topHeight) + "}";
    }
    return out + "]}";
}

// Each of the row's sizes at `value` times `factors` (a vector's numbers each by its own).
BaseShape withSizes(const BaseType& type, double value, const glm::dvec3& factors) {
    BaseShape shape = type.defaults;
    for (const BaseSize& size : type.sizes) {
        const double numbers[3] = {value * factors.x, value * factors.y, value * factors.z};
        size.write(shape, numbers);
    }
    return shape;
}

void bases() {
    std::printf("\"bases\":[");
    const auto& table = baseTypes();
    for (std::size_t r = 0; r < table.size(); ++r) {
        const BaseType& type = table[r];
        std::printf("%s{\"name\":%s,\"kind\":%d,\"summary\":%s,\"sizes\":[", r ? "," : "",
                    quoted(type.name).c_str(), static_cast<int>(type.kind),
                    quoted(type.summary).c_str());
        for (std::size_t k = 0; k < type.sizes.size(); ++k)
            std::printf("%s{\"field\":%s,\"label\":%s,\"count\":%d}", k ? "," : "",
                        quoted(type.sizes[k].field).c_str(), quoted(type.sizes[k].label).c_str(),
                        type.sizes[k].count);
        std::printf("],\"defaults\":%s,\"shapes\":[%s,%s", sizesOf(type, type.defaults).c_str(),
                    shapeFacts(type.defaults).c_str(), shapeFacts(type.example).c_str());
        // Sizes other than the defaults; a vector's with two numbers equal in each place.
        for (const auto& [value, factors] : {std::pair{0.37, glm::dvec3(1.0, 1.7, 0.45)}, {2.5e3, {1.0, 1.0, 1.0}},
                                             {0.8, {1.0, 1.0, 1.3}}, {0.8, {1.0, 1.3, 1.0}}, {0.8, {1.3, 1.0, 1.0}}})
            std::printf(",%s", shapeFacts(withSizes(type, value, factors)).c_str());
        std::printf("]");
        // A size refused: each of the row's sizes at 0 and at -1 in turn, as validateBaseShape
        // names it.
        std::printf(",\"refusals\":[");
        bool first = true;
        for (const BaseSize& size : type.sizes) {
            for (const double bad : {0.0, -1.0}) {
                BaseShape shape = type.defaults;
                double numbers[3] = {};
                size.read(shape, numbers);
                numbers[size.count - 1] = bad;
                size.write(shape, numbers);
                try {
                    validateBaseShape(shape);
                    std::fprintf(stderr, "core_facts: %s with %s %g is not refused\n", type.name, size.field, bad);
                    std::exit(1);
                } catch (const Error& e) {
                    std::printf("%s{\"sizes\":%s,\"message\":%s}", first ? "" : ",",
                                sizesOf(type, shape).c_str(), quoted(pagesMessage(e)).c_str());
                    first = false;
                }
            }
        }
        std::printf("]}");
    }
    std::printf("],\"unknownBase\":");
    try {
        baseType(std::string_view("torus"));
        std::fprintf(stderr, "core_facts: the table has a torus\n");
        std::exit(1);
    } catch (const Error& e) {
        std::printf("{\"name\":\"torus\",\"message\":%s}", quoted(pagesMessage(e)).c_str());
    }
    // The sizes of every row, each field once (the page's size boxes and URL keys).
    std::printf(",\"baseSizeFields\":[");
    const std::vector<std::string> fields = baseSizeFields();
    for (std::size_t k = 0; k < fields.size(); ++k)
        std::printf("%s%s", k ? "," : "", quoted(fields[k].c_str()).c_str());
    std::printf("]");
}

std::string sizes(const std::vector<glm::ivec2>& levels) {
    std::string out = "[";
    for (std::size_t k = 0; k < levels.size(); ++k)
        out += (k ? ",[" : "[") + std::to_string(levels[k].x) + "," + std::to_string(levels[k].y) + "]";
    return out + "]";
}

void levels() {
    std::printf(",\"levels\":[");
    const int cases[][2] = {{1, 1}, {2, 1}, {1, 9}, {256, 256}, {257, 255}, {300, 17}, {4096, 3}, {1023, 1025}};
    for (std::size_t k = 0; k < std::size(cases); ++k) {
        const int w = cases[k][0], h = cases[k][1];
        std::printf("%s{\"size\":[%d,%d],\"windows\":%s,\"maxMip\":%s,\"budget\":%d}", k ? "," : "", w, h,
                    sizes(windowLevelSizes(w, h)).c_str(), sizes(maxMipLevelSizes(w, h)).c_str(),
                    traversalBudget(w, h));
    }
    std::printf("]");
}

// Floats at every binade's edges (and the subnormals', zero's and the largest finite's):
// S, the top, and the S a build starts from, both as MaxPyramid::build writes it and as
// ReliefTextures writes it before a GPU build.
void scales() {
    std::printf(",\"scales\":[");
    const std::uint32_t mantissas[] = {0, 1, 0x1000, 0x1fff, 0x2000, 0x2001, 0x400000, 0x7fe000, 0x7fe001, 0x7fffff};
    bool first = true;
    for (std::uint32_t exponent = 0; exponent < 255; ++exponent) {
        for (const std::uint32_t mantissa : mantissas) {
            const std::uint32_t bits = exponent << 23 | mantissa;
            const float x = std::bit_cast<float>(bits);
            const int s = pyramidScaleExponent(x);
            const int fromTop = pyramidScaleExponent(pyramidTop(x));
            const int fromStored =
                pyramidScaleExponent(storedBound(x, BoundPrecision::Half, pyramidScaleExponent(x)));
            std::printf("%s[%" PRIu32 ",%d,%" PRIu32 ",%d,%d]", first ? "" : ",", bits, s,
                        std::bit_cast<std::uint32_t>(pyramidTop(x)), fromTop, fromStored);
            first = false;
        }
    }
    std::printf("]");
}

}  // namespace

int main() {
    std::printf("{");
    bases();
    levels();
    scales();
    std::printf("}\n");
    return 0;
}
