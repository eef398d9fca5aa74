#include "fuzz/FuzzSupport.h"

#include "io/HeadPlacement.h"
#include "sim/geometry/Body.h"
#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/SignedDistanceField.h"
#include "sim/groom/GrowthMap.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace wisp::fuzz {

namespace {

namespace fs = std::filesystem;

struct TempFolder {
    fs::path path;
    TempFolder()
    {
        // Memory, not disk, where there is a choice: a disk-backed /tmp made the write of every
        // input cost more than the read under a busy disk (4 ms against 0.5 ms).
        const char* base = std::getenv("TMPDIR");
        std::error_code ignored;
        const std::string folder = base && *base ? base : fs::is_directory("/dev/shm", ignored) ? "/dev/shm" : "/tmp";
        std::string pattern = folder + "/wisp-fuzz-XXXXXX";
        if (!mkdtemp(pattern.data()))
            fail("cannot make a temporary folder " + pattern);
        path = pattern;
    }
    ~TempFolder()
    {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

} // namespace

void fail(const std::string& what)
{
    std::fprintf(stderr, "wisp fuzz finding: %s\n", what.c_str());
    std::abort();
}

std::string writeInput(const std::string& name, const std::uint8_t* data, std::size_t size)
{
    static TempFolder folder;
    const fs::path path = folder.path / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out)
        fail("cannot write " + path.string());
    return path.string();
}

void placeAndExerciseHead(TriangleMesh mesh, bool zUp)
{
    io::HeadPlacementSettings settings;
    if (zUp)
        settings.up = io::Axis::PosZ; // the artist's choice; otherwise found from the shape
    const io::HeadPlacement placement = io::placeHead(mesh, settings);
    (void)io::describePlacement(placement);
    exerciseHead(mesh);
}

void exerciseHead(const TriangleMesh& mesh)
{
    if (!validateMesh(mesh).empty())
        return; // the importer refuses it with that message
    // validateMesh promises finite coordinates and indices in range: everything below relies on it.
    for (const glm::vec3& p : mesh.positions)
        if (!finite(p))
            fail("validateMesh accepted a non-finite vertex");

    const MeshBvh bvh(mesh);
    const std::vector<float> growth = scalpGrowth(mesh);
    if (growth.size() != mesh.vertexCount())
        fail("scalpGrowth gave " + std::to_string(growth.size()) + " weights for " + std::to_string(mesh.vertexCount())
            + " vertices");
    (void)defaultBody(mesh);
    (void)vertexNormals(mesh);

    // The simulation's collider, as HairSimulation::prepareHead bakes it but at 3 cells across
    // instead of 96 (the code paths are the same; the fuzzer needs thousands of inputs a second).
    const Aabb box = boundsOf(mesh);
    const float extent = glm::max(box.size().x, glm::max(box.size().y, box.size().z));
    std::string error;
    const SignedDistanceField sdf = SignedDistanceField::bake(mesh, extent / 3.0f, 0.1f * extent + 0.01f, &error, 1);
    if (!sdf.empty()) {
        (void)sdf.distance(box.center());
        (void)sdf.gradient(box.max);
    }

    // The questions the paint and style tools ask: the nearest scalp point to a brush, a ray from
    // the camera. The BVH's own promise: a finite answer for a finite question on a non-empty tree,
    // checked on heads the simulation takes (a collider baked): a project's head is not placed, and
    // on one 1e30 m across a squared distance overflows, which is no fault of the BVH.
    if (bvh.empty())
        return;
    const bool checked = !sdf.empty();
    for (const glm::vec3& p : { box.center(), box.max + glm::vec3(0.01f), box.min })
        if (const MeshBvh::ClosestPoint c = bvh.closestPoint(p);
            checked && (!finite(c.point) || !std::isfinite(c.distance)))
            fail("MeshBvh::closestPoint gave a non-finite point");
    (void)bvh.closestPointWithin(box.center(), 0.01f);
    const glm::vec3 eye = box.center() + glm::vec3(0.0f, 0.0f, 1.0f);
    if (const auto hit = bvh.raycast(eye, box.center() - eye, 2.0f); checked && hit && !finite(hit->point))
        fail("MeshBvh::raycast gave a non-finite hit");
}

} // namespace wisp::fuzz
