#pragma once
// Runs wisp-cli as a user does: a real process, its exit status and everything it printed.

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace wisp::test {

struct CliRun {
    int status = -1;
    std::string output; // stdout and stderr together
};

// `timeoutSeconds` > 0 runs it under timeout(1): a run that blocks ends with status 124. The limit
// is for the Release build; the sanitizer build (about ten times slower) gets it times
// WISP_SLOW_BUILD_FACTOR, so a slow run is not mistaken for a blocked one.
inline CliRun cli(const std::string& arguments, int timeoutSeconds = 0)
{
    const std::string prefix = timeoutSeconds > 0
        ? "timeout " + std::to_string(timeoutSeconds * WISP_SLOW_BUILD_FACTOR) + " "
        : std::string();
    const std::string command = prefix + std::string(WISP_CLI_PATH) + " " + arguments + " 2>&1";
    CliRun r;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe)
        return r;
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe))
        r.output += buffer.data();
    const int raw = pclose(pipe);
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return r;
}

} // namespace wisp::test
