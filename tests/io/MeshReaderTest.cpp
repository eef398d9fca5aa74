// Mesh reading: real heads from ../shared/assets and generated files in every format.
#include "MeshReaderTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::mesh;
using wisp::test::signedVolume;

// ---- real heads ---------------------------------------------------------------------------------

TEST(MeshReaderAssets, MaxPlanckObj)
{
    const fs::path path = assetPath("heads/max_planck_decimated.obj");
    REQUIRE_ASSET(path);
    const auto r = readMesh(path.string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    EXPECT_EQ(r.value().mesh.vertexCount(), 5272u);
    EXPECT_EQ(r.value().mesh.triangleCount(), 10540u);
    EXPECT_TRUE(r.value().warnings.empty()) << r.value().warnings.front();
    EXPECT_EQ(validateMesh(r.value().mesh), "");
}

TEST(MeshReaderAssets, CyWomanHeadBinaryPly)
{
    const fs::path path = assetPath("heads/cy_woman_head.ply");
    REQUIRE_ASSET(path);
    const auto r = readMesh(path.string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    const TriangleMesh& mesh = r.value().mesh;
    EXPECT_EQ(mesh.vertexCount(), 43662u);
    EXPECT_EQ(mesh.triangleCount(), 78520u);
    EXPECT_TRUE(r.value().warnings.empty()) << r.value().warnings.front();
    const std::string bytes = slurp(path);
    EXPECT_EQ(mesh.positions.front(), rawPlyVertex(bytes, 12, 0));
    EXPECT_EQ(mesh.positions.back(), rawPlyVertex(bytes, 12, 43661));
}

TEST(MeshReaderAssets, IgeaTriangleStrips)
{
    const fs::path path = assetPath("heads/igea_tristrips.ply");
    REQUIRE_ASSET(path);
    const auto r = readMesh(path.string()); // its load time is a figure: tests/bench, ReadHead
    ASSERT_TRUE(r.ok()) << r.error().toString();
    const TriangleMesh& mesh = r.value().mesh;
    EXPECT_EQ(mesh.vertexCount(), 134345u);
    EXPECT_EQ(mesh.triangleCount(), 268686u);
    const glm::vec3 size = boundsOf(mesh).size();
    EXPECT_GT(size.y, 0.05f);
    EXPECT_LT(size.y, 0.2f) << "igea is stored in metres, about 0.1 m tall";
    const std::string bytes = slurp(path);
    EXPECT_EQ(mesh.positions.back(), rawPlyVertex(bytes, 12, 134344));
    // Alternating winding: every strip triangle keeps the orientation of the first, so the
    // surface is consistently oriented and encloses a volume of one sign (outward here).
    EXPECT_GT(signedVolume(mesh), 0.0);
    std::size_t flipped = 0;
    const auto normals = vertexNormals(mesh);
    for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        const glm::vec3 avg = normals[tri.x] + normals[tri.y] + normals[tri.z];
        flipped += glm::dot(faceNormal(mesh, t), avg) < 0.0f ? 1 : 0;
    }
    EXPECT_LT(flipped, mesh.triangleCount() / 1000)
        << "triangles facing against their neighbours: strip winding is wrong";
}

TEST(MeshReaderAssets, Ct2HairHeadSkipsDoubleProperties)
{
    const fs::path path = assetPath("hair/ct2hair_bangs_head.ply");
    REQUIRE_ASSET(path);
    const auto r = readMesh(path.string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    const TriangleMesh& mesh = r.value().mesh;
    EXPECT_EQ(mesh.vertexCount(), 3943u);
    EXPECT_EQ(mesh.triangleCount(), 7694u);
    // x, y, z float then s, t double: 28 bytes a vertex. A wrong skip would garble later vertices.
    const std::string bytes = slurp(path);
    EXPECT_EQ(mesh.positions[0], rawPlyVertex(bytes, 28, 0));
    EXPECT_EQ(mesh.positions[1971], rawPlyVertex(bytes, 28, 1971));
    EXPECT_EQ(mesh.positions.back(), rawPlyVertex(bytes, 28, 3942));
}

TEST_F(MeshReaderFiles, TruncatedRealBinaryPlyIsRefused)
{
    const fs::path path = assetPath("heads/igea_tristrips.ply");
    REQUIRE_ASSET(path);
    const std::string bytes = slurp(path);
    const std::string text = expectError("igea_half.ply", bytes.substr(0, bytes.size() / 2));
    EXPECT_NE(text.find("truncated"), std::string::npos) << text;
    // Cut inside the strip list: the header's counts fit, the list's length does not.
    const std::string text2 = expectError("igea_cut.ply", bytes.substr(0, bytes.size() - 100));
    EXPECT_NE(text2.find("tristrips"), std::string::npos) << text2;
}

// ---- formats, generated ---------------------------------------------------------------------------

TEST_F(MeshReaderFiles, ObjQuadsAreFanTriangulated)
{
    expectUnitCube(expectMesh("cube.obj", cubeObj()), "obj");
    expectUnitCube(expectMesh("CUBE_CRLF.OBJ", cubeObj("\r\n")), "upper-case extension, CRLF");

    // A hexagon becomes four triangles; relative (negative) indices count back from the last vertex.
    std::string hex;
    for (int i = 0; i < 6; ++i) {
        const double a = i * 3.14159265358979 / 3.0;
        hex += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    hex += "f -6 -5 -4 -3 -2 -1\n";
    const MeshReadResult r = expectMesh("hexagon.obj", hex);
    EXPECT_EQ(r.mesh.vertexCount(), 6u);
    ASSERT_EQ(r.mesh.triangleCount(), 4u);
    EXPECT_EQ(r.mesh.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(r.mesh.triangles[3], glm::uvec3(0, 4, 5));
}

TEST_F(MeshReaderFiles, ObjNonManifoldFacesAreKeptWithTheirVertices)
{
    // Three triangles on one edge: an OpenMesh mesh would refuse the third ("complex edge") or
    // give it copies of its vertices. A collider wants all three on the original vertices.
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
    const MeshReadResult r = expectMesh("fin.obj", obj);
    EXPECT_EQ(r.mesh.vertexCount(), 5u);
    EXPECT_EQ(r.mesh.triangleCount(), 3u);
    EXPECT_TRUE(r.warnings.empty());
}

TEST_F(MeshReaderFiles, ObjWarningsStayOffStderr)
{
    std::string obj = "mtllib no_such_file.mtl\nusemtl skin\n" + cubeObj();
    obj += "f 1 1 2\nl 1 2\np 3\n";
    testing::internal::CaptureStderr();
    const MeshReadResult r = expectMesh("cube_with_extras.obj", obj);
    const std::string stderrText = testing::internal::GetCapturedStderr();
    EXPECT_EQ(stderrText, "");
    expectUnitCube(r, "obj with extras");
    std::string all;
    for (const std::string& w : r.warnings)
        all += w + "\n";
    // The material library is named, never opened (a missing one is no problem either).
    EXPECT_NE(all.find("ignored the material library 'no_such_file.mtl'"), std::string::npos) << all;
    EXPECT_NE(all.find("skipped 1 face"), std::string::npos) << all;
    EXPECT_NE(all.find("1 line element"), std::string::npos) << all;
}

// OpenMesh's OBJ reader refused one-component texture coordinates ("Only single 2D or 3D texture
// coordinate..."), which are legal OBJ; a collider reads no texture coordinates at all.
TEST_F(MeshReaderFiles, ObjTextureCoordinatesOfAnySizeAreSkipped)
{
    const MeshReadResult r
        = expectMesh("vt1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nvt 0.5 0.5 0.5 0.5\nf 1/1 2/2 3/1\n");
    EXPECT_EQ(r.mesh.vertexCount(), 3u);
    ASSERT_EQ(r.mesh.triangleCount(), 1u);
    EXPECT_EQ(r.mesh.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_TRUE(r.warnings.empty());
}

// A face may name a vertex written after it (positive indices are absolute); a negative index
// counts back from the vertices above the face.
TEST_F(MeshReaderFiles, ObjFacesMayNameLaterVertices)
{
    const MeshReadResult r = expectMesh("forward.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf -3 -1 -2\n");
    EXPECT_EQ(r.mesh.vertexCount(), 4u);
    ASSERT_EQ(r.mesh.triangleCount(), 2u);
    EXPECT_EQ(r.mesh.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(r.mesh.triangles[1], glm::uvec3(1, 3, 2));
    const std::string text = expectError("forward_bad.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\n");
    EXPECT_NE(text.find("line 2: a face refers to vertex 3, but the file has 2 vertices"), std::string::npos) << text;
}

// STL corners are welded by value: -0 and +0 are one corner, so the cube stays closed.
TEST_F(MeshReaderFiles, StlWeldsSignedZeros)
{
    // Every other zero coordinate of a vertex line written as -0.
    std::string signedZeros = cubeStlAscii();
    int n = 0;
    for (std::size_t at = signedZeros.find(" 0.000000"); at != std::string::npos;
         at = signedZeros.find(" 0.000000", at + 2))
        if (n++ % 2 == 1 && signedZeros.rfind("vertex", at) > signedZeros.rfind('\n', at))
            signedZeros.insert(at + 1, "-");
    ASSERT_NE(signedZeros.find("-0"), std::string::npos);
    expectUnitCube(expectMesh("signed_zero.stl", signedZeros), "ascii stl with -0");
}

TEST_F(MeshReaderFiles, OffWithCommentsColoursAndSameLineCounts)
{
    expectUnitCube(expectMesh("cube.off", cubeOff()), "off");
    std::string sameLine = cubeOff();
    sameLine.replace(0, sameLine.find("8 6 12\n") + 7, "OFF 8 6 0\n");
    expectUnitCube(expectMesh("same_line.off", sameLine), "counts on the OFF line");
    std::string coloured = "COFF\n8 6 0\n";
    for (const glm::vec3& v : kCubeVertices)
        coloured += std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + " 255 0 0 255\n";
    for (const auto& q : kCubeQuads)
        coloured += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " "
            + std::to_string(q[3]) + " 0.5 0.5 0.5\n";
    expectUnitCube(expectMesh("coloured.off", coloured), "COFF");
}

TEST_F(MeshReaderFiles, StlAsciiAndBinaryCubesWeldCorners)
{
    expectUnitCube(expectMesh("cube_ascii.stl", cubeStlAscii()), "ascii stl");
    expectUnitCube(expectMesh("cube_binary.STL", cubeStlBinary()), "binary stl");
    // A binary STL whose header happens to start with "solid" is still binary (by its size).
    std::string solidHeader = cubeStlBinary();
    solidHeader.replace(0, 5, "solid");
    expectUnitCube(expectMesh("cube_solid_header.stl", solidHeader), "binary stl with 'solid' header");
}

TEST_F(MeshReaderFiles, PlyVariantsAllGiveTheSameCube)
{
    std::vector<std::pair<std::string, PlyOptions>> variants;
    for (const std::string format : { "ascii", "binary_little_endian", "binary_big_endian" }) {
        PlyOptions o;
        o.format = format;
        variants.push_back({ format, o });
        o.extraBefore = o.extraAfter = true;
        variants.push_back({ format + " extra properties", o });
        o.doubleCoordinates = true;
        o.countType = "uint";
        o.indexType = "uint";
        variants.push_back({ format + " doubles, uint lists", o });
        o.countType = "ushort";
        o.indexType = "ushort";
        o.faceFirst = true;
        o.edgeElement = true;
        variants.push_back({ format + " faces first, ushort, edges", o });
    }
    int n = 0;
    for (const auto& [what, options] : variants) {
        const MeshReadResult r = expectMesh("cube" + std::to_string(n++) + ".ply", cubePly(options));
        expectUnitCube(r, what);
        EXPECT_EQ(r.warnings.size(), options.edgeElement ? 1u : 0u) << what;
    }
}

TEST_F(MeshReaderFiles, PlyTriangleStripsSplitAtMinusOneWithAlternatingWinding)
{
    // Two strips over a flat 2x3 grid in z = 0, ASCII so the test reads like the data:
    //   3 4 5      strip A = 0 1 3 4 gives (0 1 3) and, swapped, (3 1 4);
    //   0 1 2      strip B = 1 2 4 5 gives (1 2 4) and (4 2 5). All must face +z.
    const std::string ply
        = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
          "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
          "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n"
          "9 0 1 3 4 -1 1 2 4 5\n";
    const MeshReadResult r = expectMesh("strips.ply", ply);
    ASSERT_EQ(r.mesh.triangleCount(), 4u);
    for (std::uint32_t t = 0; t < 4; ++t)
        EXPECT_GT(faceNormal(r.mesh, t).z, 0.99f) << "triangle " << t;
    EXPECT_EQ(r.mesh.triangles[0], glm::uvec3(0, 1, 3));
    EXPECT_EQ(r.mesh.triangles[1], glm::uvec3(3, 1, 4));

    // Degenerate triangles that stitch strips together are dropped without a warning.
    const std::string stitched
        = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
          "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
          "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n"
          "6 0 1 3 4 4 1\n";
    const MeshReadResult s = expectMesh("stitched.ply", stitched);
    EXPECT_EQ(s.mesh.triangleCount(), 2u);
    EXPECT_TRUE(s.warnings.empty());
}

TEST(MeshReaderApi, SupportedExtensions)
{
    const std::vector<std::string> expected = { "obj", "ply", "off", "stl", "gltf", "glb" };
    EXPECT_EQ(supportedMeshExtensions(), expected);
}
