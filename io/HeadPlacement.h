#pragma once
// Where an imported head lands: its scale to metres, its up axis and its centre. Pure functions
// on a TriangleMesh; no Qt, no files.
//
// Mesh files rarely say their unit (OBJ, PLY, OFF and STL cannot; glTF says metres, but many
// exporters write centimetres anyway), and the solver needs metres: gravity, hair lengths and
// collision distances are all SI. A head is 0.15-0.40 m at its largest extent, and the
// candidate units are a factor of ten apart, so the extent picks the unit unambiguously:
//     150 to under 400 units   -> millimetres (x0.001)
//     15 to under 40 units     -> centimetres (x0.01)
//     0.15 to under 0.4 units  -> metres (x1)
//     anything else            -> scaled so that the head is 0.25 m tall, and `note` says so.
// The upper ends are open so that the boundary cases are not guessed: a 40-unit mesh might be a
// 0.4 m head or a 40 m model, and is scaled to fit instead.
// The artist sees the outcome ("imported at x0.001 (millimetres)", describePlacement) and can
// pick a unit or a scale instead; the caller keeps the mesh as read and places a copy again.
//
// Centring: the bounding box's centre goes to the origin on all three axes, so the viewport's
// orbit centre and the head coincide, and hair parameters that are positions (wind sources,
// brush radii) mean the same on every head. The scalp therefore sits above y = 0.
//
// Up axis: Wisp is +Y up. Scanners and some CAD tools write +Z up; `zUp` turns such a mesh
// upright (a -90 degree turn about +X: (x, y, z) -> (x, z, -y), which keeps triangle winding).
// Nothing in OBJ/PLY/OFF/STL says which axis is up, so the artist decides; glTF is +Y up by
// specification, so for .gltf/.glb the choice is fixed (formatFixesUpAxis) and no turn applies.

#include "sim/TriangleMesh.h"

#include <glm/vec3.hpp>

#include <string>

namespace wisp::io {

enum class LengthUnit {Auto, Millimetres, Centimetres, Metres};

// The head sizes the unit guess trusts, largest extent in metres (from the minimum up to but not
// including the maximum); and the height given to a head that fits no unit. Double, so that
// 40 units x 0.01 compares exactly with 0.40.
inline constexpr double headMinExtentMetres = 0.15;
inline constexpr double headMaxExtentMetres = 0.40;
inline constexpr double fittedHeadHeightMetres = 0.25;

struct HeadPlacementSettings {
    LengthUnit unit = LengthUnit::Auto; // Auto: guessed from the size, as above
    float explicitScale = 0.0f; // metres per file unit; > 0 overrides `unit`
    bool zUp = false; // the file is +Z up: turn it to +Y up first
};

// What placeHead did, so that the GUI can show it and the project can store and redo it.
// A vertex p of the file lands at rotate(p) * scale + offset, where rotate is the Z-up turn
// when rotatedUpright and the identity otherwise.
struct HeadPlacement {
    float scale = 1.0f; // metres per file unit
    LengthUnit unit = LengthUnit::Metres; // the unit `scale` stands for; Auto when it was fitted to
                                          // 0.25 m or given as an explicit factor that is no unit
    glm::vec3 offset{0.0f}; // metres, added after turning and scaling
    bool rotatedUpright = false; // turned +Z up to +Y up
    bool scaledToFit = false; // no unit fitted: scaled to fittedHeadHeightMetres tall
    std::string note; // why, when the outcome needs a word (empty otherwise)
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
void applyPlacement(TriangleMesh& mesh, const HeadPlacement& placement);

// Metres per unit: 0.001, 0.01, 1; 0 for Auto.
float metresPerUnit(LengthUnit unit);

// "millimetres", "centimetres", "metres", "auto".
const char* unitName(LengthUnit unit);

// One line for the GUI: "imported at ×0.001 (millimetres)", "imported at ×0.00625 (scaled to
// 0.25 m tall), turned Z-up to Y-up".
std::string describePlacement(const HeadPlacement& placement);

// True for files whose format fixes the up axis (glTF: +Y), where a Z-up option makes no sense.
bool formatFixesUpAxis(const std::string& path);

} // namespace wisp::io
