#pragma once
/// \file exodus_api.hpp
/// Internal helpers around the Exodus II C API (libexodusii 6.02), shared by shellfrac::io (results) and
/// shellfrac::meshio (meshes). Not part of the public API: include it only from .cpp files.
///  * SHELLFRAC_EXO_CHECK(call, msg): a failed call (return < 0) while writing throws shellfrac::OutputError naming
///    the file (msg) and Exodus' reason. Positive returns are Exodus warnings and are accepted.
///  * SHELLFRAC_EXO_INPUT_CHECK(call, msg): the same, but throws shellfrac::InputError (reading a user's file).
///  * exodus::File owns an open file id; files are opened/created with double words and the 64-bit integer API.
///  * cut_record_count(path, n): a closed netCDF classic file cut back to its first n time steps.
#include <exodusII.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"

namespace shellfrac::exodus {

/// The Exodus library's last error message ("ex_open: ... (code -51)"), for exception texts.
inline std::string last_error() {
  const char* msg = nullptr;
  const char* func = nullptr;
  int code = 0;
  ex_get_err(&msg, &func, &code);
  std::string s;
  if (func != nullptr && *func != '\0') s += std::string(func) + ": ";
  s += (msg != nullptr && *msg != '\0') ? msg : "unknown error";
  s += " (code " + std::to_string(code) + ")";
  return s;
}

/// An open Exodus file id, closed on destruction (errors on that close are ignored; call close() to check).
class File {
 public:
  File() = default;
  explicit File(int id) : id_(id) {}
  ~File() {
    if (id_ >= 0) ex_close(id_);
  }
  File(File&& o) noexcept : id_(std::exchange(o.id_, -1)) {}
  File& operator=(File&& o) noexcept {
    if (this != &o) {
      if (id_ >= 0) ex_close(id_);
      id_ = std::exchange(o.id_, -1);
    }
    return *this;
  }
  File(const File&) = delete;
  File& operator=(const File&) = delete;

  int id() const { return id_; }
  bool is_open() const { return id_ >= 0; }
  /// Closes the file; returns the ex_close code (0 if it was not open).
  int close() { return id_ >= 0 ? ex_close(std::exchange(id_, -1)) : 0; }

