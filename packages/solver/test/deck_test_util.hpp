#pragma once
/// \file deck_test_util.hpp
/// Helpers shared by the solver tests that run whole decks: a per-test, per-rank-count working directory,
/// a deck built from XML fragments, writing a file on rank 0, reading the history CSV back, and the
/// period of an oscillating history column from its upward zero crossings.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_Tuple.hpp>
#include <Teuchos_XMLParameterListCoreHelpers.hpp>

#include "shellfrac/core/parallel.hpp"

namespace shellfrac::test {

/// A fresh working directory <name>.np<size> (tests at several np may run at the same time). Collective.
inline std::string work_dir(const std::string& name) {
  namespace fs = std::filesystem;
  const std::string dir = name + ".np" + std::to_string(parallel::size());
  if (parallel::rank() == 0) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return dir;
}

/// Material data of the single block "shell" with the single material "m".
struct ShellSection {
  double thickness = 0.1, density = 1.0, young = 2.1e6, poisson = 0.3;
};

inline std::string xml_double(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

/// A whole deck: `mesh` (the Mesh sublist), the block "shell" of material "m" with `section`, `body` (time
/// integration, conditions, ...), and the Output sublist writing to `out_dir` with the probe list `probes`
/// (an Array(string) value such as "{y_max}").
inline std::string deck(const std::string& mesh, const std::string& body, const std::string& out_dir,
                        const std::string& probes = "{y_max}", const ShellSection& section = {}) {
  return "<ParameterList name=\"shellfrac\">\n" + mesh +
         "<ParameterList name=\"Blocks\"><ParameterList name=\"shell\">"
         "<Parameter name=\"Thickness\" type=\"double\" value=\"" + xml_double(section.thickness) + "\"/>"
         "<Parameter name=\"Material\" type=\"string\" value=\"m\"/></ParameterList></ParameterList>\n"
         "<ParameterList name=\"Materials\"><ParameterList name=\"m\">"
         "<Parameter name=\"Density\" type=\"double\" value=\"" + xml_double(section.density) + "\"/>"
         "<Parameter name=\"Young's Modulus\" type=\"double\" value=\"" + xml_double(section.young) + "\"/>"
         "<Parameter name=\"Poisson's Ratio\" type=\"double\" value=\"" + xml_double(section.poisson) +
         "\"/></ParameterList></ParameterList>\n" +
         body + "<ParameterList name=\"Output\"><Parameter name=\"Directory\" type=\"string\" value=\"" + out_dir +
         "\"/><Parameter name=\"Probes\" type=\"Array(string)\" value=\"" + probes + "\"/></ParameterList>\n"
         "</ParameterList>\n";
}

/// A 3-component array parameter.
inline Teuchos::Array<double> vec3(double x, double y, double z) {
  return Teuchos::Array<double>(Teuchos::tuple<double>(x, y, z));
}

/// A deck as a parameter list: the single block "shell" of material "m" with `section`, and the Output sublist
/// writing to `out_dir` (the current directory if empty). Add the Mesh and the other sublists with sublist/set.
inline Teuchos::RCP<Teuchos::ParameterList> base_deck(const ShellSection& section = {}, const std::string& out_dir = "") {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("shellfrac"));
  auto& shell = pl->sublist("Blocks").sublist("shell");
  shell.set("Thickness", section.thickness);
  shell.set("Material", std::string("m"));
  auto& m = pl->sublist("Materials").sublist("m");
  m.set("Density", section.density);
  m.set("Young's Modulus", section.young);
  m.set("Poisson's Ratio", section.poisson);
  if (!out_dir.empty()) pl->sublist("Output").set("Directory", out_dir);
  return pl;
}

/// Sets the deck's Mesh to a Rectangle generator [0, lx] x [0, ly], nx x ny cells, block "shell".
inline void set_rectangle(Teuchos::ParameterList& deck, double lx, double ly, int nx, int ny,
                          const std::string& pattern = "Alternating") {
  auto& mesh = deck.sublist("Mesh");
  mesh.set("Source", std::string("Rectangle"));
  auto& r = mesh.sublist("Rectangle");
  r.set("Length", lx), r.set("Width", ly), r.set("Elements Along Length", nx), r.set("Elements Along Width", ny);
  r.set("Diagonal Pattern", pattern), r.set("Block Name", std::string("shell"));
}

/// Writes a parameter-list deck as XML to `path` on rank 0. Collective.
inline void write_deck(const std::string& path, const Teuchos::ParameterList& deck) {
  if (parallel::rank() == 0) Teuchos::writeParameterListToXmlFile(deck, path);
  MPI_Barrier(MPI_COMM_WORLD);
}

/// Writes `text` to `path` on rank 0. Collective.
inline void write_file(const std::string& path, const std::string& text) {
  if (parallel::rank() == 0) std::ofstream(path) << text;
  MPI_Barrier(MPI_COMM_WORLD);
}

/// History CSV as rows of numbers (header dropped), with the header returned separately.
inline std::vector<std::vector<double>> read_history(const std::string& path, std::vector<std::string>& header) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  header.clear();
  std::stringstream hs(line);
  for (std::string h; std::getline(hs, h, ',');) header.push_back(h);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream ls(line);
    for (std::string v; std::getline(ls, v, ',');) row.push_back(std::stod(v));
    rows.push_back(row);
  }
  return rows;
}

