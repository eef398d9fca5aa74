#pragma once

namespace wisp::cli {

// Each returns the process exit status (see ExitCode); errors are printed to stderr.
int runSimulate(int argc, char** argv);
int runBench(int argc, char** argv);
int runConvert(int argc, char** argv);
int runValidate(int argc, char** argv);
int runBake(int argc, char** argv);
int runStyle(int argc, char** argv);

} // namespace wisp::cli
