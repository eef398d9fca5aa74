// wisp-cli style: replays one salon brush stroke on a project's hair, headless, and writes the
// project with the stroke's edits. The brush is sim/style/'s operation, the same the editor runs.

#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"
#include "app/cli/OutputCheck.h"
#include "io/ProjectFile.h"
#include "sim/solver/HairSimulation.h"
#include "sim/style/StyleOperation.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <tuple>

namespace wisp::cli {

namespace {

constexpr float kEyeDistanceMetres = 0.4f; // the default eye: this far out from the first point
constexpr float kMaxPointDistanceMetres = 10.0f; // a stroke point farther from the head is a mistake

std::vector<OptionSpec> styleOptions()
{
    return {
        { "help", "", "show this help" },
        { "brush", "NAME",
            "comb, cut, length, curl, wet or hairspray (blow-dry needs the running simulation: "
            "use the editor)" },
        { "stroke", "POINTS",
            "the stroke: 'x,y,z;x,y,z;...', head space, metres, in order. Each point is seen "
            "from the eye; dab brushes dab once at every point, comb and cut need two or more" },
        { "eye", "X,Y,Z",
            "where the artist looks from (head space, metres; default: 0.4 m out from the head's "
            "centre through the first point)" },
        { "radius", "METRES", "brush radius (default 0.02)" },
        { "strength", "S", "brush strength 0..1 (default 0.5)" },
        { "falloff", "F", "brush falloff 0..1 (default 0.5)" },
        { "mirror", "", "X symmetry: the stroke also acts mirrored across the head's middle" },
        { "invert", "", "as Ctrl in the editor: shrink, take the perm out, towel-dry, wash the spray out" },
        { "curl-radius", "METRES", "the perm's curl radius (default 0.01)" },
        { "curl-turns", "N", "the perm's turns per metre (default 10)" },
        { "no-drape", "", "brush the groom's rest pose instead of the hair hanging at rest (quicker)" },
        { "out", "FILE", "write the styled project there (required)" },
    };
}

std::optional<StyleBrush> brushNamed(const std::string& name)
{
    if (name == "comb")
        return StyleBrush::Comb;
    if (name == "cut")
        return StyleBrush::Cut;
    if (name == "length")
        return StyleBrush::Length;
    if (name == "curl")
        return StyleBrush::Curl;
    if (name == "wet")
        return StyleBrush::Wet;
    if (name == "hairspray")
        return StyleBrush::Hairspray;
    if (name == "blow-dry")
        return StyleBrush::BlowDry;
    return std::nullopt;
}

// "x,y,z" as a finite point, or nullopt.
std::optional<glm::vec3> parsePoint(const std::string& text)
{
    glm::vec3 p;
    const char* at = text.c_str();
    for (int axis = 0; axis < 3; ++axis) {
        char* end = nullptr;
        const double v = std::strtod(at, &end);
        if (end == at || !std::isfinite(v) || std::abs(v) > 1e6)
            return std::nullopt;
        p[axis] = static_cast<float>(v);
        at = end;
        while (*at == ' ')
            ++at;
        if (axis < 2 && *at++ != ',')
            return std::nullopt;
    }
    if (*at != '\0')
        return std::nullopt;
    return p;
}

std::vector<glm::vec3> parseStroke(const std::string& text, const Aabb& head)
{
    std::vector<glm::vec3> points;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ';')) {
        const auto p = parsePoint(item);
        if (!p)
            throw CliError{ kBadInput,
                "--stroke: point " + std::to_string(points.size() + 1) + " '" + item
                    + "' is not x,y,z (three finite numbers, metres)" };
        const glm::vec3 outside = glm::max(glm::max(head.min - *p, *p - head.max), glm::vec3(0.0f));
        if (glm::length(outside) > kMaxPointDistanceMetres)
            throw CliError{ kBadInput,
                "--stroke: point " + std::to_string(points.size() + 1) + " '" + item
                    + "' lies more than 10 m from the head: points are in head space, metres" };
        points.push_back(*p);
    }
    if (points.empty())
        throw CliError{ kBadInput, "--stroke: no point given (write 'x,y,z;x,y,z;...')" };
    return points;
}

} // namespace

