// microrelief-bench mesh: what the mesh base costs against the analytic base it can copy
// (issue 50's "Measured": at most 2x the plane's time for a mesh of up to 10k triangles).
// The same map, pixels and camera drawn as the plane base and as flat grids of n x n quads
// that are that plane exactly, and as the cylinder base and as tubes of S sides around that
// are it to their chords (core/base/BaseMeshes.h): each frame's time on the run's clock, the
// settings interleaved round by round (Timing.h) and each mesh's time over its base's paired
// by round; how far the two pictures agree (pixels hit by one only, and the common hits'
// distance in texels); and the texels each reads per pixel, counted by the CPU twins on the
// same rays (MultilevelTracer for the base; MeshTracer over every prism whose box the ray
// crosses, as each such prism's fragment runs on the GPU), on every `twinStride`-th pixel.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "Report.h"
#include "Timing.h"
#include "microrelief/gl/GlContext.h"

namespace microrelief::bench {

struct MeshBenchOptions {
    int width = 256, height = 256;  // the picture
    int frames = 10;                // rounds, each drawing every setting of a view once
    int mapSize = 256;              // benchRelief(mapSize), square, made seamless (Mesh.cpp)
    std::vector<int> gridQuads{1, 16, 64};  // flat grids of n x n quads: 2 n^2 triangles
    std::vector<int> tubeSides{32, 128};    // tubes of S sides and S / 4 rings: S^2 / 2 triangles
    std::vector<int> viewDegrees{20, 45, 70};
    int twinStride = 4;  // the CPU twins trace every 4th pixel of every 4th row
};

struct MeshBenchRow {
    std::string base;  // plane, cylinder
    int degrees = 0;
    std::string mesh;  // "grid 16x16", "tube 128x32"
    int triangles = 0, proxyTriangles = 0;
    double baseMs = 0.0, meshMs = 0.0;  // median frame on the clock
    Spread ratio;                       // mesh over base, paired by round
    int pixels = 0, baseHits = 0, hitMiss = 0;  // hit by one of the two pictures only
    double offsetMedian = 0.0, offsetMax = 0.0;  // common hits' distance, texels
    double baseFetches = 0.0, meshFetches = 0.0, prisms = 0.0;  // per pixel traced by the twins
    int twinPixels = 0;
};

// Runs every view of the plane and its grids, then of the cylinder and its tubes, timing
// frames on `clock` (Report.h's resolveClock: not Auto). `report` is called after each row.
void runMeshBench(GlContext& context, const MeshBenchOptions& options, Clock clock,
                  const std::function<void(const MeshBenchRow&)>& report);

// mesh.csv, a row each, written whole or not at all.
void writeMeshCsv(const std::filesystem::path& file, const std::string& renderer, Clock clock,
                  const std::vector<MeshBenchRow>& rows);
// The same as a Markdown table, returned.
std::string meshTable(const std::string& renderer, Clock clock,
                      const std::string& date, const MeshBenchOptions& options,
                      const std::vector<MeshBenchRow>& rows);

}  // namespace microrelief::bench
