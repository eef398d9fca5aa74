#pragma once
// How the head moves over time: keyframes on its rigid transform, and a procedural motion (turn,
// nod, shake, walk) layered on top. Evaluated at a time in seconds; the bake (HairBake.h) gives
// the result to Solver::setHeadTransform before each step, so roots follow and the hair swings.
//
// The head's velocity is continuous everywhere, because the hair feels the head through its roots:
// a jump in velocity is an impulse that flings the hair (Verlet integration reads velocity from the
// last two positions, so a jump of v m/s is felt as one step of acceleration v / dt).
//   - Translation between keys: cubic Hermite with Catmull-Rom tangents for uneven key spacing,
//     m_i = (p_{i+1} - p_{i-1}) / (t_{i+1} - t_{i-1}); zero tangents at the first and last key,
//     so the head eases out of and into the hold before the first and after the last key (C1).
//   - Rotation between keys: slerp along the shorter arc, with the fraction eased by smoothstep
//     (3s² - 2s³), so the angular velocity is zero at every key and continuous across it (C1).
//     (Squad would keep the head turning through a key, but is C1 only for evenly spaced keys.)
//   - A procedural motion fades in with a smoothstep envelope over its first period, so its
//     velocity is zero when it starts.
//
// Rotations turn about the head's pivot (head space, metres): the top of the neck, where a head
// turns (see pivotOf). Thread: value type, no shared state.

#include "sim/geometry/TriangleMesh.h"
#include "sim/params/MotionSettings.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace wisp {

// The head's rigid pose: turned by `rotation` about the pivot, then moved by `translationMetres`.
struct HeadPose {
    glm::vec3 translationMetres{ 0.0f };
    glm::quat rotation{ 1.0f, 0.0f, 0.0f, 0.0f }; // w, x, y, z

    bool operator==(const HeadPose&) const = default;
};

// Head space to world space: T(translation) · T(pivot) · R · T(-pivot).
glm::mat4 headToWorld(const HeadPose& pose, const glm::vec3& pivotHead);

// The composition "first `inner`, then `outer`" (both about the same pivot).
HeadPose compose(const HeadPose& outer, const HeadPose& inner);

struct HeadKey {
    double timeSeconds = 0.0;
    HeadPose pose;

    bool operator==(const HeadKey&) const = default;
};

enum class MotionKind { None, Turn, Nod, Shake, Walk };

// A repeating motion. Turn and shake turn the head about +Y (left and right: turn slowly and far,
// shake quickly and a little) and nod tilts it about +X, by `amplitude` degrees each way. Walk
// bobs the head up by `amplitude` metres twice per stride (A·sin²) and sways it sideways by half
// that once per stride: the head's path when walking on the spot.
struct ProceduralMotion {
    MotionKind kind = MotionKind::None;
    double amplitude = 0.0; // degrees (turn, nod, shake) or metres (walk)
    double frequencyHz = 1.0; // cycles (strides, for walk) per second
    double startSeconds = 0.0; // the motion fades in over its first period from here

    bool operator==(const ProceduralMotion&) const = default;
};

// "none", "turn", "nod", "shake", "walk"; and back (nullopt for anything else).
std::string_view motionName(MotionKind kind);
std::optional<MotionKind> motionFromName(std::string_view name);
// The preset of each kind: what `wisp-cli bake --motion NAME` and the editor's chooser start from.
ProceduralMotion motionPreset(MotionKind kind);

// The range a motion's amplitude has in the registry (sim/params/Parameters.h, where every motion
// range is stated): metres for walk, degrees for the others.
MotionSetting amplitudeSettingOf(MotionKind kind);

class HeadMotion {
public:
    // Sorted by time; no two keys within kSameTimeSeconds.
    const std::vector<HeadKey>& keys() const { return m_keys; }
    // Sets the pose at `timeSeconds`: replaces a key at that time or inserts one. Returns its index.
    std::size_t setKey(double timeSeconds, const HeadPose& pose);
    // False, changing nothing, when there is no such key.
    bool removeKey(std::size_t index);
    // Moves a key in time (keeping its pose); refuses (returns the message, changes nothing) when
    // another key is already at that time. Returns the key's new index in `newIndex`.
    std::string moveKey(std::size_t index, double timeSeconds, std::size_t* newIndex = nullptr);
    void clearKeys() { m_keys.clear(); }

    const ProceduralMotion& procedural() const { return m_procedural; }
    void setProcedural(const ProceduralMotion& motion) { m_procedural = motion; }

    // Empty when every key and the procedural motion are finite and within the registry's motion
    // ranges (MotionSetting), with unit rotations; otherwise what is wrong, naming the field
    // ("keys[2]: time nan is not a finite number", "motion: amplitude 120 is outside 0..90 degrees").
    std::string validate() const;
    static std::string validateProcedural(const ProceduralMotion& motion);

    // True when the head never moves (no keys away from rest and no procedural motion).
    bool isStill() const;

    // The pose at `timeSeconds`: the keys' (the first key's before it, the last's after it, rest
    // without keys), then the procedural motion on top.
    HeadPose poseAt(double timeSeconds) const;
    glm::mat4 headToWorldAt(double timeSeconds, const glm::vec3& pivotHead) const
    {
        return headToWorld(poseAt(timeSeconds), pivotHead);
    }

    // The keys' pose alone at `timeSeconds` (no procedural motion on top): what a new key keeps.
    HeadPose keyedPoseAt(double timeSeconds) const;

    bool operator==(const HeadMotion&) const = default;

    static constexpr double kSameTimeSeconds = 1e-6;

private:
    std::vector<HeadKey> m_keys;
    ProceduralMotion m_procedural;
};

// The pose a procedural motion alone gives at `timeSeconds` (rest before it starts).
HeadPose proceduralPoseAt(const ProceduralMotion& motion, double timeSeconds);

// Where a head turns: the top of the neck under it (Body.h's neck capsule), head space, metres.
glm::vec3 pivotOf(const TriangleMesh& head);

} // namespace wisp
