// Atomic file output (STYLE: "no partial output file, ever").
//
// The bytes go to a temporary file `PATH.tmp-XXXXXX` in the target's directory (so that the
// final rename(2) stays on one file system and is atomic); commit() flushes it, fsyncs it and
// renames it over PATH. A reader therefore sees either the old file or the complete new one.
// If anything fails, or the AtomicFile is destroyed without commit(), the temporary file is
// removed and PATH is left as it was. Errors throw RuntimeError naming PATH and strerror.
//
//     AtomicFile out(path);
//     std::fprintf(out.stream(), ...);   // or out.write(bytes)
//     out.commit();
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace hemirad {

class AtomicFile {
  public:
    /// Creates the temporary file beside `path` (mode 0666 minus the umask, like fopen).
    /// Throws RuntimeError naming `path` when it cannot (missing or unwritable directory).
    explicit AtomicFile(std::string path);
    /// Removes the temporary file unless committed; never throws.
    ~AtomicFile();

    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    /// Moving leaves the source empty (no file; its destructor does nothing).
    AtomicFile(AtomicFile&& other) noexcept;
    AtomicFile& operator=(AtomicFile&& other) noexcept;

    const std::string& path() const { return path_; }           ///< the final path
    const std::string& temp_path() const { return temp_path_; } ///< where bytes go until commit
    bool committed() const { return committed_; }

    /// The open stdio stream on the temporary file (binary). Valid until commit(). Write errors
    /// on it are detected at commit().
    std::FILE* stream();
    /// Appends bytes; throws RuntimeError on a write error (the temporary file is removed).
    void write(std::string_view bytes);
    /// Flushes, fsyncs, closes and renames the temporary file over path(). Throws RuntimeError
    /// (after removing the temporary file) on failure. Calling it twice is a broken invariant.
    void commit();

  private:
    void discard() noexcept; ///< close and remove the temporary file if still there
    [[noreturn]] void fail(const std::string& what, int err);

    std::string path_;
    std::string temp_path_;
    std::FILE* file_ = nullptr;
    bool committed_ = false;
};

/// Writes `contents` to `path` atomically (AtomicFile + write + commit).
void write_file_atomically(const std::string& path, std::string_view contents);

} // namespace hemirad
