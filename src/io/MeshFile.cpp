// Triangle meshes through Assimp, to the contract of docs/bases.md, "The mesh".
//
// What Assimp 5.2.5 (Debian 12) does otherwise, and what is done here instead (each seen on a
// small hand-written file; tests/cpu/MeshFileTest.cpp holds the loader to the contract):
// - aiProcess_Triangulate does not fan from the first corner: it starts a concave quad's fan
//   at the reflex corner and clips ears off larger polygons. Not used: faces come as the file
//   has them and are fanned here.
// - aiProcess_GenSmoothNormals averages the unit normals of the faces at a position without
//   their areas (faces of areas 1/2 and 2 at right angles: halfway between their normals, where
//   the contract's is 14 degrees from the larger face's), and aiProcess_GenNormals gives
//   each face its own normal. Neither is used: normals are computed here.
// - aiProcess_JoinIdenticalVertices merges corners; not used (nothing here needs it).
// - OBJ, which Assimp reads line by line (ObjFileParser.cpp): `vt u` alone is refused ("OBJ:
//   Invalid number of components"), so " 0" is appended to such a line before Assimp reads
//   the text; a texture coordinate of nan, inf or past float's range reads as 0, and a `v`
//   line of other than 3, 4 or 6 numbers is skipped (every later index then names another
//   position), and a face corner without a texture index gets (0, 0): all three are refused
//   here from the text, before Assimp reads it. Faces without normal indices get zero normals
//   (absent: computed here).
// - glTF 2.0: Assimp flips v itself (glTF2Importer.cpp: v' = 1 - v), as the contract wants;
//   it keeps node transforms in its node tree, applied here. glTF 1.0 files go to another
//   importer; refused.
#include "microrelief/io/MeshFile.h"

#include "CheckedImageInput.h"  // checkRegularFile, oneLine

#include <assimp/MemoryIOWrapper.h>
#include <assimp/commonMetaData.h>
#include <assimp/scene.h>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

enum class MeshFormat { Obj, Gltf };

std::string lowercase(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}


// The path, the extension and the size, before anything reads the file.
MeshFormat checkMeshPath(const std::filesystem::path& file, const std::string& name,
                         const MeshLimits& limits) {
    checkRegularFile(file, name, "a mesh");

    const std::string extension = lowercase(file.extension().string());
    MeshFormat format;
    if (extension == ".obj") {
        format = MeshFormat::Obj;
    } else if (extension == ".gltf" || extension == ".glb") {
        format = MeshFormat::Gltf;
    } else {
        throwBadInput(name + ": not a mesh file this program reads (.obj, .gltf or .glb)");
    }
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(file, ec);
    if (ec) throwBadInput(name + ": cannot read (" + ec.message() + ")");
    if (bytes == 0) throwBadInput(name + ": the file is empty (0 bytes)");
    if (bytes > limits.maxFileBytes) {
        throwBadInput(name + ": " + std::to_string(bytes) + " bytes, more than the " +
                      std::to_string(limits.maxFileBytes) + " a mesh file may have");
    }
    return format;
}

[[noreturn]] void refuseTriangleCount(const std::string& name, std::size_t count,
                                      const MeshLimits& limits) {
    throwBadInput(name + ": " + std::to_string(count) + " triangles or more, past the " +
                  std::to_string(limits.maxTriangles) + " a mesh may have");
}

// ---- OBJ: the text Assimp reads, with what it would read wrong refused or mended ----

// A word Assimp's OBJ reader counts as a number (ObjFileParser::getNumComponentsInDataDefinition:
// IsNumeric on the first character, or nan or inf).
bool isObjNumber(std::string_view word) {
    if (word.empty()) return false;
    const char c = word[0];
    if ((c >= '0' && c <= '9') || c == '-' || c == '+') return true;
    const std::string head = lowercase(std::string(word.substr(0, 3)));
    return head == "nan" || head == "inf";
}

// Whether a word Assimp reads as a number is a finite float (Assimp reads nan, inf and
// numbers past float's range as 0 in a texture coordinate). A word no number starts is left
// for Assimp to refuse; one past double's range either way is refused as not finite.
bool isFiniteFloat(std::string_view word) {
    if (!word.empty() && word[0] == '+') word.remove_prefix(1);  // from_chars takes no '+'
    double value = 0.0;
    const std::from_chars_result read =
        std::from_chars(word.data(), word.data() + word.size(), value);
    if (read.ec == std::errc::invalid_argument) return true;
    return read.ec == std::errc{} && std::isfinite(static_cast<float>(value));
}

