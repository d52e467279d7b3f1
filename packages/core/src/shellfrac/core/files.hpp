#pragma once
/// \file files.hpp
/// How shellfrac opens files (docs/hostile_input.md, "Files"): an input must be a regular file (a FIFO, a device
/// or a directory is refused before it is opened, so nothing blocks); a result is never written through a symbolic
/// link (a result path that is a link is refused, and files are created exclusively, O_CREAT | O_EXCL |
/// O_NOFOLLOW, so a link planted meanwhile is not followed either); a run owns its output base for its lifetime
/// (RunLock). POSIX only; no MPI: callers decide which rank does what.
#include <string>

namespace shellfrac::files {

/// InputError naming `path` and `what` ("the deck", "the mesh file", ...) unless `path` is an existing regular file
/// (links to one are followed: reading through a link is harmless). An empty path is refused too.
void require_regular_input(const std::string& path, const std::string& what);

/// OutputError naming `path` if it exists and is not a regular file (a symbolic link — even to a regular file —,
/// a directory, a FIFO, a device): a result is only ever written to a file of its own name.
void require_result_path(const std::string& path);

/// Removes `path` if it is a regular file or a symbolic link (the link itself, never what it points to). Any
/// other kind of file is an OutputError.
void remove_result(const std::string& path);

/// A file written by appending text, opened without following links. Every write is checked: a short write
/// (disk full, quota, removed directory) throws OutputError naming the file.
class OutputFile {
 public:
  enum class Mode { create, append };
  /// create: a new file (an existing regular file of that name is replaced, a link is refused: require_result_path);
  /// append: an existing regular file. OutputError naming the file on failure.
  OutputFile(const std::string& path, Mode mode);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  void write(const std::string& text);
  /// Cuts the file to its first `bytes` bytes (the writes go on at the end).
  void truncate(long long bytes);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

/// `path` + ".tmp", created exclusively for writing and then renamed over `path` by the caller: a stale temporary
/// file or a link of that name is removed first (never followed). Returns the temporary name; OutputError if it
/// cannot be created.
std::string fresh_temporary(const std::string& path);

/// `path` made absolute, with the links of its existing directories resolved: two names of one place compare equal.
std::string resolved(const std::string& path);

/// An advisory lock on a run's output base (flock on `<base>.lock`), held from construction to destruction, then
/// the lock file is removed. The file holds who owns it (host, pid, start time, deck). A second run on the same
/// base is refused with an InputError naming the owner. Locks on NFS work through the kernel's lock emulation.
class RunLock {
 public:
  /// `lock_path`: the lock file; `base`: how the message names what is locked; `deck`: recorded for others.
  RunLock(const std::string& lock_path, const std::string& base, const std::string& deck);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace shellfrac::files
