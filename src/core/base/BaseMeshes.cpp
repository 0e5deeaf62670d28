#include "microrelief/core/base/BaseMeshes.h"

#include <cmath>
#include <numbers>

namespace microrelief {

namespace {

// Two triangles for each quad of a (columns + 1) x (rows + 1) vertex lattice, vertex (i, j) at
// j (columns + 1) + i: (k, up, right) and (right, up, up + 1).
void addQuads(TriangleMesh& mesh, int columns, int rows) {
    for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < columns; ++i) {
            const unsigned k = static_cast<unsigned>(j * (columns + 1) + i), right = k + 1,
                           up = k + static_cast<unsigned>(columns) + 1;
            mesh.triangles.push_back({k, up, right});
            mesh.triangles.push_back({right, up, up + 1});
        }
    }
}

}  // namespace

TriangleMesh planeGridMesh(int n, float a, float b, glm::vec2 uvOffset, glm::vec2 uvScale) {
    TriangleMesh mesh;
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const float u = static_cast<float>(i) / static_cast<float>(n),
                        v = static_cast<float>(j) / static_cast<float>(n);
            mesh.positions.push_back({(u - 0.5f) * a, 0.0f, (v - 0.5f) * b});
            mesh.normals.push_back({0.0f, 1.0f, 0.0f});
            mesh.texCoords.push_back(uvOffset + glm::vec2(u, v) * uvScale);
        }
    }
    addQuads(mesh, n, n);
    return mesh;
}

TriangleMesh cylinderTubeMesh(int around, int along, float radius, float length, bool inward) {
    TriangleMesh mesh;
    for (int j = 0; j <= along; ++j) {
        for (int k = 0; k <= around; ++k) {
            const double u = static_cast<double>(k) / around, v = static_cast<double>(j) / along;
            const double phi = 2.0 * std::numbers::pi * (u - 0.5);
            const glm::vec3 outward(static_cast<float>(std::sin(phi)), 0.0f,
                                    static_cast<float>(std::cos(phi)));
            const float y = static_cast<float>((1.0 - 2.0 * v) * 0.5 * length);
            mesh.positions.push_back({radius * outward.x, y, radius * outward.z});
            mesh.normals.push_back(inward ? -outward : outward);
            mesh.texCoords.push_back({static_cast<float>(u), static_cast<float>(v)});
        }
    }
    addQuads(mesh, around, along);  // facing out: u grows round +y, v down the axis
    return mesh;
}

}  // namespace microrelief
