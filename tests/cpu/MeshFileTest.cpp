// The mesh loader (io/MeshFile.h) against the contract of docs/bases.md, "The mesh": small
// OBJ and glTF files written here, each case's triangles, normals and texture coordinates
// as the contract gives them, each refusal's one line; and real meshes no one here made
// (Debian's assimp-testmodels).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/io/MeshFile.h"

using namespace microrelief;

namespace {

// Float data read back exactly or through one normalisation: 1e-6 is a few float ulps of 1.
constexpr float kTolerance = 1e-6f;

void writeText(const std::filesystem::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

// A triangle as its corners' positions and texture coordinates, for comparing meshes.
struct Corner {
    glm::vec3 position;
    glm::vec2 uv;
};
using Triangle = std::array<Corner, 3>;

std::vector<Triangle> trianglesOf(const TriangleMesh& mesh) {
    std::vector<Triangle> out;
    for (const glm::uvec3& t : mesh.triangles) {
        Triangle triangle;
        for (int i = 0; i < 3; ++i) triangle[i] = {mesh.positions[t[i]], mesh.texCoords[t[i]]};
        out.push_back(triangle);
    }
    return out;
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, const std::string& what) {
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(actual[i], expected[i], kTolerance) << what << ", component " << i;
}

void expectTriangles(const TriangleMesh& mesh, const std::vector<Triangle>& expected) {
    const std::vector<Triangle> actual = trianglesOf(mesh);
    ASSERT_EQ(actual.size(), expected.size());
    for (std::size_t t = 0; t < expected.size(); ++t) {
        for (int i = 0; i < 3; ++i) {
            const std::string what =
                "triangle " + std::to_string(t) + ", corner " + std::to_string(i);
            EXPECT_EQ(actual[t][i].position, expected[t][i].position) << what;
            EXPECT_NEAR(actual[t][i].uv.x, expected[t][i].uv.x, kTolerance) << what;
            EXPECT_NEAR(actual[t][i].uv.y, expected[t][i].uv.y, kTolerance) << what;
        }
    }
}

// The normal of the vertex at `position` (there must be exactly one such vertex).
glm::vec3 normalAt(const TriangleMesh& mesh, const glm::vec3& position) {
    std::vector<glm::vec3> found;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.positions[v] == position) found.push_back(mesh.normals[v]);
    EXPECT_EQ(found.size(), 1u) << "vertices at (" << position.x << ", " << position.y << ", "
                                << position.z << ")";
    return found.empty() ? glm::vec3(0.0f) : found[0];
}

// The loader's refusal of `file`: Error(BadInput), one line, naming the file first.
std::string refusal(const std::filesystem::path& file, const MeshLimits& limits = {}) {
    try {
        loadMeshFile(file, limits);
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_EQ(e.kind(), ErrorKind::BadInput) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
        return message;
    }
    ADD_FAILURE() << file << " was read";
    return {};
}

// ---- OBJ ----

TEST(MeshFile, ObjQuadIsFannedIntoTwoTrianglesWithItsTexCoords) {
    test::ScratchDir scratch;
    const auto file = scratch / "quad.obj";
    writeText(file,
              "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
              "vt 0.1 0.2\nvt 0.9 0.2\nvt 0.9 0.7\nvt 0.1 0.7\n"
              "f 1/1 2/2 3/3 4/4\n");
    const TriangleMesh mesh = loadMeshFile(file);
    expectTriangles(
        mesh,
        {{{{{0, 0, 0}, {0.1f, 0.2f}}, {{2, 0, 0}, {0.9f, 0.2f}}, {{2, 1, 0}, {0.9f, 0.7f}}}},
         {{{{0, 0, 0}, {0.1f, 0.2f}}, {{2, 1, 0}, {0.9f, 0.7f}}, {{0, 1, 0}, {0.1f, 0.7f}}}}});
    EXPECT_EQ(mesh.vertexCount(), 4u);
    // No normals in the file: the plane's, from the counter-clockwise corners.
    for (const glm::vec3& n : mesh.normals) expectNear(n, {0, 0, 1}, "normal");
}

// Assimp's aiProcess_Triangulate starts this quad's fan at its reflex corner (2, 1); the
// contract fans from the first corner, even where a triangle comes out turned over.
TEST(MeshFile, ObjConcaveQuadIsFannedFromItsFirstCorner) {
    test::ScratchDir scratch;
    const auto file = scratch / "arrow.obj";
    writeText(file,
              "v 0 0 0\nv 1 1 0\nv 2 0 0\nv 1 3 0\nvt 0 0\nvt 0.5 0.3\nvt 1 0\nvt 0.5 1\n"
              "f 1/1 2/2 3/3 4/4\n");
    expectTriangles(loadMeshFile(file),
                    {{{{{0, 0, 0}, {0, 0}}, {{1, 1, 0}, {0.5f, 0.3f}}, {{2, 0, 0}, {1, 0}}}},
                     {{{{0, 0, 0}, {0, 0}}, {{2, 0, 0}, {1, 0}}, {{1, 3, 0}, {0.5f, 1}}}}});
}

TEST(MeshFile, ObjPentagonIsFannedFromItsFirstCorner) {
    test::ScratchDir scratch;
    const auto file = scratch / "pentagon.obj";
    writeText(file,
              "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\n"
              "vt 0 0\nvt 0.5 0\nvt 0.75 0.25\nvt 0.25 0.5\nvt 0 0.25\n"
              "f 1/1 2/2 3/3 4/4 5/5\n");
    const Corner c0{{0, 0, 0}, {0, 0}}, c1{{2, 0, 0}, {0.5f, 0}}, c2{{3, 1, 0}, {0.75f, 0.25f}},
        c3{{1, 2, 0}, {0.25f, 0.5f}}, c4{{-1, 1, 0}, {0, 0.25f}};
    expectTriangles(loadMeshFile(file), {{c0, c1, c2}, {c0, c2, c3}, {c0, c3, c4}});
}

// Triangle A: (0,0,0), (1,0,0), (0,1,0), area 1/2, facing +z, its normals given (unnormalised,
// so normalised); triangle B: (0,0,0), (0,0,4), (1,0,0), area 2, facing +y, no normals, its
// first corner a second `v` line at the same place. At (0,0,0) and (1,0,0) B gets
// normalize(1/2 (0,0,1) + 2 (0,1,0)) = (0, 4, 1) / sqrt(17); plain averaging (what Assimp's
// aiProcess_GenSmoothNormals does) would give (0, 1, 1) / sqrt(2).
TEST(MeshFile, ObjNormalsAreComputedAreaWeightedAroundAPosition) {
    test::ScratchDir scratch;
    const auto file = scratch / "fold.obj";
    writeText(file,
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 4\nv 0 0 0\nvt 0 0\nvn 0 0 2\n"
              "f 1/1/1 2/1/1 3/1/1\n"
              "f 5/1 4/1 2/1\n");
    const TriangleMesh mesh = loadMeshFile(file);
    ASSERT_EQ(mesh.triangleCount(), 2u);
    const glm::vec3 weighted = glm::vec3(0, 4, 1) / std::sqrt(17.0f);
    for (int i = 0; i < 3; ++i) {
        const unsigned a = mesh.triangles[0][i], b = mesh.triangles[1][i];
        expectNear(mesh.normals[a], {0, 0, 1}, "given normal " + std::to_string(i));
        const glm::vec3 expected =
            mesh.positions[b] == glm::vec3(0, 0, 4) ? glm::vec3(0, 1, 0) : weighted;
        expectNear(mesh.normals[b], expected, "computed normal " + std::to_string(i));
    }
}

TEST(MeshFile, ObjTexCoordOfOneNumberHasVZero) {
    test::ScratchDir scratch;
    const auto file = scratch / "u.obj";
    // Each alone on its line, at its end, before a comment: Assimp 5.2 refuses all three.
    writeText(file,
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25\nvt 0.5 \r\nvt 0.75 # u only\n"
              "f 1/1 2/2 3/3\n");
    expectTriangles(loadMeshFile(file),
                    {{{{{0, 0, 0}, {0.25f, 0}}, {{1, 0, 0}, {0.5f, 0}}, {{0, 1, 0}, {0.75f, 0}}}}});
}

TEST(MeshFile, ObjZeroAreaTrianglesAreDroppedAfterTheFan) {
    test::ScratchDir scratch;
    const auto file = scratch / "collinear.obj";
    // The fan's first triangle (0,0,0), (1,0,0), (2,0,0) has no area; a second face is a
    // triangle whose corners are one point.
    writeText(file,
              "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nvt 0 0\nvt 0.5 0\nvt 1 0\nvt 1 1\n"
              "f 1/1 2/2 3/3 4/4\nf 1/1 1/2 1/3\n");
    const TriangleMesh mesh = loadMeshFile(file);
    expectTriangles(mesh, {{{{{0, 0, 0}, {0, 0}}, {{2, 0, 0}, {1, 0}}, {{2, 1, 0}, {1, 1}}}}});
    EXPECT_EQ(mesh.vertexCount(), 3u);  // the dropped triangles' corners are not kept
}

TEST(MeshFile, ObjZeroLengthNormalIsComputed) {
    test::ScratchDir scratch;
    const auto file = scratch / "zero-normal.obj";
    writeText(file,
              "v 0 0 0\nv 0 0 1\nv 0 1 0\nvt 0 0\nvn 0 0 0\nvn 3 0 0\n"
              "f 1/1/1 3/1/2 2/1/2\n");
    const TriangleMesh mesh = loadMeshFile(file);
    ASSERT_EQ(mesh.triangleCount(), 1u);
    // The triangle faces +x: corners (0,0,0), (0,1,0), (0,0,1) counter-clockwise seen from +x.
    expectNear(normalAt(mesh, {0, 0, 0}), {1, 0, 0}, "the zero normal, computed");
    expectNear(normalAt(mesh, {0, 0, 1}), {1, 0, 0}, "a given normal, normalised");
}

// ---- glTF ----

std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t group = 0;
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        for (std::size_t k = 0; k < 3; ++k)
            group = group << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k < 4; ++k)
            out += k <= n ? digits[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// A glTF asset of one mesh of one primitive, placed by `nodes` (node 0 the scene's root).
struct GltfAsset {
    std::vector<float> positions;  // x, y, z a vertex
    std::vector<float> normals;    // none where empty
    std::vector<float>
        texCoords;  // u, v a vertex (glTF's: v from the image's top); none where empty
    std::vector<std::uint32_t> indices;  // none where empty
    std::string nodes = R"([{"mesh": 0}])";
    std::string version = "2.0";
    int mode = 4;  // TRIANGLES

    // The JSON and the binary buffer; `uri` the buffer's (none in a .glb).
    std::string json(const std::string& bin, bool embed) const {
        std::ostringstream out;
        std::ostringstream attributes, views, accessors;
        std::size_t offset = 0;
        int count = 0;
        const auto add = [&](std::size_t bytes, int components, int type,
                             const std::string& extra) {
            static const char* kTypes[] = {"", "SCALAR", "VEC2", "VEC3"};
            views << (count ? "," : "") << R"({"buffer": 0, "byteOffset": )" << offset
                  << R"(, "byteLength": )" << bytes << "}";
            accessors << (count ? "," : "") << R"({"bufferView": )" << count
                      << R"(, "componentType": )" << type << R"(, "count": )"
                      << bytes / 4 / components << R"(, "type": ")" << kTypes[components] << "\""
                      << extra << "}";
            offset += bytes;
            return count++;
        };
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (std::size_t i = 0; i + 2 < positions.size(); i += 3) {
            lo = glm::min(lo, glm::vec3(positions[i], positions[i + 1], positions[i + 2]));
            hi = glm::max(hi, glm::vec3(positions[i], positions[i + 1], positions[i + 2]));
        }
        std::ostringstream bounds;
        bounds << R"(, "min": [)" << lo.x << "," << lo.y << "," << lo.z << R"(], "max": [)" << hi.x
               << "," << hi.y << "," << hi.z << "]";
        attributes << R"("POSITION": )" << add(positions.size() * 4, 3, 5126, bounds.str());
        if (!normals.empty())
            attributes << R"(, "NORMAL": )" << add(normals.size() * 4, 3, 5126, "");
        if (!texCoords.empty())
            attributes << R"(, "TEXCOORD_0": )" << add(texCoords.size() * 4, 2, 5126, "");
        std::string indexAccessor;
        if (!indices.empty())
            indexAccessor =
                R"(, "indices": )" + std::to_string(add(indices.size() * 4, 1, 5125, ""));
        out << R"({"asset": {"version": ")" << version
            << R"("}, "scene": 0, "scenes": [{"nodes": [0]}],)"
            << R"( "nodes": )" << nodes << R"(, "meshes": [{"primitives": [{"attributes": {)"
            << attributes.str() << "}" << indexAccessor << R"(, "mode": )" << mode << "}]}],"
            << R"( "buffers": [{"byteLength": )" << bin.size()
            << (embed ? R"(, "uri": "data:application/octet-stream;base64,)" + base64(bin) + "\""
                      : "")
            << R"(}], "bufferViews": [)" << views.str() << R"(], "accessors": [)" << accessors.str()
            << "]}";
        return out.str();
    }
    std::string bin() const {
        std::string out;
        const auto append = [&](const void* data, std::size_t bytes) {
            out.append(static_cast<const char*>(data), bytes);
        };
        append(positions.data(), positions.size() * 4);
        append(normals.data(), normals.size() * 4);
        append(texCoords.data(), texCoords.size() * 4);
        append(indices.data(), indices.size() * 4);
        return out;
    }
    void writeGltf(const std::filesystem::path& file) const { writeText(file, json(bin(), true)); }
    // The binary container (glTF 2.0, 4.4): header, JSON chunk padded with spaces, BIN chunk
    // padded with zeros.
    void writeGlb(const std::filesystem::path& file) const {
        std::string data = bin();
        std::string text = json(data, false);
        text.resize((text.size() + 3) / 4 * 4, ' ');
        data.resize((data.size() + 3) / 4 * 4, '\0');
        std::string out;
        const auto word = [&](std::uint32_t w) {
            out.append(reinterpret_cast<const char*>(&w), 4);
        };
        word(0x46546C67);  // "glTF"
        word(2);
        word(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + data.size()));
        word(static_cast<std::uint32_t>(text.size()));
        word(0x4E4F534A);  // "JSON"
        out += text;
        word(static_cast<std::uint32_t>(data.size()));
        word(0x004E4942);  // "BIN\0"
        out += data;
        writeText(file, out);
    }
};

