// The table of base surfaces: one row a named base, holding what the library and the
// programs know of it beyond its traversal: its name, its sizes (the scene's base.* fields),
// its frame, box and texel size, the float limits' figures, and the factory of its
// BaseSurface. BaseShape's member functions, the scene's fields, the programs' flags, the
// viewer's list and sliders and the benchmark's --bases read the table instead of naming
// the bases (the plane and the curved bases still differ where their traversals do).
//
// A row is two halves. Its data (name, kind, summary, sizes, defaults, example, which shapes
// it names) is written once, as a `//@base` line and its `//@size` lines in
// shaders/microrelief/variants.glsl, which cmake/generate_contracts.py turns into
// glsl::kBaseRows (core/GlslConstants.h) for core/base/BaseTable.cpp and into kBaseRows
// (relief_layout.js) for the browser's hosts (web/relief_core.js). Its geometry (the
// functions below, and its GLSL file) is its kind's, written beside the kind's BaseSurface
// (core/base/CylinderSurface.cpp: cylinderGeometry()).
//
// Adding a base (docs/bases.md, "Adding a base"): a row of a kind the table has (another
// name for some ellipsoids) is its `//@base` lines alone. A new kind: its GLSL file defining
// the mr_base* set (shaders/microrelief/base_surface.glsl) with its line in that file's
// choice, one C++ file with its BaseSurface and its geometry (as core/base/
// CylinderSurface.cpp has: <name>Geometry()), its MR_BASE_* value and row in variants.glsl
// (BaseKind's enumerator and BaseTable.cpp's list of geometries are generated from it; its
// sizes' members in BaseShape and kShapeMembers where BaseShape has them not yet), and its
// frame and box in web/relief_core.js. The exact
// references the tests hold the traversal to (core/trace/CurvedReference.cpp) are written
// apart from the table on purpose: a check that read the row would repeat its mistakes.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "microrelief/core/base/BaseShape.h"

namespace microrelief {

class BaseSurface;

struct BaseShapeMember;  // core/base/BaseTable.cpp: the members of BaseShape a size sets

// One size of a base as the scene holds it: a field ("base.radius"; a program derives its
// flag from it) of `count` numbers (1, or 3 for a vector), each a positive length in world
// units, read from and written into a member of the shape.
struct BaseSize {
    const char* field;  // the scene's field, "base.radius"
    const char* label;  // what the viewer's slider says: "Radius"
    int count;          // 1, or 3 (x, y, z)
    // The member of BaseShape it is: `count` of its numbers, or one number for all three
    // (the sphere's radius sets the ellipsoid's radii).
    const BaseShapeMember* member;
    // Its `count` numbers of `shape`; `shape` with them.
    void read(const BaseShape& shape, double* numbers) const;
    void write(BaseShape& shape, const double* numbers) const;
};

// A row of the table. Every function takes a shape of the row's kind.
struct BaseType {
    // The row's data (variants.glsl's //@base line) and its kind's GLSL file: a kind's
    // geometry (core/base/CylinderSurface.cpp: cylinderGeometry()) leaves the data to
    // BaseTable.cpp, which fills it from the row.
    const char* name = nullptr;        // the scene's "base" (and --base): "plane", "sphere"
    BaseKind kind = BaseKind::Plane;   // the shader's MICRORELIEF_BASE
    const char* shaderFile = nullptr;  // the GLSL file base_surface.glsl chooses for `kind`
    const char* summary = nullptr;     // one line for --help: what the base is
    std::vector<BaseSize> sizes = {};
    // The shape a scene gets when it names the base and none of its sizes.
    BaseShape defaults = {};
    // A shape the viewer offers when the base is picked from its list: the defaults, or
    // sizes that show what the base is (an ellipsoid that is not a sphere).
    BaseShape example = {};
    // Whether the row names only the shapes of `kind` its sizes can give, a size of one
    // number setting a member of three (a sphere is the ellipsoid with equal radii: takes);
    // false: every shape of `kind` that no row with `names` takes (a row with `names` that
    // takes it wins wherever it sits: baseType(shape)).
    bool names = false;
    // Whether `shape`, of `kind`, is one the row's sizes can give: every member that a size
    // of one number sets has its numbers equal.
    bool takes(const BaseShape& shape) const;

