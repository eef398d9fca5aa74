// glTF files with hostile structure (issue 12): misspelled keys, unaligned chunks, escaping URIs.
#include "GltfTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::gltf;
using wisp::test::assetPath;
using wisp::test::slurp;

// ---- hostile structure (issue 12) -------------------------------------------------------------

// A typo in a bufferView key (`byteOffet`) used to be ignored by tinygltf, so the view started at
// byte 0 and the head was read from the index bytes; a JSON value of the wrong type (`true`) was
// taken as absent. Both are refused with the key path.
TEST(GltfReader, MisspelledKeysAndWrongTypesAreRefusedWithTheirKeyPath)
{
    TempDir dir;
    const auto tetra = [](const std::function<void(GltfBuilder&)>& edit) {
        GltfBuilder b;
        const int indices = b.indices<std::uint16_t>(tetraIndices);
        b.mesh(b.floats(tetraCorners), indices);
        b.node({ { "mesh", 0 } });
        b.scene({ 0 });
        edit(b);
        return b;
    };
    // The untouched file reads: what follows fails because of the edit alone.
    GltfBuilder plain = tetra([](GltfBuilder&) {});
    ASSERT_TRUE(readMesh(dir.write("plain.gltf", plain.gltf()).string()).ok());

    GltfBuilder typo = tetra([](GltfBuilder& b) {
        Json& view = b.root["bufferViews"][1];
        view["byteOffet"] = view["byteOffset"];
        view.erase("byteOffset");
    });
    const Result<MeshReadResult> typoRead = readMesh(dir.write("typo.gltf", typo.gltf()).string());
    ASSERT_FALSE(typoRead.ok());
    EXPECT_EQ(typoRead.error().location, "bufferViews[1].byteOffet");
    EXPECT_NE(typoRead.error().message.find("did you mean 'byteOffset'?"), std::string::npos)
        << typoRead.error().toString();

    GltfBuilder boolean = tetra([](GltfBuilder& b) { b.root["bufferViews"][1]["byteOffset"] = true; });
    const Result<MeshReadResult> boolRead = readMesh(dir.write("bool.glb", boolean.glb()).string());
    ASSERT_FALSE(boolRead.ok());
    EXPECT_EQ(boolRead.error().location, "bufferViews[1].byteOffset");
    EXPECT_EQ(boolRead.error().message, "must be a whole number, not true");

    const std::vector<std::pair<std::function<void(GltfBuilder&)>, std::pair<std::string, std::string>>> cases = {
        { [](GltfBuilder& b) { b.root["accessors"][1]["count"] = "4"; },
            { "accessors[1].count", "must be a whole number, not a string" } },
        { [](GltfBuilder& b) { b.root["accessors"][1]["count"] = 2.5; },
            { "accessors[1].count", "must be a whole number, not 2.5" } },
        { [](GltfBuilder& b) { b.root["accessors"][1]["count"] = 0; },
            { "accessors[1].count", "0 is outside at least 1" } },
        { [](GltfBuilder& b) { b.root["accessors"][1].erase("componentType"); },
            { "accessors[1].componentType", "missing; the glTF schema requires it" } },
        { [](GltfBuilder& b) {
             Json& primitive = b.root["meshes"][0]["primitives"][0];
             primitive["atributes"] = primitive["attributes"];
             primitive.erase("attributes");
         },
            { "meshes[0].primitives[0].atributes",
                "unknown key (did you mean 'attributes'?); glTF readers ignore it, so "
                "the file would not mean what it says" } },
        { [](GltfBuilder& b) { b.root["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = "1"; },
            { "meshes[0].primitives[0].attributes.POSITION", "must be an accessor index, not a string" } },
        { [](GltfBuilder& b) {
             b.root["nodes"][0]["translaton"] = { 1, 2, 3 };
         },
            { "nodes[0].translaton",
                "unknown key (did you mean 'translation'?); glTF readers ignore it, so the file "
                "would not mean what it says" } },
        { [](GltfBuilder& b) {
             b.root["nodes"][0]["scale"] = { 1, "2", 3 };
         },
            { "nodes[0].scale[1]", "must be a finite number, not a string" } },
        { [](GltfBuilder& b) { b.root["bufferViews"] = Json::object(); },
            { "bufferViews", "must be a list, not an object" } },
        { [](GltfBuilder& b) {
             b.root["acessors"] = b.root["accessors"];
             b.root.erase("accessors");
         },
            { "acessors",
                "unknown top-level key (did you mean 'accessors'?); glTF readers ignore it, so the file would "
                "not mean what it says" } },
        { [](GltfBuilder& b) { b.root["scene"] = -1; }, { "scene", "must be a scene index, not -1" } },
    };
    // A number too large for a double: nlohmann's raw out_of_range text used to come through.
    const std::string overflow = "{\"asset\": {\"version\": \"2.0\"},\n \"scene\": 1e999}";
    const Result<MeshReadResult> overflowRead = readMesh(dir.write("overflow.gltf", overflow).string());
    ASSERT_FALSE(overflowRead.ok());
    EXPECT_EQ(overflowRead.error().toString(),
        (dir.path() / "overflow.gltf").string()
            + ": line 2, column 11: invalid JSON: the number 1e999 is too large "
              "to hold (it overflows a double)");
    int n = 0;
    for (const auto& [edit, want] : cases) {
        GltfBuilder b = tetra(edit);
        const Result<MeshReadResult> read
            = readMesh(dir.write("case" + std::to_string(n++) + ".gltf", b.gltf()).string());
        ASSERT_FALSE(read.ok()) << want.first;
        EXPECT_EQ(read.error().location, want.first);
        EXPECT_EQ(read.error().message, want.second);
    }
}

// Khronos' validator: CHUNK_LENGTH_UNALIGNED. Such a GLB was accepted.
TEST(GltfReader, UnalignedGlbChunkIsRefused)
{
    TempDir dir;
    GltfBuilder b;
    b.mesh(b.floats(tetraCorners), b.indices<std::uint16_t>(tetraIndices));
    b.node({ { "mesh", 0 } });
    b.scene({ 0 });
    std::string glb = b.glb();
    ASSERT_TRUE(readMesh(dir.write("ok.glb", glb).string()).ok());
    // One byte off the JSON chunk's padding: its length is no longer a multiple of 4, and the BIN
    // chunk header moves with it.
    std::uint32_t jsonBytes = 0, total = 0;
    std::memcpy(&jsonBytes, glb.data() + 12, 4);
    ASSERT_EQ(glb[20 + jsonBytes - 1], ' ') << "the builder pads the JSON";
    const std::string json = glb.substr(20, jsonBytes);
    const std::size_t trimmed = json.find_last_not_of(' ') + 1;
    ASSERT_NE(trimmed % 4, 0u) << "pick a JSON whose length is not already aligned";
    std::string unaligned = glb.substr(0, 20) + json.substr(0, trimmed) + glb.substr(20 + jsonBytes);
    const auto shorter = static_cast<std::uint32_t>(trimmed);
    std::memcpy(unaligned.data() + 12, &shorter, 4);
    total = static_cast<std::uint32_t>(unaligned.size());
    std::memcpy(unaligned.data() + 8, &total, 4);
    const Result<MeshReadResult> read = readMesh(dir.write("unaligned.glb", unaligned).string());
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().location, "byte 12");
    EXPECT_NE(read.error().message.find("GLB chunk lengths are multiples of 4"), std::string::npos)
        << read.error().toString();
}

// A glTF shared between artists must not read outside its folder: `../secret.txt` was followed
// and `convert --head` then embedded that file in its output.
TEST(GltfReader, BufferUrisMustStayInTheFilesFolder)
{
    TempDir dir;
    GltfBuilder b;
    b.mesh(b.floats(tetraCorners), b.indices<std::uint16_t>(tetraIndices));
    b.node({ { "mesh", 0 } });
    b.scene({ 0 });
    const Json embedded = Json::parse(b.gltf());
    const std::string& bytes = b.buffer();
    fs::create_directories(dir.path() / "head");
    dir.write("secret.bin", bytes);
    dir.write("head/inside.bin", bytes);
    fs::create_symlink(dir.path() / "secret.bin", dir.path() / "head" / "link.bin");
    fs::create_directories(dir.path() / "head" / "folder.bin");
    const auto readWithUri = [&](const std::string& bufferUri) {
        Json copy = embedded;
        copy["buffers"][0]["uri"] = bufferUri;
        return readMesh(dir.write("head/h.gltf", copy.dump()).string());
    };
    const Result<MeshReadResult> inside = readWithUri("inside.bin");
    ASSERT_TRUE(inside.ok()) << inside.error().toString();
    EXPECT_EQ(inside.value().mesh.triangleCount(), 4u);

    const std::vector<std::pair<std::string, std::string>> refused = {
        { "../secret.bin", "lies outside the glTF file's folder" },
        { "%2E%2E/secret.bin", "lies outside the glTF file's folder" },
        { "sub/../../secret.bin", "lies outside the glTF file's folder" },
        { "link.bin", "lies outside the glTF file's folder" },
        { (dir.path() / "secret.bin").string(), "is an absolute path" },
        { "/proc/self/environ", "is an absolute path" },
        { "/dev/zero", "is an absolute path" },
        { "file:///etc/passwd", "is a URL" },
        { "folder.bin", "is not a regular file" },
        { "missing.bin", "does not exist in the glTF file's folder" },
    };
    for (const auto& [bufferUri, why] : refused) {
        const Result<MeshReadResult> read = readWithUri(bufferUri);
        ASSERT_FALSE(read.ok()) << bufferUri;
        EXPECT_EQ(read.error().location, "buffers[0].uri") << bufferUri;
        EXPECT_NE(read.error().message.find(why), std::string::npos) << read.error().toString();
    }
}
