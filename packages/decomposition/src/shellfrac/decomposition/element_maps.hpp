#pragma once
/// \file element_maps.hpp
/// Tpetra side of the distributed mesh (heavy header: include only where Tpetra objects are used).
/// Element rows: `owned` is one-to-one; `overlap` = owned GIDs first then ghosts (the one ghost layer);
/// `ghosts` = the ghost GIDs alone, in the overlap's order.
/// Data flow every step (docs/parallel.md): owned -> Import(INSERT) -> ghosts -> kernels. The per-step
/// transfers use `send_importer`, from `senders` (the owned rows other ranks hold as ghosts, `send_rows`) to
/// `ghosts`: only those rows are packed, into a vector of their size, and only the ghost rows are received; the
/// owned rows are never copied (at np = 1 nothing moves at all).
#include <Tpetra_Import.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <type_traits>
#include <vector>

#include "shellfrac/core/types.hpp"

namespace shellfrac::decomposition {

using map_type = Tpetra::Map<>;
using tpetra_lo = map_type::local_ordinal_type;
using tpetra_go = map_type::global_ordinal_type;
using node_type = map_type::node_type;
using import_type = Tpetra::Import<tpetra_lo, tpetra_go, node_type>;
using multivector_type = Tpetra::MultiVector<double, tpetra_lo, tpetra_go, node_type>;
using execution_space = multivector_type::execution_space;
static_assert(std::is_same_v<tpetra_go, long long> || sizeof(tpetra_go) == sizeof(GlobalId),
              "shellfrac::GlobalId must match Tpetra's global ordinal width");

/// Maps and transfers of element rows, built once.
struct ElementMaps {
  Teuchos::RCP<const map_type> owned;    ///< one-to-one: the elements this rank owns
  Teuchos::RCP<const map_type> overlap;  ///< owned then ghosts
  Teuchos::RCP<const import_type> importer;  ///< owned -> overlap (ghost values from their owners)
  Teuchos::RCP<const map_type> ghosts;       ///< the ghosts only: overlap rows num_owned.. in the same order
  Teuchos::RCP<const import_type> ghost_importer;  ///< owned -> ghosts (remote rows only, no same/permute rows)
  std::vector<LocalId> send_rows;  ///< owned rows that another rank holds as a ghost (sorted, unique)
  Teuchos::RCP<const map_type> senders;  ///< one-to-one: the GIDs of send_rows, in that order
  Teuchos::RCP<const import_type> send_importer;  ///< senders -> ghosts (what the time loop uses)
};

}  // namespace shellfrac::decomposition
