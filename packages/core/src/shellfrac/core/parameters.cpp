#include "shellfrac/core/parameters.hpp"

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLObject.hpp>
#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string_view>

#include "shellfrac/core/deck_structure.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"

namespace shellfrac::params {

namespace {

/// Number range validator with clear messages (the Teuchos one reports neither units nor open bounds).
template <class T>
class RangeValidator : public Teuchos::ParameterEntryValidator {
 public:
  RangeValidator(T min, T max, bool open_min, bool open_max)
      : min_(min), max_(max), open_min_(open_min), open_max_(open_max) {}

  const std::string getXMLTypeName() const override { return "shellfracRangeValidator"; }

  void printDoc(const std::string& doc, std::ostream& out) const override { out << "# " << doc << " " << range() << "\n"; }

  ValidStringsList validStringValues() const override { return Teuchos::null; }

  void validate(const Teuchos::ParameterEntry& entry, const std::string& name,
                const std::string& sublist) const override {
    const T v = Teuchos::any_cast<T>(entry.getAny());
    const bool ok_min = open_min_ ? v > min_ : v >= min_;
    const bool ok_max = open_max_ ? v < max_ : v <= max_;
    if (!(ok_min && ok_max) || (std::is_floating_point_v<T> && !std::isfinite(static_cast<double>(v)))) {
      std::ostringstream os;
      os << "value " << v << " is out of range: must be " << range();
      throw Teuchos::Exceptions::InvalidParameterValue(os.str());
    }
  }

  std::string range() const {
    std::ostringstream os;
    const bool has_min = min_ > std::numeric_limits<T>::lowest();
    const bool has_max = max_ < std::numeric_limits<T>::max();
    if (has_min && has_max)
      os << "in " << (open_min_ ? "(" : "[") << min_ << ", " << max_ << (open_max_ ? ")" : "]");
    else if (has_min)
      os << (open_min_ ? "> " : ">= ") << min_;
    else if (has_max)
      os << (open_max_ ? "< " : "<= ") << max_;
    else
      os << "finite";
    return os.str();
  }

 private:
  T min_, max_;
  bool open_min_, open_max_;
};

std::string type_name(const Teuchos::ParameterEntry& e) {
  if (e.isList()) return "ParameterList";
  const std::string t = e.getAny().typeName();
  if (t == "d") return "double";
  if (t == "i") return "int";
  if (t == "b") return "bool";
  if (t.find("basic_string") != std::string::npos) return "string";
  return e.getAny().typeName();
}

std::string list_names(const ParameterList& valid) {
  std::ostringstream os;
  bool first = true;
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    os << (first ? "" : ", ") << "'" << valid.name(it) << "'";
    if (valid.entry(it).isList()) os << " (sublist)";
    first = false;
  }
  return first ? std::string("(none)") : os.str();
}

std::string closest(const std::string& name, const ParameterList& valid) {
  std::string best;
  std::size_t best_d = std::numeric_limits<std::size_t>::max();
  auto lower = [](std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
  };
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const auto d = edit_distance(lower(name), lower(valid.name(it)));
    if (d < best_d) best_d = d, best = valid.name(it);
  }
  return best_d <= std::max<std::size_t>(2, name.size() / 3) ? best : std::string();
}

/// The useful part of a Teuchos exception text: Teuchos prefixes its message with the throwing source file,
/// a throw count and the failed test ("./packages/teuchos/...:72:\n\nThrow number = 1\n\nThrow test that
/// evaluated to true: ...\n\n<message>"); only <message> is for the user, on one line.
std::string teuchos_message(const std::string& what) {
  std::string text = what;
  const std::string marker = "Throw test that evaluated to true:";
  if (const auto at = text.find(marker); at != std::string::npos) {
    const auto end = text.find("\n\n", at);
    if (end != std::string::npos) text = text.substr(end + 2);
  }
  std::string out;
  for (char c : text) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    if (c == ' ' && (out.empty() || out.back() == ' ')) continue;
    out += c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

/// True if `text` (surrounding blanks allowed) is a whole integer in [lo, hi].
bool is_integer(std::string_view text, long long lo, long long hi) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  if (text.size() > 1 && text.front() == '+' && std::isdigit(static_cast<unsigned char>(text[1]))) text.remove_prefix(1);
  long long v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return !text.empty() && ec == std::errc() && end == text.data() + text.size() && v >= lo && v <= hi;
}

