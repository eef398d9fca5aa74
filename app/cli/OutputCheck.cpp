#include "app/cli/OutputCheck.h"

#include "app/cli/CommandLine.h"
#include "io/RegularFile.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>

namespace wisp::cli {

namespace fs = std::filesystem;

void checkOutputPath(const std::string& path, const std::string& what, const std::vector<std::string>& extensions)
{
    const std::string prefix = what + ": " + path + ": ";
    if (path.empty())
        throw CliError{ kBadInput, what + ": the output path is empty" };
    if (!extensions.empty()) {
        const std::string ext = io::lowerExtension(path);
        if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
            std::string list;
            for (const std::string& e : extensions)
                list += (list.empty() ? "." : ", .") + e;
            throw CliError{ kBadInput,
                prefix + (ext.empty() ? "no extension" : "'." + ext + "' is not a format Wisp writes")
                    + "; the extension picks the format: " + list };
        }
    }
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw CliError{ kBadInput, prefix + "this is a folder; give a file name" };
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty())
        folder = ".";
    const fs::file_status status = fs::status(folder, ec);
    if (status.type() == fs::file_type::not_found)
        throw CliError{ kBadInput, prefix + "the folder " + folder.string() + " does not exist" };
    if (!fs::is_directory(status))
        throw CliError{ kBadInput, prefix + folder.string() + " is not a folder" };
    // The file is written beside itself and renamed (io/AtomicFile), so the folder must be writable.
    if (::access(folder.c_str(), W_OK | X_OK) != 0)
        throw CliError{ kBadInput, prefix + "cannot write in the folder " + folder.string() };
}

} // namespace wisp::cli
