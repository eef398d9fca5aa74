// Fuzz target: io::parseProject (what readProject does after reading the file), the editor's
// steps on the project's head, and the promise that a project read writes and reads back.
// A project whose head is only referenced gets a small tetrahedron from the head loader, so the
// rest of the file is still read.

#include "fuzz/FuzzSupport.h"
#include "io/ProjectFile.h"

#include <string_view>

namespace {

wisp::io::Result<wisp::TriangleMesh> loadTetrahedron(const std::string&)
{
    wisp::TriangleMesh mesh;
    mesh.positions = { { 0.0f, 0.0f, 0.0f }, { 0.2f, 0.0f, 0.0f }, { 0.0f, 0.2f, 0.0f }, { 0.0f, 0.0f, 0.2f } };
    mesh.triangles = { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } };
    return mesh;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::string projectPath = "/nonexistent-wisp-fuzz/project.wisp";
    const wisp::io::Result<wisp::io::ProjectReadResult> read
        = wisp::io::parseProject(text, projectPath, loadTetrahedron);
    if (!read)
        return 0;
    const wisp::io::Project& project = read.value().project;
    const std::string written = wisp::io::projectToJson(project, projectPath);
    const wisp::io::Result<wisp::io::ProjectReadResult> again
        = wisp::io::parseProject(written, projectPath, loadTetrahedron);
    if (!again)
        wisp::fuzz::fail("a project read does not read back once written: " + again.error().toString());
    // The document takes the head as placed (it is stored in metres): only the checks and builds.
    wisp::fuzz::exerciseHead(project.head);
    return 0;
}