/// True if `text` (surrounding blanks allowed) is a whole decimal number that strtod reads without overflow
/// ("nan" and "inf" are numbers here: the range validators reject them with a clear message). Hexadecimal is
/// refused: Teuchos reads it as a number in a scalar but as 0 in an array.
bool is_real(const std::string& text) {
  if (text.find_first_of("xX") != std::string::npos) return false;
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end == begin) return false;
  while (*end != '\0' && std::isspace(static_cast<unsigned char>(*end))) ++end;
  return *end == '\0' && !(errno == ERANGE && std::isinf(v));
}

/// True if `text` is a number (is_real) and finite: no array has a validator that could reject nan or inf, so
/// every element of a numeric array must be finite.
bool is_finite_real(const std::string& text) { return is_real(text) && std::isfinite(std::strtod(text.c_str(), nullptr)); }

/// Teuchos converts numbers without checking that the whole text was used, keeping whatever prefix it could
/// read: "0.01mm" is 0.01, "zero point three" is 0, "10.7" as an int is 10, "99999999999999" as an int is
/// 276447231, and "{0, x, 1}" is {0, 0, 1}, all without an error. This walk of the XML checks that every
/// numeric value (and array element) is a whole number of its type.
void check_numbers(const Teuchos::XMLObject& xml, const std::string& file, const std::string& path) {
  for (int i = 0; i < xml.numChildren(); ++i) {
    const Teuchos::XMLObject& child = xml.getChild(i);
    const std::string name = child.hasAttribute("name") ? child.getAttribute("name") : std::string("?");
    const std::string child_path = path.empty() ? name : path + "->" + name;
    if (child.getTag() == "ParameterList") {
      check_numbers(child, file, child_path);
      continue;
    }
    if (child.getTag() != "Parameter" || !child.hasAttribute("type") || !child.hasAttribute("value")) continue;
    std::string type = child.getAttribute("type");
    const std::string& value = child.getAttribute("value");
    std::vector<std::string> items{value};
    const bool is_array = type.rfind("Array(", 0) == 0 && type.back() == ')';
    if (is_array) {  // "{a, b, c}"; Teuchos checks the braces
      type = type.substr(6, type.size() - 7);
      items.clear();
      const auto open = value.find('{'), close = value.rfind('}');
      if (open == std::string::npos || close == std::string::npos || close < open) continue;
      const std::string inner = value.substr(open + 1, close - open - 1);
      if (inner.find_first_not_of(" \t\r\n") == std::string::npos) continue;  // {}
      for (std::size_t start = 0;;) {
        const auto comma = inner.find(',', start);
        items.push_back(inner.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
    }
    const char* what = nullptr;
    for (const std::string& item : items) {
      if (type == "int" && !is_integer(item, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()))
        what = "an integer in [-2147483648, 2147483647]";
      else if (type == "long long" && !is_integer(item, std::numeric_limits<long long>::min(),
                                                  std::numeric_limits<long long>::max()))
        what = "a 64-bit integer";
      else if ((type == "double" || type == "float") && !is_real(item))
        what = "a number";
      else if ((type == "double" || type == "float") && is_array && !is_finite_real(item))
        what = "a finite number (array elements must be finite)";
      if (what != nullptr) {
        std::ostringstream os;
        os << file << ": parameter '" << child_path << "' (type " << child.getAttribute("type") << "): ";
        if (value.find('{') != std::string::npos) {
          const auto first = item.find_first_not_of(" \t\r\n"), last = item.find_last_not_of(" \t\r\n");
          os << "the element '" << (first == std::string::npos ? std::string() : item.substr(first, last - first + 1))
             << "' of '" << value << "'";
        } else {
          os << "the value '" << value << "'";
        }
        os << " is not " << what;
        throw InputError(os.str());
      }
    }
  }
}

std::string value_string(const Teuchos::ParameterEntry& e) {
  std::ostringstream os;
  os << e.getAny();
  return os.str();
}

}  // namespace

std::vector<double> fixed_array(const ParameterList& pl, const std::string& name, std::size_t n, const Context& ctx) {
  const auto v = pl.get<Teuchos::Array<double>>(name);
  SHELLFRAC_INPUT_REQUIRE(v.size() == static_cast<Teuchos::Array<double>::size_type>(n),
                          ctx.file << ": '" << ctx.path << "->" << name << "' must have " << n << " components, not "
                                   << v.size());
  for (double x : v)
    SHELLFRAC_INPUT_REQUIRE(std::isfinite(x), ctx.file << ": '" << ctx.path << "->" << name << "' is not finite");
  return std::vector<double>(v.begin(), v.end());
}

void refuse_inapplicable(const ParameterList& user, const ParameterList& valid, const std::string& kind,
                         const std::function<bool(const std::string& name)>& applies, const Context& ctx) {
  std::vector<std::string> used;
  for (auto it = valid.begin(); it != valid.end(); ++it)
    if (applies(valid.name(it))) used.push_back("'" + valid.name(it) + "'");
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    if (applies(name) || !valid.isParameter(name) || valid.getEntry(name).isList()) continue;
    if (user.entry(it).getAny() == valid.getEntry(name).getAny()) continue;  // the default: means nothing
    std::ostringstream os;
    os << ctx.file << ": '" << ctx.path << "->" << name << "' = ";
    if (const auto& e = user.entry(it); e.isType<Teuchos::Array<double>>()) {
      const auto& a = Teuchos::getValue<Teuchos::Array<double>>(e);
      os << "{";
      for (long i = 0; i < static_cast<long>(a.size()); ++i) os << (i ? ", " : "") << a[i];
      os << "}";
    } else {
      os << value_string(e);
    }
    os << " does not apply to " << kind << " and would be ignored; the parameters of " << kind << " are";
    for (std::size_t i = 0; i < used.size(); ++i) os << (i ? ", " : " ") << used[i];
    os << ". Remove it, or choose the kind it belongs to";
    throw InputError(os.str());
  }
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

RCP<ParameterList> read_deck(const std::string& file, MPI_Comm comm) {
  std::string text;
  parallel::on_root_then_agree(
      [&] {
        text = read_deck_text(file);
        check_deck_structure(text, file);
        try {
          Teuchos::getParametersFromXmlString(text);
        } catch (const std::exception& e) {
          SHELLFRAC_INPUT_REQUIRE(false, file << ": not a valid Teuchos XML parameter list: " << teuchos_message(e.what()));
        }
        const Teuchos::XMLObject xml = Teuchos::StringInputSource(text).getObject();
        check_numbers(xml, file, xml.hasAttribute("name") ? xml.getAttribute("name") : std::string());
      },
      0, comm);
  parallel::broadcast(text, 0, comm);
  return Teuchos::getParametersFromXmlString(text);
}

void validate(ParameterList& user, const ParameterList& valid, const Context& ctx) {
  // 1. names and types
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    const Teuchos::ParameterEntry* v = valid.getEntryPtr(name);
    if (v == nullptr) {
      std::ostringstream os;
      os << ctx.file << ": unknown parameter '" << name << "' in '" << ctx.path << "'.";
      const std::string guess = closest(name, valid);
      if (!guess.empty()) os << " Did you mean '" << guess << "'?";
      os << " Valid names here: " << list_names(valid) << ".";
      throw InputError(os.str());
    }
    Teuchos::ParameterEntry& u = user.getEntry(name);
    const std::string ut = type_name(u), vt = type_name(*v);
    if (ut == "int" && vt == "double") {  // accept 2 where 2.0 is meant
      user.set(name, static_cast<double>(Teuchos::getValue<int>(u)), v->docString());
      continue;
    }
    SHELLFRAC_INPUT_REQUIRE(ut == vt, ctx.file << ": parameter '" << ctx.path << "->" << name << "' has type " << ut
                                               << " but must have type " << vt
                                               << (vt == "ParameterList" ? " (a <ParameterList name=...> element)" : "")
                                               << ". " << v->docString());
  }
  // 2. values; a double without a range of its own must be finite
  constexpr double max_double = std::numeric_limits<double>::max();
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    const Teuchos::ParameterEntry& v = valid.getEntry(name);
    auto validator = v.validator();
    if (v.isList()) continue;
    if (validator.is_null() && type_name(v) == "double") validator = double_range(-max_double, max_double);
    if (validator.is_null()) continue;
    try {
      validator->validate(user.getEntry(name), name, ctx.path);
    } catch (const std::exception& e) {
      std::ostringstream os;
      os << ctx.file << ": invalid value '" << value_string(user.getEntry(name)) << "' for parameter '" << ctx.path
         << "->" << name << "' (" << v.docString() << "): ";
      if (auto choices = validator->validStringValues(); !choices.is_null()) {
        os << "valid choices are";
        for (const auto& c : *choices) os << " '" << c << "'";
        os << ".";
      } else {
        os << e.what();
      }
      throw InputError(os.str());
    }
  }
  // 3. defaults (and the int->string mapping of enumerations)
  try {
    user.validateParametersAndSetDefaults(valid, 0);
  } catch (const std::exception& e) {
    throw InputError(ctx.file + ": in '" + ctx.path + "': " + e.what());
  }
}

