#pragma once
// Where an imported head lands: its scale to metres, its up axis and its centre. Pure functions
// on a TriangleMesh; no Qt, no files.
//
// Mesh files rarely say their unit (OBJ, PLY, OFF and STL cannot; glTF says metres, but many
// exporters write centimetres anyway), and the solver needs metres: gravity, hair lengths and
// collision distances are all SI. The unit is picked by the skull's width (io/HeadOrientation.h's
// skullWidth: the widest left-right extent near the top of the head), not by the whole mesh, so
// that a bust with shoulders is sized by its head. An adult skull is about 0.15 m wide (0.18 m
// over the ears), and the candidate units are a factor of ten apart, so:
//     100 to under 300 units   -> millimetres (x0.001)
//     10 to under 30 units     -> centimetres (x0.01)
//     0.1 to under 0.3 units   -> metres (x1)
//     anything else            -> scaled so that the skull is 0.16 m wide, and `note` says so.
// The artist sees the outcome ("imported at x0.001 (millimetres)", describePlacement) and can
// pick a unit or a scale instead; the caller keeps the mesh as read and places a copy again.
//
// Up axis: Wisp is +Y up with the face toward +Z. The head's up and front are found from its
// shape (io/HeadOrientation.h: mirror symmetry, the nose, the skull above the nose) and the mesh
// is turned so; when the shape does not say, the file's axes are kept and `orientation` says why.
// The artist can name the up axis instead (`up`; the face then goes where the smallest turn puts
// it). glTF is +Y up, face +Z by specification, so for .gltf/.glb nothing is turned
// (formatFixesUpAxis).
//
// Centring: the bounding box's centre goes to the origin on all three axes, so the viewport's
// orbit centre and the head coincide, and hair parameters that are positions (wind sources,
// brush radii) mean the same on every head. The scalp therefore sits above y = 0.

#include "sim/geometry/TriangleMesh.h"

#include "io/HeadOrientation.h"

#include <glm/vec3.hpp>

#include <optional>
#include <span>
#include <string>

namespace wisp::io {

enum class LengthUnit { Auto, Millimetres, Centimetres, Metres };

// The skull widths the unit guess trusts, in metres (from the minimum up to but not including the
// maximum); and the width given to a skull that fits no unit. Double, so that 30 units x 0.01
// compares exactly with 0.30.
inline constexpr double skullMinWidthMetres = 0.10;
inline constexpr double skullMaxWidthMetres = 0.30;
inline constexpr double fittedSkullWidthMetres = 0.16;

struct HeadPlacementSettings {
    LengthUnit unit = LengthUnit::Auto; // Auto: guessed from the size, as above
    float explicitScale = 0.0f; // metres per file unit; > 0 overrides `unit`
    std::optional<Axis> up; // the file's up axis as the artist names it; nullopt: found from the shape
};

// What placeHead did, so that the GUI can show it and the project can store and redo it.
// A vertex p of the file lands at orient(p, up, front) * scale + offset (io/HeadOrientation.h).
struct HeadPlacement {
    float scale = 1.0f; // metres per file unit
    LengthUnit unit = LengthUnit::Metres; // the unit `scale` stands for; Auto when it was fitted to
                                          // 0.25 m or given as an explicit factor that is no unit
    glm::vec3 offset{ 0.0f }; // metres, added after turning and scaling
    Axis up = Axis::PosY; // the file's axis that became +Y
    Axis front = Axis::PosZ; // the file's axis that became +Z (where the face looks)
    bool upFromShape = false; // up and front were found from the shape (not given, not kept)
    std::string orientation; // how up was decided: found from the shape (and how), given, or kept (and why)
    bool scaledToFit = false; // no unit fitted: scaled to fittedSkullWidthMetres wide
    float skullWidthMetres = 0.0f; // after placing
    std::string note; // warnings: what the artist should check (empty when all is as expected)

    bool turned() const { return up != Axis::PosY || front != Axis::PosZ; }
};

// Scales, turns and centres `mesh` in place and returns what was applied. `explicitScale` > 0
// (metres per file unit) overrides `unit`. An empty mesh or one without extent is left as is.
HeadPlacement placeHead(TriangleMesh& mesh, LengthUnit unit = LengthUnit::Auto, float explicitScale = 0.0f);
HeadPlacement placeHead(TriangleMesh& mesh, const HeadPlacementSettings& settings);

// What a placed head must be for the groom and the solver to use it (wisp-cli validate, simulate
// and the editor's Open Head all ask): a valid mesh (sim/TriangleMesh's validateMesh), at least
// headMinAxisExtentMetres deep on every axis (a flat or collapsed mesh has no inside to collide
// with, and a subnormal extent broke the BVH build), and at most headMaxPlacedExtentMetres at its
// largest (one stray vertex far away made the scalp area, and with it the groom's work, absurd).
// Empty when usable, else the reason in an artist's words.
inline constexpr double headMinAxisExtentMetres = 0.01;
inline constexpr double headMaxPlacedExtentMetres = 3.0;
std::string checkPlacedHead(const TriangleMesh& placed);

// Applies a placement (as returned by placeHead, or stored in a project) to a mesh as read.
// The same for points in the head file's frame (strands that came with the head).
void applyPlacement(TriangleMesh& mesh, const HeadPlacement& placement);
void applyPlacement(std::span<glm::vec3> points, const HeadPlacement& placement);

// Metres per unit: 0.001, 0.01, 1; 0 for Auto.
float metresPerUnit(LengthUnit unit);

// "millimetres", "centimetres", "metres", "auto".
const char* unitName(LengthUnit unit);

// One line for the GUI: "imported at ×0.001 (millimetres)", "imported at ×0.00186 (scaled to a
// 0.16 m wide skull), +Z up, face +X (from its shape)".
std::string describePlacement(const HeadPlacement& placement);

// True for files whose format fixes the up axis (glTF: +Y), where an up option makes no sense.
bool formatFixesUpAxis(const std::string& path);

} // namespace wisp::io
