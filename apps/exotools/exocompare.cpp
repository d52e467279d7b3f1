/// \file exocompare.cpp
/// shellfrac_exocompare A B [--tolerances FILE] [--abs X] [--rel Y]
/// Compares two DG results data sets (single files or per-rank sets) by element global id.
/// Exit status: 0 equal within tolerance, 1 different (differences printed), 2 usage or input error.
#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "shellfrac/io/results_compare.hpp"

namespace {

constexpr const char* usage =
    "usage: shellfrac_exocompare A B [--tolerances FILE] [--abs X] [--rel Y] [--max-report N]\n"
    "  A, B              results files, or base names of per-rank sets (A.<np>.<rank>)\n"
    "  --tolerances FILE per-variable tolerances (docs/output.md); lines '<name> [absolute A] [relative R]'\n"
    "  --abs X, --rel Y  default tolerances (override the file's 'default' line); default 0 = exact\n"
    "  --max-report N    at most N difference lines (default 20)\n"
    "exit status: 0 equal within tolerance, 1 different, 2 usage or input error\n";

/// Parses a non-negative number for `option`; throws std::invalid_argument with a message otherwise.
double parse_number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double x = -1;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(x) || x < 0)
    throw std::invalid_argument(option + " needs a non-negative number, got '" + text + "'");
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::string> files;
    std::string tol_file;
    double abs_tol = -1, rel_tol = -1;
    std::size_t max_report = 20;
    for (int k = 1; k < argc; ++k) {
      const std::string arg = argv[k];
      auto value = [&]() -> std::string {
        if (k + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
        return argv[++k];
      };
      if (arg == "-h" || arg == "--help") {
        std::cout << usage;
        return 0;
      } else if (arg == "--tolerances") {
        tol_file = value();
      } else if (arg == "--abs") {
        abs_tol = parse_number(arg, value());
      } else if (arg == "--rel") {
        rel_tol = parse_number(arg, value());
      } else if (arg == "--max-report") {
        max_report = static_cast<std::size_t>(parse_number(arg, value()));
      } else if (arg.size() > 1 && arg[0] == '-') {
        throw std::invalid_argument("unknown option '" + arg + "'");
      } else {
        files.push_back(arg);
      }
    }
    if (files.size() != 2) throw std::invalid_argument("expected two data sets A and B");

    shellfrac::io::CompareTolerances tol;
    if (!tol_file.empty()) tol = shellfrac::io::CompareTolerances::from_file(tol_file);
    if (abs_tol >= 0) tol.default_abs = abs_tol;
    if (rel_tol >= 0) tol.default_rel = rel_tol;

    const auto a = shellfrac::io::read_results(files[0]);
    const auto b = shellfrac::io::read_results(files[1]);
    const auto diffs = shellfrac::io::compare_results(a, b, tol, max_report);
    if (diffs.empty()) {
      std::cout << "shellfrac_exocompare: " << files[0] << " and " << files[1] << " are equal within tolerance ("
                << a.element_gids.size() << " elements, " << a.times.size() << " steps, "
                << a.nodal_names.size() + a.element_names.size() << " variables)\n";
      return 0;
    }
    std::cout << "shellfrac_exocompare: " << files[0] << " (A) and " << files[1] << " (B) differ:\n";
    for (const auto& d : diffs) std::cout << "  " << d << "\n";
    return 1;
  } catch (const std::invalid_argument& e) {
    std::cerr << "shellfrac_exocompare: " << e.what() << "\n" << usage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "shellfrac_exocompare: error: " << e.what() << "\n";
    return 2;
  }
}
