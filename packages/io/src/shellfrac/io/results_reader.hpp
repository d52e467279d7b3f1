#pragma once
/// \file results_reader.hpp
/// Reading DG results files back (one file or a per-rank set, merged by element global id), for the tools
/// (shellfrac_exojoin, shellfrac_exocompare) and the tests. The file format: results_writer.hpp, docs/output.md.
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"
#include "shellfrac/io/results_writer.hpp"

namespace shellfrac::io {

/// A results data set read back: one file or a whole per-rank set, merged and sorted by element global id.
struct ExodusResults {
  std::string title;
  int nodes_per_element = 3;
  std::vector<GlobalId> element_gids;   ///< ascending
  std::vector<int> element_block_ids;   ///< Exodus block id per element
  std::vector<std::string> block_names; ///< by block id order as in the file(s)
  std::vector<int> block_ids;
  std::vector<Vec3> node_coords;        ///< element-major, as written
  std::vector<double> times;
  std::vector<std::string> nodal_names;    ///< scalar names as stored, e.g. displ_x
  std::vector<std::string> element_names;
  /// nodal[step][var][node], element[step][var][element]
  std::vector<std::vector<std::vector<double>>> nodal, element;
  std::vector<std::string> global_names;     ///< global variables (the history columns of a shellfrac run)
  std::vector<std::vector<double>> global;   ///< global[step][var]
  std::vector<std::string> info;
  std::vector<ResultsSet> node_sets, side_sets;  ///< merged over the files of a set
  int num_files = 1;
};

/// Reads `path` if it exists; otherwise the per-rank set `path.<np>.<rank>` (np found from the directory).
/// Throws InputError naming the path if neither exists or a file is not a shellfrac-style results file.
ExodusResults read_results(const std::string& path);

/// The files of the per-rank set `path.<np>.<rank>` found next to `path` (ordered by rank; empty if there is
/// none). Throws InputError if the set is incomplete or several sets (different np) are present.
std::vector<std::string> find_rank_files(const std::string& path);

/// The output times of one Exodus file (its time steps, in file order), without reading anything else. Throws
/// InputError naming the file if it cannot be read as Exodus.
std::vector<double> read_result_times(const std::string& file);

/// Reads the given files (e.g. find_rank_files(path)) as one data set, merged by element global id.
ExodusResults read_results_files(const std::vector<std::string>& files);

}  // namespace shellfrac::io
