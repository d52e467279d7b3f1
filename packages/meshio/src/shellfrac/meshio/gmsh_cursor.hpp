#pragma once
/// \file gmsh_cursor.hpp
/// A bounds-checked reader over a Gmsh file's content (internal to meshio, used by gmsh_file.cpp): ASCII tokens
/// and lines, and raw binary values, each read checked against the bytes that remain.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>

#include "shellfrac/core/error.hpp"

namespace shellfrac::meshio::gmsh {

/// Bounds-checked reader over the file content: ASCII tokens and lines, and raw binary values.
class Cursor {
 public:
  Cursor(const std::string& path, const std::string& data) : path_(path), data_(data) {}

  /// Where the cursor is, for messages: the line of the last token in ASCII files, the byte offset in
  /// binary files (line numbers are meaningless once binary data has been crossed).
  std::string where() const {
    return binary_ ? "byte " + std::to_string(token_pos_) : "line " + std::to_string(token_line_);
  }
  void set_binary(bool binary) { binary_ = binary; }
  void set_swap(bool swap) { swap_ = swap; }
  std::size_t remaining() const { return data_.size() - pos_; }
  /// " (truncated file?)" when the cursor is at the end of the file: a malformed last token is then most
  /// likely a cut, not a typo.
  const char* eof_hint() const { return pos_ >= data_.size() ? " (truncated file?)" : ""; }
  std::size_t position() const { return pos_; }

  /// Skips white space; true if the end of the file is reached.
  bool at_end() {
    skip_space();
    return pos_ >= data_.size();
  }

  /// Next white-space separated token; `what` names what was expected, for the message.
  std::string_view token(const char* what) {
    skip_space();
    token_pos_ = pos_;
    token_line_ = line_;
    SHELLFRAC_INPUT_REQUIRE(pos_ < data_.size(),
                            path_ << ": unexpected end of file (truncated?) while reading " << what);
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
    return std::string_view(data_).substr(start, pos_ - start);
  }

  /// Next token as an integer in [lo, hi].
  std::int64_t integer(const char* what, std::int64_t lo = std::numeric_limits<std::int64_t>::min(),
                       std::int64_t hi = std::numeric_limits<std::int64_t>::max()) {
    const std::string_view t = token(what);
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    SHELLFRAC_INPUT_REQUIRE(ec == std::errc() && end == t.data() + t.size(),
                            path_ << ": " << where() << ": expected an integer (" << what << "), found '"
                                  << shorten(t) << "'" << eof_hint());
    SHELLFRAC_INPUT_REQUIRE(value >= lo && value <= hi, path_ << ": " << where() << ": " << what << " "
                                                              << value << " is out of range [" << lo << ", "
                                                              << hi << "]");
    return value;
  }

  /// Next token as a count, bounded so that `count * min_bytes_each` fits in what remains of the file
  /// (guards the allocations that follow against hostile counts).
  std::size_t count(const char* what, std::size_t min_bytes_each) {
    const std::int64_t n = integer(what, 0);
    check_count(static_cast<std::uint64_t>(n), min_bytes_each, what);
    return static_cast<std::size_t>(n);
  }

  /// Next token as a finite double.
  double real(const char* what) {
    const std::string_view t = token(what);
    double value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    SHELLFRAC_INPUT_REQUIRE(ec == std::errc() && end == t.data() + t.size() && std::isfinite(value),
                            path_ << ": " << where() << ": expected a finite number (" << what << "), found '"
                                  << shorten(t) << "'" << eof_hint());
    return value;
  }

  /// The rest of the current line (without the newline), consumed.
  std::string_view rest_of_line() {
    const std::size_t start = pos_;
    while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    const std::string_view line = std::string_view(data_).substr(start, pos_ - start);
    if (pos_ < data_.size()) {
      ++pos_;
      ++line_;
    }
    return line;
  }

  /// Consumes blanks up to and including the end of the line; binary data starts right after it.
  void end_of_line(const char* after) {
    while (pos_ < data_.size() && (data_[pos_] == ' ' || data_[pos_] == '\t' || data_[pos_] == '\r')) ++pos_;
    SHELLFRAC_INPUT_REQUIRE(pos_ < data_.size() && data_[pos_] == '\n',
                            path_ << ": " << where() << ": expected the end of the line after " << after
                                  << eof_hint());
    ++pos_;
    ++line_;
  }

