// glTF reading, hand-made files: each rule on its own.
#include "GltfTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::gltf;
using wisp::test::assetPath;
using wisp::test::signedVolume;
using wisp::test::slurp;

// ---- hand-made files: each rule on its own ----------------------------------------------------

TEST(GltfReader, StripsAndFansBecomeTrianglesWithOneWinding)
{
    TempDir dir;
    for (int mode : { 5, 6 }) {
        GltfBuilder b;
        const int positions = b.floats(squareCorners);
        // Strip 0 1 3 2 and fan 0 1 2 3 both cover the square with two counter-clockwise triangles.
        const int indices
            = mode == 5 ? b.indices<std::uint8_t>({ 0, 1, 3, 2 }) : b.indices<std::uint8_t>({ 0, 1, 2, 3 });
        b.node({ { "mesh", b.mesh(positions, indices, mode) } });
        b.scene({ 0 });
        const Result<MeshReadResult> read = readMesh(dir.write("mode.gltf", b.gltf()).string());
        ASSERT_TRUE(read.ok()) << read.error().toString();
        const TriangleMesh& mesh = read.value().mesh;
        ASSERT_EQ(mesh.triangleCount(), 2u) << "mode " << mode;
        for (std::uint32_t t = 0; t < 2; ++t)
            expectNear(faceNormal(mesh, t), { 0, 0, 1 }, 1e-6f, "mode " + std::to_string(mode));
        EXPECT_NEAR(triangleArea(mesh, 0) + triangleArea(mesh, 1), 1.0f, 1e-6f);
    }
}

