// Fuzz target: io::parsePreset (what readPreset does after reading the file), and the promise
// that a preset read is a preset that writes and reads back as the same preset.

#include "fuzz/FuzzSupport.h"
#include "io/PresetFile.h"

#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const wisp::io::Result<wisp::io::PresetReadResult> read = wisp::io::parsePreset(text, "fuzz.json");
    if (!read)
        return 0;
    const wisp::io::Preset& preset = read.value().preset;
    const std::string written = wisp::io::presetToJson(preset);
    const wisp::io::Result<wisp::io::PresetReadResult> again = wisp::io::parsePreset(written, "fuzz.json");
    if (!again)
        wisp::fuzz::fail("a preset read does not read back once written: " + again.error().toString());
    if (!(again.value().preset == preset))
        wisp::fuzz::fail("a preset read reads back different once written");
    return 0;
}
