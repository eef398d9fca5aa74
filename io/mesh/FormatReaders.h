#pragma once
// One reader per mesh format, each in its own file under io/mesh/, all fed the bytes that
// io/MeshReader read once through io/RegularFile. Each throws io::ReadFailure (io/ReadFailure.h)
// with the line or byte of the problem; readMesh turns it into an IoError naming the file.

#include "io/mesh/MeshBuilder.h"

#include <string>
#include <string_view>
#include <vector>

namespace wisp::io::mesh {

void readPly(std::string_view bytes, MeshBuilder& builder, std::vector<std::string>& warnings);
void readOff(std::string_view bytes, MeshBuilder& builder);
void readObj(std::string_view bytes, MeshBuilder& builder, std::vector<std::string>& warnings);
void readStl(std::string_view bytes, MeshBuilder& builder, std::vector<std::string>& warnings);

} // namespace wisp::io::mesh
