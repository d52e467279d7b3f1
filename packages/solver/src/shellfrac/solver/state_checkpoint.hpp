#pragma once
/// \file state_checkpoint.hpp
/// The state as checkpoint tables by global id (io/checkpoint.hpp), and back, on any rank count. The columns
/// are the fields listed by ShellState::visit_element_fields / visit_interface_fields, in that order; plastic
/// states get a table of their own (one row per element: its area points).
#include <map>
#include <string>
#include <vector>

#include "shellfrac/io/checkpoint.hpp"
#include "shellfrac/solver/shell_state.hpp"

namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

/// Each rank's owned element rows and owned interface rows, with the time, the step and the global element
/// count as scalars. `plastic`: add the plastic table (a model with plastic elements anywhere).
io::CheckpointData state_checkpoint(const ShellState& s, const decomposition::DistributedMesh& dm, bool plastic);

/// The rows restore_state reads on this rank, by table: the owned elements' ids (elements, plastic) and every
/// local interface's id (interfaces), for io::read_checkpoint.
std::map<std::string, std::vector<GlobalId>> checkpoint_rows(const decomposition::DistributedMesh& dm, bool plastic);

/// Restores the owned element rows and every local interface row from a checkpoint written by
/// state_checkpoint on any rank count (the ghosts' rows are not touched). InputError naming `file` if the
/// checkpoint does not fit this model (another element count, a missing row or table, another width).
void restore_state(const io::CheckpointData& data, const std::string& file, const decomposition::DistributedMesh& dm,
                   bool plastic, ShellState& s);

}  // namespace shellfrac::solver
