#pragma once
/// \file state_checkpoint.hpp
/// The state as checkpoint tables by global id (io/checkpoint.hpp), and back, on any rank count. The columns
/// are the fields listed by ShellState::visit_element_fields / visit_interface_fields, in that order; plastic
/// states get a table of their own (one row per element: its area points).
#include <map>
#include <set>
#include <string>
#include <vector>

#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/solver/model/shell_state.hpp"

namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

/// Each rank's owned element rows and owned interface rows, with the time, the step and the global element
/// count as scalars. `plastic`: add the plastic table (a model with plastic elements anywhere).
io::CheckpointData state_checkpoint(const ShellState& s, const decomposition::DistributedMesh& dm, bool plastic);

/// The rows StateRestore reads on this rank, by table (io::WantedRows): the owned elements' ids (element tables,
/// plastic) and every local interface's id (interface tables), both sorted; row k of a table is owned element k or
/// local interface k. Null for a table of no state field.
class CheckpointRows {
 public:
  CheckpointRows(const decomposition::DistributedMesh& dm, bool plastic);
  const std::vector<GlobalId>* operator()(const std::string& table) const;
  /// The names of the tables the state needs.
  std::vector<std::string> tables() const;

 private:
  std::vector<GlobalId> elements_, interfaces_;
  std::map<std::string, const std::vector<GlobalId>*> of_;
};

/// Restores the owned element rows and every local interface row of `s` from a checkpoint written by
/// state_checkpoint on any rank count, given a block of rows at a time (io::read_checkpoint with callbacks):
/// header(), then table() for each block of each table in turn (tables of no state field are ignored), then
/// finish(). The ghosts' rows are not
/// touched. InputError naming `file` if the checkpoint does not fit this model (another element count, a missing
/// row or table, another width) or holds values no run can have written (a step that is not a whole number >= 0, a
/// time that is not finite and >= 0, a non-finite value, a director that is not a unit vector, an interface mode
/// other than intact, cohesive or separated): the checksum proves the file unchanged, not its contents sound.
class StateRestore {
 public:
  StateRestore(std::string file, const decomposition::DistributedMesh& dm, bool plastic, ShellState& s);
  /// The time and the step; the element count checked against the mesh.
  void header(const io::CheckpointData& header);
  void table(const std::string& name, const io::CheckpointTable& rows);
  /// Every table the state needs was given, with a row for every owned element or local interface (else
  /// InputError on every rank). Collective.
  void finish();
  /// The rows to ask the checkpoint for.
  const CheckpointRows& rows() const { return needed_; }

 private:
  void finish_table();
  std::string implausible(const std::string& name, const io::CheckpointTable& rows) const;
  std::string file_;
  const decomposition::DistributedMesh& dm_;
  ShellState& s_;
  CheckpointRows needed_;
  std::set<std::string> restored_;
  std::string current_;     ///< the table being restored
  std::vector<char> seen_;  ///< its rows restored so far
  std::string missing_;     ///< the first missing row, reported by finish()
  std::string invalid_;     ///< the first value no run can have written, reported by finish()
};

}  // namespace shellfrac::solver
