#pragma once
// The groom: where strands grow (roots on the head), how they are grouped into wisps, and the rest
// shape each strand returns to. Follows Lee et al., "An Interactive System for 3D Hairstyles":
// a growth map places pores by density, pores are grouped into wisps of `wisp size` strands, each
// wisp has a key hair, and members follow it by clump-degree and clump-rate.

#include "sim/geometry/HairCurves.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/params/Parameters.h"
#include "sim/solver/Solver.h"
#include "sim/style/StyleEdits.h"

#include <glm/mat3x3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace wisp {

class SignedDistanceField;
class MeshBvh;

struct GroomSettings {
    float densityPerCm2 = 0.0f; // drawn strands per cm² where the growth weight is 1
    int wispSize = 1; // strands per wisp
    float clumpDegree = 0.0f; // -1..1
    float clumpRate = 0.0f; // 0..1, fraction of the strand length where clumping starts
    float lengthMetres = 0.0f; // arc length
    float lengthVariation = 0.0f;
    int segments = 0; // per strand; particles = segments + 1
    float curlRadiusMetres = 0.0f;
    float curlTurnsPerMetre = 0.0f;
    std::uint32_t seed = 0;
    float hairOffsetMetres = 0.0f; // rest shapes keep this far from the skin
};

GroomSettings groomSettingsFrom(const ParameterValues& values);

// Empty when usable; otherwise names the setting and the problem ("segments: 1 is outside 2..127").
[[nodiscard]] std::string validateGroomSettings(const GroomSettings& settings);

// The helix a curl winds along (the perm of Lee et al.), counted per metre of hair: the hair (arc
// length along the helix) makes `turnsPerMetre` turns per metre. A turn takes 1 / T of hair, of
// which 2 pi r goes around the axis, so the helix advances p = sqrt(1 / T^2 - (2 pi r)^2) along its
// centreline per turn. Hair cannot wind tighter than a flat ring (2 pi r T = 1): turns are clamped
// to kMaxCurlWrap / (2 pi r), the tightest curl of that radius (its pitch is then 31% of a turn's
// hair); `clamped` says so. The groom places the strand's points a whole segment apart along the hair,
// each anglePerSegment further around, so the polyline keeps both the strand's length and T.
constexpr float kMaxCurlWrap = 0.95f;
struct CurlHelix {
    float radiusMetres = 0.0f;
    float turnsPerMetre = 0.0f; // per metre of hair, after the clamp; 0: straight
    float pitchMetres = 0.0f; // centreline advance per turn (the smooth helix)
    float anglePerSegment = 0.0f; // radians around the centreline per segment of the strand
    bool clamped = false; // asked for more turns than the radius allows
};
CurlHelix curlHelix(float lengthMetres, int segments, float radiusMetres, float turnsPerMetreOfHair);

// One growth region's part of a groom (see GrowthRegion.h): where it grows and its wisp settings.
struct GroomRegionInput {
    std::uint32_t id = 0; // stable region identity; seeds its roots
    std::span<const float> weights; // one per head vertex, 0..1
    GroomSettings settings; // its wisp settings; segments, seed and hair offset come from the shared ones
    float stiffnessScale = 1.0f; // multiplies the solver's stiffness for this region's strands
    // Imported strands (GrowthRegion::importedStrands): each its own wisp, resampled to the shared
    // segment count and rooted at the nearest point of the head; `weights` are then ignored.
    const HairCurves* importedStrands = nullptr;
};

struct Groom {
    GroomSettings settings; // shared by every region: segments, seed, hair offset (and, with one region, its settings)
    // Per strand (every drawn strand):
    std::vector<SurfacePoint> roots;
    std::vector<glm::vec3> rootPositions; // head space, metres (the surface points, evaluated)
    std::vector<std::uint32_t> rootIds; // stable identity of the root in the weight-independent pore set
    std::vector<float> lengths; // metres
    std::vector<std::uint32_t> wispOf;
    std::vector<std::uint16_t> regionOfStrand; // index into the per-region vectors below
    std::vector<std::uint64_t> styleHash; // restShapeHash of the strand's salon edit (0: none)
    HeadCurves rest; // rest shape of every strand, head space (members built from their key hair)
    // Per wisp:
    std::vector<std::uint32_t> keyStrand; // the strand that is the wisp's key hair
    std::vector<std::uint32_t> siteOfWisp; // the wisp's site in its region's layout (identity for reuse)
    // Per region that grew (in the order given):
    std::vector<std::uint32_t> regionIds;
    std::vector<GroomSettings> regionSettings; // complete: the shared settings merged in
    std::vector<float> regionStiffnessScale;

    std::size_t strandCount() const { return roots.size(); }
    std::size_t wispCount() const { return keyStrand.size(); }
    bool isKey(std::size_t strand) const { return keyStrand[wispOf[strand]] == strand; }
    const GroomSettings& settingsOfWisp(std::size_t wisp) const
    {
        return regionSettings[regionOfStrand[keyStrand[wisp]]];
    }
    // Identity of a strand across regrooms: its region and its pore in that region's layout.
    std::uint64_t strandIdentity(std::size_t strand) const
    {
        return (static_cast<std::uint64_t>(regionIds[regionOfStrand[strand]]) << 32) | rootIds[strand];
    }
};