    // World size of the canonical frame's unit along x, y, z (BaseShape::frameScale).
    glm::dvec3 (*frameScale)(const BaseShape& shape);
    // The largest corner of the relief's world-space box for a largest height `top`
    // (s max h), and whether the box is symmetric about the origin (else it starts at
    // y = 0, as the plane's does): BaseShape::boxMin / boxMax.
    glm::dvec3 (*boxMax)(const BaseShape& shape, int mapWidth, int mapHeight, double top);
    bool boxIsSymmetric;
    // The world size of a texel, the unit positions are compared in (BaseShape::texelSize).
    double (*texelSize)(const BaseShape& shape, int mapWidth, int mapHeight);
    // Texels per unit of the base's frame, the most over its axes (core/scene/FloatLimits).
    double (*texelsPerFrameUnit)(int mapWidth, int mapHeight);
    // The object size of a texel's shorter side where texels are smallest but for a
    // pole's shrinking ones (the equator of the smallest radius on an ellipsoid): what
    // core/scene/FloatLimits counts double's rounding of positions in.
    double (*shortestTexelSide)(const BaseShape& shape, int mapWidth, int mapHeight);
    // Whether the frame's unit can be far longer than the texels where the frame point is
    // largest, so that the frame's float rounding at the eye (|object coordinate| 2^-23
    // object units an axis) must be counted in shortestTexelSide too (FloatLimits, check
    // 4): an ellipsoid of radii 4e5, 0.5, 0.5 seen near its tip, where texels are 0.006
    // wide and the frame's x unit 4e5 (8 pixels' silhouettes wrong at 48 x 32, measured).
    // Not where the frame's axes are its texels' (the plane; the cylinder, whose axis
    // rounding moves a ray along texels as long as the frame's unit allows: a cylinder
    // 1e6 long seen near y = 4.5e5 is exact).
    bool frameStretchesPastTexels;
    // The least and the most length of the object-space normals the shader makes before
    // it normalises them, for height scale s and heights up to `maxHeight` (core/scene/
    // FloatLimits, check 3). The gradient is at most `maxHeight` map units a texel: the
    // samples lie in [0, max h], so a bilinear cell's slope, and the quadratic B-spline's
    // (a linear spline of the samples' differences), is at most max h a texel.
    std::pair<double, double> (*objectNormalRange)(const BaseShape& shape, int mapWidth,
                                                   int mapHeight, double s, double maxHeight);
    // The object-space point over map point (X, Y) (texels) at height h (map units) for
    // height scale s: the inverse of BaseSurface::mapPoint, in object space.
    glm::dvec3 (*objectPoint)(const BaseShape& shape, int mapWidth, int mapHeight, double s,
                              const glm::dvec2& mapPoint, double h);
    // Its BaseSurface, the CPU twin of its GLSL file (core/base/BaseSurface.h).
    std::unique_ptr<BaseSurface> (*makeSurface)(const BaseShape& shape, int mapWidth, int mapHeight,
                                                double heightScale, double maxHeight);
};

// The table, in the order --help and the viewer list the bases; the plane first (a scene's
// default base).
const std::vector<BaseType>& baseTypes();
// The row a shape goes by (its kind's rows, the first whose `names` takes it).
const BaseType& baseType(const BaseShape& shape);
// The row named `name`; throws Error(BadInput) for an unknown name, listing the names.
const BaseType& baseType(std::string_view name);
// The scene's base size fields of every row, each once, in the table's order.
std::vector<std::string> baseSizeFields();

}  // namespace microrelief
