// A triangle mesh as the mesh base holds it (docs/bases.md, "The mesh"): plain data, no GL
// and no file format. What io/MeshFile.h reads a file into, and what a host that has its
// own vertex buffers fills in itself.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace microrelief {

// One entry of positions, normals and texCoords a vertex; each triangle names three
// vertices. Positions are in the file's world units (its node transforms applied), normals
// unit length, texture coordinates OpenGL's: (0, 0) the bottom-left corner of the map's
// image, (1, 1) its top-right, repeating outside. Every triangle has a non-zero area.
struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> texCoords;
    std::vector<glm::uvec3> triangles;  // indices into the three arrays above

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return triangles.size(); }
};

}  // namespace microrelief
