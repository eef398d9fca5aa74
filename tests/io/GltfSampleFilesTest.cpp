// glTF reading of the shared sample files (Khronos samples, the validator suite, damaged copies).
#include "GltfTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::gltf;
using wisp::test::assetPath;
using wisp::test::signedVolume;
using wisp::test::slurp;

// ---- the shared sample files ------------------------------------------------------------------

TEST(GltfReader, BoxEmbeddedAppliesTheNodeMatrix)
{
    const fs::path path = assetPath("gltf/Box_embedded.gltf");
    REQUIRE_ASSET(path);
    // Through readMesh: .gltf must be dispatched to the glTF reader.
    const Result<MeshReadResult> read = readMesh(path.string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    const TriangleMesh& mesh = read.value().mesh;
    EXPECT_EQ(mesh.triangleCount(), 12u);
    // The file has 24 vertices (each corner once per face, for its normals); welded, 8.
    EXPECT_EQ(mesh.vertexCount(), 8u);

    // The file's first triangle is corners 0, 1, 2 of its POSITION accessor: (-0.5, -0.5, 0.5),
    // (0.5, -0.5, 0.5), (-0.5, 0.5, 0.5), on the +Z face. The root node's matrix (columns
    // (1,0,0), (0,0,-1), (0,1,0)) maps (x, y, z) to (x, z, -y), so the face moves to +Y.
    const glm::uvec3 first = mesh.triangles[0];
    expectNear(mesh.positions[first.x], { -0.5f, 0.5f, 0.5f }, 1e-6f, "corner 0");
    expectNear(mesh.positions[first.y], { 0.5f, 0.5f, 0.5f }, 1e-6f, "corner 1");
    expectNear(mesh.positions[first.z], { -0.5f, 0.5f, -0.5f }, 1e-6f, "corner 2");
    expectNear(faceNormal(mesh, 0), { 0.0f, 1.0f, 0.0f }, 1e-6f, "normal of the first triangle");
    // A unit cube wound outward.
    EXPECT_NEAR(signedVolume(mesh), 1.0, 1e-6);
    // The sample keeps glTF 1.0's accessor byteStride (Khronos' validator: UNEXPECTED_PROPERTY);
    // it is no near miss of an accessor key, so it is ignored with a warning, not refused.
    ASSERT_EQ(read.value().warnings.size(), 3u) << joined(read.value().warnings);
    EXPECT_EQ(read.value().warnings[0], "accessors[0].byteStride: unknown key, ignored");
}

TEST(GltfReader, BoxTexturedGlbEmbeddedAndExternalGiveTheSameTriangles)
{
    const fs::path glb = assetPath("gltf/BoxTextured.glb");
    const fs::path embedded = assetPath("gltf/BoxTextured_embedded.gltf");
    const fs::path external = assetPath("gltf/BoxTextured_external/BoxTextured.gltf");
    REQUIRE_ASSET(glb);
    REQUIRE_ASSET(embedded);
    REQUIRE_ASSET(external);
    std::vector<TriangleMesh> meshes;
    for (const fs::path& path : { glb, embedded, external }) {
        const Result<MeshReadResult> read = readMesh(path.string());
        ASSERT_TRUE(read.ok()) << read.error().toString();
        meshes.push_back(read.value().mesh);
    }
    ASSERT_EQ(meshes[0].triangleCount(), 12u);
    EXPECT_NEAR(signedVolume(meshes[0]), 1.0, 1e-6);
    for (std::size_t m = 1; m < meshes.size(); ++m) {
        ASSERT_EQ(meshes[m].triangleCount(), meshes[0].triangleCount());
        ASSERT_EQ(meshes[m].vertexCount(), meshes[0].vertexCount());
        for (std::size_t t = 0; t < meshes[0].triangleCount(); ++t)
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(
                    meshes[m].positions[meshes[m].triangles[t][c]], meshes[0].positions[meshes[0].triangles[t][c]])
                    << "file " << m << " triangle " << t << " corner " << c;
    }
}

TEST(GltfReader, ExternalBufferIsFoundFromAnotherWorkingDirectory)
{
    const fs::path external = assetPath("gltf/BoxTextured_external/BoxTextured.gltf");
    REQUIRE_ASSET(external);
    // A relative path to the .gltf, with the working directory elsewhere: the .bin is found
    // beside the file, not beside the program.
    const fs::path before = fs::current_path();
    TempDir dir;
    fs::current_path(dir.path());
    const Result<MeshReadResult> read = readMesh(fs::relative(external, dir.path()).string());
    fs::current_path(before);
    ASSERT_TRUE(read.ok()) << read.error().toString();
    EXPECT_EQ(read.value().mesh.triangleCount(), 12u);
}

TEST(GltfReader, MissingExternalBufferIsAnErrorNamingIt)
{
    const fs::path external = assetPath("gltf/BoxTextured_external/BoxTextured.gltf");
    REQUIRE_ASSET(external);
    TempDir dir;
    const fs::path copy = dir.write("lonely.gltf", slurp(external)); // without its .bin
    const Result<MeshReadResult> read = readMesh(copy.string());
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().toString().find("lonely.gltf"), std::string::npos) << read.error().toString();
    EXPECT_NE(read.error().message.find("BoxTextured0.bin"), std::string::npos) << read.error().toString();
}

