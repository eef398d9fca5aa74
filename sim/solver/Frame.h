#pragma once
// One published state of the simulation: immutable once made, shared by the simulation thread
// (which makes it) and the viewport (which draws it). Readers hold a shared_ptr<const Frame>; the
// simulation thread never touches a frame after publishing it, so no lock is held while drawing.

#include "sim/geometry/HairCurves.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace wisp {

// How a region's hair looks: sRGB 0..1 at the root and the tip, and how thick it is.
struct StrandLook {
    glm::vec3 rootColour{ 0.0f };
    glm::vec3 tipColour{ 0.0f };
    float rootThicknessMetres = 0.0f; // one hair's, at the root (Param::HairThickness); 0: the viewport's own
};

// The groom behind a frame, shared by every frame of one groom: the rest pose of every drawn
// strand (head space) and which strands are the simulated key hairs, for exports of the rest pose
// or of the keys only, and what the styling brushes need to name strands (StyleEdits.h).
struct GroomShape {
    HeadCurves rest; // every drawn strand's rest shape, head space
    std::vector<std::uint32_t> keyStrands; // the simulated strands, ascending
    std::vector<std::uint64_t> identities; // per drawn strand: Groom::strandIdentity
    std::vector<std::uint32_t> wispOf; // per drawn strand
    std::vector<std::uint32_t> keyOfWisp; // per wisp: its key hair
    std::vector<float> lengths; // per drawn strand: its groomed length, metres (a member's
                                // rest arc length differs a little: it rides beside its key)
};

struct Frame {
    std::uint64_t step = 0; // steps taken since the groom was (re)built or reset
    std::uint64_t groomVersion = 0; // changes when the strands' count or layout changes
    double simulatedSeconds = 0.0;
    WorldCurves strands; // every drawn strand, world space, metres; members rebuilt from keys
    std::vector<StrandLook> looks; // one per growing region
    std::vector<std::uint16_t> lookOfStrand; // per drawn strand, index into looks; empty: the viewport's colours
    std::size_t simulatedStrands = 0;
    std::size_t simulatedParticles = 0;
    double stepMilliseconds = 0.0; // wall-clock time of the solver step that made this frame
    double timeScale = 1.0; // simulated seconds per wall-clock second (below 1: slow motion)
    bool fallingBehind = false; // the solver could not keep real time
    glm::vec3 wind{ 0.0f }; // m/s, world space (for the viewport's arrow)
    // Head space to world space as the solver had it for this frame (the viewport draws the head
    // with it), and the head's pose about its pivot (the editor's head drag starts from it).
    glm::mat4 headToWorld{ 1.0f };
    glm::vec3 headTranslationMetres{ 0.0f };
    glm::quat headRotation{ 1.0f, 0.0f, 0.0f, 0.0f };
    std::vector<float> wetness; // per drawn strand, 0..1; empty when all the hair is dry
    std::shared_ptr<const GroomShape> groomShape;
};

using FramePtr = std::shared_ptr<const Frame>;

} // namespace wisp
