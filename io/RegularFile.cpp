#include "io/RegularFile.h"

#include "io/ReadFailure.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace wisp::io {

namespace {

class Descriptor {
public:
    explicit Descriptor(int fd)
        : m_fd(fd)
    {
    }
    ~Descriptor()
    {
        if (m_fd >= 0)
            ::close(m_fd);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return m_fd; }

private:
    int m_fd;
};

std::string kindOf(mode_t mode)
{
    if (S_ISDIR(mode))
        return "a folder";
    if (S_ISFIFO(mode))
        return "a pipe (FIFO)";
    if (S_ISCHR(mode))
        return "a character device";
    if (S_ISBLK(mode))
        return "a block device";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a regular file";
}

} // namespace

std::string megabytesText(std::uint64_t bytes)
{
    // Whole mebibytes, rounded up, so a file just over a cap never reads as equal to it.
    char text[32];
    std::snprintf(text, sizeof text, "%.0f MB", std::ceil(static_cast<double>(bytes) / (1 << 20)));
    return text;
}

Result<std::string> readRegularFile(const std::string& path, const RegularFileRules& rules)
{
    const std::string what = rules.what;
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer forever.
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) {
        const int error = errno;
        if (error == ENOENT)
            return IoError{ path, "", "the file does not exist" };
        if (error == ENXIO) // a socket, or a FIFO opened without a writer on some systems
            return IoError{ path, "", "this is not a regular file; a " + what + " file must be one" };
        return IoError{ path, "", std::string("cannot open the file: ") + std::strerror(error) };
    }
    struct stat info { };
    if (::fstat(fd.get(), &info) != 0)
        return IoError{ path, "", std::string("cannot look at the file: ") + std::strerror(errno) };
    if (S_ISDIR(info.st_mode))
        return IoError{ path, "", "this is a folder, not a " + what + " file" };
    if (!S_ISREG(info.st_mode))
        return IoError{ path, "",
            "this is " + kindOf(info.st_mode) + ", not a regular file; a " + what + " file must be a regular file" };
    const auto size = static_cast<std::uint64_t>(info.st_size);
    if (size > rules.maxBytes)
        return IoError{ path, "",
            "the file is " + megabytesText(size) + "; a " + what + " file is at most "
                + megabytesText(rules.maxBytes) };
    if (size == 0 && !rules.allowEmpty)
        return IoError{ path, "", "the file is empty (0 bytes)" };
    // Back to blocking reads: a regular file never blocks for long, and EAGAIN is not worth a loop.
    if (const int flags = ::fcntl(fd.get(), F_GETFL); flags >= 0)
        ::fcntl(fd.get(), F_SETFL, flags & ~O_NONBLOCK);
    std::string bytes(static_cast<std::size_t>(size), '\0');
    std::size_t got = 0;
    while (got < bytes.size()) {
        const ssize_t n = ::read(fd.get(), bytes.data() + got, bytes.size() - got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return IoError{ path, "byte " + std::to_string(got),
                std::string("reading failed: ") + std::strerror(errno) };
        if (n == 0)
            break;
        got += static_cast<std::size_t>(n);
    }
    // A file that shrank while it was read is cut short: say so rather than parse what is there.
    if (got != bytes.size())
        return IoError{ path, "byte " + std::to_string(got),
            "could not read the whole file (" + std::to_string(got) + " of " + std::to_string(size)
                + " bytes): it changed while it was read" };
    return bytes;
}

std::string readRegularFileOrFail(const std::string& path, const RegularFileRules& rules)
{
    Result<std::string> file = readRegularFile(path, rules);
    if (!file)
        fail(file.error().location, file.error().message);
    return std::move(file).value();
}

std::string lowerExtension(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty() && ext.front() == '.')
        ext.erase(0, 1);
    std::transform(
        ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

} // namespace wisp::io
