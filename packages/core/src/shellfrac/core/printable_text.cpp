#include "shellfrac/core/printable_text.hpp"

#include <Teuchos_Array.hpp>
#include <cstdio>

#include "shellfrac/core/error.hpp"

namespace shellfrac::params {

namespace {

std::string hex(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02x", c);
  return buf;
}

/// The length of the UTF-8 sequence that starts with `lead`, or 0 if `lead` cannot start one.
std::size_t sequence_length(unsigned char lead) {
  if (lead >= 0xc2 && lead <= 0xdf) return 2;
  if (lead >= 0xe0 && lead <= 0xef) return 3;
  if (lead >= 0xf0 && lead <= 0xf4) return 4;
  return 0;
}

/// The code point of the valid sequence of length n at text[i], or -1 (bad continuation byte, overlong form,
/// surrogate or above U+10FFFF).
long code_point(std::string_view text, std::size_t i, std::size_t n) {
  if (i + n > text.size()) return -1;
  long cp = static_cast<unsigned char>(text[i]) & (0x7f >> n);
  for (std::size_t k = 1; k < n; ++k) {
    const auto c = static_cast<unsigned char>(text[i + k]);
    if ((c & 0xc0) != 0x80) return -1;
    cp = (cp << 6) | (c & 0x3f);
  }
  const long smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < smallest[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return -1;
  return cp;
}

/// InputError if `text` is not printable UTF-8; `what` says where it is ("the name 'shellfrac->...'").
void check_text(std::string_view text, const std::string& file, const std::string& what) {
  const std::string problem = unprintable_part(text);
  SHELLFRAC_INPUT_REQUIRE(problem.empty(),
                          file << ": " << what << " has " << problem << "; names and text must be printable UTF-8");
}

}  // namespace

std::string unprintable_part(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::string at = " at position " + std::to_string(i + 1);
    if (c < 0x20 || c == 0x7f) return "a control character (byte " + hex(c) + ")" + at;
    if (c < 0x80) {
      ++i;
      continue;
    }
    const std::size_t n = sequence_length(c);
    const long cp = n == 0 ? -1 : code_point(text, i, n);
    if (cp < 0) return "a byte that is not UTF-8 (" + hex(c) + ")" + at;
    if (cp >= 0x80 && cp <= 0x9f)
      return "a control character (U+00" + hex(static_cast<unsigned char>(cp)).substr(2) + ")" + at;
    i += n;
  }
  return "";
}

std::string escaped(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    out += c >= 0x20 && c < 0x7f ? std::string(1, ch) : "\\x" + hex(c).substr(2);
  }
  return out;
}

void check_printable(const ParameterList& pl, const Context& ctx) {
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    check_text(name, ctx.file, "the name '" + ctx.path + "->" + escaped(name) + "'");
    const Context child = ctx / name;
    const std::string of = "' of '" + child.path + "'";
    const auto& entry = pl.entry(it);
    if (entry.isList()) {
      check_printable(pl.sublist(name), child);
    } else if (entry.isType<std::string>()) {
      const auto& value = Teuchos::getValue<std::string>(entry);
      check_text(value, ctx.file, "the value '" + escaped(value) + of);
    } else if (entry.isType<Teuchos::Array<std::string>>()) {
      for (const auto& s : Teuchos::getValue<Teuchos::Array<std::string>>(entry))
        check_text(s, ctx.file, "the element '" + escaped(s) + of);
    }
  }
}

}  // namespace shellfrac::params
