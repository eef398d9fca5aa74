#pragma once
// Option parsing for wisp-cli's commands: "--name value", "--name=value" and "--flag".
// Wrong usage (unknown option, missing value) is exit status 2; a bad value is exit status 1.

#include "sim/params/Parameters.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace wisp::cli {

enum ExitCode { kSuccess = 0, kBadInput = 1, kUsage = 2 };

struct CliError {
    int exitCode;
    std::string message;
};

struct OptionSpec {
    std::string name; // without the dashes
    std::string valueName; // empty: a flag without a value
    std::string help;
};

class CommandLine {
public:
    // Parses argv[first..]; throws CliError{kUsage} for unknown options or missing values, and for
    // arguments that are not options unless `positionals` allows that many (files of convert and
    // validate).
    CommandLine(int argc, char** argv, int first, const std::vector<OptionSpec>& options, std::size_t positionals = 0);

    const std::vector<std::string>& positional() const { return m_positional; }

    bool has(const std::string& name) const { return m_values.count(name) > 0; }
    std::optional<std::string> text(const std::string& name) const;
    // Typed values; a malformed or out-of-range value throws CliError{kBadInput} naming the option.
    long long integer(const std::string& name, long long fallback, long long minimum, long long maximum) const;
    double real(const std::string& name, double fallback) const;
    // Applies every --<parameter key> given, in the order given; throws CliError{kBadInput}.
    void applyParameters(ParameterValues& values) const;

private:
    std::map<std::string, std::string> m_values;
    std::vector<std::string> m_order;
    std::vector<std::string> m_positional;
};

// Option specs for every registry parameter (--gravity, --wind_speed, ...), help text from the registry.
std::vector<OptionSpec> parameterOptions();
// A simulating command's table: --help, its own options in order, then every registry parameter.
std::vector<OptionSpec> optionsWithParameters(std::vector<OptionSpec> own);

// Formats a usage block: "  --name VALUE   help".
std::string describeOptions(const std::vector<OptionSpec>& options);

} // namespace wisp::cli
