#pragma once
/// \file ghost_exchange.hpp
/// The one place where the time loop talks to other ranks about element data (docs/parallel.md): rows of
/// per-element buffers go from their owners to the ranks that hold the element as a ghost, by a Tpetra Import
/// with INSERT (no arithmetic, so deterministic). Only the owned rows another rank needs are packed, into
/// buffers of their size, and only the ghost rows are received; at np = 1 nothing moves. The Tpetra types stay in ghost_exchange.cpp.
#include <initializer_list>
#include <memory>

#include "shellfrac/core/types.hpp"

namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

/// A per-element buffer over the overlap: `width` doubles per element row, rows in overlap order.
struct RowBuffer {
  double* data;
  int width;
};

class GhostExchange {
 public:
  /// A channel per transfer, each of the given total width (the sum of the widths of the buffers it carries).
  GhostExchange(const decomposition::DistributedMesh& dm, std::initializer_list<int> channel_widths);
  ~GhostExchange();
  GhostExchange(const GhostExchange&) = delete;
  GhostExchange& operator=(const GhostExchange&) = delete;
  /// Fills the ghost rows of `buffers` from their owners through channel `channel` (buffers packed side by
  /// side in the given order). Collective.
  void import_ghost_rows(int channel, std::initializer_list<RowBuffer> buffers);
  /// Bytes of the transfer buffers on this rank.
  double bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shellfrac::solver
