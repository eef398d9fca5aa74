#pragma once
// Shared meshes for the BVH and SDF tests: an icosphere, a minimal OBJ reader and the path of the
// Max Planck head in the test assets.

#include "sim/geometry/TriangleMesh.h"

#include "../SharedAssets.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace wisp::test {

// An icosphere: the icosahedron with every triangle split in four `subdivisions` times, corners
// pushed onto the sphere. Counter-clockwise seen from outside; 20 * 4^subdivisions triangles.
inline TriangleMesh makeIcosphere(float radius, int subdivisions)
{
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    TriangleMesh m;
    m.positions = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t }, { 0, 1, t }, { 0, -1, -t },
        { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 }, { -t, 0, 1 } };
    m.triangles = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 },
        { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 },
        { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<unsigned, unsigned>, unsigned> midpoints;
        auto midpoint = [&](unsigned a, unsigned b) {
            const auto key = std::minmax(a, b);
            if (auto it = midpoints.find(key); it != midpoints.end())
                return it->second;
            m.positions.push_back(0.5f * (m.positions[a] + m.positions[b]));
            const auto index = static_cast<unsigned>(m.positions.size() - 1);
            midpoints.emplace(key, index);
            return index;
        };
        std::vector<glm::uvec3> next;
        next.reserve(4 * m.triangles.size());
        for (const glm::uvec3& tri : m.triangles) {
            const unsigned ab = midpoint(tri.x, tri.y), bc = midpoint(tri.y, tri.z), ca = midpoint(tri.z, tri.x);
            next.push_back({ tri.x, ab, ca });
            next.push_back({ tri.y, bc, ab });
            next.push_back({ tri.z, ca, bc });
            next.push_back({ ab, bc, ca });
        }
        m.triangles = std::move(next);
    }
    for (glm::vec3& p : m.positions)
        p = radius * glm::normalize(p);
    return m;
}

// The mesh in an OBJ file, positions multiplied by `scale`. Just enough OBJ for the test assets:
// "v x y z" and "f a b c ..." (also "a/b/c"), 1-based indices. An empty mesh when the file cannot
// be read.
inline TriangleMesh readObj(const std::filesystem::path& path, float scale)
{
    TriangleMesh mesh;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        std::string tag;
        s >> tag;
        if (tag == "v") {
            glm::vec3 p;
            s >> p.x >> p.y >> p.z;
            mesh.positions.push_back(scale * p);
        } else if (tag == "f") {
            std::vector<unsigned> corners;
            std::string word;
            while (s >> word)
                corners.push_back(static_cast<unsigned>(std::stoul(word)) - 1);
            for (std::size_t i = 2; i < corners.size(); ++i)
                mesh.triangles.push_back({ corners[0], corners[i - 1], corners[i] });
        }
    }
    return mesh;
}

// Where Max Planck's head (in millimetres) lies in the shared test assets; the file may be absent.
inline std::filesystem::path planckPath()
{
    return wisp::test::sharedAssetsDir() / "heads" / "max_planck_decimated.obj";
}

} // namespace wisp::test
