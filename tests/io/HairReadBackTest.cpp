// Wisp reads back the strands it writes: OBJ polylines, glTF and GLB (a LINES primitive with
// _WIDTH), with the head written beside them; broken files name the file and the problem.
#include "IoTestSupport.h"
#include "io/HairFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include <glm/geometric.hpp>

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test;

namespace {

HairCurves groom()
{
    HairCurves c;
    const std::uint32_t counts[] = { 2, 7, 4, 16 };
    for (std::uint32_t n : counts) {
        const std::size_t s = c.addStrand(n);
        std::span<glm::vec3> p = c.strandForWrite(s);
        for (std::uint32_t i = 0; i < n; ++i)
            p[i] = { 0.0123456f * float(s) + 1e-7f * float(i), 0.1f - 0.0121f * float(i) / 3.0f,
                -0.003f * float(s * i) };
    }
    return c;
}

TriangleMesh head()
{
    return { { { 0, 0, 0 }, { 0.1f, 0, 0 }, { 0, 0.1f, 0 }, { 0, 0, 0.1f } },
        { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } } };
}

void writeText(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

} // namespace

TEST(HairReadBack, ObjGltfAndGlbStrandsComeBackWithin1e6Metres)
{
    const auto dir = freshTestFolder("wisp-readback");
    const HairCurves written = groom();
    const TriangleMesh h = head();
    HairExportOptions options;
    options.head = &h;
    for (const char* name : { "s.obj", "s.gltf", "s.glb" }) {
        SCOPED_TRACE(name);
        const std::string path = (dir / name).string();
        ASSERT_TRUE(writeHair(path, written, options).ok());
        const Result<HairReadResult> read = readHair(path);
        ASSERT_TRUE(read) << read.error().toString();
        const HairCurves& back = read.value().strands;
        ASSERT_EQ(back.offsets, written.offsets);
        for (std::size_t i = 0; i < written.pointCount(); ++i)
            ASSERT_LT(glm::distance(back.positions[i], written.positions[i]), 1e-6f) << "point " << i;
        if (std::string(name) == "s.obj") {
            EXPECT_TRUE(read.value().widthsMetres.empty());
            ASSERT_EQ(read.value().warnings.size(), 1u); // the head's faces
            EXPECT_EQ(read.value().warnings[0], "skipped 4 faces (a mesh, such as a head written beside the hair)");
        } else {
            const std::vector<float>& w = read.value().widthsMetres;
            ASSERT_EQ(w.size(), written.pointCount());
            EXPECT_FLOAT_EQ(w[0], options.rootWidthMetres);
            EXPECT_FLOAT_EQ(w[1], options.tipWidthMetres); // a 2-point strand: root, tip
            EXPECT_FLOAT_EQ(w[written.offsets[4] - 1], options.tipWidthMetres);
        }
    }
}

TEST(HairReadBack, BrokenFilesNameTheFileThePlaceAndTheProblem)
{
    const auto dir = freshTestFolder("wisp-readback");
    auto error = [&](const char* name, const std::string& text) {
        writeText(dir / name, text);
        const Result<HairReadResult> r = readHair((dir / name).string());
        return r ? std::string("accepted") : r.error().toString();
    };
    const std::string obj = (dir / "a.obj").string();
    EXPECT_EQ(error("a.obj", "v 0 0 0\nv 0 1 0\nl 1 3\n"), obj + ": line 3: vertex 3 does not exist (the file has 2)");
    EXPECT_EQ(error("a.obj", "v 0 0 0\nv 0 x 0\nl 1 2\n"), obj + ": line 2: a vertex needs 3 numbers; 'x' is not one");
    EXPECT_EQ(error("a.obj", "v 0 0 0\nv 0 1 0\nl 1 two\n"), obj + ": line 3: 'two' is not a vertex number");
    // Read by the mesh readers' tokenizer: a number too large for a float is named as such, and
    // CRLF line endings, tabs and a leading '+' read as in an OBJ mesh.
    EXPECT_EQ(
        error("a.obj", "v 0 0 0\nv 0 1e40 0\nl 1 2\n"), obj + ": line 2: a vertex coordinate is not a finite number");
    writeText(dir / "c.obj", "# hair\r\nv\t0 0 0\r\nv +0.5 1 0\r\n\r\nl 1 2\r\n");
    const Result<HairReadResult> crlf = readHair((dir / "c.obj").string());
    ASSERT_TRUE(crlf);
    EXPECT_EQ(crlf.value().strands.positions[1], glm::vec3(0.5f, 1, 0));
    EXPECT_EQ(error("a.obj", "v 0 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n"),
        obj + ": no strands: an OBJ polyline is an 'l' line of two vertices or more");
    // Negative indices count back from the last vertex (the OBJ spec).
    writeText(dir / "b.obj", "v 0 0 0\nv 0 1 0\nl -2 -1\n");
    const Result<HairReadResult> relative = readHair((dir / "b.obj").string());
    ASSERT_TRUE(relative);
    EXPECT_EQ(relative.value().strands.positions[1], glm::vec3(0, 1, 0));

    // glTF: a lines file turned into points, a truncated buffer, and a truncated GLB.
    ASSERT_TRUE(writeHair((dir / "g.gltf").string(), groom()).ok());
    nlohmann::json json = nlohmann::json::parse(slurp(dir / "g.gltf"));
    json["meshes"][0]["primitives"][0]["mode"] = 0;
    const std::string gltf = (dir / "p.gltf").string();
    EXPECT_EQ(error("p.gltf", json.dump()), gltf + ": no strands: the file has no LINES or LINE_STRIP primitive");
    json = nlohmann::json::parse(slurp(dir / "g.gltf"));
    json["accessors"][0]["count"] = 100000;
    EXPECT_NE(error("q.gltf", json.dump()).find((dir / "q.gltf").string() + ": accessors[0]"), std::string::npos);
    ASSERT_TRUE(writeHair((dir / "g.glb").string(), groom()).ok());
    const std::string glb = slurp(dir / "g.glb");
    const std::string cut = error("cut.glb", glb.substr(0, glb.size() / 2));
    EXPECT_EQ(cut.rfind((dir / "cut.glb").string() + ": ", 0), 0u) << cut;
    EXPECT_NE(cut, "accepted");
}
