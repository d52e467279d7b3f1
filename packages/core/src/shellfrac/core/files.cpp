#include "shellfrac/core/files.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>

#include "shellfrac/core/error.hpp"

namespace shellfrac::files {

namespace {

/// What kind of file `st` is, in words for a message.
std::string kind_of(const struct stat& st) {
  if (S_ISLNK(st.st_mode)) return "a symbolic link";
  if (S_ISDIR(st.st_mode)) return "a directory";
  if (S_ISFIFO(st.st_mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) return "a device";
  return "not a regular file";
}

std::string reason() { return std::strerror(errno); }

}  // namespace

void require_regular_input(const std::string& path, const std::string& what) {
  SHELLFRAC_INPUT_REQUIRE(!path.empty(), what << ": the file name is empty");
  struct stat st {};
  SHELLFRAC_INPUT_REQUIRE(::stat(path.c_str(), &st) == 0, path << ": cannot read " << what << " (" << reason() << ")");
  SHELLFRAC_INPUT_REQUIRE(S_ISREG(st.st_mode), path << ": " << what << " is " << kind_of(st)
                                                   << ", not a regular file; name the file itself");
}

void require_result_path(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return;  // does not exist yet
  if (S_ISREG(st.st_mode)) return;
  throw OutputError(path + ": a result file of this name is " + kind_of(st) +
                    "; shellfrac writes its results only to files of their own (never through a link): remove it, "
                    "or choose another 'Output->Base Name' or 'Output->Directory'");
}

void remove_result(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return;
  if (!S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode)) require_result_path(path);
  if (::unlink(path.c_str()) != 0 && errno != ENOENT)
    throw OutputError(path + ": cannot remove the earlier result file (" + reason() + ")");
}

OutputFile::OutputFile(const std::string& path, Mode mode) : path_(path) {
  require_result_path(path);
  if (mode == Mode::create) {
    remove_result(path);
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  } else {
    fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_NOFOLLOW | O_CLOEXEC);
  }
  if (fd_ < 0)
    throw OutputError(path + ": cannot " + (mode == Mode::create ? "create" : "append to") + " the file (" +
                      reason() + ")");
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw OutputError(path + ": not a regular file; shellfrac writes its results only to files of their own");
  }
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::write(const std::string& text) {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw OutputError(path_ + ": writing failed (" + (n < 0 ? reason() : std::string("nothing written")) +
                        "; disk full, quota or file removed?); the run stops");
    p += n, left -= std::size_t(n);
  }
}

void OutputFile::truncate(long long bytes) {
  if (::ftruncate(fd_, off_t(bytes)) != 0)
    throw OutputError(path_ + ": cannot cut the file to " + std::to_string(bytes) + " bytes (" + reason() + ")");
}

std::string fresh_temporary(const std::string& path) {
  const std::string tmp = path + ".tmp";
  remove_result(tmp);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError(tmp + ": cannot create the temporary file (" + reason() + ")");
  ::close(fd);
  return tmp;
}

std::string resolved(const std::string& path) {
  std::error_code ec;
  const auto absolute = std::filesystem::absolute(path, ec);
  if (ec) return path;
  const auto p = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute.string() : p.string();
}

namespace {

/// The lock file's text: who holds it.
std::string owner_record(const std::string& deck) {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::time_t now = std::time(nullptr);
  char when[64] = {};
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S %Z", std::localtime(&now));
  return "host " + std::string(host) + ", pid " + std::to_string(::getpid()) + ", started " + when + ", deck " +
         deck + "\n";
}

std::string read_owner(int fd) {
  std::string text(512, '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? std::size_t(n) : 0);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\0')) text.pop_back();
  return text.empty() ? "a run that is still starting" : text;
}

}  // namespace

RunLock::RunLock(const std::string& lock_path, const std::string& base, const std::string& deck) : path_(lock_path) {
  // Lock, then check that the file locked is still the one of that name (its owner may have removed it between our
  // open and our lock, and a third run locked a new one): else try again.
  for (int attempt = 0; attempt < 100; ++attempt) {
    require_result_path(path_);
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd_ < 0) throw OutputError(path_ + ": cannot create the run's lock file (" + reason() + ")");
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string owner = read_owner(fd_);
      ::close(fd_);
      fd_ = -1;
      if (error == EWOULDBLOCK)
        throw InputError(base + ": another run is writing results of this name (" + owner + "; lock file " + path_ +
                         "); wait for it to end, or give this run another 'Output->Base Name' or 'Output->Directory'");
      throw OutputError(path_ + ": cannot lock the run's lock file (" + std::strerror(error) + ")");
    }
    struct stat held {}, named {};
    if (::fstat(fd_, &held) == 0 && ::lstat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      const std::string owner = owner_record(deck);
      if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, owner.data(), owner.size(), 0) != ssize_t(owner.size())) {
        const std::string why = reason();
        ::close(fd_);
        fd_ = -1;
        throw OutputError(path_ + ": cannot write the run's lock file (" + why + ")");
      }
      return;
    }
    ::close(fd_);
    fd_ = -1;
  }
  throw OutputError(path_ + ": the run's lock file keeps being replaced by other runs; cannot lock it");
}

RunLock::~RunLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still holding the lock: a run waiting on the old file retries on a new one
  ::close(fd_);
}

}  // namespace shellfrac::files
