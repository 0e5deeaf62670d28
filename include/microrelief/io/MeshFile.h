// Triangle meshes from OBJ and glTF 2.0 files, through Assimp (the microrelief::io
// component), to the contract of docs/bases.md, "The mesh":
//
// - OBJ (.obj): polygons fan-triangulated from their first corner; `vt u` alone is v = 0;
//   every face corner needs a texture coordinate; materials (.mtl) are not read.
// - glTF 2.0 (.gltf, .glb): every triangle primitive (strips and fans too) of every node of
//   the scene, each node's transform applied (normals by its inverse transpose, the corners
//   of a mirrored node's triangles swapped so that they stay counter-clockwise, as glTF's
//   spec says); glTF's top-left texture origin converted to OpenGL's bottom-left: v' = 1 - v.
// - Either: triangles of zero world area dropped (after the fan triangulation); a normal of
//   zero length counts as absent, the others are normalised; where a vertex has no normal it
//   gets the normalised sum, over all triangles that use its position (an equal world
//   position, in any part of the file), of the triangle's area times its unit normal.
//
// What Assimp 5.2 (Debian 12) does otherwise and this loader does itself is listed in
// src/io/MeshFile.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "microrelief/core/base/TriangleMesh.h"

namespace microrelief {

// At most 2^19 = 524,288 triangles, counted after the fan triangulation and before triangles
// of zero area are dropped. The mesh base is for an object an engine draws as one piece: the
// issue that made it (50) sets its performance target at 10k triangles and names a mesh of a
// million triangles as one to refuse. Every triangle is a prism that the renderer covers with
// a hull and the traversal, the CPU twin and the exact reference walk into; 2^19 is fifty
// times the target, the largest power of two under a million, and its corners' data
// (positions, normals, texture coordinates: 96 bytes a triangle) about 50 MB. An OBJ is
// counted from its face lines before Assimp reads it; a glTF after Assimp has read it (its
// counts are in its JSON, which only Assimp parses), before this loader allocates anything.
inline constexpr std::size_t kMaxMeshTriangles = std::size_t{1} << 19;

// At most 512 MiB in the file, refused before Assimp reads it (Assimp holds the whole file
// and its own copy of every vertex). An OBJ with kMaxMeshTriangles triangles and a position,
// texture coordinate and normal of its own at every corner is about 200 MB of text; a .glb
// may add its embedded textures.
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{1} << 29;

struct MeshLimits {
    std::size_t maxTriangles = kMaxMeshTriangles;
    std::uintmax_t maxFileBytes = kMaxMeshFileBytes;
};

// Reads an OBJ (.obj) or glTF 2.0 (.gltf, .glb) file, by its extension in any case. Throws
// Error(BadInput), one line naming the file and the reason, for: a path that is not a regular
// file, an empty file or one past limits.maxFileBytes, another extension, a file Assimp
// cannot read (Assimp's reason in the message), glTF 1.0, OBJ text with a NUL byte (UTF-16 or
// binary: the OBJ checks read ASCII or UTF-8), an OBJ line Assimp 5.2 would read
// wrong without a word (a position of other than 3, 4 or 6 numbers, which it skips, so that
// every later index names the wrong position; a texture coordinate that is not finite,
// which it reads as 0), a face corner or part without texture coordinates, positions,
// normals or texture coordinates that are not finite (in the file or after a node's
// transform), an index past its part's vertices, more than limits.maxTriangles triangles, no
// triangle of non-zero area, and a vertex without a normal whose triangles' normals cancel
// (their sum under 1e-9 of their summed lengths: its direction would be rounding's).
// Error(Runtime) naming the file when memory runs out.
TriangleMesh loadMeshFile(const std::filesystem::path& file, const MeshLimits& limits = {});

// How many of `mesh`'s triangles have zero area in texture space: their three texture
// coordinates on one point or one line (|(T1 - T0) x (T2 - T0)| at most 2^-20 of
// |T1 - T0| |T2 - T0|, the sine of their angle below what float coordinates tell from
// zero). Over such a triangle the map is read at one point or along one line: one height,
// or stripes, and no relief of the map's shows (a file with one `vt` for every corner has
// them all). loadMeshFile reads them as the contract says; microrelief-render warns.
std::size_t zeroUvAreaTriangles(const TriangleMesh& mesh);

}  // namespace microrelief
