// Fuzz target: io::readParameterText (wisp-cli's "key = value" files), then what `wisp-cli
// simulate --params` does with the values: set them, then make and check the solver's settings.

#include "fuzz/FuzzSupport.h"
#include "io/ParameterText.h"
#include "sim/params/Parameters.h"
#include "sim/solver/SolverSettings.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string path = wisp::fuzz::writeInput("params.txt", data, size);
    const wisp::io::Result<wisp::io::ParameterFile> read = wisp::io::readParameterText(path);
    if (!read)
        return 0;
    wisp::ParameterValues values;
    for (const auto& [id, value] : read.value().values)
        if (const std::string error = values.set(id, value); !error.empty())
            wisp::fuzz::fail("readParameterText accepted a value the registry refuses: " + error);
    (void)wisp::validateSolverSettings(wisp::solverSettingsFrom(values));
    return 0;
}
