#include "io/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>

#include "io/error.hpp"

namespace iblab {
namespace {

namespace fs = std::filesystem;

std::string errnoText(int err) { return std::strerror(err); }

// A name no other writer uses: pid + a process-wide counter + random bits, and O_EXCL
// makes the claim race-free. The leading dot keeps half-written files out of globs such
// as galleryEnvironments()'s "*.exr".
std::string reserveTempPath(const std::string& path, const fs::path& dir, const std::string& base)
{
    static std::atomic<unsigned> counter{0};
    thread_local std::mt19937_64 rng{std::random_device{}()};
    for (int attempt = 0; attempt < 64; ++attempt) {
        std::ostringstream name;
        name << '.' << base << ".tmp-" << ::getpid() << '-' << counter.fetch_add(1) << '-' << std::hex
             << (rng() & 0xffffffu);
        const std::string temp = (dir / name.str()).string();
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return temp;
        }
        if (errno == EEXIST)
            continue;
        const int err = errno;
        std::error_code ec;
        if (!fs::is_directory(dir, ec))
            throw Error(path, "cannot write: directory '" + dir.string() + "' does not exist");
        throw Error(path, "cannot create a temporary file in '" + dir.string() + "': " + errnoText(err));
    }
    throw Error(path, "cannot create a unique temporary file in '" + dir.string() + "'");
}

// fsync so that the rename never publishes a file whose data is still only in the page
// cache (after a power cut the target would otherwise exist but be empty).
void syncFile(const std::string& path, const std::string& subject)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        throw Error(subject, "cannot reopen the temporary file '" + path + "': " + errnoText(errno));
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (rc != 0)
        throw Error(subject, "cannot flush the temporary file to disk: " + errnoText(err));
}

void syncDirectoryBestEffort(const fs::path& dir)
{
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        ::fsync(fd); // best effort: some file systems refuse fsync on directories
        ::close(fd);
    }
}

} // namespace

void writeFileAtomic(const std::string& path, const std::function<void(const std::string& tempPath)>& writeTemp, Durability durability)
{
    const fs::path target(path);
    if (!target.has_filename())
        throw Error(path, "cannot write: the path names a directory, not a file");
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string temp = reserveTempPath(path, dir, target.filename().string());
    try {
        writeTemp(temp);
        if (durability == Durability::Flush)
            syncFile(temp, path);
        if (std::rename(temp.c_str(), path.c_str()) != 0)
            throw Error(path, "cannot replace the file: " + errnoText(errno));
    } catch (...) {
        std::error_code ec;
        fs::remove(temp, ec);
        throw;
    }
    if (durability == Durability::Flush)
        syncDirectoryBestEffort(dir);
}

void writeWholeFile(const std::string& path, std::string_view contents)
{
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0)
        throw Error(path, "cannot open for writing: " + errnoText(errno));
    std::size_t done = 0;
    while (done < contents.size()) {
        const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            const int err = n < 0 ? errno : EIO;
            ::close(fd);
            throw Error(path, "write failed: " + errnoText(err));
        }
        done += std::size_t(n);
    }
    if (::close(fd) != 0)
        throw Error(path, "write failed on close: " + errnoText(errno));
}

void writeTextFileAtomic(const std::string& path, std::string_view contents, Durability durability)
{
    writeFileAtomic(path, [&](const std::string& temp) { writeWholeFile(temp, contents); }, durability);
}

namespace {

std::optional<Error> missingOrDirectory(const std::string& path)
{
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status))
        return Error(path, "no such file");
    if (fs::is_directory(status))
        return Error(path, "is a directory, not a file");
    return std::nullopt;
}

} // namespace

void requireFile(const std::string& path)
{
    if (std::optional<Error> error = missingOrDirectory(path))
        throw *error;
}

Error cannotOpenForReading(const std::string& path, int error)
{
    return missingOrDirectory(path).value_or(Error(path, "cannot open for reading: " + errnoText(error)));
}

std::string readTextFile(const std::string& path)
{
    requireFile(path);
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw cannotOpenForReading(path, errno);
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad())
        throw Error(path, "read failed");
    return text.str();
}

} // namespace iblab
