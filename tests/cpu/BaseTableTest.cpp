// The table of bases (core/base/BaseType.h): each row's name, sizes and defaults agree
// with the lookups built on them, and its geometry with its own BaseSurface: the object
// point it places over a map point reads back as that map point, and the relief's box holds
// every such point up to the top height.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "microrelief/core/Error.h"
#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/SceneFields.h"

using namespace microrelief;

namespace {

// A shape of the row other than its defaults: every size scaled by 1.3 (and the vector's
// numbers made unequal, so that the shape still goes by the row's name unless the row names
// only equal ones).
BaseShape resized(const BaseType& type) {
    BaseShape shape = type.defaults;
    for (const BaseSize& size : type.sizes) {
        double numbers[3] = {};
        size.read(shape, numbers);
        for (int i = 0; i < size.count; ++i) numbers[i] *= 1.3 + (type.names ? 0.0 : 0.1 * i);
        size.write(shape, numbers);
    }
    return shape;
}

}  // namespace

// A size's flag is its field's name (core/scene/SceneFields.h: sceneFieldFlag), and only
// the sizes of this table have one: a field of their form that no base has sets nothing,
// though a message may name it (isSceneField goes by the form alone).
TEST(BaseTable, OnlyItsSizesHaveFlags) {
    EXPECT_EQ(sceneFieldFlag("base.radius"), "--radius");
    EXPECT_EQ(sceneFieldFlag("base.radii"), "--radii");
    EXPECT_EQ(sceneFieldFlag("camera.eye"), "--eye");
    EXPECT_EQ(sceneFieldFlag("map.samples"), "");
    EXPECT_TRUE(isBaseSizeField("base.minorRadius"));
    EXPECT_EQ(sceneFieldFlag("base.minorRadius"), "");
}

TEST(BaseTable, NamesAndSizesAgreeWithTheLookups) {
    std::set<std::string> names;
    for (const BaseType& type : baseTypes()) {
        SCOPED_TRACE(type.name);
        EXPECT_TRUE(names.insert(type.name).second) << "two rows named " << type.name;
        EXPECT_EQ(&baseType(type.name), &type);
        EXPECT_EQ(parseBaseKind(type.name), type.kind);
        for (const BaseShape& shape : {type.defaults, type.example, resized(type)}) {
            EXPECT_EQ(shape.kind, type.kind);
            EXPECT_NO_THROW(validateBaseShape(shape));
        }
        // The example the viewer offers and a resized shape go by the row's name (the
        // ellipsoid's defaults, equal radii, go by the sphere's).
        EXPECT_EQ(baseName(type.example), type.name);
        EXPECT_EQ(baseName(resized(type)), type.name);
        for (const BaseSize& size : type.sizes) {
            EXPECT_TRUE(isBaseSizeField(size.field)) << size.field;
            EXPECT_TRUE(isSceneField(size.field)) << size.field;
            // A size whose first number is zero is refused, naming the field.
            BaseShape shape = resized(type);
            double numbers[3] = {};
            size.read(shape, numbers);
            numbers[0] = 0.0;
            size.write(shape, numbers);
            try {
                validateBaseShape(shape);
                ADD_FAILURE() << size.field << " 0 was taken";
            } catch (const Error& e) {
                // what() writes each field by its own name, without braces
                EXPECT_NE(std::string(e.what()).find(size.field), std::string::npos) << e.what();
            }
        }
    }
    EXPECT_EQ(baseTypes().front().kind, BaseKind::Plane);  // the scene's default base
    EXPECT_THROW(baseType("torus"), Error);
}

TEST(BaseTable, ObjectPointsReadBackAndLieInTheBox) {
    constexpr int kWidth = 48, kHeight = 32;
    constexpr double kMaxHeight = 0.7;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> x(0.0, kWidth), y(0.0, kHeight), h(0.0, kMaxHeight);
    for (const BaseType& type : baseTypes()) {
        for (const BaseShape& shape : {type.defaults, resized(type)}) {
            for (double s : {0.05, 0.4}) {
                SCOPED_TRACE(std::string(type.name) + " s " + std::to_string(s));
                const auto surface = type.makeSurface(shape, kWidth, kHeight, s, kMaxHeight);
                const glm::dvec3 lo = shape.boxMin(kWidth, kHeight, s * kMaxHeight);
                const glm::dvec3 hi = shape.boxMax(kWidth, kHeight, s * kMaxHeight);
                for (int k = 0; k < 500; ++k) {
                    // Away from the poles and the caps' rims, where X or Y is not defined.
                    const glm::dvec2 p(x(random), std::clamp(y(random), 0.01, kHeight - 0.01));
                    const double height = k < 20 ? kMaxHeight : h(random);
                    const glm::dvec3 object =
                        type.objectPoint(shape, kWidth, kHeight, s, p, height);
                    for (int axis = 0; axis < 3; ++axis) {
                        // The box is a bound: every surface point lies in it (rounding
                        // aside: a point on the top may round out by an ulp).
                        const double slack = 1e-12 * (hi[axis] - lo[axis]);
                        EXPECT_GE(object[axis], lo[axis] - slack) << "axis " << axis;
                        EXPECT_LE(object[axis], hi[axis] + slack) << "axis " << axis;
                    }
                    const FrameRay ray = surface->frameRay({object, {0.0, 0.0, 1.0}});
                    const glm::dvec3 back = surface->mapPoint(ray.origin);
                    EXPECT_NEAR(back.x, p.x, 1e-9 * kWidth);
                    EXPECT_NEAR(back.y, p.y, 1e-9 * kHeight);
                    EXPECT_NEAR(back.z, height, 1e-9);
                }
            }
        }
    }
}

// Every MR_BASE_* of variants.glsl is a kind the table has (BaseKind's enumerators and the
// kinds' geometry are generated from that list), and BaseShape's defaults, members and
// factories, are its rows' (BaseShape.h takes them from glsl::kBaseRows).
TEST(BaseTable, EveryKindHasItsRowAndBaseShapeTakesTheRowsDefaults) {
    for (const glsl::EnumMember& member : glsl::kBaseKindValues) {
        SCOPED_TRACE(member.name);
        BaseShape shape;
        shape.kind = static_cast<BaseKind>(member.value);
        EXPECT_EQ(static_cast<int>(baseType(shape).kind), member.value);
    }
    EXPECT_EQ(BaseShape{}, baseType("plane").defaults);
    EXPECT_EQ(BaseShape::plane(), baseType("plane").defaults);
    EXPECT_EQ(BaseShape::cylinder(), baseType("cylinder").defaults);
    EXPECT_EQ(BaseShape::ellipsoid(), baseType("ellipsoid").defaults);
    EXPECT_EQ(BaseShape::sphere(), baseType("sphere").defaults);
}