RCP<const Teuchos::ParameterEntryValidator> double_range(double min, double max, bool open_min, bool open_max) {
  return Teuchos::rcp(new RangeValidator<double>(min, max, open_min, open_max));
}
RCP<const Teuchos::ParameterEntryValidator> positive_double() {
  return double_range(0.0, std::numeric_limits<double>::max(), true, false);
}
RCP<const Teuchos::ParameterEntryValidator> non_negative_double() {
  return double_range(0.0, std::numeric_limits<double>::max(), false, false);
}
RCP<const Teuchos::ParameterEntryValidator> int_range(int min, int max) {
  return Teuchos::rcp(new RangeValidator<int>(min, max, false, false));
}

void set_choice(ParameterList& pl, const std::string& name, const std::string& default_value, const std::string& doc,
                const std::vector<std::string>& choices) {
  Teuchos::Array<std::string> c(choices.begin(), choices.end());
  pl.set(name, default_value, doc, Teuchos::rcp(new Teuchos::StringValidator(c)));
}

void strip_validators(ParameterList& pl) {
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    auto& e = pl.getEntry(pl.name(it));
    if (e.isList())
      strip_validators(pl.sublist(pl.name(it)));
    else
      e.setValidator(Teuchos::null);
  }
}

namespace {
/// Text made safe for an XML comment: "--" is not allowed inside one.
std::string comment_text(std::string s) {
  for (std::size_t at; (at = s.find("--")) != std::string::npos;) s.replace(at, 2, "- -");
  return s;
}
}  // namespace

