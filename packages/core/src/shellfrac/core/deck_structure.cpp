#include "shellfrac/core/deck_structure.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/files.hpp"

namespace shellfrac::params {

namespace {

constexpr auto npos = std::string_view::npos;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

/// One open element: its parameter path and, for a ParameterList, the line of each named child.
struct OpenElement {
  std::string path;
  bool is_list = false;
  std::map<std::string, long, std::less<>> child_lines;
};

/// The tag and the name attribute of a start tag, and where it ends.
struct StartTag {
  std::string_view tag, name;
  bool has_name = false, self_closing = false;
  std::size_t end = 0;  ///< one past the closing '>'
};

/// Reads the start tag that begins at text[at] == '<'. False if it is not well-formed (the XML parser reports
/// that).
bool read_start_tag(std::string_view text, std::size_t at, StartTag& t) {
  std::size_t i = at + 1;
  while (i < text.size() && !is_space(text[i]) && text[i] != '>' && text[i] != '/') ++i;
  t.tag = text.substr(at + 1, i - at - 1);
  while (i < text.size()) {
    if (text[i] == '>') return t.end = i + 1, true;
    if (text.compare(i, 2, "/>") == 0) return t.self_closing = true, t.end = i + 2, true;
    if (is_space(text[i])) {
      ++i;
      continue;
    }
    const std::size_t attribute = i;  // name = "value" (or 'value')
    while (i < text.size() && !is_space(text[i]) && text[i] != '=' && text[i] != '>') ++i;
    const std::string_view attribute_name = text.substr(attribute, i - attribute);
    while (i < text.size() && is_space(text[i])) ++i;
    if (i >= text.size() || text[i] != '=') return false;
    for (++i; i < text.size() && is_space(text[i]);) ++i;
    if (i >= text.size() || (text[i] != '"' && text[i] != '\'')) return false;
    const std::size_t close = text.find(text[i], i + 1);
    if (close == npos) return false;
    if (attribute_name == "name") t.name = text.substr(i + 1, close - i - 1), t.has_name = true;
    i = close + 1;
  }
  return false;
}

/// If text[at] begins a comment, CDATA section, processing instruction or declaration: the position after
/// it (npos if it is not terminated). Otherwise `at`.
std::size_t skip_markup(std::string_view text, std::size_t at) {
  const auto after = [&](std::string_view open, std::string_view close) {
    const std::size_t end = text.find(close, at + open.size());
    return end == npos ? npos : end + close.size();
  };
  if (text.compare(at, 4, "<!--") == 0) return after("<!--", "-->");
  if (text.compare(at, 9, "<![CDATA[") == 0) return after("<![CDATA[", "]]>");
  if (text.compare(at, 2, "<?") == 0) return after("<?", "?>");
  if (text.compare(at, 2, "<!") == 0) return after("<!", ">");
  return at;
}

[[noreturn]] void too_deep(const std::string& file, long line) {
  throw InputError(file + ": line " + std::to_string(line) + ": the XML elements are nested more than " +
                   std::to_string(max_deck_nesting) + " levels deep (a deck needs only a few levels of sublists)");
}

/// Records the child `t` of the open ParameterList `parent` (found on `line`); InputError if the name is taken.
void add_child(OpenElement& parent, const StartTag& t, long line, const std::string& file) {
  if (!parent.is_list || !t.has_name || (t.tag != "Parameter" && t.tag != "ParameterList")) return;
  const auto [it, added] = parent.child_lines.emplace(std::string(t.name), line);
  if (added) return;
  throw InputError(file + ": '" + parent.path + "->" + std::string(t.name) + "' is given twice, on lines " +
                   std::to_string(it->second) + " and " + std::to_string(line) +
                   " (only the last would count); give each parameter or sublist once");
}

}  // namespace

std::string read_deck_text(const std::string& file) {
  const std::string cannot_open = file + ": cannot open the input deck (does the file exist and is it readable?)";
  struct stat st {};
  SHELLFRAC_INPUT_REQUIRE(stat(file.c_str(), &st) == 0, cannot_open);
  SHELLFRAC_INPUT_REQUIRE(!S_ISDIR(st.st_mode), file << ": is a directory, not an input deck");
  files::require_regular_input(file, "the input deck");  // a FIFO would block in open(), a device never end
  const std::size_t mib = max_deck_bytes >> 20;
  SHELLFRAC_INPUT_REQUIRE(
      static_cast<std::size_t>(st.st_size) <= max_deck_bytes,
      file << ": the input deck has " << st.st_size << " bytes, more than the " << mib << " MiB a deck may have");
  std::ifstream in(file, std::ios::binary);
  SHELLFRAC_INPUT_REQUIRE(in.good(), cannot_open);
  std::string text;
  std::vector<char> chunk(1 << 16);
  while (in && text.size() <= max_deck_bytes) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
  }
  SHELLFRAC_INPUT_REQUIRE(text.size() <= max_deck_bytes, file << ": the input deck grew beyond the " << mib
                                                              << " MiB a deck may have while it was read");
  return text;
}

void check_deck_structure(std::string_view text, const std::string& file) {
  std::vector<OpenElement> open;
  long line = 1;
  std::size_t counted = 0;  // the newlines before `counted` are in `line`
  for (std::size_t at = text.find('<'); at != npos; at = text.find('<', at)) {
    if (const std::size_t end = skip_markup(text, at); end != at) {
      if (end == npos) return;
      at = end;
      continue;
    }
    if (text.compare(at, 2, "</") == 0) {
      if (!open.empty()) open.pop_back();
      ++at;
      continue;
    }
    StartTag t;
    if (!read_start_tag(text, at, t)) return;
    line += std::count(text.begin() + counted, text.begin() + at, '\n');
    counted = at;
    if (open.size() >= static_cast<std::size_t>(max_deck_nesting)) too_deep(file, line);
    if (!open.empty()) add_child(open.back(), t, line, file);
    at = t.end;
    if (t.self_closing) continue;
    const std::string name(t.has_name ? t.name : t.tag);
    open.push_back({open.empty() ? name : open.back().path + "->" + name, t.tag == "ParameterList", {}});
  }
}

}  // namespace shellfrac::params