// One triangle in the z = 0 plane, its normals tilted (1, 0, 1) / sqrt(2) to see the inverse
// transpose, its texture coordinates as glTF has them.
GltfAsset tiltedTriangle() {
    GltfAsset asset;
    asset.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float h = std::sqrt(0.5f);
    asset.normals = {h, 0, h, h, 0, h, h, 0, h};
    asset.texCoords = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.625f};
    return asset;
}

// The parent node moves by (1, 2, 3), its child scales x by 2: positions (0,0,0), (1,0,0),
// (0,1,0) go to (1,2,3), (3,2,3), (1,3,3); the normal goes by the inverse transpose,
// diag(1/2, 1, 1): normalize(1/2, 0, 1) = (1, 0, 2) / sqrt(5); v becomes 1 - v.
TEST(MeshFile, GltfNodeTransformsAndTheTexCoordOriginAreApplied) {
    test::ScratchDir scratch;
    GltfAsset asset = tiltedTriangle();
    asset.nodes =
        R"([{"translation": [1, 2, 3], "children": [1]}, {"scale": [2, 1, 1], "mesh": 0}])";
    const auto gltf = scratch / "placed.gltf", glb = scratch / "placed.glb";
    asset.writeGltf(gltf);
    asset.writeGlb(glb);
    for (const auto& file : {gltf, glb}) {
        SCOPED_TRACE(file.string());
        const TriangleMesh mesh = loadMeshFile(file);
        expectTriangles(mesh, {{{{{1, 2, 3}, {0.1f, 1 - 0.2f}},
                                 {{3, 2, 3}, {0.3f, 1 - 0.4f}},
                                 {{1, 3, 3}, {0.5f, 1 - 0.625f}}}}});
        for (const glm::vec3& n : mesh.normals)
            expectNear(n, glm::vec3(1, 0, 2) / std::sqrt(5.0f), "normal");
    }
}

