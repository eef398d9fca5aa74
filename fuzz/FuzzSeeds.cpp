// wisp_fuzz_seeds <corpus folder>: writes the seeds that Wisp's own writers make best into
// <folder>/project, <folder>/preset and <folder>/hair (scripts/fuzz-corpus.sh calls it). Small on
// purpose: a seed of a few hundred bytes lets libFuzzer try thousands of mutations a second, and
// still carries every key and section the reader knows.

#include "io/HairFiles.h"
#include "io/PresetFile.h"
#include "io/ProjectFile.h"
#include "io/StrandText.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace wisp;
namespace fs = std::filesystem;

namespace {

void writeText(const fs::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

TriangleMesh tetrahedron()
{
    TriangleMesh mesh;
    mesh.positions = { { 0.0f, 0.0f, 0.0f }, { 0.2f, 0.0f, 0.0f }, { 0.0f, 0.2f, 0.0f }, { 0.0f, 0.0f, 0.2f } };
    mesh.triangles = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } };
    return mesh;
}

HairCurves twoStrands()
{
    HairCurves strands;
    strands.offsets = { 0, 3, 5 };
    strands.positions = { { 0.0f, 0.2f, 0.0f }, { 0.0f, 0.25f, 0.01f }, { 0.0f, 0.3f, 0.03f }, { 0.1f, 0.1f, 0.0f },
        { 0.15f, 0.05f, 0.0f } };
    return strands;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: wisp_fuzz_seeds <corpus folder>\n");
        return 2;
    }
    const fs::path root = argv[1];
    for (const char* target : { "project", "preset", "hair" })
        fs::create_directories(root / target);

    // Projects: an embedded head with two regions (one painted, one of imported strands), a solo,
    // a camera and salon edits; and a head referenced by path (the fuzz target's loader answers
    // with a tetrahedron).
    io::Project project;
    project.head = tetrahedron();
    GrowthRegion painted;
    painted.id = 1;
    painted.name = "crown";
    painted.weights = { 1.0f, 0.5f, 0.0f, 0.25f };
    GrowthRegion imported;
    imported.id = 2;
    imported.name = "bangs";
    imported.weights = std::vector<float>(4, 0.0f);
    imported.importedStrands = std::make_shared<const HairCurves>(twoStrands());
    project.regions = { painted, imported };
    project.soloRegion = 2;
    StrandStyle style;
    style.lengthMetres = 0.1f;
    style.curlRadiusMetres = 0.01f;
    style.curlTurnsPerMetre = 20.0f;
    style.stiffnessScale = 2.0f;
    style.wetness = 0.5f;
    style.shape = { { 0.0f, 0.2f, 0.0f }, { 0.0f, 0.1f, 0.05f } };
    project.style[(std::uint64_t(1) << 32) | 7] = style;
    const std::string projectPath = (root / "project" / "seed.wisp").string();
    writeText(root / "project" / "embedded.wisp", io::projectToJson(project, projectPath));
    project.headEmbedded = false;
    project.headSource = (root / "project" / "head.obj").string();
    project.style.clear();
    writeText(root / "project" / "referenced.wisp", io::projectToJson(project, projectPath));

    // Presets: the defaults, and one with two region looks.
    io::Preset preset;
    preset.name = "seed";
    preset.description = "two regions";
    writeText(root / "preset" / "defaults.json", io::presetToJson(io::Preset{}));
    preset.regions.resize(2);
    preset.regions[0].name = "crown";
    preset.regions[1].name = "nape";
    writeText(root / "preset" / "regions.json", io::presetToJson(preset));

    // Strands in every format the hair target reads.
    const HairCurves strands = twoStrands();
    bool ok = io::writeHair((root / "hair" / "two.hair").string(), strands).ok()
        && io::writeHair((root / "hair" / "two.data").string(), strands).ok()
        && io::writeStrandText((root / "hair" / "two-strands.txt").string(), strands).ok();
    if (!ok) {
        std::fprintf(stderr, "wisp_fuzz_seeds: cannot write the hair seeds in %s\n", (root / "hair").c_str());
        return 1;
    }
    return 0;
}
