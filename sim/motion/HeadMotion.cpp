#include "sim/motion/HeadMotion.h"

#include "sim/geometry/Body.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace {

std::string number(double v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// 3s² - 2s³ on 0..1: zero slope at both ends.
double smoothstep(double s)
{
    s = std::clamp(s, 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
}

glm::quat axisAngle(double degrees, const glm::vec3& axis)
{
    return glm::angleAxis(static_cast<float>(glm::radians(degrees)), axis);
}

} // namespace

glm::mat4 headToWorld(const HeadPose& pose, const glm::vec3& pivotHead)
{
    // T(translation) · T(pivot) · R · T(-pivot), written out: rotation columns, then the offset.
    glm::mat4 m = glm::mat4_cast(pose.rotation);
    const glm::vec3 offset = pose.translationMetres + pivotHead - glm::mat3(m) * pivotHead;
    m[3] = glm::vec4(offset, 1.0f);
    return m;
}

HeadPose compose(const HeadPose& outer, const HeadPose& inner)
{
    // Both about the same pivot p: x -> Ro(Ri(x - p) + p + ti - p) + p + to = RoRi(x - p) + p + Ro ti + to.
    return { outer.translationMetres + outer.rotation * inner.translationMetres,
        glm::normalize(outer.rotation * inner.rotation) };
}

std::string_view motionName(MotionKind kind)
{
    switch (kind) {
    case MotionKind::None:
        return "none";
    case MotionKind::Turn:
        return "turn";
    case MotionKind::Nod:
        return "nod";
    case MotionKind::Shake:
        return "shake";
    case MotionKind::Walk:
        return "walk";
    }
    return "none";
}

std::optional<MotionKind> motionFromName(std::string_view name)
{
    for (MotionKind k : { MotionKind::None, MotionKind::Turn, MotionKind::Nod, MotionKind::Shake, MotionKind::Walk })
        if (motionName(k) == name)
            return k;
    return std::nullopt;
}

ProceduralMotion motionPreset(MotionKind kind)
{
    switch (kind) {
    case MotionKind::None:
        return {};
    // Looking over one shoulder and the other, about once every 3 s.
    case MotionKind::Turn:
        return { MotionKind::Turn, 50.0, 0.3, 0.0 };
    case MotionKind::Nod:
        return { MotionKind::Nod, 20.0, 0.8, 0.0 };
    // A "no": a little under 2 shakes a second.
    case MotionKind::Shake:
        return { MotionKind::Shake, 30.0, 1.75, 0.0 };
    // Walking at about 0.9 strides (1.8 steps) a second; the head rises and falls about 4 cm.
    case MotionKind::Walk:
        return { MotionKind::Walk, 0.04, 0.9, 0.0 };
    }
    return {};
}

HeadPose proceduralPoseAt(const ProceduralMotion& motion, double timeSeconds)
{
    const double since = timeSeconds - motion.startSeconds;
    if (motion.kind == MotionKind::None || !(since > 0.0) || !(motion.frequencyHz > 0.0))
        return {};
    const double period = 1.0 / motion.frequencyHz;
    const double envelope = smoothstep(since / period);
    const double phase = 2.0 * glm::pi<double>() * motion.frequencyHz * since;
    const double wave = envelope * std::sin(phase);
    HeadPose pose;
    switch (motion.kind) {
    case MotionKind::None:
        break;
    case MotionKind::Turn:
    case MotionKind::Shake:
        pose.rotation = axisAngle(motion.amplitude * wave, { 0.0f, 1.0f, 0.0f });
        break;
    case MotionKind::Nod:
        pose.rotation = axisAngle(motion.amplitude * wave, { 1.0f, 0.0f, 0.0f });
        break;
    case MotionKind::Walk: {
        const double s = std::sin(phase);
        pose.translationMetres = glm::vec3(static_cast<float>(envelope * 0.5 * motion.amplitude * s),
            static_cast<float>(envelope * motion.amplitude * s * s), 0.0f);
        break;
    }
    }
    return pose;
}

std::size_t HeadMotion::setKey(double timeSeconds, const HeadPose& pose)
{
    auto at = std::lower_bound(m_keys.begin(), m_keys.end(), timeSeconds - kSameTimeSeconds,
        [](const HeadKey& k, double t) { return k.timeSeconds < t; });
    if (at != m_keys.end() && std::abs(at->timeSeconds - timeSeconds) <= kSameTimeSeconds) {
        at->pose = pose;
        return static_cast<std::size_t>(at - m_keys.begin());
    }
    at = m_keys.insert(at, HeadKey{ timeSeconds, pose });
    return static_cast<std::size_t>(at - m_keys.begin());
}

bool HeadMotion::removeKey(std::size_t index)
{
    if (index >= m_keys.size())
        return false;
    m_keys.erase(m_keys.begin() + static_cast<std::ptrdiff_t>(index));
    return true;
}

std::string HeadMotion::moveKey(std::size_t index, double timeSeconds, std::size_t* newIndex)
{
    if (index >= m_keys.size())
        return "there is no key " + std::to_string(index);
    if (std::string problem = checkMotionSetting(MotionSetting::Time, timeSeconds); !problem.empty())
        return "time " + problem;
    for (std::size_t i = 0; i < m_keys.size(); ++i)
        if (i != index && std::abs(m_keys[i].timeSeconds - timeSeconds) <= kSameTimeSeconds)
            return "there is already a key at " + number(timeSeconds) + " s";
    const HeadPose pose = m_keys[index].pose;
    m_keys.erase(m_keys.begin() + static_cast<std::ptrdiff_t>(index));
    const std::size_t at = setKey(timeSeconds, pose);
    if (newIndex)
        *newIndex = at;
    return {};
}

MotionSetting amplitudeSettingOf(MotionKind kind)
{
    return kind == MotionKind::Walk ? MotionSetting::WalkAmplitude : MotionSetting::TurnAmplitude;
}

std::string HeadMotion::validateProcedural(const ProceduralMotion& m)
{
    if (std::string problem = checkMotionSetting(amplitudeSettingOf(m.kind), m.amplitude); !problem.empty())
        return "amplitude " + problem;
    if (std::string problem = checkMotionSetting(MotionSetting::Frequency, m.frequencyHz); !problem.empty())
        return "frequency " + problem;
    if (std::string problem = checkMotionSetting(MotionSetting::Time, m.startSeconds); !problem.empty())
        return "start " + problem;
    return {};
}

std::string HeadMotion::validate() const
{
    for (std::size_t i = 0; i < m_keys.size(); ++i) {
        const HeadKey& k = m_keys[i];
        const std::string where = "keys[" + std::to_string(i) + "]: ";
        if (std::string problem = checkMotionSetting(MotionSetting::Time, k.timeSeconds); !problem.empty())
            return where + "time " + problem;
        if (i > 0 && !(k.timeSeconds - m_keys[i - 1].timeSeconds > kSameTimeSeconds))
            return where + "time " + number(k.timeSeconds) + " s does not come after the key before it";
        for (int axis = 0; axis < 3; ++axis)
            if (std::string problem = checkMotionSetting(MotionSetting::Translation, k.pose.translationMetres[axis]);
                !problem.empty())
                return where + "translation[" + std::to_string(axis) + "] " + problem;
        const glm::quat& q = k.pose.rotation;
        const float length = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
        if (!std::isfinite(length) || std::abs(length - 1.0f) > 1e-3f)
            return where + "rotation is not a unit quaternion (length " + number(length) + ")";
    }
    if (const std::string e = validateProcedural(m_procedural); !e.empty())
        return "motion: " + e;
    return {};
}

bool HeadMotion::isStill() const
{
    if (m_procedural.kind != MotionKind::None && m_procedural.amplitude > 0.0)
        return false;
    return std::all_of(m_keys.begin(), m_keys.end(), [](const HeadKey& k) { return k.pose == HeadPose{}; });
}

HeadPose HeadMotion::keyedPoseAt(double t) const
{
    if (m_keys.empty())
        return {};
    if (t <= m_keys.front().timeSeconds)
        return m_keys.front().pose;
    if (t >= m_keys.back().timeSeconds)
        return m_keys.back().pose;
    const auto next = std::upper_bound(
        m_keys.begin(), m_keys.end(), t, [](double time, const HeadKey& k) { return time < k.timeSeconds; });
    const std::size_t i1 = static_cast<std::size_t>(next - m_keys.begin()), i0 = i1 - 1;
    const HeadKey& k0 = m_keys[i0];
    const HeadKey& k1 = m_keys[i1];
    const double h = k1.timeSeconds - k0.timeSeconds;
    const double s = (t - k0.timeSeconds) / h;

    // Catmull-Rom tangents (m/s) for uneven spacing; zero at the ends (ease in and out of the hold).
    auto tangent = [&](std::size_t i) -> glm::dvec3 {
        if (i == 0 || i + 1 >= m_keys.size())
            return glm::dvec3(0.0);
        return (glm::dvec3(m_keys[i + 1].pose.translationMetres) - glm::dvec3(m_keys[i - 1].pose.translationMetres))
            / (m_keys[i + 1].timeSeconds - m_keys[i - 1].timeSeconds);
    };
    // Cubic Hermite basis.
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    const glm::dvec3 p = h00 * glm::dvec3(k0.pose.translationMetres) + h10 * h * tangent(i0)
        + h01 * glm::dvec3(k1.pose.translationMetres) + h11 * h * tangent(i1);

    glm::quat q1 = k1.pose.rotation;
    if (glm::dot(k0.pose.rotation, q1) < 0.0f)
        q1 = -q1; // the shorter arc
    const glm::quat q = glm::normalize(glm::slerp(k0.pose.rotation, q1, static_cast<float>(smoothstep(s))));
    return { glm::vec3(p), q };
}

HeadPose HeadMotion::poseAt(double timeSeconds) const
{
    const HeadPose keyed = keyedPoseAt(timeSeconds);
    if (m_procedural.kind == MotionKind::None)
        return keyed;
    return compose(keyed, proceduralPoseAt(m_procedural, timeSeconds));
}

glm::vec3 pivotOf(const TriangleMesh& head)
{
    const std::vector<Capsule> body = defaultBody(head);
    if (body.size() > kBodyNeck)
        return body[kBodyNeck].a;
    return glm::vec3(0.0f);
}

} // namespace wisp