// A node that mirrors x turns the triangle clockwise; its corners are swapped so that it
// faces its normals (which the inverse transpose keeps at +z).
TEST(MeshFile, GltfMirroringNodeKeepsTrianglesFacingTheirNormals) {
    test::ScratchDir scratch;
    GltfAsset asset = tiltedTriangle();
    asset.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    asset.nodes = R"([{"scale": [-1, 1, 1], "mesh": 0}])";
    const auto file = scratch / "mirrored.gltf";
    asset.writeGltf(file);
    const TriangleMesh mesh = loadMeshFile(file);
    ASSERT_EQ(mesh.triangleCount(), 1u);
    const glm::uvec3 t = mesh.triangles[0];
    const glm::vec3 facing = glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                        mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (int i = 0; i < 3; ++i) {
        expectNear(mesh.normals[t[i]], {0, 0, 1}, "normal");
        EXPECT_GT(glm::dot(facing, mesh.normals[t[i]]), 0.0f) << "corner " << i;
    }
}

TEST(MeshFile, GltfWithoutNormalsGetsThemComputedAndIndicesAreFollowed) {
    test::ScratchDir scratch;
    GltfAsset asset = tiltedTriangle();
    asset.normals.clear();
    asset.positions.insert(asset.positions.end(), {1, 1, 0});
    asset.texCoords.insert(asset.texCoords.end(), {0.7f, 0.8f});
    asset.indices = {0, 1, 2, 2, 1, 3};
    const auto file = scratch / "indexed.gltf";
    asset.writeGltf(file);
    const TriangleMesh mesh = loadMeshFile(file);
    expectTriangles(
        mesh,
        {{{{{0, 0, 0}, {0.1f, 0.8f}}, {{1, 0, 0}, {0.3f, 0.6f}}, {{0, 1, 0}, {0.5f, 0.375f}}}},
         {{{{0, 1, 0}, {0.5f, 0.375f}}, {{1, 0, 0}, {0.3f, 0.6f}}, {{1, 1, 0}, {0.7f, 0.2f}}}}});
    EXPECT_EQ(mesh.vertexCount(), 4u);  // shared as the file shares them
    for (const glm::vec3& n : mesh.normals) expectNear(n, {0, 0, 1}, "normal");
}

