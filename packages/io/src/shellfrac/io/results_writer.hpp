#pragma once
/// \file results_writer.hpp
/// Writing DG results in Exodus II (docs/output.md); reading them back: results_reader.hpp, comparing them:
/// results_compare.hpp.
///  * Nodes are DG nodes: every element writes its own copies (3 for P1, 6 for P2), so discontinuities
///    and cracks open in ParaView. Global DG node id = element_gid * nodes_per_element + a (written +1 in
///    the node id map); element id map = element_gid + 1.
///  * Element blocks TRISHELL3/TRISHELL6, one per mesh block (same ids and names in every file, possibly
///    empty on a rank).
///  * Nodal vectors are written as <name>_x/_y/_z (ParaView glues them; "displ" is applied as displacement
///    automatically); element scalars as element variables in every block.
///  * Parallel: np == 1 writes `path`; np > 1 writes one file per rank `path.<np>.<rank>` (Nemesis naming,
///    rank zero-padded to the width of np, e.g. run.exo.3.0, run.exo.12.03), which ParaView opens as one data set;
///    shellfrac_exojoin merges a set into one file. Each file of a set carries the Nemesis I global information
///    (the set's totals, and the rank's load-balance parameters: every node and element internal, no
///    communication maps); a 1-rank file and a joined file carry none.
///  * The mesh's node sets and side sets (and the deck's regions) are written on the DG copies: a node set holds
///    every DG copy of its nodes, a side set the element edges as shell edge sides 3..5 (edge k -> side k + 3).
///    Every file of a set declares every set, possibly empty on a rank.
///  * Coordinate names x, y, z; a QA record (program, version, date and time of writing).
///  * Each step is flushed (ex_update) so a crashed run leaves a readable file.
#include <mpi.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::io {

/// A node set or side set on the DG copies. Node set: `entries` are global DG node ids (element gid *
/// nodes_per_element + a), ascending. Side set: `entries` are element gids and `edges` their local edges (0..2),
/// ascending by (element, edge).
struct ResultsSet {
  std::string name;
  int id = 0;
  std::vector<GlobalId> entries;
  std::vector<int> edges;  ///< side sets only
  bool operator==(const ResultsSet& o) const {
    return name == o.name && id == o.id && entries == o.entries && edges == o.edges;
  }
};

/// What one rank writes: its owned elements and their DG nodes. Plain data (no Tpetra).
struct ResultsLayout {
  std::string title = "shellfrac";
  int nodes_per_element = 3;                ///< 3 or 6
  std::vector<GlobalId> element_gids;       ///< this rank's elements, ascending
  std::vector<int> element_block;           ///< per element: index into block_names/block_ids
  std::vector<std::string> block_names;     ///< all mesh blocks (same on every rank)
  std::vector<int> block_ids;               ///< Exodus ids of block_names
  std::vector<Vec3> node_coords;            ///< element-major: element i, node a -> [i*npe + a] (reference)
  std::vector<std::string> nodal_vectors;   ///< e.g. {"displ", "velocity", "director"}
  std::vector<std::string> element_scalars; ///< e.g. {"block", "rank"}
  std::vector<std::string> global_variables; ///< e.g. the history columns (one value per step, every file)
  std::vector<std::string> info;             ///< information records (e.g. the expanded input deck lines); written
                                             ///< to the file of rank 0 only (the set has them once)
  std::vector<ResultsSet> node_sets, side_sets;  ///< this rank's part of every set (same names and ids everywhere)
};

/// Longest block, set or variable name an Exodus II file stores (Exodus' MAX_NAME_LENGTH).
constexpr std::size_t max_exodus_name_length = 32;
/// Longest global variable name written (the file then declares its longer names; readers accept up to 255).
constexpr std::size_t max_global_name_length = 80;

/// File name of rank `rank` of `np` for base path `path` (see above).
std::string rank_file_name(const std::string& path, int np, int rank);

/// Writes time steps of DG results; one file per rank (or one file on one rank). Collective constructor.
class ExodusResultsWriter {
 public:
  /// Creates (overwrites) the file(s) and writes the mesh part. Throws Error naming the file on failure.
  /// The layout is taken by value: pass a temporary (or std::move) so that its arrays are not copied.
  ExodusResultsWriter(const std::string& path, ResultsLayout layout, MPI_Comm comm = MPI_COMM_WORLD);
  ~ExodusResultsWriter();
  ExodusResultsWriter(const ExodusResultsWriter&) = delete;
  ExodusResultsWriter& operator=(const ExodusResultsWriter&) = delete;

  /// Appends a step. nodal[v] has num_nodes entries (element-major, as node_coords) for layout.nodal_vectors[v];
  /// element[s] has one value per element for layout.element_scalars[s]; global has one value per
  /// layout.global_variables entry. Returns the 1-based step index.
  int write_step(double time, const std::vector<std::vector<Vec3>>& nodal,
                 const std::vector<std::vector<double>>& element, const std::vector<double>& global = {});
  /// Component c of nodal vector v (layout.nodal_vectors order) at every node, element-major as node_coords,
  /// written to `out` (num_nodes values).
  using NodalComponent = std::function<void(std::size_t v, int c, double* out)>;
  /// The same, asking for one component of one nodal vector at a time: only one is held in memory.
  int write_step(double time, const NodalComponent& nodal, const std::vector<std::vector<double>>& element,
                 const std::vector<double>& global = {});

  /// The file this rank writes.
  const std::string& file_name() const { return file_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string file_;
};

struct ExodusResults;

/// Writes a merged data set as one file (the join tool).
void write_results(const ExodusResults& results, const std::string& path);

}  // namespace shellfrac::io
