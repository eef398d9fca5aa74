// The one file writer (io/AtomicFile.h): a process killed while writing leaves the old file and a
// temporary that the next start's cleanup removes (never a live writer's); nothing planted at a
// temporary name can redirect the write; a symbolic link stays a link; permissions are kept;
// every failure leaves the old file and no temporary, and names the path.
#include "io/AtomicFile.h"
#include "IoTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace wisp::io;
using namespace wisp::test;
namespace fs = std::filesystem;

namespace {

// The error as one line ("PATH: what went wrong"), or "" on success.
std::string messageOf(const Result<void>& written)
{
    return written ? std::string() : written.error().toString();
}

void put(const fs::path& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
}

std::vector<std::string> namesIn(const fs::path& folder)
{
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

unsigned modeOf(const fs::path& path)
{
    struct stat st { };
    EXPECT_EQ(::stat(path.c_str(), &st), 0) << path;
    return st.st_mode & 07777;
}

// A pid no process has: a child that has exited and been reaped (reuse within the test is remote).
pid_t deadPid()
{
    const pid_t child = ::fork();
    if (child == 0)
        ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return child;
}

// Puts the temporary names the writer tries next, in order, then back to random names.
class NameSequence {
public:
    explicit NameSequence(std::vector<std::string> names)
        : m_names(std::move(names))
    {
        detail::setTemporaryNameSourceForTests(
            [this] { return m_next < m_names.size() ? m_names[m_next++] : std::string("ffffffffffffffff"); });
    }
    ~NameSequence() { detail::setTemporaryNameSourceForTests(nullptr); }

private:
    std::vector<std::string> m_names;
    std::size_t m_next = 0;
};

} // namespace

TEST(AtomicFile, KillDuringAWriteLeavesTheOldFileAndTheNextStartRemovesOnlyDeadWritersTemporaries)
{
    const fs::path dir = freshTestFolder("wisp-atomic");
    const fs::path target = dir / "look.wisp";
    const std::string old = "the previous project, exactly\n";
    put(target, old);

    int ready[2];
    int never[2];
    ASSERT_EQ(::pipe(ready), 0);
    ASSERT_EQ(::pipe(never), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        // The child writes a big file through the writer, says so once 8 MiB are in the temporary,
        // then waits (still inside the write) for a byte that never comes: it is killed mid-write.
        ::close(ready[0]);
        ::close(never[1]);
        static_cast<void>(writeFileAtomically(target.string(), [&](std::ostream& out) {
            const std::string block(1 << 20, 'x');
            for (int i = 0; i < 8; ++i)
                out << block;
            out.flush();
            const char go = 'T';
            if (::write(ready[1], &go, 1) != 1)
                ::_exit(3);
            char nothing;
            while (::read(never[0], &nothing, 1) != 0) { }
            out << "never";
        }));
        ::_exit(0); // only when the parent died first
    }
    ::close(ready[1]);
    ::close(never[0]);
    char got = 0;
    const ssize_t n = ::read(ready[0], &got, 1); // returns 0 at once if the child died instead
    ::close(ready[0]);

    // The temporary is beside the target, named with the child's pid, and holds the 8 MiB.
    const std::regex childTemporary("look\\.wisp\\.[0-9a-f]{16}\\.tmp-" + std::to_string(child));
    fs::path temporary;
    for (const std::string& name : namesIn(dir))
        if (std::regex_match(name, childTemporary))
            temporary = dir / name;
    std::error_code sizeError;
    const std::uintmax_t bytes = fs::file_size(temporary, sizeError);

    // Killed before any assertion can return early and leave it running.
    EXPECT_EQ(::kill(child, SIGKILL), 0);
    int status = 0;
    EXPECT_EQ(::waitpid(child, &status, 0), child);
    ::close(never[1]);
    ASSERT_EQ(n, 1) << "the child did not get to write";
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    ASSERT_FALSE(temporary.empty()) << "no temporary among the files of " << dir;
    EXPECT_EQ(bytes, 8u << 20);

    EXPECT_EQ(slurp(target), old) << "the old file is untouched";
    EXPECT_TRUE(fs::exists(temporary)) << "a killed writer cannot clean up after itself";

    // A live writer's temporary (this process's), a dead writer's of the older "<name>.tmp-<pid>"
    // form, and files that only look like temporaries.
    const std::string dead = std::to_string(deadPid());
    const fs::path live = dir / ("look.wisp.0123456789abcdef.tmp-" + std::to_string(::getpid()));
    put(live, "a save in progress");
    put(dir / ("look.wisp.tmp-" + dead), "older writer's leftover");
    put(dir / ("notes.tmp-" + dead), "someone's own file: no notes beside it");
    put(dir / ("look.wisp.0123456789ABCDEF.tmp-" + dead), "not our digits");

    EXPECT_EQ(removeStaleTemporaryFiles(dir.string()), 2u);
    EXPECT_EQ(namesIn(dir),
        (std::vector<std::string>{
            "look.wisp", "look.wisp.0123456789ABCDEF.tmp-" + dead, live.filename().string(), "notes.tmp-" + dead }));
    EXPECT_EQ(slurp(target), old);
    EXPECT_EQ(removeStaleTemporaryFiles(dir.string()), 0u);
    fs::remove_all(dir);
}

TEST(AtomicFile, NothingPlantedAtATemporaryNameRedirectsTheWrite)
{
    const fs::path dir = freshTestFolder("wisp-atomic");
    const fs::path target = dir / "look.wisp";
    const fs::path victim = dir / "victim.txt";
    put(target, "old");
    put(victim, "must stay");

    // The name the writer used to take ("<name>.tmp-<pid>"), and the exact names it will try first:
    // symbolic links to the victim, and a plain file.
    const std::string pid = std::to_string(::getpid());
    fs::create_symlink(victim, dir / ("look.wisp.tmp-" + pid));
    fs::create_symlink(victim, dir / ("look.wisp.aaaaaaaaaaaaaaaa.tmp-" + pid));
    put(dir / ("look.wisp.bbbbbbbbbbbbbbbb.tmp-" + pid), "someone else's");
    {
        NameSequence names({ "aaaaaaaaaaaaaaaa", "bbbbbbbbbbbbbbbb", "cccccccccccccccc" });
        ASSERT_TRUE(writeFileAtomically(target.string(), [](std::ostream& out) { out << "new"; }));
    }
    EXPECT_EQ(slurp(target), "new");
    EXPECT_EQ(slurp(victim), "must stay");
    EXPECT_EQ(slurp(dir / ("look.wisp.bbbbbbbbbbbbbbbb.tmp-" + pid)), "someone else's");
    EXPECT_TRUE(fs::is_symlink(dir / ("look.wisp.aaaaaaaaaaaaaaaa.tmp-" + pid)));
    EXPECT_FALSE(fs::exists(dir / ("look.wisp.cccccccccccccccc.tmp-" + pid))) << "renamed into place";
    EXPECT_EQ(namesIn(dir).size(), 5u);

    // The backup's hard link takes the same care.
    fs::create_symlink(victim, dir / ("look.wisp.bak.dddddddddddddddd.tmp-" + pid));
    {
        NameSequence names({ "dddddddddddddddd", "eeeeeeeeeeeeeeee" });
        ASSERT_TRUE(keepCopyAtomically(target.string(), (dir / "look.wisp.bak").string()));
    }
    EXPECT_EQ(slurp(dir / "look.wisp.bak"), "new");
    EXPECT_EQ(slurp(victim), "must stay");
    EXPECT_FALSE(fs::exists(dir / ("look.wisp.bak.eeeeeeeeeeeeeeee.tmp-" + pid)));
    fs::remove_all(dir);
}

TEST(AtomicFile, ASymbolicLinkStaysALinkAndTheFileItLeadsToGetsTheContent)
{
    const fs::path dir = freshTestFolder("wisp-atomic");
    fs::create_directories(dir / "real");
    put(dir / "real" / "look.wisp", "old");
    fs::create_symlink("real/look.wisp", dir / "hop.wisp"); // relative, as `ln -s` makes them
    fs::create_symlink(dir / "hop.wisp", dir / "look.wisp"); // two links in a row

    ASSERT_TRUE(writeFileAtomically((dir / "look.wisp").string(), [](std::ostream& out) { out << "new"; }));
    EXPECT_TRUE(fs::is_symlink(dir / "look.wisp"));
    EXPECT_TRUE(fs::is_symlink(dir / "hop.wisp"));
    EXPECT_EQ(fs::read_symlink(dir / "hop.wisp"), fs::path("real/look.wisp"));
    EXPECT_EQ(slurp(dir / "real" / "look.wisp"), "new");
    EXPECT_EQ(namesIn(dir / "real"), (std::vector<std::string>{ "look.wisp" })) << "no temporary left";

    // A link to nowhere yet: the file appears where it points.
    fs::create_symlink("real/later.wisp", dir / "later.wisp");
    ASSERT_TRUE(writeFileAtomically((dir / "later.wisp").string(), [](std::ostream& out) { out << "made"; }));
    EXPECT_TRUE(fs::is_symlink(dir / "later.wisp"));
    EXPECT_EQ(slurp(dir / "real" / "later.wisp"), "made");

    // A loop is refused by name, and nothing is written.
    fs::create_symlink("loop-b", dir / "loop-a");
    fs::create_symlink("loop-a", dir / "loop-b");
    const std::string error
        = messageOf(writeFileAtomically((dir / "loop-a").string(), [](std::ostream& out) { out << "x"; }));
    EXPECT_NE(error.find((dir / "loop-a").string() + ": "), std::string::npos) << error;
    EXPECT_NE(error.find("symbolic links"), std::string::npos) << error;
    fs::remove_all(dir);
}

TEST(AtomicFile, PermissionsOfTheReplacedFileAreKept)
{
    const fs::path dir = freshTestFolder("wisp-atomic");
    for (const unsigned mode : { 0600u, 0640u, 0664u }) {
        const fs::path path = dir / ("mode-" + std::to_string(mode));
        put(path, "old");
        ASSERT_EQ(::chmod(path.c_str(), mode), 0);
        ASSERT_TRUE(writeFileAtomically(path.string(), [](std::ostream& out) { out << "new"; }));
        EXPECT_EQ(modeOf(path), mode) << std::oct << mode;
        EXPECT_EQ(slurp(path), "new");

        // A backup has the permissions of the file it keeps.
        ASSERT_TRUE(keepCopyAtomically(path.string(), path.string() + ".bak"));
        EXPECT_EQ(modeOf(path.string() + ".bak"), mode) << std::oct << mode;
    }
    // A new file: 0666 less the umask, as any program's.
    const mode_t mask = ::umask(022);
    ASSERT_TRUE(writeFileAtomically((dir / "new").string(), [](std::ostream& out) { out << "x"; }));
    ::umask(mask);
    EXPECT_EQ(modeOf(dir / "new"), 0644u);
    fs::remove_all(dir);
}

TEST(AtomicFile, AFailedWriteLeavesTheOldFileAndNoTemporaryAndNamesThePath)
{
    const fs::path dir = freshTestFolder("wisp-atomic");
    const fs::path target = dir / "look.wisp";
    put(target, "old");

    // The content cannot be made (the stream fails)...
    std::string error = messageOf(writeFileAtomically(target.string(), [](std::ostream& out) {
        out << "half";
        out.setstate(std::ios::failbit);
    }));
    EXPECT_EQ(error.rfind(target.string() + ": writing failed", 0), 0u) << error;
    // ...or its maker throws.
    EXPECT_THROW(writeFileAtomically(target.string(),
                     [](std::ostream& out) {
                         out << "half";
                         throw std::runtime_error("out of memory");
                     }),
        std::runtime_error);
    EXPECT_EQ(slurp(target), "old");
    EXPECT_EQ(namesIn(dir), (std::vector<std::string>{ "look.wisp" }));

    // Only regular files are replaced: a link to a device is refused by name.
    fs::create_symlink("/dev/full", dir / "full.wisp");
    error = messageOf(writeFileAtomically((dir / "full.wisp").string(), [](std::ostream& out) { out << "x"; }));
    EXPECT_EQ(error.rfind((dir / "full.wisp").string() + ": ", 0), 0u) << error;
    EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;

    // A folder that does not exist: the system's reason, naming the path.
    const fs::path missing = dir / "no-such-folder" / "look.wisp";
    error = messageOf(writeFileAtomically(missing.string(), [](std::ostream& out) { out << "x"; }));
    EXPECT_EQ(error,
        missing.string() + ": cannot write there (No such file or directory, creating a temporary file in "
            + missing.parent_path().string() + ")");
    fs::remove_all(dir);
}
