#pragma once
// What reading (ProjectReader.cpp) and writing (ProjectFile.cpp) a project share: where its paths
// resolve, how a place in it is named, and the checks that need the whole project. Not io/'s API.

#include "io/ProjectFile.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <filesystem>
#include <string>

namespace wisp::io::project_detail {

constexpr std::size_t kMaxPathBytes = 4096;

// The folder a project's relative paths resolve against.
std::filesystem::path projectFolder(const std::string& projectPath);
std::filesystem::path resolveAgainst(const std::filesystem::path& folder, const std::string& source);

std::string regionPath(std::size_t index); // "regions[2]"
std::string stylePath(std::size_t index); // "style[0]"

bool isUnitColour(const glm::vec3& c); // every channel 0..1 (false for NaN)

// Throws the Refusal that reading such a file would give: the checks that need the whole project
// (counts against the head, ids against each other). writeProject runs it too.
void checkProject(const Project& project);

} // namespace wisp::io::project_detail
