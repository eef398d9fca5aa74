#pragma once
// The salon edits an artist made on the hair (Ward et al., "Modeling Hair Using Level-of-Detail
// Representations"/"Virtual Hair Salon"; Lee et al.'s cut, comb and perm): per strand, what the
// brushes changed. They are keyed by strand identity (Groom::strandIdentity: the region's id and
// the strand's pore), so they survive regrooms, painting elsewhere, reordering regions and
// reloading a project, and are independent of presets: applying a preset changes the regions'
// parameters, not these.
//
// Where a value is "unset" the strand takes what its region says.

#include <glm/vec3.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace wisp {

struct StrandStyle {
    // Cut, grow or shrink: the strand's arc length in metres; 0 = the region's length.
    float lengthMetres = 0.0f;
    // Perm: curl radius (metres) and turns per metre of the strand's key hair; < 0 = the region's.
    float curlRadiusMetres = -1.0f;
    float curlTurnsPerMetre = -1.0f;
    // Hairspray: multiplies the strand's stiffness (>= 1; the solver caps the product at 1).
    float stiffnessScale = 1.0f;
    // Wet brush: how wet the brush made the strand, 0..1. The simulation dries it over time and
    // under the dryer; this is the value as applied (and as saved).
    float wetness = 0.0f;
    // Comb and hairspray: where the strand should rest under gravity, head space, metres, root
    // first (any number of points >= 2; the groom resamples it). Empty = the groom's rest shape.
    // The simulation solves for the rest shape that sags onto this one (HairSimulation).
    std::vector<glm::vec3> shape;

    bool operator==(const StrandStyle&) const = default;
    // True when nothing is changed (such entries are dropped from the edits).
    bool isDefault() const { return *this == StrandStyle{}; }
};

// Sorted by identity so files and hashes are deterministic.
using StyleEdits = std::map<std::uint64_t, StrandStyle>;
using StyleEditsPtr = std::shared_ptr<const StyleEdits>;

// Limits every brush and file respects.
constexpr float kStyleMinLengthMetres = 0.005f; // the Length parameter's minimum
constexpr float kStyleMaxLengthMetres = 2.0f; // its maximum
constexpr float kStyleMaxStiffnessScale = 50.0f;
constexpr float kStyleMaxCurlRadiusMetres = 0.05f;
constexpr float kStyleMaxCurlTurnsPerMetre = 200.0f;
constexpr std::size_t kStyleMaxShapePoints = 1024;

// Empty when usable; otherwise names the strand and the problem
// ("strand 4294967298: wetness 3 is outside 0..1").
[[nodiscard]] std::string validateStrandStyle(std::uint64_t identity, const StrandStyle& style);

// A hash of everything that changes a strand's rest shape (length, curl, shape); 0 for none.
std::uint64_t restShapeHash(const StrandStyle& style);

// `shape` cut to `lengthMetres` of arc length (a cut), or continued straight along its last
// segment to that length (growing). Returns the input when it has fewer than 2 points.
std::vector<glm::vec3> shapeWithLength(std::span<const glm::vec3> shape, float lengthMetres);

} // namespace wisp
