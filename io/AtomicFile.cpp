#include "io/AtomicFile.h"

#include <array>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

namespace wisp::io {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxSymlinks = 40; // as the kernel's path walk (ELOOP)
constexpr int kNameAttempts = 100; // an O_EXCL clash with 64 random bits is someone's doing
constexpr std::size_t kRandomDigits = 16; // 64 bits
constexpr std::size_t kMaxBaseBytes = 200; // leaves room for the suffix under NAME_MAX (255)
constexpr const char* kTmpTag = ".tmp-";

std::mutex g_nameSourceMutex;
std::function<std::string()> g_nameSource; // tests only

std::string reason(int error)
{
    return std::strerror(error);
}

std::string randomDigits()
{
    {
        std::lock_guard lock(g_nameSourceMutex);
        if (g_nameSource)
            return g_nameSource();
    }
    std::array<unsigned char, kRandomDigits / 2> bytes{};
    if (::getrandom(bytes.data(), bytes.size(), 0) != static_cast<ssize_t>(bytes.size())) {
        std::random_device device; // getrandom before Linux 3.17; still unpredictable
        for (unsigned char& b : bytes)
            b = static_cast<unsigned char>(device());
    }
    static constexpr char kHex[] = "0123456789abcdef";
    std::string digits;
    for (unsigned char b : bytes) {
        digits += kHex[b >> 4];
        digits += kHex[b & 15];
    }
    return digits;
}

std::string temporaryNameFor(const fs::path& target)
{
    std::string base = target.filename().string();
    if (base.size() > kMaxBaseBytes)
        base.resize(kMaxBaseBytes);
    return (target.parent_path() / (base + "." + randomDigits() + kTmpTag + std::to_string(::getpid()))).string();
}

std::string folderOf(const fs::path& target)
{
    const fs::path folder = target.parent_path();
    return folder.empty() ? std::string(".") : folder.string();
}

// Makes the rename durable: a crash after it must not bring the old name back. Some file systems
// refuse fsync on a folder (EINVAL); the rename has happened by then, so that is not an error.
void syncFolder(const std::string& folder)
{
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return;
    ::fsync(fd);
    ::close(fd);
}

// An output stream buffer on a file descriptor that remembers the first write error (errno).
class FdStreamBuf : public std::streambuf {
public:
    explicit FdStreamBuf(int fd)
        : m_fd(fd)
        , m_buffer(std::size_t(1) << 16)
    {
        setp(m_buffer.data(), m_buffer.data() + m_buffer.size());
    }
    int error() const { return m_error; }

protected:
    int_type overflow(int_type ch) override
    {
        if (!drain())
            return traits_type::eof();
        if (!traits_type::eq_int_type(ch, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(ch);
            pbump(1);
        }
        return traits_type::not_eof(ch);
    }
    int sync() override { return drain() ? 0 : -1; }
    std::streamsize xsputn(const char* data, std::streamsize count) override
    {
        if (count < static_cast<std::streamsize>(m_buffer.size()))
            return std::streambuf::xsputn(data, count);
        // Large blocks go straight to the file.
        if (!drain() || !writeAll(data, static_cast<std::size_t>(count)))
            return 0;
        return count;
    }

private:
    bool drain()
    {
        const std::size_t pending = static_cast<std::size_t>(pptr() - pbase());
        if (pending > 0 && !writeAll(pbase(), pending))
            return false;
        setp(m_buffer.data(), m_buffer.data() + m_buffer.size());
        return true;
    }
    bool writeAll(const char* data, std::size_t size)
    {
        while (m_error == 0 && size > 0) {
            const ssize_t written = ::write(m_fd, data, size);
            if (written < 0) {
                if (errno != EINTR)
                    m_error = errno;
                continue;
            }
            data += written;
            size -= static_cast<std::size_t>(written);
        }
        return m_error == 0;
    }

    int m_fd;
    std::vector<char> m_buffer;
    int m_error = 0;
};

// The writer both public functions share. `permissionsFrom`: the file whose mode (and owner, where
// allowed) the new file takes; null for the file being replaced.
std::string writeWithPermissionsOf(
    const std::string& path, const std::function<void(std::ostream&)>& write, const struct stat* permissionsFrom)
{
    std::string why;
    const std::string target = writeTargetOf(path, &why);
    if (target.empty())
        return path + ": " + why;

    struct stat old { };
    bool replacing = false;
    if (::stat(target.c_str(), &old) == 0) {
        if (S_ISDIR(old.st_mode))
            return path + ": this is a folder, not a file";
        if (!S_ISREG(old.st_mode))
            return path + ": this is not a regular file; nothing was written";
        replacing = true;
    } else if (errno != ENOENT) {
        return path + ": cannot look at the file (" + reason(errno) + ")";
    }
    const struct stat* like = permissionsFrom ? permissionsFrom : (replacing ? &old : nullptr);

    // O_EXCL with O_CREAT never follows a symbolic link at the name and fails if anything is there.
    std::string temporary;
    int fd = -1;
    for (int attempt = 0; attempt < kNameAttempts && fd < 0; ++attempt) {
        temporary = temporaryNameFor(target);
        fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, like ? 0600 : 0666);
        if (fd < 0 && errno != EEXIST)
            return path + ": cannot write there (" + reason(errno) + ", creating a temporary file in "
                + folderOf(target) + ")";
    }
    if (fd < 0)
        return path + ": cannot write there (every temporary name tried in " + folderOf(target) + " exists)";