void write_documented_xml(std::ostream& os, const ParameterList& valid, int indent) {
  const std::string pad(indent, ' ');
  if (indent == 0) os << "<ParameterList name=\"" << valid.name() << "\">\n";
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    const auto& e = valid.entry(it);
    const std::string in = pad + "  ";
    if (e.isList()) {
      const auto& sub = valid.sublist(name);
      if (!e.docString().empty()) os << in << "<!-- " << comment_text(e.docString()) << " -->\n";
      os << in << "<ParameterList name=\"" << name << "\">\n";
      write_documented_xml(os, sub, indent + 2);
      os << in << "</ParameterList>\n";
      continue;
    }
    std::ostringstream comment;
    comment << e.docString();
    if (!e.docString().empty() && e.docString().back() != '.') comment << '.';
    if (auto v = e.validator(); !v.is_null()) {
      if (auto choices = v->validStringValues(); !choices.is_null()) {
        comment << " Choices:";
        for (const auto& c : *choices) comment << " '" << c << "'";
        comment << ".";
      } else if (auto r = Teuchos::rcp_dynamic_cast<const RangeValidator<double>>(v); !r.is_null()) {
        comment << " Range: " << r->range() << ".";
      } else if (auto ri = Teuchos::rcp_dynamic_cast<const RangeValidator<int>>(v); !ri.is_null()) {
        comment << " Range: " << ri->range() << ".";
      }
    }
    std::string value = value_string(e);
    if (type_name(e) == "bool") value = Teuchos::getValue<bool>(e) ? "true" : "false";
    if (type_name(e) == "double") {
      std::ostringstream ds;
      ds << std::setprecision(17) << Teuchos::getValue<double>(e);
      value = ds.str();
    }
    os << in << "<!-- " << comment_text(comment.str()) << " -->\n";
    os << in << "<Parameter name=\"" << name << "\" type=\"" << type_name(e) << "\" value=\"" << value << "\"/>\n";
  }
  if (indent == 0) os << "</ParameterList>\n";
}

}  // namespace shellfrac::params