// A face corner "v/vt", "v/vt/vn" has a texture index; "v" and "v//vn" do not.
bool cornerHasTexCoord(std::string_view corner) {
    const std::size_t slash = corner.find('/');
    return slash != std::string_view::npos && slash + 1 < corner.size() && corner[slash + 1] != '/';
}

struct ObjLine {
    std::size_t number = 0;               // of its first physical line, from 1
    std::vector<std::string_view> words;  // up to a comment ('#'), views into the text
    bool comment = false;                 // a comment has begun
};

// Calls `visit` with each logical line of `text` (a line ending in '\' continues, as Assimp's
// IOStreamBuffer joins them).
template <typename Visit>
void forEachObjLine(const std::string& text, Visit visit) {
    ObjLine line;
    std::size_t number = 1;
    std::size_t at = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;  // a UTF-8 BOM, as Assimp skips it
    while (at < text.size()) {
        const std::size_t newline = std::min(text.find('\n', at), text.size());
        std::size_t end = newline;
        if (end > at && text[end - 1] == '\r') --end;
        const bool continues = end > at && text[end - 1] == '\\';
        if (line.number == 0) line.number = number;
        const std::string_view content(text.data() + at, (continues ? end - 1 : end) - at);
        for (std::size_t w = 0; w < content.size() && !line.comment;) {
            const std::size_t start = content.find_first_not_of(" \t\f\v", w);
            if (start == std::string_view::npos) break;
            const std::size_t stop =
                std::min(content.find_first_of(" \t\f\v", start), content.size());
            line.comment = content[start] == '#';
            if (!line.comment) line.words.push_back(content.substr(start, stop - start));
            w = stop;
        }
        if (!continues) {
            if (!line.words.empty()) visit(line);
            line = ObjLine{};
        }
        at = newline + 1;
        ++number;
    }
    if (!line.words.empty()) visit(line);
}

// Reads the OBJ file's text and makes it what Assimp reads as the contract says (`vt u` gets
// " 0"), refusing what it would read wrong without a word and a file of too many triangles
// (counted from its face lines before Assimp allocates them).
std::string objTextForAssimp(const std::filesystem::path& file, const std::string& name,
                             const MeshLimits& limits) {
    std::ifstream in(file, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) throwBadInput(name + ": cannot read the file");
    // Assimp converts UTF-16 and UTF-32 to UTF-8 before it reads; the checks below read bytes.
    if (text.find('\0') != std::string::npos)
        throwBadInput(name + ": not OBJ text in ASCII or UTF-8 (a NUL byte: UTF-16, or binary)");

    std::vector<std::size_t> appendZeroAt;  // after the u of `vt u` lines
    std::size_t triangles = 0, texCoordLines = 0, faces = 0, cornerWithoutTexCoord = 0;
    forEachObjLine(text, [&](const ObjLine& line) {
        const std::string_view keyword = line.words[0];
        const auto numbers = std::count_if(line.words.begin() + 1, line.words.end(), isObjNumber);
        const auto at = [&] { return name + ": line " + std::to_string(line.number) + ": "; };
        if (keyword == "v" && numbers != 3 && numbers != 4 && numbers != 6) {
            throwBadInput(at() + "a position of " + std::to_string(numbers) +
                          " numbers (3, 4 or 6 are read; Assimp skips the line)");
        } else if (keyword == "vt") {
            ++texCoordLines;
            if (line.words.size() == 2 && numbers == 1)
                appendZeroAt.push_back(line.words[1].data() + line.words[1].size() - text.data());
            for (std::size_t w = 1; w < line.words.size(); ++w) {
                if (!isObjNumber(line.words[w])) continue;
                if (!isFiniteFloat(line.words[w]))
                    throwBadInput(at() + "a texture coordinate that is not finite");
            }
        } else if (keyword == "f") {
            ++faces;
            const std::size_t corners = line.words.size() - 1;
            if (corners >= 3) triangles += corners - 2;
            if (triangles > limits.maxTriangles) refuseTriangleCount(name, triangles, limits);
            for (std::size_t w = 1; w < line.words.size() && cornerWithoutTexCoord == 0; ++w)
                if (!cornerHasTexCoord(line.words[w])) cornerWithoutTexCoord = line.number;
        }
    });
    if (faces > 0 && texCoordLines == 0) throwBadInput(name + ": no texture coordinates");
    if (cornerWithoutTexCoord > 0) {
        throwBadInput(name + ": line " + std::to_string(cornerWithoutTexCoord) +
                      ": a face corner without a texture coordinate");
    }

    if (appendZeroAt.empty()) return text;
    std::string mended;
    mended.reserve(text.size() + 2 * appendZeroAt.size());
    std::size_t from = 0;
    for (const std::size_t at : appendZeroAt) {
        mended.append(text, from, at - from).append(" 0");
        from = at;
    }
    mended.append(text, from, std::string::npos);
    return mended;
}

