// wisp-cli: Wisp's simulation without a window, for batch work, pipelines and benchmarks.

#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"

#include <cstring>
#include <iostream>

namespace {

const char* kUsage
    = "usage: wisp-cli COMMAND [options]\n"
      "\n"
      "commands:\n"
      "  simulate   groom a head, simulate N steps, write the strands, print timings\n"
      "  bench      time the solver on standard workloads (table, or --json lines)\n"
      "  convert    hair from one format to another: wisp-cli convert IN OUT\n"
      "  validate   say what a head, hair, preset or project file holds, or what is wrong with it\n"
      "  bake       simulate frames with the head moving, write USD (.usda) or a .hair sequence\n"
      "  style      replay a salon brush stroke on a project: wisp-cli style PROJECT --brush comb --stroke ...\n"
      "\n"
      "'wisp-cli COMMAND --help' lists a command's options.\n"
      "exit status: 0 success, 1 bad input (a file or a value), 2 wrong usage\n";

} // namespace

int main(int argc, char** argv)
{
    if (argc < 2) {
        std::cerr << kUsage;
        return wisp::cli::kUsage;
    }
    const char* command = argv[1];
    if (!std::strcmp(command, "--help") || !std::strcmp(command, "-h") || !std::strcmp(command, "help")) {
        std::cout << kUsage;
        return wisp::cli::kSuccess;
    }
    try {
        if (!std::strcmp(command, "simulate"))
            return wisp::cli::runSimulate(argc, argv);
        if (!std::strcmp(command, "bench"))
            return wisp::cli::runBench(argc, argv);
        if (!std::strcmp(command, "convert"))
            return wisp::cli::runConvert(argc, argv);
        if (!std::strcmp(command, "validate"))
            return wisp::cli::runValidate(argc, argv);
        if (!std::strcmp(command, "bake"))
            return wisp::cli::runBake(argc, argv);
        if (!std::strcmp(command, "style"))
            return wisp::cli::runStyle(argc, argv);
    } catch (const wisp::cli::CliError& e) {
        std::cerr << "wisp-cli " << command << ": " << e.message << "\n";
        return e.exitCode;
    } catch (const std::exception& e) { // out of memory and the like: say so rather than abort
        std::cerr << "wisp-cli " << command << ": " << e.what() << "\n";
        return wisp::cli::kBadInput;
    }
    std::cerr << "wisp-cli: unknown command '" << command << "'\n\n" << kUsage;
    return wisp::cli::kUsage;
}