    auto abandon = [&](const std::string& message) {
        ::close(fd);
        ::unlink(temporary.c_str());
        return message;
    };
    if (like) {
        // The owner first: changing it may clear the mode's set-id bits, which are not kept anyway.
        [[maybe_unused]] const int owned = ::fchown(fd, like->st_uid, like->st_gid); // allowed or not: best effort
        if (::fchmod(fd, like->st_mode & 0777) != 0)
            return abandon(path + ": cannot give the new file the permissions of the old (" + reason(errno) + ")");
    }

    FdStreamBuf buffer(fd);
    std::ostream out(&buffer);
    try {
        write(out);
        out.flush();
    } catch (...) {
        abandon({});
        throw;
    }
    if (!out || buffer.error() != 0)
        return abandon(path + ": writing failed ("
            + (buffer.error() ? reason(buffer.error()) : "the content could not be made") + ")");
    if (::fsync(fd) != 0)
        return abandon(path + ": writing failed (" + reason(errno) + ")");
    if (::close(fd) != 0) { // NFS reports some write errors only here
        const int error = errno;
        ::unlink(temporary.c_str());
        return path + ": writing failed (" + reason(error) + ")";
    }
    if (::rename(temporary.c_str(), target.c_str()) != 0) {
        const int error = errno;
        ::unlink(temporary.c_str());
        return path + ": cannot replace the file (" + reason(error) + ")";
    }
    syncFolder(folderOf(target));
    return {};
}

// "<name>.<16 hex>.tmp-<pid>" or "<name>.tmp-<pid>": the pid, and where <name> ends; 0 otherwise.
long temporaryOwner(const std::string& name, std::size_t* baseEnd, bool* random)
{
    const std::size_t tag = name.rfind(kTmpTag);
    if (tag == std::string::npos || tag == 0)
        return 0;
    const std::string digits = name.substr(tag + std::strlen(kTmpTag));
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
        return 0;
    *random = tag > kRandomDigits + 1 && name[tag - kRandomDigits - 1] == '.'
        && name.substr(tag - kRandomDigits, kRandomDigits).find_first_not_of("0123456789abcdef") == std::string::npos;
    *baseEnd = *random ? tag - kRandomDigits - 1 : tag;
    return std::stol(digits);
}

} // namespace

std::string writeTargetOf(const std::string& path, std::string* error)
{
    fs::path current = path;
    for (int hops = 0; hops <= kMaxSymlinks; ++hops) {
        std::error_code code;
        if (!fs::is_symlink(fs::symlink_status(current, code)))
            return current.string();
        const fs::path next = fs::read_symlink(current, code);
        if (code) {
            if (error)
                *error = "cannot follow the symbolic link " + current.string() + " (" + code.message() + ")";
            return {};
        }
        current = next.is_absolute() ? next : current.parent_path() / next;
    }
    if (error)
        *error = "more than " + std::to_string(kMaxSymlinks) + " symbolic links in a row (a loop?)";
    return {};
}