// Serves the OBJ's text to Assimp under the file's own name and opens nothing else (its
// materials are not read).
class ObjTextSystem final : public Assimp::IOSystem {
public:
    ObjTextSystem(std::string path, const std::string& text)
        : path_(std::move(path)), text_(text) {}

    using Assimp::IOSystem::Exists;
    using Assimp::IOSystem::Open;
    bool Exists(const char* file) const override { return path_ == file; }
    char getOsSeparator() const override { return '/'; }
    Assimp::IOStream* Open(const char* file, const char* mode) override {
        if (path_ != file || std::string_view(mode).find_first_of("wa+") != std::string_view::npos)
            return nullptr;
        return new Assimp::MemoryIOStream(reinterpret_cast<const std::uint8_t*>(text_.data()),
                                          text_.size());
    }
    void Close(Assimp::IOStream* stream) override { delete stream; }

private:
    std::string path_;
    const std::string& text_;
};

// ---- Assimp's scene to the contract's mesh ----

glm::dmat4 toGlm(const aiMatrix4x4& m) {
    glm::dmat4 out;
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column) out[column][row] = m[row][column];
    return out;
}

// A part (an aiMesh) where a node places it.
struct PartInstance {
    const aiMesh* part;
    glm::dmat4 toWorld;
};

std::size_t fanTriangles(const aiMesh& part) {
    std::size_t count = 0;
    for (unsigned f = 0; f < part.mNumFaces; ++f)
        if (part.mFaces[f].mNumIndices >= 3) count += part.mFaces[f].mNumIndices - 2;
    return count;
}

// Every part with triangles, once for each node that places it, with the node's transform
// to the world; refuses past the triangle limit while it walks.
std::vector<PartInstance> placedParts(const aiScene& scene, const std::string& name,
                                      const MeshLimits& limits) {
    std::vector<std::size_t> trianglesOf(scene.mNumMeshes);
    for (unsigned m = 0; m < scene.mNumMeshes; ++m)
        trianglesOf[m] = fanTriangles(*scene.mMeshes[m]);

    std::vector<PartInstance> parts;
    std::size_t triangles = 0;
    std::vector<std::pair<const aiNode*, glm::dmat4>> stack;
    if (scene.mRootNode) stack.emplace_back(scene.mRootNode, glm::dmat4(1.0));
    while (!stack.empty()) {
        const auto [node, parentToWorld] = stack.back();
        stack.pop_back();
        const glm::dmat4 toWorld = parentToWorld * toGlm(node->mTransformation);
        for (unsigned i = 0; i < node->mNumMeshes; ++i) {
            const unsigned m = node->mMeshes[i];
            if (m >= scene.mNumMeshes || trianglesOf[m] == 0) continue;
            triangles += trianglesOf[m];
            if (triangles > limits.maxTriangles) refuseTriangleCount(name, triangles, limits);
            parts.push_back({scene.mMeshes[m], toWorld});
        }
        for (unsigned c = node->mNumChildren; c-- > 0;)
            stack.emplace_back(node->mChildren[c], toWorld);
    }
    if (parts.empty()) throwBadInput(name + ": no triangles in it");
    return parts;
}

