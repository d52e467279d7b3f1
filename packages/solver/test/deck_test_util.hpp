#pragma once
/// \file deck_test_util.hpp
/// Helpers shared by the solver tests that run whole decks: a per-test, per-rank-count working directory,
/// a deck built as a Teuchos::ParameterList (from scratch or from an example deck of xml/) and written on rank 0,
/// reading the history CSV back, and the period of an oscillating history column from its upward zero crossings.
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

/// A fresh working directory <name>.np<size> (tests at several np may run at the same time). The name must be
/// unique over all test executables: ctest runs them in parallel, and a second user would remove the first's files.
/// Collective.
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

/// Sets the deck's Mesh to a Cylindrical Panel generator of radius r, length l and opening `angle` (degrees),
/// n_axial x n_circ cells, block "shell".
inline void set_cylindrical_panel(Teuchos::ParameterList& deck, double r, double l, double angle, int n_axial,
                                  int n_circ) {
  auto& mesh = deck.sublist("Mesh");
  mesh.set("Source", std::string("Cylindrical Panel"));
  auto& p = mesh.sublist("Cylindrical Panel");
  p.set("Radius", r), p.set("Length", l), p.set("Angle", angle);
  p.set("Axial Elements", n_axial), p.set("Circumferential Elements", n_circ), p.set("Block Name", std::string("shell"));
}

/// Sets the deck's Mesh to the mesh file `file` (a relative path is relative to the deck's directory).
inline void set_mesh_file(Teuchos::ParameterList& deck, const std::string& file) {
  auto& mesh = deck.sublist("Mesh");
  mesh.set("Source", std::string("File")), mesh.set("File", file);
}

/// Sets Output->Probes, the node sets whose mean motion the history records (none if empty).
inline void set_probes(Teuchos::ParameterList& deck, const std::vector<std::string>& node_sets) {
  deck.sublist("Output").set("Probes", Teuchos::Array<std::string>(node_sets.begin(), node_sets.end()));
}

/// The material "m" of the block "shell" (base_deck), to add e.g. plasticity or fracture parameters to.
inline Teuchos::ParameterList& shell_material(Teuchos::ParameterList& deck) {
  return deck.sublist("Materials").sublist("m");
}

/// Adds Boundary Conditions-><name> of `type` on `node_set`; returns it for the type's other parameters.
inline Teuchos::ParameterList& boundary_condition(Teuchos::ParameterList& deck, const std::string& name,
                                                  const std::string& type, const std::string& node_set) {
  auto& bc = deck.sublist("Boundary Conditions").sublist(name);
  bc.set("Type", type), bc.set("Node Set", node_set);
  return bc;
}

/// Adds Initial Conditions-><name>: the initial `velocity` of the elements `elements`; returns it for further
/// parameters (Angular Velocity, Center).
inline Teuchos::ParameterList& initial_velocity(Teuchos::ParameterList& deck, const std::string& name,
                                                const std::string& elements, const Teuchos::Array<double>& velocity) {
  auto& ic = deck.sublist("Initial Conditions").sublist(name);
  ic.set("Elements", elements), ic.set("Velocity", velocity);
  return ic;
}

/// The example deck xml/<name> of the source tree, made to run from a test: its mesh file (relative to xml/ in
/// the examples) by absolute path, and its results written to `out_dir`. Edit it with sublist(...).set(...).
inline Teuchos::RCP<Teuchos::ParameterList> example_deck(const std::string& name, const std::string& out_dir) {
  const std::string xml_dir = std::string(SHELLFRAC_SOURCE_DIR) + "/xml/";
  auto deck = Teuchos::getParametersFromXmlFile(xml_dir + name);
  if (deck->isSublist("Mesh") && deck->sublist("Mesh").isType<std::string>("File")) {
    auto& mesh = deck->sublist("Mesh");
    const std::string file = mesh.get<std::string>("File");
    if (!file.empty() && file.front() != '/') mesh.set("File", xml_dir + file);
  }
  deck->sublist("Output").set("Directory", out_dir);
  return deck;
}

/// Writes a parameter-list deck as XML to `path` on rank 0 of `comm`. Collective over `comm`.
inline void write_deck(const std::string& path, const Teuchos::ParameterList& deck, MPI_Comm comm = MPI_COMM_WORLD) {
  if (parallel::rank(comm) == 0) Teuchos::writeParameterListToXmlFile(deck, path);
  MPI_Barrier(comm);
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

/// The whole text of the file `path`.
inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace shellfrac::test