/// Index of the history column `name`, or header.size() if absent.
inline std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
}

/// Upward zero crossings (linear interpolation) of the mean-free signal rows[.][col] against the time
/// rows[.][time_col]; the mean is taken over all rows.
inline std::vector<double> upward_crossings(const std::vector<std::vector<double>>& rows, std::size_t col,
                                            std::size_t time_col = 1) {
  double mean = 0;
  for (const auto& r : rows) mean += r[col] / rows.size();
  std::vector<double> crossings;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const double w0 = rows[i][col] - mean, w1 = rows[i + 1][col] - mean;
    if (w0 < 0 && w1 >= 0)
      crossings.push_back(rows[i][time_col] - w0 * (rows[i + 1][time_col] - rows[i][time_col]) / (w1 - w0));
  }
  return crossings;
}

/// Frequency of the strongest spectral peak of rows[.][col] in [f_lo, f_hi]: the maximizer of the magnitude of
/// the Hann-windowed discrete-time Fourier transform of the mean-free signal, evaluated continuously in f
/// (grid search over 200 points, then golden section). For a signal made of a few sines, the estimate is
/// free of the bias that a second component puts on zero crossings; its own bias (leakage from the mirror
/// peak at -f) is below 1e-4 relative once the window holds more than ~5 periods.
inline double peak_frequency(const std::vector<std::vector<double>>& rows, std::size_t col, double f_lo, double f_hi,
                             std::size_t time_col = 1) {
  const std::size_t n = rows.size();
  if (n < 4) return 0.0;
  const double t0 = rows.front()[time_col], span = rows.back()[time_col] - t0;
  double mean = 0;
  for (const auto& r : rows) mean += r[col] / n;
  std::vector<double> t(n), x(n);
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = rows[i][time_col] - t0;
    x[i] = (rows[i][col] - mean) * 0.5 * (1 - std::cos(2 * M_PI * t[i] / span));
  }
  const auto magnitude = [&](double f) {
    double re = 0, im = 0;
    for (std::size_t i = 0; i < n; ++i) re += x[i] * std::cos(2 * M_PI * f * t[i]), im -= x[i] * std::sin(2 * M_PI * f * t[i]);
    return std::hypot(re, im);
  };
  const int grid = 200;
  int best = 0;
  double best_mag = -1;
  for (int k = 0; k <= grid; ++k) {
    const double m = magnitude(f_lo + (f_hi - f_lo) * k / grid);
    if (m > best_mag) best_mag = m, best = k;
  }
  const double df = (f_hi - f_lo) / grid, g = (std::sqrt(5.0) - 1) / 2;
  double lo = f_lo + df * std::max(best - 1, 0), hi = f_lo + df * std::min(best + 1, grid);
  double c = hi - g * (hi - lo), d = lo + g * (hi - lo), mc = magnitude(c), md = magnitude(d);
  while (hi - lo > 1e-9 * f_hi) {
    if (mc > md) {
      hi = d, d = c, md = mc, c = hi - g * (hi - lo), mc = magnitude(c);
    } else {
      lo = c, c = d, mc = md, d = lo + g * (hi - lo), md = magnitude(d);
    }
  }
  return 0.5 * (lo + hi);
}

