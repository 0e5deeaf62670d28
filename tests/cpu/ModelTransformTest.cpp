// The model transform (core/scene/ModelTransform.h): --model's rows read back, what is refused,
// and that a ray taken into object space keeps its t.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "microrelief/core/Error.h"
#include "microrelief/core/scene/ModelTransform.h"

using namespace microrelief;

TEST(ModelTransform, RowsReadBackAndTheInverseUndoesThem) {
    const std::array<double, 12> rows = {0.7, 0.0,  0.7,  0.1, 0.0, 1.6,
                                         0.0, 0.05, -0.6, 0.0, 0.8, -2.0};
    const ModelTransform m = ModelTransform::fromRows(rows);
    EXPECT_EQ(m.rows(), rows);
    const glm::dvec3 p(0.3, -0.2, 0.9);
    const glm::dvec3 world = m.pointToWorld(p);
    EXPECT_NEAR(world.x, 0.7 * 0.3 + 0.7 * 0.9 + 0.1, 1e-15);
    EXPECT_NEAR(world.z, -0.6 * 0.3 + 0.8 * 0.9 - 2.0, 1e-15);
    const glm::dvec3 back = m.pointToObject(world);
    EXPECT_NEAR(glm::length(back - p), 0.0, 1e-14);
    EXPECT_FALSE(m.isIdentity());
    EXPECT_TRUE(ModelTransform().isIdentity());
}

TEST(ModelTransform, ARayKeepsItsParameterInObjectSpace) {
    const ModelTransform m(glm::rotate(glm::scale(glm::dmat4(1.0), glm::dvec3(2.0, 0.5, 1.5)), 0.7,
                                       glm::dvec3(1.0, 1.0, 0.0)));
    const Ray world{{1.0, 2.0, -3.0}, {-0.3, -0.5, 0.8}};
    const Ray object = m.toObject(world);
    for (double t : {0.0, 0.5, 3.0}) {
        const glm::dvec3 a = m.pointToObject(world.origin + t * world.direction);
        EXPECT_NEAR(glm::length(a - (object.origin + t * object.direction)), 0.0, 1e-13) << t;
    }
    // Normals go through the inverse transpose: a world normal stays square to a world
    // tangent that came from an object tangent square to the object normal.
    const glm::dvec3 n(0.0, 1.0, 0.0), tangent(1.0, 0.0, 0.3);
    const glm::dvec3 worldTangent = glm::dmat3(m.objectToWorld()) * tangent;
    EXPECT_NEAR(glm::dot(m.normalToWorld(n), worldTangent), 0.0, 1e-14);
}

TEST(ModelTransform, SingularNonAffineAndNonFiniteMatricesAreRefused) {
    glm::dmat4 flat(1.0);
    flat[1][1] = 0.0;  // squashes y
    EXPECT_THROW(ModelTransform{flat}, Error);
    glm::dmat4 projective(1.0);
    projective[2][3] = 0.5;
    EXPECT_THROW(ModelTransform{projective}, Error);
    glm::dmat4 nan(1.0);
    nan[3][0] = std::nan("");
    EXPECT_THROW(ModelTransform{nan}, Error);
    glm::dmat4 tiny(1.0);
    tiny[0][0] = 1e-14;  // condition 1e14
    EXPECT_THROW(ModelTransform{tiny}, Error);
    EXPECT_NO_THROW(ModelTransform(glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, 1e-3, 1e3))));
}

// Issue 25: a determinant of 1 is no singular matrix. An invertible but ill-conditioned one
// is called so, with its condition number; the scales FloatLimits bounds are exact for the
// identity and a diagonal.
TEST(ModelTransform, IllConditionedIsNotCalledSingularAndScalesAreKnown) {
    const auto message = [](const glm::dmat4& m) {
        try {
            ModelTransform{m};
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string stretched =
        message(glm::scale(glm::dmat4(1.0), glm::dvec3(1e7, 1e-7, 1.0)));  // determinant 1
    EXPECT_NE(stretched.find("ill-conditioned (condition number 1e+14"), std::string::npos)
        << stretched;
    EXPECT_EQ(stretched.find("singular"), std::string::npos) << stretched;
    glm::dmat4 flat(1.0);
    flat[2][2] = 0.0;
    EXPECT_NE(message(flat).find("singular"), std::string::npos);
    EXPECT_EQ(ModelTransform().largestScale(), 1.0);
    EXPECT_EQ(ModelTransform().smallestScale(), 1.0);
    const ModelTransform uneven(glm::scale(glm::dmat4(1.0), glm::dvec3(-2.0, 1e-3, 1e3)));
    EXPECT_NEAR(uneven.largestScale(), 1e3, 1e-9);
    EXPECT_NEAR(uneven.smallestScale(), 1e-3, 1e-15);
    // Sheared: the singular values of [[1, 1e3], [0, 1]] in x, y: 1e3 and 1e-3 (to 1e-6).
    glm::dmat4 sheared(1.0);
    sheared[1][0] = 1e3;
    const ModelTransform shear(sheared);
    EXPECT_NEAR(shear.largestScale() * shear.smallestScale(), 1.0, 1e-9);
    EXPECT_NEAR(shear.largestScale(), 1000.001, 1e-3);
}