int runStyle(int argc, char** argv)
{
    const std::vector<OptionSpec> options = styleOptions();
    const CommandLine args(argc, argv, 2, options, 1);
    if (args.has("help")) {
        std::cout << "usage: wisp-cli style PROJECT --brush NAME --stroke 'x,y,z;...' --out FILE [options]\n\n"
                  << describeOptions(options);
        return kSuccess;
    }
    if (args.positional().size() != 1)
        throw CliError{ kUsage, "give one project file (wisp-cli style PROJECT --brush NAME --stroke ... --out FILE)" };
    const auto out = args.text("out");
    if (!out)
        throw CliError{ kUsage, "--out FILE is required" };
    checkOutputPath(*out, "--out", {});
    const auto brushText = args.text("brush");
    if (!brushText)
        throw CliError{ kUsage, "--brush NAME is required (comb, cut, length, curl, wet or hairspray)" };
    const std::optional<StyleBrush> brush = brushNamed(*brushText);
    if (!brush)
        throw CliError{ kBadInput,
            "--brush: '" + *brushText + "' is no brush (comb, cut, length, curl, wet or hairspray)" };
    if (*brush == StyleBrush::BlowDry)
        throw CliError{ kBadInput,
            "--brush blow-dry: the dryer blows and dries the running simulation over time; "
            "style with it in the editor" };

    BrushContext context;
    context.brush.radiusMetres = static_cast<float>(args.real("radius", 0.02));
    context.brush.strength = static_cast<float>(args.real("strength", 0.5));
    context.brush.falloff = static_cast<float>(args.real("falloff", 0.5));
    context.brush.mirrorX = args.has("mirror");
    if (const std::string problem = validateBrush(context.brush); !problem.empty())
        throw CliError{ kBadInput, problem };
    context.curlRadiusMetres = static_cast<float>(args.real("curl-radius", 0.01));
    context.curlTurnsPerMetre = static_cast<float>(args.real("curl-turns", 10.0));
    for (const auto& [setting, value, what] :
        { std::tuple{ ToolSetting::PermRadius, context.curlRadiusMetres, "--curl-radius" },
            std::tuple{ ToolSetting::PermTurns, context.curlTurnsPerMetre, "--curl-turns" } })
        if (const std::string problem = checkToolSetting(setting, value, what); !problem.empty())
            throw CliError{ kBadInput, problem };

    const std::string& path = args.positional().front();
    io::Result<io::ProjectReadResult> read = io::readProject(path, io::readHeadFile);
    if (!read)
        throw CliError{ kBadInput, read.error().toString() };
    for (const std::string& warning : read.value().warnings)
        std::cerr << "wisp-cli style: " << path << ": " << warning << "\n";
    io::Project project = std::move(read).value().project;

    const auto strokeText = args.text("stroke");
    if (!strokeText)
        throw CliError{ kUsage, "--stroke 'x,y,z;...' is required" };
    const Aabb headBox = boundsOf(project.head);
    const std::vector<glm::vec3> stroke = parseStroke(*strokeText, headBox);
    if ((*brush == StyleBrush::Comb || *brush == StyleBrush::Cut) && stroke.size() < 2)
        throw CliError{ kBadInput, "--stroke: the " + *brushText + " moves from point to point: give two or more" };
    glm::vec3 eye = stroke.front() + kEyeDistanceMetres * glm::normalize(stroke.front() - headBox.center());
    if (const auto text = args.text("eye")) {
        const auto given = parsePoint(*text);
        if (!given)
            throw CliError{ kBadInput, "--eye: '" + *text + "' is not x,y,z (three finite numbers, metres)" };
        eye = *given;
    }
    for (std::size_t i = 0; i < stroke.size(); ++i)
        if (glm::distance(stroke[i], eye) < 1e-4f)
            throw CliError{ kBadInput, "--stroke: point " + std::to_string(i + 1) + " is where the eye is" };

    // The hair as the editor shows it: groomed with the project's edits, hanging at rest.
    HairSimulation sim(0);
    std::string error = sim.setup(project.head, project.regions, project.soloRegion, project.parameters);
    if (error.empty() && !project.style.empty()) {
        sim.setStyle(std::make_shared<const StyleEdits>(project.style));
        error = sim.regroom(project.regions, project.soloRegion, project.parameters);
    }
    if (!error.empty())
        throw CliError{ kBadInput, path + ": " + error };
    if (!args.has("no-drape"))
        sim.drapeAtRest();
    auto frame = std::make_shared<Frame>();
    sim.buildFrame(frame->strands);
    frame->groomShape = groomShapeOf(sim);
    context.frame = frame;
    context.head = std::make_shared<const HeadModel>(project.head);
    context.everyStrandSimulated = project.parameters.get(Param::SimulateAllStrands) != 0.0;

    auto sampleAt = [&](const glm::vec3& point) {
        BrushSample s;
        s.eye_ws = eye;
        s.direction_ws = glm::normalize(point - eye);
        s.aimDepthMetres = glm::distance(point, eye);
        s.inverted = args.has("invert");
        return s;
    };
    StyleEdits edits = project.style;
    const std::unique_ptr<StyleOperation> operation = makeStyleOperation(*brush);
    operation->begin(context, sampleAt(stroke.front()), edits);
    for (std::size_t i = 1; i < stroke.size(); ++i)
        operation->step(context, sampleAt(stroke[i]), edits);
    operation->end(context, edits);

    std::erase_if(edits, [](const auto& entry) { return entry.second.isDefault(); });
    int changed = 0;
    for (const auto& [id, style] : edits) {
        if (const std::string problem = validateStrandStyle(id, style); !problem.empty())
            throw CliError{ kBadInput, "the stroke made an edit no file may hold: " + problem };
        const auto before = project.style.find(id);
        changed += before == project.style.end() || !(before->second == style) ? 1 : 0;
    }
    for (const auto& [id, style] : project.style)
        changed += edits.count(id) ? 0 : 1;
    project.style = std::move(edits);
    if (const auto written = io::writeProject(*out, project); !written)
        throw CliError{ kBadInput, written.error().toString() };
    std::cout << *brushText << ": " << changed << (changed == 1 ? " strand" : " strands") << " changed, "
              << operation->changedStrands(changed) << " drawn strands moved or changed; wrote " << *out << "\n";
    return kSuccess;
}

} // namespace wisp::cli