namespace {

// The messages above start with the path they are about; IoError carries the file on its own.
Result<void> asResult(const std::string& path, const std::string& message)
{
    if (message.empty())
        return {};
    if (message.rfind(path + ": ", 0) == 0)
        return IoError{ path, "", message.substr(path.size() + 2) };
    return IoError{ path, "", message };
}

std::string keepCopyMessage(const std::string& source, const std::string& copyPath)
{
    std::string why;
    const std::string realSource = writeTargetOf(source, &why);
    if (realSource.empty())
        return source + ": " + why;
    const std::string target = writeTargetOf(copyPath, &why);
    if (target.empty())
        return copyPath + ": " + why;
    struct stat sourceStat { };
    if (::stat(realSource.c_str(), &sourceStat) != 0)
        return source + ": cannot look at the file (" + reason(errno) + ")";

    // link(2) fails on an existing name and never follows a link planted there, as O_EXCL does.
    std::string temporary;
    int linked = -1;
    int error = EEXIST;
    for (int attempt = 0; attempt < kNameAttempts && linked != 0 && error == EEXIST; ++attempt) {
        temporary = temporaryNameFor(target);
        linked = ::link(realSource.c_str(), temporary.c_str());
        error = linked == 0 ? 0 : errno;
    }
    if (linked != 0) {
        if (error == EEXIST)
            return copyPath + ": cannot write there (every temporary name tried in " + folderOf(target) + " exists)";
        // Another file system, or one without hard links: a copy, written as any file is.
        std::ifstream in(realSource, std::ios::binary);
        if (!in)
            return source + ": cannot read the file (" + reason(errno) + ")";
        return writeWithPermissionsOf(
            copyPath,
            [&](std::ostream& out) {
                if (in.peek() != std::ifstream::traits_type::eof())
                    out << in.rdbuf();
                if (in.bad())
                    out.setstate(std::ios::badbit);
            },
            &sourceStat);
    }
    if (::rename(temporary.c_str(), target.c_str()) != 0) {
        const int renameError = errno;
        ::unlink(temporary.c_str());
        return copyPath + ": cannot replace the file (" + reason(renameError) + ")";
    }
    // rename(2) of a name onto another link of the same file does nothing: the temporary stays.
    ::unlink(temporary.c_str());
    syncFolder(folderOf(target));
    return {};
}

} // namespace

Result<void> writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
    return asResult(path, writeWithPermissionsOf(path, write, nullptr));
}

Result<void> keepCopyAtomically(const std::string& source, const std::string& copyPath)
{
    return asResult(copyPath, keepCopyMessage(source, copyPath));
}

std::size_t removeStaleTemporaryFiles(const std::string& folder)
{
    std::size_t removed = 0;
    std::error_code code;
    for (fs::directory_iterator it(folder, code), end; !code && it != end; it.increment(code)) {
        const std::string name = it->path().filename().string();
        std::size_t baseEnd = 0;
        bool random = false;
        const long pid = temporaryOwner(name, &baseEnd, &random);
        if (pid <= 0 || pid == ::getpid() || isProcessAlive(pid))
            continue;
        std::error_code ignored;
        if (!fs::is_regular_file(it->symlink_status(ignored)))
            continue;
        // The older names ("<name>.tmp-<pid>") are common enough to be someone's own file: only
        // when the file they were replacing is beside them.
        if (!random && !fs::exists(fs::symlink_status(fs::path(folder) / name.substr(0, baseEnd), ignored)))
            continue;
        if (::unlink(it->path().c_str()) == 0)
            ++removed;
    }
    return removed;
}

bool isProcessAlive(long pid)
{
    if (pid <= 0 || pid > INT_MAX)
        return false; // kill(0) and kill(-1) would ask about groups, not a process
    return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

namespace detail {
void setTemporaryNameSourceForTests(std::function<std::string()> next)
{
    std::lock_guard lock(g_nameSourceMutex);
    g_nameSource = std::move(next);
}
} // namespace detail

} // namespace wisp::io
