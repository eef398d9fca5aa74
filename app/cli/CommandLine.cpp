#include "app/cli/CommandLine.h"

#include <cerrno>
#include <cstdlib>
#include <iterator>
#include <sstream>

namespace wisp::cli {

CommandLine::CommandLine(
    int argc, char** argv, int first, const std::vector<OptionSpec>& options, std::size_t positionals)
{
    for (int i = first; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg.rfind("--", 0) != 0 || arg.size() < 3) {
            if (m_positional.size() < positionals && !arg.empty()) {
                m_positional.push_back(arg);
                continue;
            }
            throw CliError{ kUsage, "unexpected argument '" + arg + "' (options start with --)" };
        }
        std::string name = arg.substr(2);
        std::optional<std::string> value;
        if (const auto eq = name.find('='); eq != std::string::npos) {
            value = name.substr(eq + 1);
            name.resize(eq);
        }
        const OptionSpec* spec = nullptr;
        for (const OptionSpec& o : options)
            if (o.name == name)
                spec = &o;
        if (!spec)
            throw CliError{ kUsage, "unknown option --" + name + " (see --help)" };
        if (spec->valueName.empty()) {
            if (value)
                throw CliError{ kUsage, "--" + name + " takes no value" };
            value = "";
        } else if (!value) {
            if (i + 1 >= argc)
                throw CliError{ kUsage, "--" + name + " needs a value (" + spec->valueName + ")" };
            value = argv[++i];
        }
        if (!m_values.count(name))
            m_order.push_back(name);
        m_values[name] = *value;
    }
}

std::optional<std::string> CommandLine::text(const std::string& name) const
{
    const auto it = m_values.find(name);
    if (it == m_values.end())
        return std::nullopt;
    return it->second;
}

long long CommandLine::integer(const std::string& name, long long fallback, long long minimum, long long maximum) const
{
    const auto value = text(name);
    if (!value)
        return fallback;
    char* end = nullptr;
    errno = 0;
    const long long n = std::strtoll(value->c_str(), &end, 10);
    if (value->empty() || end != value->c_str() + value->size() || errno == ERANGE)
        throw CliError{ kBadInput, "--" + name + ": '" + *value + "' is not a whole number" };
    if (n < minimum || n > maximum)
        throw CliError{ kBadInput,
            "--" + name + ": " + *value + " is outside " + std::to_string(minimum) + ".." + std::to_string(maximum) };
    return n;
}

double CommandLine::real(const std::string& name, double fallback) const
{
    const auto value = text(name);
    if (!value)
        return fallback;
    char* end = nullptr;
    const double d = std::strtod(value->c_str(), &end);
    if (value->empty() || end != value->c_str() + value->size())
        throw CliError{ kBadInput, "--" + name + ": '" + *value + "' is not a number" };
    return d;
}

void CommandLine::applyParameters(ParameterValues& values) const
{
    for (const std::string& name : m_order) {
        const ParameterInfo* info = findParameter(name);
        if (!info)
            continue;
        const double value = real(name, 0.0);
        if (std::string error = values.set(info->id, value); !error.empty())
            throw CliError{ kBadInput, "--" + error };
    }
}

std::vector<OptionSpec> parameterOptions()
{
    std::vector<OptionSpec> options;
    for (const ParameterInfo& p : allParameters()) {
        std::ostringstream help;
        help.precision(10);
        help << p.help << " [" << p.minimum << ".." << p.maximum;
        if (!p.unit.empty())
            help << " " << p.unit;
        help << ", default " << p.defaultValue << "]";
        options.push_back({ std::string(p.key), p.kind == ParamKind::Toggle ? "0|1" : "NUMBER", help.str() });
    }
    return options;
}

std::vector<OptionSpec> optionsWithParameters(std::vector<OptionSpec> own)
{
    std::vector<OptionSpec> options{ { "help", "", "show this help" } };
    options.insert(options.end(), std::make_move_iterator(own.begin()), std::make_move_iterator(own.end()));
    const std::vector<OptionSpec> parameters = parameterOptions();
    options.insert(options.end(), parameters.begin(), parameters.end());
    return options;
}

std::string describeOptions(const std::vector<OptionSpec>& options)
{
    std::ostringstream out;
    for (const OptionSpec& o : options) {
        std::string left = "  --" + o.name + (o.valueName.empty() ? "" : " " + o.valueName);
        if (left.size() < 30)
            left.resize(30, ' ');
        else
            left += "\n" + std::string(30, ' ');
        out << left << o.help << "\n";
    }
    return out.str();
}

} // namespace wisp::cli
