#include "output/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <random>
#include <utility>

#include <fcntl.h>
#include <unistd.h>

#include "hemirad/error.h"

namespace hemirad {

namespace {

/// A 6-character [0-9a-z] suffix, different on every call within a process and (with high
/// probability) across processes; O_EXCL guarantees uniqueness, this only avoids retries.
std::string random_suffix() {
    static const std::uint64_t seed = [] {
        std::random_device rd;
        return (std::uint64_t(rd()) << 32) ^ rd() ^ (std::uint64_t(::getpid()) << 16);
    }();
    static std::atomic<std::uint64_t> counter{0};
    // splitmix64 of seed + counter
    std::uint64_t z = seed + 0x9e3779b97f4a7c15ull * (counter.fetch_add(1) + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    static constexpr char digits[] = "0123456789abcdefghijklmnopqrstuvwxyz";
    std::string s(6, '0');
    for (char& c : s) {
        c = digits[z % 36];
        z /= 36;
    }
    return s;
}

std::string error_text(int err) {
    return std::strerror(err);
}

} // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
    if (path_.empty()) throw RuntimeError("cannot write a file with an empty path");
    int fd = -1;
    for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
        temp_path_ = path_ + ".tmp-" + random_suffix();
        fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST) break;
    }
    if (fd < 0) {
        const int err = errno;
        const std::string temp = temp_path_;
        temp_path_.clear(); // nothing of ours to remove
        throw RuntimeError(path_ + ": cannot create temporary file " + temp + ": " +
                           error_text(err));
    }
    file_ = ::fdopen(fd, "wb");
    if (!file_) {
        const int err = errno;
        ::close(fd);
        fail("cannot open a stream on " + temp_path_, err);
    }
}

AtomicFile::~AtomicFile() {
    discard();
}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : path_(std::move(other.path_)), temp_path_(std::exchange(other.temp_path_, {})),
      file_(std::exchange(other.file_, nullptr)), committed_(other.committed_) {}

AtomicFile& AtomicFile::operator=(AtomicFile&& other) noexcept {
    if (this != &other) {
        discard();
        path_ = std::move(other.path_);
        temp_path_ = std::exchange(other.temp_path_, {});
        file_ = std::exchange(other.file_, nullptr);
        committed_ = other.committed_;
    }
    return *this;
}

std::FILE* AtomicFile::stream() {
    HEMIRAD_CHECK(file_ != nullptr);
    return file_;
}

void AtomicFile::write(std::string_view bytes) {
    HEMIRAD_CHECK(file_ != nullptr);
    if (bytes.empty()) return;
    if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
        fail("write to " + temp_path_ + " failed", errno ? errno : EIO);
}

void AtomicFile::commit() {
    HEMIRAD_CHECK(file_ != nullptr && !committed_);
    errno = 0;
    if (std::fflush(file_) != 0) fail("write to " + temp_path_ + " failed", errno);
    if (std::ferror(file_)) fail("write to " + temp_path_ + " failed", errno ? errno : EIO);
    // Data on disk before the rename makes it visible; EINVAL: the file system cannot sync.
    if (::fsync(::fileno(file_)) != 0 && errno != EINVAL)
        fail("fsync of " + temp_path_ + " failed", errno);
    std::FILE* f = std::exchange(file_, nullptr);
    if (std::fclose(f) != 0) fail("closing " + temp_path_ + " failed", errno);
    if (std::rename(temp_path_.c_str(), path_.c_str()) != 0)
        fail("cannot rename " + temp_path_ + " over it", errno);
    committed_ = true;
    temp_path_.clear();
}

void AtomicFile::discard() noexcept {
    if (file_) {
        std::fclose(file_);
        file_ = nullptr;
    }
    if (!committed_ && !temp_path_.empty()) {
        ::unlink(temp_path_.c_str());
        temp_path_.clear();
    }
}

void AtomicFile::fail(const std::string& what, int err) {
    discard();
    throw RuntimeError(path_ + ": " + what + ": " + error_text(err));
}

void write_file_atomically(const std::string& path, std::string_view contents) {
    AtomicFile file(path);
    file.write(contents);
    file.commit();
}

} // namespace hemirad