// Pore candidates a region's layout may draw over the whole head (4 per strand at the asked
// density). Past it the layout is made sparser, evenly, and GroomResult warns: a stray vertex far
// away used to make the candidates, and a groom, take 12-34 s and 266 MB.
// 2,097,152: the built-in head at the highest density (200 strands/cm²) needs 1.4 million.
inline constexpr std::size_t kMaxPoreCandidates = std::size_t{ 1 } << 21;

struct GroomResult {
    Groom groom;
    std::string error; // empty on success
    std::vector<std::string> warnings{}; // what the artist should know (a capped layout); sim never logs
    bool ok() const { return error.empty(); }
};

// Places roots where growthWeights (one per vertex, 0..1) allow, groups them into wisps and builds
// rest shapes. Deterministic for a seed, and local: changing the weights in one area adds or removes
// roots only there. If `collider` is given, rest nodes that fall inside the head are pushed out
// (Lee et al. 3.4) so the rest shape drapes over the head.
GroomResult buildGroom(const TriangleMesh& head, std::span<const float> growthWeights, const GroomSettings& settings,
    const SignedDistanceField* collider = nullptr);

// Builds the groom of several regions on one head, as the editor does on every brush dab and slider
// move. It keeps what does not depend on the painted weights (each region's pore and wisp-site
// layout, the head's normals), and with `previous` (a groom it built on the same head) it copies the
// rest shapes of wisps whose members and settings did not change, so a dab costs work near the
// brush, not over the whole head. Regions that grow no strand are allowed (an empty groom too).
//
// Thread: one owner.
class GroomBuilder {
public:
    GroomBuilder();
    ~GroomBuilder();
    GroomBuilder(GroomBuilder&&) noexcept;
    GroomBuilder& operator=(GroomBuilder&&) noexcept;

    // `bvh` (of `head`) is needed only by regions of imported strands, to root them on the head.
    // `style` (salon edits by strand identity) overrides lengths and curl and gives rest shapes
    // (comb): a combed strand's rest shape is its edit's shape, resampled.
    GroomResult build(const TriangleMesh& head, std::span<const GroomRegionInput> regions, const GroomSettings& shared,
        const SignedDistanceField* collider, const Groom* previous = nullptr, const MeshBvh* bvh = nullptr,
        const StyleEdits* style = nullptr);
    // Drops everything kept for the head (call when the head changes).
    void forgetHead();
    // Wisps whose rest shapes the last build copied from `previous`, and built anew.
    std::size_t reusedWisps() const { return m_reused; }
    std::size_t builtWisps() const { return m_built; }
    // Pore candidates behind the layouts the last build used (each at most maxPoreCandidates()).
    std::size_t poreCandidates() const { return m_poreCandidates; }
    // The cap on one layout's candidates: kMaxPoreCandidates unless a test lowers it to check the
    // capping with little work. Changing it forgets the kept layouts.
    void setMaxPoreCandidates(std::size_t cap);
    std::size_t maxPoreCandidates() const { return m_maxPoreCandidates; }

private:
    struct Cache;
    std::unique_ptr<Cache> m_cache;
    std::size_t m_reused = 0;
    std::size_t m_built = 0;
    std::size_t m_poreCandidates = 0;
    std::size_t m_maxPoreCandidates = kMaxPoreCandidates;
};

// `strand` resampled to `points` points evenly spaced along its arc length (the first and last
// points kept). Strands of imported hair have any number of points; the solver wants one count.
std::vector<glm::vec3> resampleByArcLength(std::span<const glm::vec3> strand, std::size_t points);

// The first paper's layout: width x height strands of `particlesPerStrand` particles each, rooted on a
// grid over the top of the head (azimuth x polar angle around the head's centre), every strand its
// own wisp so all are simulated.
GroomResult buildGridGroom(const TriangleMesh& head, const MeshBvh& bvh, int width, int height, int particlesPerStrand,
    float lengthMetres, const SignedDistanceField* collider = nullptr);

// Rebuilds every member strand from its wisp's key hair (level of detail: the keys are simulated,
// members follow). `keyPositions` holds the key strands' points, wisp after wisp, each with the same
// point count as in groom.rest; `headRotation` turns head-space root offsets into world space.
// `out` must have the layout of groom.rest; keys are copied, members written.
// `wetClumpOfWisp` (per wisp, 0..1, empty for none) pulls each wisp's clump degree toward 1 by
// that share: wet hair sticks together.
// `contact` (optional): the head every drawn strand must stay out of, in the frame's space. With
// it, each member is rebuilt with its own rest lengths (follow-the-leader along the guide its key
// gives) and pushed out of the head keeping them (keepMemberShape), so what is drawn keeps the
// solver's invariants: length, and outside the head.
struct MemberContact {
    const SignedDistanceField* head = nullptr; // head space
    glm::mat3 headRotation{ 1.0f }; // head to frame space
    glm::vec3 headTranslation{ 0.0f };
    float offsetMetres = 0.0f; // kept between hair and skin
    std::span<const Capsule> body; // neck and shoulders, frame space (none: empty)
};
void buildMembers(const Groom& groom, std::span<const glm::vec3> keyPositions, const glm::mat3& headRotation,
    HairCurves& out, std::span<const float> wetClumpOfWisp = {}, const MemberContact* contact = nullptr);
// One member's points (root first, root kept) made `rest`'s segment lengths and put outside the head.
void keepMemberShape(std::span<const glm::vec3> rest, const MemberContact& contact, std::span<glm::vec3> points);

// The key strands' rest shapes, wisp after wisp (the layout buildMembers reads).
HeadCurves keyRestCurves(const Groom& groom);

} // namespace wisp