/// The Mesh sublist of a Rectangle generator [0, lx] x [0, ly], nx x ny cells, Alternating diagonals, block "shell".
inline std::string rectangle_mesh(double lx, double ly, int nx, int ny) {
  return "<ParameterList name=\"Mesh\"><Parameter name=\"Source\" type=\"string\" value=\"Rectangle\"/>"
         "<ParameterList name=\"Rectangle\"><Parameter name=\"Length\" type=\"double\" value=\"" + xml_double(lx) +
         "\"/><Parameter name=\"Width\" type=\"double\" value=\"" + xml_double(ly) + "\"/>"
         "<Parameter name=\"Elements Along Length\" type=\"int\" value=\"" + std::to_string(nx) + "\"/>"
         "<Parameter name=\"Elements Along Width\" type=\"int\" value=\"" + std::to_string(ny) + "\"/>"
         "<Parameter name=\"Diagonal Pattern\" type=\"string\" value=\"Alternating\"/>"
         "<Parameter name=\"Block Name\" type=\"string\" value=\"shell\"/></ParameterList></ParameterList>\n";
}

/// The Mesh sublist of a Cylindrical Panel generator (angle in degrees), block "shell".
inline std::string cylindrical_panel_mesh(double r, double l, double angle, int n_axial, int n_circ) {
  return "<ParameterList name=\"Mesh\"><Parameter name=\"Source\" type=\"string\" value=\"Cylindrical Panel\"/>"
         "<ParameterList name=\"Cylindrical Panel\"><Parameter name=\"Radius\" type=\"double\" value=\"" +
         xml_double(r) + "\"/><Parameter name=\"Length\" type=\"double\" value=\"" + xml_double(l) +
         "\"/><Parameter name=\"Angle\" type=\"double\" value=\"" + xml_double(angle) + "\"/>"
         "<Parameter name=\"Axial Elements\" type=\"int\" value=\"" + std::to_string(n_axial) + "\"/>"
         "<Parameter name=\"Circumferential Elements\" type=\"int\" value=\"" + std::to_string(n_circ) + "\"/>"
         "<Parameter name=\"Block Name\" type=\"string\" value=\"shell\"/></ParameterList></ParameterList>\n";
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Replaces the first occurrence of `from` in `text` (which must be there) by `to`.
inline void replace(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

/// The example deck xml/<name> of the source tree, made to run from a test: its mesh files ("meshes/...")
/// by absolute path, and its results written to `out_dir` (a Directory entry before its Probes).
inline std::string example_deck(const std::string& name, const std::string& out_dir) {
  std::string text = slurp(std::string(SHELLFRAC_SOURCE_DIR) + "/xml/" + name);
  EXPECT_FALSE(text.empty()) << "xml/" << name;
  const auto at = text.find("value=\"meshes/");
  if (at != std::string::npos)
    text.replace(at, 14, "value=\"" + std::string(SHELLFRAC_SOURCE_DIR) + "/xml/meshes/");
  replace(text, "<Parameter name=\"Probes\"",
          "<Parameter name=\"Directory\" type=\"string\" value=\"" + out_dir + "\"/><Parameter name=\"Probes\"");
  return text;
}

}  // namespace shellfrac::test
