#include "io/MotionJson.h"

#include <cmath>
#include <set>

namespace wisp::io::detail {

namespace {

using nlohmann::json;
using nlohmann::ordered_json;

void warnUnknown(const json& object, const std::string& path, const std::set<std::string>& known, Warnings& warnings)
{
    for (const auto& [key, value] : object.items())
        if (!known.contains(key))
            warnings.add(childPath(path, key), "unknown key, ignored");
}

int readFrame(const json& value, const std::string& path)
{
    const double n = readFiniteNumber(value, path);
    if (std::floor(n) != n || n < 1.0 || n > BakeRange::kMaxFrame)
        throw Refusal{ path, describe(value) + " is not a frame 1.." + std::to_string(BakeRange::kMaxFrame) };
    return static_cast<int>(n);
}

// A finite number inside the registry's range for `setting`; refused at `path` otherwise.
double readMotionSetting(const json& value, const std::string& path, MotionSetting setting)
{
    const double x = readFiniteNumber(value, path);
    if (std::string problem = checkMotionSetting(setting, x); !problem.empty())
        throw Refusal{ path, problem };
    return x;
}

} // namespace

ordered_json motionToJson(const HeadMotion& motion)
{
    ordered_json keys = ordered_json::array();
    for (const HeadKey& k : motion.keys()) {
        ordered_json key;
        key["time"] = k.timeSeconds;
        key["translation"] = vec3ToJson(k.pose.translationMetres);
        const glm::quat& q = k.pose.rotation;
        key["rotation"] = { shortestDoubleForFloat(q.w), shortestDoubleForFloat(q.x), shortestDoubleForFloat(q.y),
            shortestDoubleForFloat(q.z) };
        keys.push_back(std::move(key));
    }
    const ProceduralMotion& p = motion.procedural();
    ordered_json procedural;
    procedural["kind"] = std::string(motionName(p.kind));
    procedural["amplitude"] = p.amplitude;
    procedural["frequency"] = p.frequencyHz;
    procedural["start"] = p.startSeconds;
    ordered_json out;
    out["keys"] = std::move(keys);
    out["procedural"] = std::move(procedural);
    return out;
}

ordered_json timelineToJson(const BakeRange& timeline)
{
    ordered_json out;
    out["first_frame"] = timeline.firstFrame;
    out["last_frame"] = timeline.lastFrame;
    out["fps"] = timeline.fps;
    return out;
}

HeadMotion readMotion(const json& value, const std::string& path, Warnings& warnings)
{
    requireObject(value, path);
    warnUnknown(value, path, { "keys", "procedural" }, warnings);
    HeadMotion motion;
    if (const auto it = value.find("keys"); it != value.end()) {
        const std::string keysPath = childPath(path, "keys");
        if (!it->is_array())
            throw Refusal{ keysPath, "expected a list [ ... ] of keys, found " + describe(*it) };
        constexpr std::size_t kMaxKeys = 100000;
        if (it->size() > kMaxKeys)
            throw Refusal{ keysPath, std::to_string(it->size()) + " keys; at most " + std::to_string(kMaxKeys) };
        double previous = -INFINITY;
        for (std::size_t i = 0; i < it->size(); ++i) {
            const json& k = (*it)[i];
            const std::string keyPath = keysPath + "[" + std::to_string(i) + "]";
            requireObject(k, keyPath);
            warnUnknown(k, keyPath, { "time", "translation", "rotation" }, warnings);
            HeadKey key;
            const auto time = k.find("time");
            if (time == k.end())
                throw Refusal{ childPath(keyPath, "time"), "missing" };
            key.timeSeconds = readMotionSetting(*time, childPath(keyPath, "time"), MotionSetting::Time);
            if (!(key.timeSeconds - previous > HeadMotion::kSameTimeSeconds))
                throw Refusal{ childPath(keyPath, "time"), "keys must be in increasing time" };
            previous = key.timeSeconds;
            if (const auto t = k.find("translation"); t != k.end()) {
                const std::string tPath = childPath(keyPath, "translation");
                if (!t->is_array() || t->size() != 3)
                    throw Refusal{ tPath, "expected 3 finite numbers (metres)" };
                for (int c = 0; c < 3; ++c)
                    key.pose.translationMetres[c] = static_cast<float>(
                        readMotionSetting((*t)[c], tPath + "[" + std::to_string(c) + "]", MotionSetting::Translation));
            }
            if (const auto r = k.find("rotation"); r != k.end()) {
                const std::string rPath = childPath(keyPath, "rotation");
                if (!r->is_array() || r->size() != 4)
                    throw Refusal{ rPath, "expected a unit quaternion [w, x, y, z]" };
                float q[4];
                for (int c = 0; c < 4; ++c)
                    q[c] = static_cast<float>(readFiniteNumber((*r)[c], rPath));
                key.pose.rotation = glm::quat(q[0], q[1], q[2], q[3]);
            }
            motion.setKey(key.timeSeconds, key.pose);
        }
    }
    if (const auto it = value.find("procedural"); it != value.end()) {
        const std::string pPath = childPath(path, "procedural");
        requireObject(*it, pPath);
        warnUnknown(*it, pPath, { "kind", "amplitude", "frequency", "start" }, warnings);
        ProceduralMotion p;
        if (const auto kind = it->find("kind"); kind != it->end()) {
            const std::string name = readText(*kind, childPath(pPath, "kind"), 32);
            const std::optional<MotionKind> k = motionFromName(name);
            if (!k)
                throw Refusal{ childPath(pPath, "kind"), "'" + name + "' is not none, turn, nod, shake or walk" };
            p = motionPreset(*k);
        }
        if (const auto a = it->find("amplitude"); a != it->end())
            p.amplitude = readMotionSetting(*a, childPath(pPath, "amplitude"), amplitudeSettingOf(p.kind));
        if (const auto f = it->find("frequency"); f != it->end())
            p.frequencyHz = readMotionSetting(*f, childPath(pPath, "frequency"), MotionSetting::Frequency);
        if (const auto s = it->find("start"); s != it->end())
            p.startSeconds = readMotionSetting(*s, childPath(pPath, "start"), MotionSetting::Time);
        if (std::string e = HeadMotion::validateProcedural(p); !e.empty())
            throw Refusal{ pPath, e };
        motion.setProcedural(p);
    }
    if (std::string e = motion.validate(); !e.empty())
        throw Refusal{ path, e };
    return motion;
}

BakeRange readTimeline(const json& value, const std::string& path, Warnings& warnings)
{
    requireObject(value, path);
    warnUnknown(value, path, { "first_frame", "last_frame", "fps" }, warnings);
    BakeRange range;
    if (const auto it = value.find("first_frame"); it != value.end())
        range.firstFrame = readFrame(*it, childPath(path, "first_frame"));
    if (const auto it = value.find("last_frame"); it != value.end())
        range.lastFrame = readFrame(*it, childPath(path, "last_frame"));
    if (const auto it = value.find("fps"); it != value.end())
        range.fps = readFiniteNumber(*it, childPath(path, "fps"));
    if (std::string e = validateBakeRange(range); !e.empty())
        throw Refusal{ path, e };
    return range;
}

} // namespace wisp::io::detail
