#include "io/AtomicFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <unistd.h>

namespace wisp::io {

std::string writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
    const std::string temporary = path + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            return path + ": cannot write there (" + std::strerror(errno) + ")";
        write(out);
        out.flush();
        if (!out) {
            out.close();
            std::remove(temporary.c_str());
            return path + ": writing failed (disk full?)";
        }
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        std::remove(temporary.c_str());
        return path + ": cannot replace the file (" + reason + ")";
    }
    return {};
}

}  // namespace wisp::io