 private:
  int id_ = -1;
};

/// Opens an existing file read-only (double words, 64-bit integer API). Returns a closed File on failure.
inline File open_read(const std::string& path) {
  int cpu_ws = 8, io_ws = 0;
  float version = 0;
  const int id = ex_open(path.c_str(), EX_READ | EX_ALL_INT64_API, &cpu_ws, &io_ws, &version);
  if (id < 0) return File();
  File f(id);
  // Read names as long as the file stores them (Exodus truncates to the library's current maximum).
  const auto used = ex_inquire_int(id, EX_INQ_DB_MAX_USED_NAME_LENGTH);
  ex_set_max_name_length(id, static_cast<int>(std::clamp<std::int64_t>(used, MAX_NAME_LENGTH, 255)));
  return f;
}

/// Creates (replaces) a file with 8-byte reals on disk and the 64-bit integer API (32-bit integers on disk,
/// the most widely readable form). An existing regular file or symbolic link of that name is removed first (a link
/// is never followed), any other kind of file is an OutputError (core/files.hpp); the file is then created
/// exclusively, so a link planted meanwhile is not followed either. Returns a closed File on failure.
inline File create(const std::string& path) {
  files::remove_result(path);
  int cpu_ws = 8, io_ws = 8;
  const int id = ex_create(path.c_str(), EX_NOCLOBBER | EX_ALL_INT64_API, &cpu_ws, &io_ws);
  if (id < 0) return File();
  ex_set_max_name_length(id, MAX_NAME_LENGTH);
  return File(id);
}

/// Largest value an integer stored by create() can take (ids, connectivity, map entries).
constexpr std::int64_t max_stored_int = 2147483647;

/// Buffer size of a name read by open_read() (max name length + NUL + slack).
constexpr std::size_t name_buffer = 257;

/// Reads the names of all `count` entities of `type` (element blocks, sets, variables when `variables`).
/// Empty strings where the file has none. Throws InputError naming `path` on failure.
inline std::vector<std::string> get_names(int exo, ex_entity_type type, std::int64_t count, const std::string& path,
                                          bool variables = false) {
  std::vector<std::string> out;
  if (count <= 0) return out;
  std::vector<std::vector<char>> buf(static_cast<std::size_t>(count), std::vector<char>(name_buffer, '\0'));
  std::vector<char*> ptr;
  for (auto& b : buf) ptr.push_back(b.data());
  const int rc = variables ? ex_get_variable_names(exo, type, static_cast<int>(count), ptr.data())
                           : ex_get_names(exo, type, ptr.data());
  SHELLFRAC_INPUT_REQUIRE(rc >= 0, path << ": cannot read " << (variables ? "variable " : "entity ") << "names: "
                                        << last_error());
  for (auto& b : buf) {
    b.back() = '\0';
    std::string s(b.data());
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    out.push_back(std::move(s));
  }
  return out;
}

/// Checks that every name fits Exodus' 32-character limit (Error otherwise; `what` names the kind).
inline void check_name_lengths(const std::vector<std::string>& names, const std::string& what,
                               const std::string& path) {
  for (const auto& n : names)
    SHELLFRAC_REQUIRE(n.size() <= static_cast<std::size_t>(MAX_NAME_LENGTH),
                      path << ": " << what << " name '" << n << "' is longer than Exodus' limit of " << MAX_NAME_LENGTH
                           << " characters");
}

/// Writes names for all entities of `type` (or variable names when `variables`).
inline int put_names(int exo, ex_entity_type type, const std::vector<std::string>& names, bool variables = false) {
  if (names.empty()) return 0;
  std::vector<std::vector<char>> buf;
  std::vector<char*> ptr;
  for (const auto& n : names) buf.emplace_back(n.c_str(), n.c_str() + n.size() + 1);
  for (auto& b : buf) ptr.push_back(b.data());
  return variables ? ex_put_variable_names(exo, type, static_cast<int>(names.size()), ptr.data())
                   : ex_put_names(exo, type, ptr.data());
}

/// Writes information records (each at most 80 characters: longer lines are wrapped over several records).
inline int put_info(int exo, const std::vector<std::string>& lines) {
  std::vector<std::vector<char>> buf;
  for (const auto& line : lines) {
    std::size_t pos = 0;
    do {
      const std::string part = line.substr(pos, MAX_LINE_LENGTH);
      buf.emplace_back(part.c_str(), part.c_str() + part.size() + 1);
      pos += MAX_LINE_LENGTH;
    } while (pos < line.size());
  }
  if (buf.empty()) return 0;
  std::vector<char*> ptr;
  for (auto& b : buf) ptr.push_back(b.data());
  return ex_put_info(exo, static_cast<int>(ptr.size()), ptr.data());
}

/// Cuts a closed netCDF classic file (CDF-1, -2 or -5, as create() writes them) back to its first `records` time
/// steps (records of the unlimited dimension) by lowering the record count in its header (bytes 4..7, or 4..11
/// for CDF-5; "NetCDF Classic Format Specification"); the bytes of the later records stay in the file but are
/// no longer part of it. Used when a frame could not be written on every rank. Never raises the count, never
/// follows a link. Returns false if the file cannot be opened, is not such a file, or the header write fails.
inline bool cut_record_count(const std::string& path, std::uint64_t records) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  unsigned char head[12] = {};
  bool ok = ::pread(fd, head, sizeof head, 0) == static_cast<ssize_t>(sizeof head) && head[0] == 'C' &&
            head[1] == 'D' && head[2] == 'F' && (head[3] == 1 || head[3] == 2 || head[3] == 5);
  if (ok) {
    const int n = head[3] == 5 ? 8 : 4;
    std::uint64_t stored = 0;
    for (int i = 0; i < n; ++i) stored = (stored << 8) | head[4 + i];
    const bool streaming = n == 4 && stored == 0xffffffffu;  // the count was never written
    if (streaming || stored > records) {
      unsigned char count[8];
      for (int i = 0; i < n; ++i) count[i] = static_cast<unsigned char>(records >> (8 * (n - 1 - i)));
      ok = ::pwrite(fd, count, static_cast<std::size_t>(n), 4) == n && ::fsync(fd) == 0;
    }
  }
  return ::close(fd) == 0 && ok;
}

/// Upper-cased copy (element type names are case-insensitive).
inline std::string upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace shellfrac::exodus

/// Checks an Exodus call made while writing: a negative return throws shellfrac::Error with `msg` and the
/// library's message.
#define SHELLFRAC_EXO_CHECK(call, msg)                                                                    \
  do {                                                                                                  \
    const int shellfrac_exo_rc_ = (call);                                                               \
    if (shellfrac_exo_rc_ < 0) {                                                                        \
      std::ostringstream shellfrac_os_;                                                                 \
      shellfrac_os_ << msg << ": writing failed (" << ::shellfrac::exodus::last_error()                 \
                    << "; disk full, quota or file removed?)";                                          \
      throw ::shellfrac::OutputError(shellfrac_os_.str());                                              \
    }                                                                                                   \
  } while (0)

/// Checks an Exodus call made while reading a user's file: a negative return throws shellfrac::InputError.
#define SHELLFRAC_EXO_INPUT_CHECK(call, msg)                                                              \
  do {                                                                                                  \
    const int shellfrac_exo_rc_ = (call);                                                               \
    SHELLFRAC_INPUT_REQUIRE(shellfrac_exo_rc_ >= 0, msg << ": " << ::shellfrac::exodus::last_error());   \
  } while (0)