  /// Requires the next token to be `expected` (e.g. "$EndNodes").
  void expect(std::string_view expected, const char* context) {
    const std::string_view t = token(context);
    SHELLFRAC_INPUT_REQUIRE(t == expected, path_ << ": " << where() << ": expected '" << expected << "' "
                                                 << context << ", found '" << shorten(t) << "'"
                                                 << eof_hint());
  }

  /// Throws unless `n` items of at least `min_bytes_each` bytes fit in the rest of the file.
  void check_count(std::uint64_t n, std::size_t min_bytes_each, const char* what) const {
    SHELLFRAC_INPUT_REQUIRE(n <= remaining() / std::max<std::size_t>(min_bytes_each, 1),
                            path_ << ": " << where() << ": " << what << " " << n
                                  << " is larger than the rest of the file can hold (truncated or corrupt file)");
  }

  /// Reads one binary value of type T (int32, uint64 or double), swapping bytes if needed.
  template <class T>
  T binary(const char* what) {
    token_pos_ = pos_;
    SHELLFRAC_INPUT_REQUIRE(remaining() >= sizeof(T), path_ << ": unexpected end of file (truncated?) at byte "
                                                            << pos_ << " while reading " << what);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    if (swap_) std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }

  /// Binary int32 in [lo, hi].
  int binary_int(const char* what, int lo = std::numeric_limits<int>::min(),
                 int hi = std::numeric_limits<int>::max()) {
    const std::int32_t v = binary<std::int32_t>(what);
    SHELLFRAC_INPUT_REQUIRE(v >= lo && v <= hi, path_ << ": " << where() << ": " << what << " " << v
                                                      << " is out of range [" << lo << ", " << hi << "]");
    return v;
  }

  /// Binary size_t (8 bytes in 4.1 files) as a non-negative int64.
  std::int64_t binary_size(const char* what) {
    const std::uint64_t v = binary<std::uint64_t>(what);
    SHELLFRAC_INPUT_REQUIRE(v <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()),
                            path_ << ": " << where() << ": " << what << " " << v << " is out of range");
    return static_cast<std::int64_t>(v);
  }

  /// Binary size_t used as a count, bounded like count().
  std::size_t binary_count(const char* what, std::size_t min_bytes_each) {
    const std::uint64_t n = binary<std::uint64_t>(what);
    check_count(n, min_bytes_each, what);
    return static_cast<std::size_t>(n);
  }

  /// Binary finite double.
  double binary_real(const char* what) {
    const double v = binary<double>(what);
    SHELLFRAC_INPUT_REQUIRE(std::isfinite(v), path_ << ": " << where() << ": " << what << " is not finite");
    return v;
  }

  /// Skips to just after the line "$End<name>" (sections this reader does not use); returns what it skipped
  /// before that line (the section's body).
  std::string_view skip_section(std::string_view name) {
    const std::string end = "$End" + std::string(name);
    const std::size_t start = pos_;
    std::size_t at = pos_;
    for (;;) {
      at = data_.find(end, at);
      SHELLFRAC_INPUT_REQUIRE(at != std::string::npos, path_ << ": " << where() << ": section $" << name
                                                             << " has no " << end << " (truncated file?)");
      const std::size_t after = at + end.size();
      // Must be a whole token at the start of a line: "$EndNode" must not match "$EndNodeData".
      if ((at == 0 || data_[at - 1] == '\n') && (after == data_.size() || is_space(data_[after]))) {
        line_ += static_cast<std::size_t>(std::count(data_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                                     data_.begin() + static_cast<std::ptrdiff_t>(after), '\n'));
        pos_ = after;
        return std::string_view(data_).substr(start, at - start);
      }
      at = after;
    }
  }

  static std::string shorten(std::string_view t) {
    std::string s(t.substr(0, 40));
    for (char& c : s)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    return t.size() > 40 ? s + "..." : s;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  void skip_space() {
    while (pos_ < data_.size() && is_space(data_[pos_])) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  const std::string& path_;
  const std::string& data_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  std::size_t token_pos_ = 0;
  std::size_t token_line_ = 1;
  bool binary_ = false;
  bool swap_ = false;
};

}  // namespace shellfrac::meshio::gmsh
