#pragma once
// What the fuzz targets share: handing libFuzzer's bytes to readers that take a path, and doing
// with a mesh what the editor does with a head it has just read.

#include "sim/geometry/TriangleMesh.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace wisp::fuzz {

// Writes `size` bytes to a file named `name` in this process's own temporary folder (made once,
// under $TMPDIR, else /dev/shm, else /tmp; removed at exit) and returns its path. The same name is overwritten on
// every call, so a run leaves one file however many inputs it tries.
std::string writeInput(const std::string& name, const std::uint8_t* data, std::size_t size);

// The editor's steps after a head is read (app/editor/HeadImporter.cpp, then the document, the
// paint tool and the simulation): check it and, when it is usable, build its BVH, its growth map,
// its body and a coarse collider, and ask the BVH the questions the tools ask. A finding here is
// a crash, a sanitizer report, or a broken promise of sim/ (see the .cpp).
void exerciseHead(const TriangleMesh& mesh);
// The same for a head as read from a mesh file: placed first (unit, centre, Z-up turn if asked).
void placeAndExerciseHead(TriangleMesh mesh, bool zUp);

// Stops the run with a message libFuzzer keeps with the input (a broken promise, not a crash).
[[noreturn]] void fail(const std::string& what);

} // namespace wisp::fuzz