TEST(GltfReader, PointsAndLinesAreSkippedWithAWarning)
{
    TempDir dir;
    GltfBuilder b;
    const int positions = b.floats(squareCorners);
    const int triangles = b.indices<std::uint16_t>({ 0, 1, 2, 0, 2, 3 });
    const Json pointPrimitive = { { "attributes", { { "POSITION", positions } } }, { "mode", 0 } };
    const Json linePrimitive = { { "attributes", { { "POSITION", positions } } }, { "mode", 1 } };
    const Json trianglePrimitive = { { "attributes", { { "POSITION", positions } } }, { "indices", triangles } };
    const Json mesh = { { "primitives", Json::array({ pointPrimitive, linePrimitive, trianglePrimitive }) } };
    b.root["meshes"].push_back(mesh);
    b.node({ { "mesh", 0 } });
    b.scene({ 0 });
    const Result<MeshReadResult> read = readMesh(dir.write("mixed.gltf", b.gltf()).string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    EXPECT_EQ(read.value().mesh.triangleCount(), 2u);
    const std::string warnings = joined(read.value().warnings);
    EXPECT_NE(warnings.find("skipped 2 primitives of points or lines"), std::string::npos) << warnings;

    // Only points: no triangles at all is an error that says so.
    GltfBuilder onlyPoints;
    onlyPoints.node({ { "mesh", onlyPoints.mesh(onlyPoints.floats(squareCorners), -1, 0) } });
    onlyPoints.scene({ 0 });
    const Result<MeshReadResult> points = readMesh(dir.write("points.gltf", onlyPoints.gltf()).string());
    ASSERT_FALSE(points.ok());
    EXPECT_EQ(points.error().message.rfind("no triangles", 0), 0u) << points.error().toString();
    EXPECT_NE(points.error().message.find("points and lines"), std::string::npos) << points.error().toString();
}

TEST(GltfReader, TranslationRotationScaleComposeDownTheHierarchy)
{
    TempDir dir;
    GltfBuilder b;
    const int mesh = b.mesh(b.floats(tetraCorners), b.indices(tetraIndices));
    // Child: scale 2, then a quarter turn about +Y ((x, y, z) -> (z, y, -x)), then up by 1.
    // Parent: moves everything +10 in x.
    const double s = std::sqrt(0.5);
    const int child = b.node(
        { { "mesh", mesh }, { "scale", { 2, 2, 2 } }, { "rotation", { 0, s, 0, s } }, { "translation", { 0, 1, 0 } } });
    const int parent = b.node({ { "children", { child } }, { "translation", { 10, 0, 0 } } });
    b.scene({ parent });
    const Result<MeshReadResult> read = readMesh(dir.write("trs.gltf", b.gltf()).string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    const TriangleMesh& m = read.value().mesh;
    ASSERT_EQ(m.vertexCount(), 4u);
    // Corner (1, 0, 0) -> scaled (2, 0, 0) -> turned (0, 0, -2) -> (10, 1, -2).
    bool found = false;
    for (const glm::vec3& p : m.positions)
        found = found || glm::length(p - glm::vec3(10, 1, -2)) < 1e-5f;
    EXPECT_TRUE(found);
    EXPECT_NEAR(signedVolume(m), 8.0 / 6.0, 1e-5); // volume 1/6, scaled by 2^3, still outward
}

TEST(GltfReader, MirroringTransformKeepsTrianglesOutward)
{
    TempDir dir;
    GltfBuilder b;
    const int mesh = b.mesh(b.floats(tetraCorners), b.indices(tetraIndices));
    b.node({ { "mesh", mesh }, { "scale", { -1, 1, 1 } } });
    b.scene({ 0 });
    const Result<MeshReadResult> read = readMesh(dir.write("mirror.gltf", b.gltf()).string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    EXPECT_NEAR(signedVolume(read.value().mesh), 1.0 / 6.0, 1e-6);
}

TEST(GltfReader, InstancedMeshIsMergedOncePerNodeAndSceneLessFilesUseRootNodes)
{
    TempDir dir;
    GltfBuilder b;
    const int mesh = b.mesh(b.floats(tetraCorners), b.indices(tetraIndices));
    b.node({ { "mesh", mesh } });
    b.node({ { "mesh", mesh }, { "translation", { 5, 0, 0 } } });
    // No scenes: both nodes are roots.
    const Result<MeshReadResult> read = readMesh(dir.write("twice.glb", b.glb()).string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    EXPECT_EQ(read.value().mesh.triangleCount(), 8u);
    EXPECT_EQ(read.value().mesh.vertexCount(), 8u); // the two instances touch nowhere
    EXPECT_FLOAT_EQ(boundsOf(read.value().mesh).max.x, 5.0f + 1.0f);
}

TEST(GltfReader, QuantizedAndNormalizedPositionsAndByteStride)
{
    TempDir dir;
    GltfBuilder b;
    // Positions as normalized unsigned shorts, 8 bytes apart (6 used, 2 padding): 65535 is 1.0.
    std::vector<std::uint16_t> packed = { 0, 0, 0, 0, 65535, 0, 0, 0, 65535, 65535, 0, 0, 0, 65535, 0, 0 };
    const int view = b.view(GltfBuilder::bytesOf(packed), 8);
    const int positions = b.accessor(view, 5123, 4, "VEC3", true);
    b.node({ { "mesh", b.mesh(positions, b.indices<std::uint32_t>({ 0, 1, 2, 0, 2, 3 })) } });
    b.scene({ 0 });
    b.root["extensionsUsed"] = { "KHR_mesh_quantization" };
    b.root["extensionsRequired"] = { "KHR_mesh_quantization" };
    const Result<MeshReadResult> read = readMesh(dir.write("quantized.gltf", b.gltf()).string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    const Aabb box = boundsOf(read.value().mesh);
    expectNear(box.min, { 0, 0, 0 }, 0.0f, "lower bounds");
    expectNear(box.max, { 1, 1, 0 }, 0.0f, "upper bounds");
}

TEST(GltfReader, OutOfBoundsAccessorIsAnError)
{
    TempDir dir;
    GltfBuilder b;
    const int positions = b.floats(squareCorners);
    b.root["accessors"][static_cast<std::size_t>(positions)]["count"] = 5; // one past the 4 stored
    b.node({ { "mesh", b.mesh(positions, b.indices<std::uint8_t>({ 0, 1, 2 })) } });
    b.scene({ 0 });
    const Result<MeshReadResult> read = readMesh(dir.write("bounds.gltf", b.gltf()).string());
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().message.find("out of its buffer's bounds"), std::string::npos) << read.error().toString();
    EXPECT_EQ(read.error().location.rfind("accessors[0]", 0), 0u) << read.error().toString();

    // A byteOffset that pushes the view past its buffer.
    GltfBuilder far;
    const int farPositions = far.floats(squareCorners);
    far.root["bufferViews"][0]["byteOffset"] = 1u << 30;
    far.node({ { "mesh", far.mesh(farPositions, -1) } });
    far.scene({ 0 });
    const Result<MeshReadResult> farRead = readMesh(dir.write("far.glb", far.glb()).string());
    ASSERT_FALSE(farRead.ok());
    EXPECT_NE(farRead.error().message.find("out of its buffer's bounds"), std::string::npos)
        << farRead.error().toString();
}

TEST(GltfReader, IndexOutOfRangeIsAnError)
{
    TempDir dir;
    GltfBuilder b;
    b.node({ { "mesh", b.mesh(b.floats(squareCorners), b.indices<std::uint16_t>({ 0, 1, 4 })) } });
    b.scene({ 0 });
    const Result<MeshReadResult> read = readMesh(dir.write("index.gltf", b.gltf()).string());
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().location, "meshes[0].primitives[0]");
    EXPECT_NE(read.error().message.find("index 2 is 4, out of range"), std::string::npos) << read.error().toString();
}

TEST(GltfReader, UnsupportedRequiredExtensionsAreRefusedByName)
{
    TempDir dir;
    for (const std::string name : { "EXT_meshopt_compression", "EXT_mesh_gpu_instancing", "VENDOR_private_geometry" }) {
        GltfBuilder b;
        b.node({ { "mesh", b.mesh(b.floats(squareCorners), b.indices<std::uint8_t>({ 0, 1, 2 })) } });
        b.scene({ 0 });
        b.root["extensionsRequired"] = { name };
        const Result<MeshReadResult> read = readMesh(dir.write("extension.gltf", b.gltf()).string());
        ASSERT_FALSE(read.ok()) << name;
        EXPECT_NE(read.error().message.find(name), std::string::npos) << read.error().toString();
    }
    // A required material extension changes only the look: the geometry reads.
    GltfBuilder look;
    look.node({ { "mesh", look.mesh(look.floats(squareCorners), look.indices<std::uint8_t>({ 0, 1, 2 })) } });
    look.scene({ 0 });
    look.root["extensionsRequired"] = { "KHR_materials_pbrSpecularGlossiness" };
    EXPECT_TRUE(readMesh(dir.write("look.gltf", look.gltf()).string()).ok());
}

TEST(GltfReader, NodeCyclesAndBadReferencesAreErrors)
{
    TempDir dir;
    const auto readWith = [&dir](const std::function<void(GltfBuilder&)>& edit) {
        GltfBuilder b;
        b.mesh(b.floats(squareCorners), b.indices<std::uint8_t>({ 0, 1, 2 }));
        edit(b);
        return readMesh(dir.write("nodes.gltf", b.gltf()).string());
    };
    const auto cycle = readWith([](GltfBuilder& b) {
        b.node({ { "mesh", 0 }, { "children", { 1 } } });
        b.node({ { "children", { 0 } } });
        b.scene({ 0 });
    });
    ASSERT_FALSE(cycle.ok());
    EXPECT_NE(cycle.error().message.find("reached twice"), std::string::npos) << cycle.error().toString();

    const auto missingChild = readWith([](GltfBuilder& b) {
        b.node({ { "mesh", 0 }, { "children", { 7 } } });
        b.scene({ 0 });
    });
    ASSERT_FALSE(missingChild.ok());
    EXPECT_EQ(missingChild.error().location, "nodes[0].children");

    const auto missingMesh = readWith([](GltfBuilder& b) {
        b.node({ { "mesh", 3 } });
        b.scene({ 0 });
    });
    ASSERT_FALSE(missingMesh.ok());
    EXPECT_NE(missingMesh.error().message.find("meshes[3]"), std::string::npos) << missingMesh.error().toString();

    const auto badMatrix = readWith([](GltfBuilder& b) {
        b.node({ { "mesh", 0 }, { "matrix", { 1, 0, 0, 1 } } });
        b.scene({ 0 });
    });
    ASSERT_FALSE(badMatrix.ok());
    EXPECT_NE(badMatrix.error().message.find("matrix has 4 numbers"), std::string::npos)
        << badMatrix.error().toString();

    const auto badScene = readWith([](GltfBuilder& b) {
        b.node({ { "mesh", 0 } });
        b.scene({ 0 });
        b.root["scene"] = 4;
    });
    ASSERT_FALSE(badScene.ok());
    EXPECT_EQ(badScene.error().location, "scene");
}

TEST(GltfReader, OddBuffersAreErrorsNotCrashes)
{
    TempDir dir;
    const auto readEdited = [&dir](bool binary, const std::function<void(Json&)>& edit) {
        GltfBuilder b;
        b.node({ { "mesh", b.mesh(b.floats(squareCorners), b.indices<std::uint8_t>({ 0, 1, 2 })) } });
        b.scene({ 0 });
        std::string bytes = binary ? b.glb() : b.gltf();
        // Edit the JSON after the builder has filled in the buffer.
        if (binary) {
            std::uint32_t jsonBytes = 0;
            std::memcpy(&jsonBytes, bytes.data() + 12, 4);
            Json json = Json::parse(bytes.substr(20, jsonBytes));
            edit(json);
            std::string text = json.dump();
            text.resize(jsonBytes, ' '); // the edits below only shorten the JSON
            bytes.replace(20, jsonBytes, text);
        } else {
            Json json = Json::parse(bytes);
            edit(json);
            bytes = json.dump();
        }
        return readMesh(dir.write(binary ? "odd.glb" : "odd.gltf", bytes).string());
    };
    const auto zeroLength = readEdited(true, [](Json& j) { j["buffers"][0]["byteLength"] = 0; });
    EXPECT_FALSE(zeroLength.ok());
    const auto longerThanBin = readEdited(true, [](Json& j) { j["buffers"][0]["byteLength"] = 9999; });
    ASSERT_FALSE(longerThanBin.ok());
    EXPECT_NE(longerThanBin.error().toString().find("odd.glb"), std::string::npos);
    const auto badBase64
        = readEdited(false, [](Json& j) { j["buffers"][0]["uri"] = "data:application/octet-stream;base64,!!!!"; });
    ASSERT_FALSE(badBase64.ok());
    EXPECT_NE(badBase64.error().toString().find("odd.gltf"), std::string::npos);
    // A buffer URI naming a pipe must not block the read (opening a FIFO waits for a writer).
    ASSERT_EQ(::mkfifo((dir.path() / "pipe.bin").c_str(), 0600), 0);
    const auto pipe = readEdited(false, [](Json& j) { j["buffers"][0]["uri"] = "pipe.bin"; });
    ASSERT_FALSE(pipe.ok());
    EXPECT_NE(pipe.error().message.find("pipe.bin"), std::string::npos) << pipe.error().toString();
    const auto positionAccessor = [](Json& j) -> Json& {
        return j["accessors"][j["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<std::size_t>()];
    };
    const auto noView = readEdited(false, [&](Json& j) { positionAccessor(j)["bufferView"] = 42; });
    ASSERT_FALSE(noView.ok());
    EXPECT_NE(noView.error().message.find("bufferViews[42]"), std::string::npos) << noView.error().toString();
    const auto hugeZeros = readEdited(false, [&](Json& j) {
        positionAccessor(j).erase("bufferView");
        positionAccessor(j)["count"] = 4'000'000'000u;
    });
    ASSERT_FALSE(hugeZeros.ok());
    EXPECT_NE(hugeZeros.error().message.find("no data"), std::string::npos) << hugeZeros.error().toString();
}

TEST(GltfReader, JsonErrorsNameTheLine)
{
    TempDir dir;
    const Result<MeshReadResult> read
        = readMesh(dir.write("broken.gltf", "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [}\n").string());
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().location, "line 3, column 13") << read.error().toString();
    EXPECT_NE(read.error().message.find("invalid JSON"), std::string::npos) << read.error().toString();

    const Result<MeshReadResult> old = readMesh(dir.write("old.gltf", R"({"asset": {"version": "1.0"}})").string());
    ASSERT_FALSE(old.ok());
    EXPECT_NE(old.error().message.find("glTF 2.0"), std::string::npos) << old.error().toString();

    std::string deep
        = R"({"asset": {"version": "2.0"}, "extras": )" + std::string(100000, '[') + std::string(100000, ']') + "}";
    const Result<MeshReadResult> nested = readMesh(dir.write("deep.gltf", deep).string());
    ASSERT_FALSE(nested.ok());
    EXPECT_NE(nested.error().message.find("nests more than"), std::string::npos) << nested.error().toString();
}

TEST(GltfReader, BinaryFileNamedGltfStillReads)
{
    TempDir dir;
    GltfBuilder b;
    b.node({ { "mesh", b.mesh(b.floats(squareCorners), b.indices<std::uint8_t>({ 0, 1, 2, 0, 2, 3 })) } });
    b.scene({ 0 });
    const Result<MeshReadResult> read = readMesh(dir.write("binary.gltf", b.glb()).string());
    ASSERT_TRUE(read.ok()) << read.error().toString();
    EXPECT_EQ(read.value().mesh.triangleCount(), 2u);
    EXPECT_NE(joined(read.value().warnings).find("binary glTF"), std::string::npos);

    // The other way round: text named .glb is refused with a hint.
    const Result<MeshReadResult> text = readMesh(dir.write("text.glb", b.gltf()).string());
    ASSERT_FALSE(text.ok());
    EXPECT_NE(text.error().message.find("looks like a text glTF"), std::string::npos) << text.error().toString();
}

TEST(GltfReader, ExtensionsAreOffered)
{
    const std::vector<std::string>& extensions = supportedMeshExtensions();
    EXPECT_NE(std::find(extensions.begin(), extensions.end(), "gltf"), extensions.end());
    EXPECT_NE(std::find(extensions.begin(), extensions.end(), "glb"), extensions.end());
}