bool isFinite(const aiVector3D& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A part's data as the file gives it, before anything uses it.
void checkPart(const aiMesh& part, const std::string& name) {
    const std::string which =
        part.mName.length > 0 ? std::string(" (part '") + part.mName.C_Str() + "')" : "";
    for (unsigned v = 0; v < part.mNumVertices; ++v) {
        if (!isFinite(part.mVertices[v]))
            throwBadInput(name + ": positions that are not finite" + which);
        if (part.mNormals && !isFinite(part.mNormals[v]))
            throwBadInput(name + ": normals that are not finite" + which);
    }
    if (!part.mTextureCoords[0]) throwBadInput(name + ": no texture coordinates" + which);
    for (unsigned v = 0; v < part.mNumVertices; ++v) {
        const aiVector3D& uv = part.mTextureCoords[0][v];
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
            throwBadInput(name + ": texture coordinates that are not finite" + which);
    }
    for (unsigned f = 0; f < part.mNumFaces; ++f)
        for (unsigned i = 0; i < part.mFaces[f].mNumIndices; ++i)
            if (part.mFaces[f].mIndices[i] >= part.mNumVertices)
                throwBadInput(name + ": a face with an index past its vertices" + which);
}

// The mesh as it is built: for each vertex, whether the file gave it a normal.
struct MeshBuilder {
    TriangleMesh mesh;
    std::vector<bool> normalGiven;
};

// Twice the triangle's area times its unit normal, in double from the float positions.
glm::dvec3 areaNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    return glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
}

void addPart(const PartInstance& instance, const std::string& name, MeshBuilder& out) {
    const aiMesh& part = *instance.part;
    // Normals go by the inverse transpose of the linear part: its cofactor matrix (columns
    // a1 x a2, a2 x a0, a0 x a1) times the determinant's sign, defined where it is singular.
    const glm::dmat3 linear(instance.toWorld);
    const double det = glm::determinant(linear);
    glm::dmat3 normalMatrix(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                            glm::cross(linear[0], linear[1]));
    if (det < 0.0) normalMatrix = -normalMatrix;

    std::vector<glm::vec3> world(part.mNumVertices);
    for (unsigned v = 0; v < part.mNumVertices; ++v) {
        const aiVector3D& p = part.mVertices[v];
        world[v] = glm::vec3(instance.toWorld * glm::dvec4(p.x, p.y, p.z, 1.0));
        if (!std::isfinite(world[v].x) || !std::isfinite(world[v].y) || !std::isfinite(world[v].z))
            throwBadInput(name + ": positions that are not finite after a node's transform");
    }

    constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> vertexOf(part.mNumVertices, kUnset);
    const auto vertex = [&](unsigned v) {
        if (vertexOf[v] != kUnset) return vertexOf[v];
        vertexOf[v] = static_cast<std::uint32_t>(out.mesh.positions.size());
        out.mesh.positions.push_back(world[v]);
        const aiVector3D& uv = part.mTextureCoords[0][v];
        out.mesh.texCoords.emplace_back(uv.x, uv.y);
        glm::dvec3 normal(0.0);
        if (part.mNormals) {
            const aiVector3D& n = part.mNormals[v];
            normal = normalMatrix * glm::dvec3(n.x, n.y, n.z);
        }
        const double length = glm::length(normal);
        const bool given = length > 0.0 && std::isfinite(length);
        out.mesh.normals.push_back(given ? glm::vec3(normal / length) : glm::vec3(0.0f));
        out.normalGiven.push_back(given);
        return vertexOf[v];
    };

    // A mirroring transform turns the triangles clockwise: swapping two corners keeps them
    // counter-clockwise in the world (glTF 2.0: the determinant of a node's transform decides
    // the winding).
    const bool mirrored = det < 0.0;
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
        const aiFace& face = part.mFaces[f];
        for (unsigned k = 1; k + 1 < face.mNumIndices; ++k) {  // the fan from the first corner
            std::array<unsigned, 3> c{face.mIndices[0], face.mIndices[k], face.mIndices[k + 1]};
            if (mirrored) std::swap(c[1], c[2]);
            if (areaNormal(world[c[0]], world[c[1]], world[c[2]]) == glm::dvec3(0.0)) continue;
            const std::uint32_t a = vertex(c[0]), b = vertex(c[1]);  // in the corners' order
            out.mesh.triangles.emplace_back(a, b, vertex(c[2]));
        }
    }
}