// Strips and fans (glTF 2.0, 3.7.2.1) become triangles that keep one winding: a strip's
// second triangle is (1, 3, 2), a fan's (0, 2, 3), all facing +z here.
TEST(MeshFile, GltfStripsAndFansAreTriangles) {
    test::ScratchDir scratch;
    struct Case {
        const char* name;
        int mode;
        std::vector<float> positions;
        std::array<std::array<glm::vec3, 3>, 2> triangles;  // each from any corner
    };
    const glm::vec3 p0(0, 0, 0), p1(1, 0, 0), p2(0, 1, 0), p3(1, 1, 0), q3(-1, 1, 0);
    const Case cases[] = {
        {"strip", 5, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, {{{p0, p1, p2}, {p1, p3, p2}}}},
        {"fan", 6, {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 1, 0}, {{{p0, p1, p2}, {p0, p2, q3}}}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        GltfAsset asset;
        asset.mode = c.mode;
        asset.positions = c.positions;
        asset.texCoords = {0, 0, 1, 0, 0, 1, 1, 1};
        const auto file = scratch / (std::string(c.name) + ".gltf");
        asset.writeGltf(file);
        const TriangleMesh mesh = loadMeshFile(file);
        ASSERT_EQ(mesh.triangleCount(), 2u);
        for (int t = 0; t < 2; ++t) {
            std::array<glm::vec3, 3> corners;
            for (int i = 0; i < 3; ++i) corners[i] = mesh.positions[mesh.triangles[t][i]];
            // The same cycle of corners, whichever comes first.
            const auto& expected = c.triangles[t];
            const int first =
                int(std::find(corners.begin(), corners.end(), expected[0]) - corners.begin());
            ASSERT_LT(first, 3) << "triangle " << t;
            for (int i = 0; i < 3; ++i)
                EXPECT_EQ(corners[(first + i) % 3], expected[i]) << "triangle " << t;
        }
        for (const glm::vec3& n : mesh.normals) expectNear(n, {0, 0, 1}, "normal");
    }
}

// ---- Refusals ----

TEST(MeshFile, RefusesWhatIsNotAMeshFile) {
    test::ScratchDir scratch;
    const auto folder = scratch / "folder.obj";
    std::filesystem::create_directory(folder);
    EXPECT_NE(refusal(folder).find("is a directory, not a mesh"), std::string::npos);
    const auto fifo = scratch / "fifo.obj";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_NE(refusal(fifo).find("is not a regular file"), std::string::npos);
    EXPECT_NE(refusal(scratch / "missing.obj").find("no such file"), std::string::npos);

    const auto picture = scratch / "picture.png";
    writeText(picture, "\x89PNG\r\n\x1a\n");
    EXPECT_NE(refusal(picture).find("not a mesh file this program reads (.obj, .gltf or .glb)"),
              std::string::npos);
    const auto empty = scratch / "empty.obj";
    writeText(empty, "");
    EXPECT_NE(refusal(empty).find("the file is empty"), std::string::npos);
    const auto text = scratch / "text.glb";
    writeText(text, "this is not a mesh\n");
    EXPECT_NE(refusal(text).find("not a mesh Assimp reads ("), std::string::npos);
    const auto utf16 = scratch / "utf16.obj";
    const char utf16Text[] = {'\xFE', '\xFF', 0, 'v', 0, ' ', 0, '0'};  // "v 0", a BOM first
    writeText(utf16, std::string(utf16Text, sizeof utf16Text));
    EXPECT_NE(refusal(utf16).find("not OBJ text in ASCII or UTF-8"), std::string::npos);
    const auto json = scratch / "other.gltf";
    writeText(json, R"({"a": 1})");
    EXPECT_NE(refusal(json).find("not a mesh Assimp reads ("), std::string::npos);

    const auto big = scratch / "big.obj";
    writeText(big, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    EXPECT_NE(
        refusal(big, {.maxFileBytes = 16}).find("bytes, more than the 16 a mesh file may have"),
        std::string::npos);
}

TEST(MeshFile, RefusesAMeshWithoutTexCoords) {
    test::ScratchDir scratch;
    const auto none = scratch / "none.obj";
    writeText(none, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(refusal(none).find(": no texture coordinates"), std::string::npos);
    const auto corner = scratch / "corner.obj";
    writeText(corner,
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1 2/1 3/1\nf 1/1 2//1 3/1\n");
    EXPECT_NE(refusal(corner).find(": line 7: a face corner without a texture coordinate"),
              std::string::npos);
    GltfAsset asset = tiltedTriangle();
    asset.texCoords.clear();
    const auto gltf = scratch / "none.gltf";
    asset.writeGltf(gltf);
    EXPECT_NE(refusal(gltf).find(": no texture coordinates"), std::string::npos);
}

TEST(MeshFile, RefusesDataThatIsNotFinite) {
    test::ScratchDir scratch;
    struct Case {
        const char* name;
        std::string obj;
        std::string message;
    };
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const Case cases[] = {
        {"position", "v nan 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n",
         ": positions that are not finite"},
        {"normal", triangle + "vt 0 0\nvn 0 inf 0\nf 1/1/1 2/1/1 3/1/1\n",
         ": normals that are not finite"},
        {"texcoord", triangle + "vt 0 0\nvt 0.5 NaN\nf 1/1 2/2 3/1\n",
         ": line 5: a texture coordinate that is not finite"},
        {"texcoord past float", triangle + "vt 1e39 0\nf 1/1 2/1 3/1\n",
         ": line 4: a texture coordinate that is not finite"},
        {"position past float", "v 1e39 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n",
         ": positions that are not finite"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const auto file = scratch / (std::string(c.name) + ".obj");
        writeText(file, c.obj);
        EXPECT_NE(refusal(file).find(c.message), std::string::npos) << refusal(file);
    }

    GltfAsset asset = tiltedTriangle();
    asset.texCoords[3] = std::numeric_limits<float>::quiet_NaN();
    const auto uv = scratch / "uv.gltf";
    asset.writeGltf(uv);
    EXPECT_NE(refusal(uv).find(": texture coordinates that are not finite"), std::string::npos)
        << refusal(uv);
    asset = tiltedTriangle();
    asset.positions[3] = 1e30f;
    asset.nodes = R"([{"scale": [1e30, 1, 1], "mesh": 0}])";
    const auto far = scratch / "far.gltf";
    asset.writeGltf(far);
    EXPECT_NE(refusal(far).find(": positions that are not finite after a node's transform"),
              std::string::npos);
}

TEST(MeshFile, RefusesAMeshWithoutTriangles) {
    test::ScratchDir scratch;
    const auto lines = scratch / "lines.obj";
    writeText(lines, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nl 1/1 2/1 3/1\n");
    EXPECT_NE(refusal(lines).find(": no triangles in it"), std::string::npos);
    const auto flat = scratch / "flat.obj";
    writeText(flat, "v 0 0 0\nv 1 0 0\nv 2 0 0\nvt 0 0\nf 1/1 2/1 3/1\nf 3/1 2/1 1/1\n");
    EXPECT_NE(refusal(flat).find(": every triangle has zero area"), std::string::npos);
}

TEST(MeshFile, RefusesMoreTrianglesThanTheLimit) {
    test::ScratchDir scratch;
    // A million triangles (the issue's bad mesh), every face the same: counted from the
    // text, refused before Assimp reads it.
    const auto million = scratch / "million.obj";
    {
        std::ofstream out(million, std::ios::binary);
        out << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n";
        for (int i = 0; i < 1000000; ++i) out << "f 1/1 2/1 3/1\n";
    }
    EXPECT_NE(refusal(million).find(": 524289 triangles or more, past the 524288 a mesh may have"),
              std::string::npos);

    // A million in a .glb, a million index triples over three vertices: counted from what
    // Assimp read.
    GltfAsset asset = tiltedTriangle();
    asset.indices.resize(3000000);
    for (std::size_t i = 0; i < asset.indices.size(); ++i) asset.indices[i] = i % 3;
    const auto glb = scratch / "million.glb";
    asset.writeGlb(glb);
    EXPECT_NE(refusal(glb).find(": 1000000 triangles or more, past the 524288"), std::string::npos);

    // Polygons count as their fans: a quad is two.
    const auto quad = scratch / "quad.obj";
    writeText(quad, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n");
    EXPECT_NE(refusal(quad, {.maxTriangles = 1}).find(": 2 triangles or more, past the 1"),
              std::string::npos);
    EXPECT_EQ(loadMeshFile(quad, {.maxTriangles = 2}).triangleCount(), 2u);
}

TEST(MeshFile, RefusesObjLinesAssimpWouldReadWrong) {
    test::ScratchDir scratch;
    const auto short_ = scratch / "short.obj";
    writeText(short_, "v 0 0 0\nv 1 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    EXPECT_NE(refusal(short_).find(": line 2: a position of 2 numbers (3, 4 or 6 are read"),
              std::string::npos);
    // The same on the first line after a UTF-8 byte order mark (which Assimp skips).
    const auto bom = scratch / "bom.obj";
    writeText(bom, "\xEF\xBB\xBFv 1 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 2/1 3/1 4/1\n");
    EXPECT_NE(refusal(bom).find(": line 1: a position of 2 numbers"), std::string::npos);
}

TEST(MeshFile, RefusesAVertexWhoseTrianglesCancel) {
    test::ScratchDir scratch;
    const auto sheet = scratch / "sheet.obj";
    writeText(sheet, "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1/1 3/1 2/1\n");
    EXPECT_NE(refusal(sheet).find(": no normal at (0.000000, 0.000000, 0.000000): the triangles"),
              std::string::npos)
        << refusal(sheet);
}

TEST(MeshFile, RefusesGltfOtherThan2) {
    test::ScratchDir scratch;
    GltfAsset asset = tiltedTriangle();
    asset.version = "3.0";
    const auto file = scratch / "future.gltf";
    asset.writeGltf(file);
    EXPECT_NE(refusal(file).find(": not a mesh Assimp reads ("), std::string::npos);
}

// ---- Real meshes no one here made: Debian's assimp-testmodels (scripts/setup.sh) ----

const std::filesystem::path kTestModels = "/usr/share/assimp/models";

// Every normal unit length, every texture coordinate and position finite, every triangle of
// non-zero area and its indices in range.
void expectWellFormed(const TriangleMesh& mesh) {
    ASSERT_EQ(mesh.normals.size(), mesh.vertexCount());
    ASSERT_EQ(mesh.texCoords.size(), mesh.vertexCount());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        EXPECT_NEAR(glm::length(mesh.normals[v]), 1.0f, kTolerance) << "vertex " << v;
        EXPECT_TRUE(std::isfinite(mesh.texCoords[v].x) && std::isfinite(mesh.texCoords[v].y));
    }
    for (const glm::uvec3& t : mesh.triangles) {
        ASSERT_TRUE(t.x < mesh.vertexCount() && t.y < mesh.vertexCount() &&
                    t.z < mesh.vertexCount());
        EXPECT_NE(glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                             mesh.positions[t.z] - mesh.positions[t.x]),
                  glm::vec3(0.0f));
    }
}

// zeroUvAreaTriangles: the triangles over which no relief of the map's shows (microrelief-
// render warns of them). Counted: three uvs at one point, on one line, on one line up to
// float's rounding (three points of v = 4 u - 0.1); not counted: a
// sliver of uv area 1e-6 of its sides' product (a thin triangle, still mapped), and a whole
// unit triangle. Seen red with the sine's bound at 0 (the rounded line not counted) and at
// 1e-5 (the sliver counted).
TEST(MeshFile, ZeroUvAreaTrianglesAreThoseOnAPointOrALine) {
    TriangleMesh mesh;
    const auto add = [&](glm::vec2 a, glm::vec2 b, glm::vec2 c) {
        const auto base = static_cast<unsigned>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        mesh.normals.insert(mesh.normals.end(), 3, glm::vec3(0, 0, 1));
        mesh.texCoords.insert(mesh.texCoords.end(), {a, b, c});
        mesh.triangles.push_back({base, base + 1, base + 2});
    };
    add({0.3f, 0.3f}, {0.3f, 0.3f}, {0.3f, 0.3f});  // one point
    EXPECT_EQ(zeroUvAreaTriangles(mesh), 1u);
    add({0.0f, 0.5f}, {1.0f, 0.5f}, {0.25f, 0.5f});  // one line
    add({0.1f, 0.3f}, {0.2f, 0.7f}, {0.3f, 1.1f});   // v = 4 u - 0.1, rounded to float
    EXPECT_EQ(zeroUvAreaTriangles(mesh), 3u);
    add({0.0f, 0.0f}, {1.0f, 0.0f}, {0.5f, 1e-6f});  // a sliver
    add({0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f});
    EXPECT_EQ(zeroUvAreaTriangles(mesh), 3u);
}

TEST(MeshFile, ReadsRealMeshes) {
    if (!std::filesystem::exists(kTestModels))
        GTEST_SKIP() << kTestModels << " is missing: Debian's assimp-testmodels (scripts/setup.sh)";
    // A textured spider exported by MilkShape 3D: 1368 triangles, a normal at every corner,
    // 56 of them with three distinct corners on a line (read here apart from the loader:
    // the file's triangles' first index of each corner).
    const TriangleMesh spider = loadMeshFile(kTestModels / "OBJ/spider.obj");
    expectWellFormed(spider);
    std::vector<glm::vec3> positions;
    std::size_t faces = 0, flat = 0;
    std::ifstream in(kTestModels / "OBJ/spider.obj");
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "v") {
            std::string x, y, z;
            words >> x >> y >> z;
            positions.emplace_back(std::stof(x), std::stof(y), std::stof(z));
        } else if (keyword == "f") {
            std::array<glm::dvec3, 3> p;
            for (glm::dvec3& corner : p) {
                std::string word;
                words >> word;
                corner = positions.at(std::stoul(word) - 1);
            }
            ++faces;
            flat += glm::cross(p[1] - p[0], p[2] - p[0]) == glm::dvec3(0.0);
        }
    }
    EXPECT_EQ(faces, 1368u);
    EXPECT_EQ(flat, 56u);
    EXPECT_EQ(spider.triangleCount(), faces - flat);

    // Khronos' BoxTextured: 12 triangles in a unit cube, the same in each container.
    const TriangleMesh box = loadMeshFile(kTestModels / "glTF2/BoxTextured-glTF/BoxTextured.gltf");
    expectWellFormed(box);
    EXPECT_EQ(box.triangleCount(), 12u);
    for (const glm::vec3& p : box.positions)
        for (int i = 0; i < 3; ++i) EXPECT_EQ(std::abs(p[i]), 0.5f);
    for (const auto* other : {"glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
                              "glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
        const TriangleMesh same = loadMeshFile(kTestModels / other);
        EXPECT_EQ(same.positions, box.positions) << other;
        EXPECT_EQ(same.normals, box.normals) << other;
        EXPECT_EQ(same.texCoords, box.texCoords) << other;
        EXPECT_EQ(same.triangles, box.triangles) << other;
    }
}

TEST(MeshFile, RefusesRealBadMeshes) {
    if (!std::filesystem::exists(kTestModels))
        GTEST_SKIP() << kTestModels << " is missing: Debian's assimp-testmodels (scripts/setup.sh)";
    EXPECT_NE(refusal(kTestModels / "glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb")
                  .find("that are not finite"),
              std::string::npos);
    EXPECT_NE(refusal(kTestModels / "glTF/BoxTextured-glTF/BoxTextured.gltf")
                  .find(": glTF 1.0; only glTF 2.0 is read"),
              std::string::npos);
    EXPECT_NE(refusal(kTestModels / "OBJ/box.obj").find(": no texture coordinates"),
              std::string::npos);
    EXPECT_NE(refusal(kTestModels / "OBJ/box_UTF16BE.obj").find(": not OBJ text in ASCII or UTF-8"),
              std::string::npos);
    EXPECT_NE(refusal(kTestModels / "OBJ/multiple_spaces.obj")
                  .find(": line 11: a face corner without a texture coordinate"),
              std::string::npos);
}

}  // namespace
