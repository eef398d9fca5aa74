#pragma once
// File names of a frame sequence: the last run of '#' in a pattern is the frame number,
// zero-padded to the run's length (hair.####.hair: hair.0001.hair, hair.0002.hair, ...; a number
// longer than the run is written whole). Used by `wisp-cli bake` and the editor's bake export.
//
// Thread safety: any thread; no shared state.

#include <string>

namespace wisp::io {

// True when `pattern`'s file name (after the last '/') has a '#' for the frame number.
inline bool isFramePattern(const std::string& pattern)
{
    const std::size_t slash = pattern.find_last_of('/');
    return pattern.find('#', slash == std::string::npos ? 0 : slash + 1) != std::string::npos;
}

// `pattern` with its last run of '#' replaced by `frame`; a pattern without '#' unchanged.
inline std::string framePath(const std::string& pattern, int frame)
{
    const std::size_t last = pattern.find_last_of('#');
    if (last == std::string::npos)
        return pattern;
    std::size_t first = last;
    while (first > 0 && pattern[first - 1] == '#')
        --first;
    std::string number = std::to_string(frame);
    const std::size_t width = last - first + 1;
    if (number.size() < width)
        number.insert(0, width - number.size(), '0');
    return pattern.substr(0, first) + number + pattern.substr(last + 1);
}

} // namespace wisp::io