// A position as a key: its three floats' bits, -0 made +0.
struct PositionKey {
    std::array<std::uint32_t, 3> bits;
    explicit PositionKey(const glm::vec3& p)
        : bits{std::bit_cast<std::uint32_t>(p.x + 0.0f), std::bit_cast<std::uint32_t>(p.y + 0.0f),
               std::bit_cast<std::uint32_t>(p.z + 0.0f)} {}
    bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
    std::size_t operator()(const PositionKey& k) const {
        std::uint64_t h = 1469598103934665603ull;
        for (const std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
        return static_cast<std::size_t>(h);
    }
};

// Each vertex without a normal gets the normalised sum of area times unit normal over the
// triangles that use its position.
void computeAbsentNormals(MeshBuilder& out, const std::string& name) {
    TriangleMesh& mesh = out.mesh;
    struct Sum {
        glm::dvec3 areaNormals{0.0};
        double lengths = 0.0;
    };
    std::unordered_map<PositionKey, Sum, PositionHash> sums;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        if (!out.normalGiven[v]) sums.try_emplace(PositionKey(mesh.positions[v]));
    if (sums.empty()) return;

    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 n =
            areaNormal(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
        for (int i = 0; i < 3; ++i) {
            const auto it = sums.find(PositionKey(mesh.positions[t[i]]));
            if (it == sums.end()) continue;
            it->second.areaNormals += n;
            it->second.lengths += glm::length(n);
        }
    }
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        if (out.normalGiven[v]) continue;
        const Sum& sum = sums.at(PositionKey(mesh.positions[v]));
        const double length = glm::length(sum.areaNormals);
        // Each term's rounding is near 2^-52 of its length: a sum under 1e-9 of the lengths
        // has a direction that rounding may have chosen.
        if (!(length > 1e-9 * sum.lengths)) {
            const glm::vec3& p = mesh.positions[v];
            throwBadInput(
                name + ": no normal at (" + std::to_string(p.x) + ", " + std::to_string(p.y) +
                ", " + std::to_string(p.z) +
                "): the triangles around it face opposite ways; give normals in the file");
        }
        mesh.normals[v] = glm::vec3(sum.areaNormals / length);
    }
}

TriangleMesh meshFromScene(const aiScene& scene, const std::string& name,
                           const MeshLimits& limits) {
    const std::vector<PartInstance> parts = placedParts(scene, name, limits);
    for (const PartInstance& instance : parts) checkPart(*instance.part, name);
    MeshBuilder out;
    for (const PartInstance& instance : parts) addPart(instance, name, out);
    if (out.mesh.triangles.empty()) throwBadInput(name + ": every triangle has zero area");
    computeAbsentNormals(out, name);
    return std::move(out.mesh);
}

void checkGltfVersion(const aiScene& scene, const std::string& name) {
    aiString version;
    if (scene.mMetaData && scene.mMetaData->Get(AI_METADATA_SOURCE_FORMAT_VERSION, version) &&
        version.C_Str()[0] == '2')
        return;
    throwBadInput(name + ": glTF " +
                  (version.length > 0 ? version.C_Str() : std::string("of no version")) +
                  "; only glTF 2.0 is read");
}

}  // namespace

std::size_t zeroUvAreaTriangles(const TriangleMesh& mesh) {
    std::size_t count = 0;
    for (const glm::uvec3& t : mesh.triangles) {
        // In double: the float coordinates' differences exactly, the area to double's
        // rounding, far below the bound (which is float's: uvs far from 0 with edges of a
        // few of their ulps may fall either side of it, a warning's margin).
        const glm::dvec2 a = glm::dvec2(mesh.texCoords[t[1]]) - glm::dvec2(mesh.texCoords[t[0]]);
        const glm::dvec2 b = glm::dvec2(mesh.texCoords[t[2]]) - glm::dvec2(mesh.texCoords[t[0]]);
        const double area = std::abs(a.x * b.y - a.y * b.x);
        count += area <= std::ldexp(1.0, -20) * glm::length(a) * glm::length(b);
    }
    return count;
}

TriangleMesh loadMeshFile(const std::filesystem::path& file, const MeshLimits& limits) {
    const std::string name = file.string();
    const MeshFormat format = checkMeshPath(file, name, limits);
    try {
        std::string objText;  // outlives the importer, which reads it
        Assimp::Importer importer;
        if (format == MeshFormat::Obj) {
            objText = objTextForAssimp(file, name, limits);
            importer.SetIOHandler(new ObjTextSystem(name, objText));  // the importer owns it
        }
        // No post-processing: each step the contract needs is done here (see the top).
        const aiScene* scene = importer.ReadFile(name, 0);
        if (!scene) {
            throwBadInput(name + ": not a mesh Assimp reads (" +
                          oneLine(importer.GetErrorString()) + ")");
        }
        if (format == MeshFormat::Gltf) checkGltfVersion(*scene, name);
        return meshFromScene(*scene, name, limits);
    } catch (const std::bad_alloc&) {
        throwRuntime(name + ": not enough memory to read the mesh");
    }
}

}  // namespace microrelief