TEST(GltfReader, SparseAccessorReplacesPositions)
{
    const fs::path path = assetPath("gltf/SimpleSparseAccessor_embedded.gltf");
    REQUIRE_ASSET(path);
    const Result<MeshReadResult> read = readMesh(path.string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    const TriangleMesh& mesh = read.value().mesh;
    EXPECT_EQ(mesh.triangleCount(), 12u);
    EXPECT_EQ(mesh.vertexCount(), 14u);
    // The first triangle is (0, 8, 7). Element 8 is (1, 1, 0) in the bufferView and (1, 2, 0)
    // after the sparse substitution (elements 8, 10 and 12 are replaced).
    expectNear(mesh.positions[mesh.triangles[0].y], { 1.0f, 2.0f, 0.0f }, 0.0f, "sparse element 8");
    expectNear(mesh.positions[mesh.triangles[0].z], { 0.0f, 1.0f, 0.0f }, 0.0f, "element 7, not replaced");
    const Aabb box = boundsOf(mesh);
    EXPECT_FLOAT_EQ(box.max.y, 4.0f); // element 12 became (5, 4, 0)
}

TEST(GltfReader, TwoCylinderEngineHasEveryPrimitiveWithItsNodeTransform)
{
    const fs::path path = assetPath("gltf/2CylinderEngine.glb");
    REQUIRE_ASSET(path);
    const std::string bytes = slurp(path);

    // Independently of the reader: the triangles of every primitive each node of the default
    // scene instances (index count / 3), walking the JSON.
    const Json gltf = glbJson(bytes);
    std::size_t fileTriangles = 0;
    std::size_t primitives = 0;
    std::vector<int> pending = gltf["scenes"][gltf.value("scene", 0)]["nodes"].get<std::vector<int>>();
    while (!pending.empty()) {
        const Json& node = gltf["nodes"][static_cast<std::size_t>(pending.back())];
        pending.pop_back();
        if (node.contains("mesh"))
            for (const Json& primitive : gltf["meshes"][node["mesh"].get<std::size_t>()]["primitives"]) {
                ASSERT_EQ(primitive.value("mode", 4), 4);
                fileTriangles
                    += gltf["accessors"][primitive["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3;
                ++primitives;
            }
        if (node.contains("children"))
            for (int child : node["children"])
                pending.push_back(child);
    }
    EXPECT_EQ(gltf["nodes"].size(), 82u);
    EXPECT_EQ(fileTriangles, 121'496u);

    const Result<MeshReadResult> read = readMesh(path.string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    const TriangleMesh& mesh = read.value().mesh;
    // The file repeats an index in 11,154 of its triangles, and 6 more have two distinct
    // vertices at the same position (counted once with a separate script); those 11,160 are
    // dropped and reported, every other triangle is kept. Welding bit-identical positions leaves
    // 60,040 vertices (same script).
    const std::string warnings = joined(read.value().warnings);
    EXPECT_NE(warnings.find("skipped 11160 triangles with fewer than 3 distinct corners"), std::string::npos)
        << warnings;
    EXPECT_EQ(mesh.triangleCount() + 11'160u, fileTriangles);
    EXPECT_EQ(mesh.vertexCount(), 60'040u);

    // Bounds of the used vertices with the node matrices applied, computed once with a separate
    // script (Python, float64). Without the transforms they would be
    // (-330.44, -199.18, -230.00) to (211.16, 469.65, 147.69).
    const Aabb box = boundsOf(mesh);
    expectNear(box.min, { -371.69226f, -180.97156f, -139.99999f }, 2e-3f, "lower bounds");
    expectNear(box.max, { 371.69217f, 92.04156f, 128.0f }, 2e-3f, "upper bounds");
}

TEST(GltfReader, InterleavedSkinnedMeshReadsItsPositions)
{
    const fs::path path = assetPath("gltf/unassigned-skeleton_interleaved.gltf");
    REQUIRE_ASSET(path);
    const Result<MeshReadResult> read = readMesh(path.string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    const TriangleMesh& mesh = read.value().mesh;
    EXPECT_EQ(mesh.triangleCount(), 8u);
    EXPECT_EQ(mesh.vertexCount(), 10u);
    // POSITION is every 72 bytes in a buffer shared with five other attributes: a ladder of
    // x = +-0.5, y = 0, 0.5, ... 2, z = 0.
    for (const glm::vec3& p : mesh.positions) {
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
        EXPECT_FLOAT_EQ(std::abs(p.x), 0.5f);
        EXPECT_FLOAT_EQ(std::fmod(p.y, 0.5f), 0.0f);
        EXPECT_FLOAT_EQ(p.z, 0.0f);
    }
    const Aabb box = boundsOf(mesh);
    EXPECT_FLOAT_EQ(box.min.y, 0.0f);
    EXPECT_FLOAT_EQ(box.max.y, 2.0f);
}

TEST(GltfReader, SparseMorphTargetCubeReadsAtDefaultWeights)
{
    const fs::path path = assetPath("gltf/singleBlendshapeCube_sparse.glb");
    REQUIRE_ASSET(path);
    const Result<MeshReadResult> read = readMesh(path.string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    const TriangleMesh& mesh = read.value().mesh;
    EXPECT_EQ(mesh.triangleCount(), 12u);
    // The morph weight is 0, so the cube is as stored: 1 cm wide.
    const Aabb box = boundsOf(mesh);
    expectNear(box.min, glm::vec3(-0.005f), 1e-7f, "lower bounds");
    expectNear(box.max, glm::vec3(0.005f), 1e-7f, "upper bounds");
}

TEST(GltfReader, DracoIsRefusedByName)
{
    const fs::path path = assetPath("gltf/2CylinderEngine_draco/2CylinderEngine.gltf");
    REQUIRE_ASSET(path);
    const Result<MeshReadResult> read = readMesh(path.string());
    ASSERT_FALSE(read.ok());
    const std::string text = read.error().toString();
    EXPECT_NE(text.find("2CylinderEngine.gltf"), std::string::npos) << text;
    EXPECT_NE(text.find("KHR_draco_mesh_compression"), std::string::npos) << text;
    EXPECT_NE(text.find("uses Draco mesh compression"), std::string::npos) << text;
    EXPECT_EQ(read.error().location, "extensionsRequired");
}

// Every file of the Khronos validator's GLB suite: the valid ones load or say they hold no
// triangles (none has a mesh), the malformed ones are errors naming the file; none crashes or
// takes long.
TEST(GltfReader, ValidatorGlbSuiteGivesAClearOutcomeForEveryFile)
{
    const fs::path folder = assetPath("gltf/validator_glb");
    REQUIRE_ASSET(folder);
    // File -> what the message must say ("" for files the validator finds valid).
    const std::map<std::string, std::string> expected = {
        { "bom.glb", "" }, // the validator objects to the byte-order mark; we skip it with a warning
        { "empty_file.glb", "empty" },
        { "empty_json_chunk.glb", "JSON chunk is empty" },
        { "empty_json_object.glb", "'asset'" },
        { "extra_data.glb", "" },
        { "invalid_json_chunk.glb", "invalid JSON" },
        { "invalid_magic.glb", "does not start with 'glTF'" },
        { "invalid_version.glb", "GLB version 0" },
        { "json_and_two_buffers.glb", "second BIN chunk" },
        { "misplaced_bin_chunk.glb", "BIN chunk must directly follow" },
        { "no_header.glb", "too short" },
        { "only_bin_chunk.glb", "first chunk must be JSON" },
        { "only_header.glb", "too small" },
        { "truncated_chunk_header.glb", "too small" },
        { "two_empty_bin_chunks.glb", "first chunk must be JSON" },
        { "two_empty_json_chunks.glb", "JSON chunk is empty" },
        { "two_images.glb", "" },
        { "two_valid_json_chunks.glb", "second JSON chunk" },
        { "unknown_chunk.glb", "first chunk must be JSON" },
        { "valid.glb", "" },
        { "valid_buffer.glb", "" },
        { "zero_length.glb", "too small" },
    };
    std::size_t seen = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
        if (entry.path().extension() != ".glb")
            continue;
        const std::string name = entry.path().filename().string();
        SCOPED_TRACE(name);
        const Result<MeshReadResult> read = readMesh(entry.path().string()); // returns at all: no hang on bad input
        const auto it = expected.find(name);
        ASSERT_NE(it, expected.end()) << "a new file in validator_glb/: add its expected outcome here";
        ++seen;
        if (read.ok()) {
            EXPECT_TRUE(it->second.empty()) << "loaded, but the validator calls it malformed";
            continue;
        }
        const std::string text = read.error().toString();
        std::cout << "[          ] " << text << "\n";
        EXPECT_NE(text.find(name), std::string::npos) << text;
        if (it->second.empty())
            EXPECT_EQ(read.error().message.rfind("no triangles", 0), 0u) << text;
        else
            EXPECT_NE(read.error().message.find(it->second), std::string::npos) << text;
    }
    EXPECT_EQ(seen, expected.size());
}

TEST(GltfReader, TruncatedGlbNeverCrashes)
{
    const fs::path box = assetPath("gltf/BoxTextured.glb");
    const fs::path engine = assetPath("gltf/2CylinderEngine.glb");
    REQUIRE_ASSET(box);
    REQUIRE_ASSET(engine);
    TempDir dir;
    // The small file cut at every length through its header and first chunk header, around
    // each chunk boundary, and at 60 places in between (each cut is a file write, which is what
    // takes the time); the big one at the lengths around its structure.
    const std::string boxBytes = slurp(box);
    std::uint32_t boxJsonBytes = 0;
    std::memcpy(&boxJsonBytes, boxBytes.data() + 12, 4);
    std::set<std::size_t> lengths;
    for (std::size_t length = 0; length <= 40; ++length)
        lengths.insert(length);
    for (std::size_t length = 16 + boxJsonBytes; length <= 32 + boxJsonBytes; ++length)
        lengths.insert(length);
    for (std::size_t k = 1; k < 60; ++k)
        lengths.insert(boxBytes.size() * k / 60);
    lengths.insert(boxBytes.size() - 1);
    for (const std::size_t length : lengths) {
        const fs::path cut = dir.write("cut_box.glb", boxBytes.substr(0, length));
        const Result<MeshReadResult> read = readMesh(cut.string());
        ASSERT_FALSE(read.ok()) << "cut at " << length;
        EXPECT_NE(read.error().toString().find("cut_box.glb"), std::string::npos) << read.error().toString();
    }
    const std::string engineBytes = slurp(engine);
    std::uint32_t jsonBytes = 0;
    std::memcpy(&jsonBytes, engineBytes.data() + 12, 4);
    for (std::size_t length : { std::size_t{ 12 }, std::size_t{ 19 }, std::size_t{ 20 }, std::size_t{ 21 },
             std::size_t{ 20 } + jsonBytes / 2, std::size_t{ 20 } + jsonBytes, std::size_t{ 28 } + jsonBytes,
             engineBytes.size() / 2, engineBytes.size() - 4, engineBytes.size() - 1 }) {
        const fs::path cut = dir.write("cut_engine.glb", engineBytes.substr(0, length));
        const Result<MeshReadResult> read = readMesh(cut.string());
        ASSERT_FALSE(read.ok()) << "cut at " << length;
        EXPECT_NE(read.error().message.find("truncated"), std::string::npos) << read.error().toString();
    }
}

TEST(GltfReader, CorruptedBytesNeverCrash)
{
    const fs::path box = assetPath("gltf/BoxTextured.glb");
    REQUIRE_ASSET(box);
    TempDir dir;
    const std::string original = slurp(box);
    std::mt19937 random(20240611);
    std::uniform_int_distribution<std::size_t> position(0, original.size() - 1);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int trial = 0; trial < 200; ++trial) {
        std::string bytes = original;
        for (int k = 0; k < 1 + trial % 4; ++k)
            bytes[position(random)] = static_cast<char>(byte(random));
        const fs::path path = dir.write("corrupt.glb", bytes);
        const Result<MeshReadResult> read = readMesh(path.string());
        if (read.ok())
            EXPECT_TRUE(validateMesh(read.value().mesh).empty());
        else
            EXPECT_NE(read.error().toString().find("corrupt.glb"), std::string::npos) << read.error().toString();
    }
}
