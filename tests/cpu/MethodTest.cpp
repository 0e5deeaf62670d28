// The methods as rows (MR_TRAITS_MAXMIP ... in shaders/microrelief/variants.glsl): the
// checks, names and messages follow the rows. The sets below are the published contract
// (docs/cli.md: which methods run where); a row that changes one changes this test too.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <set>
#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/core/scene/Method.h"

using namespace microrelief;

namespace {

constexpr Method kMethods[] = {Method::Multilevel, Method::Normal, Method::Offset,
                               Method::Steep,      Method::Pom,    Method::Relief,
                               Method::MaxMip,     Method::Cone,   Method::Rcsm};

std::set<std::string> methodsWhere(bool (*has)(Method)) {
    std::set<std::string> names;
    for (Method m : kMethods)
        if (has(m)) names.insert(methodName(m));
    return names;
}

// The message of what `run` throws, its fields as {path}, or "" where it throws nothing.
template <class F>
std::string refusal(F run) {
    try {
        run();
    } catch (const Error& e) {
        return e.message([](const std::string& field) { return "{" + field + "}"; });
    }
    return "";
}

}  // namespace

TEST(MethodRows, NamesReadBackAndAnUnknownNameListsThemAll) {
    for (Method m : kMethods) EXPECT_EQ(parseMethod(methodName(m)), m) << methodName(m);
    EXPECT_EQ(refusal([] { parseMethod("marching"); }),
              "unknown {method} 'marching' (expected multilevel, normal, offset, steep, pom, "
              "relief, maxmip, cone or rcsm)");
}

TEST(MethodRows, EachPredicateIsItsColumn) {
    using Names = std::set<std::string>;
    EXPECT_EQ(methodsWhere(methodHasSteps), (Names{"steep", "pom", "relief", "rcsm"}));
    EXPECT_EQ(methodsWhere(methodTracesTheSolid), (Names{"multilevel", "maxmip", "cone"}));
    EXPECT_EQ(methodsWhere(methodTakesTiles),
              (Names{"multilevel", "normal", "offset", "steep", "pom", "relief"}));
    EXPECT_EQ(methodsWhere([](Method m) { return methodRunsOnBase(m, BaseShape::sphere()); }),
              (Names{"multilevel", "maxmip", "pom", "relief"}));
    EXPECT_EQ(methodsWhere([](Method m) { return methodRunsOnBase(m, BaseShape{}); }).size(), 9u);
    // The tangent-frame peers are the curved ones that do not trace the solid.
    for (Method m : kMethods) {
        EXPECT_EQ(methodHas(m, MethodTrait::TangentFrame),
                  methodHas(m, MethodTrait::Curved) && !methodTracesTheSolid(m))
            << methodName(m);
    }
    // Each map texture beyond the samples is read by one method.
    EXPECT_TRUE(methodHas(Method::MaxMip, MethodTrait::MaxPyramid));
    EXPECT_TRUE(methodHas(Method::Cone, MethodTrait::ConeMap));
    EXPECT_TRUE(methodHas(Method::Rcsm, MethodTrait::RelaxedConeMap));
    EXPECT_TRUE(methodHas(Method::Offset, MethodTrait::OffRay));
    for (MethodTrait texture :
         {MethodTrait::MaxPyramid, MethodTrait::ConeMap, MethodTrait::RelaxedConeMap}) {
        EXPECT_EQ(std::count_if(std::begin(kMethods), std::end(kMethods),
                                [&](Method m) { return methodHas(m, texture); }),
                  1);
    }
}

TEST(MethodRows, RefusalsNameTheMethodsTheRowsAllow) {
    EXPECT_EQ(refusal([] { checkMethodSupportsBase(Method::Cone, BaseShape::sphere()); }),
              "{method} cone does not run on {base} sphere (curved bases take multilevel, pom, "
              "relief and maxmip)");
    EXPECT_EQ(refusal([] { checkMethodSupportsBase(Method::Cone, BaseShape{}); }), "");
    EXPECT_EQ(refusal([] { checkMethodSupportsTiles(Method::MaxMip, {2, 1}); }),
              "{method} maxmip does not take {tiles} (its quadtree is the map's own; "
              "multilevel, normal, offset, steep, pom and relief do)");
    EXPECT_EQ(refusal([] { checkMethodSupportsTiles(Method::Rcsm, {1, 3}); }),
              "{method} rcsm does not take {tiles} (its cone map is the map's own; "
              "multilevel, normal, offset, steep, pom and relief do)");
    EXPECT_EQ(refusal([] { checkMethodSupportsTiles(Method::Rcsm, {1, 1}); }), "");
    EXPECT_EQ(refusal([] { checkMethodSupportsTiles(Method::Pom, {4, 4}); }), "");
}
