#include "shellfrac/solver/model/ghost_exchange.hpp"

#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/decomposition/element_maps.hpp"

namespace shellfrac::solver {

struct GhostExchange::Impl {
  const decomposition::DistributedMesh& dm;
  // Per channel: the send rows (ElementMaps::senders, in send_rows order) and the ghost rows.
  std::vector<Teuchos::RCP<decomposition::multivector_type>> send, ghost;
  std::vector<int> width;
};

GhostExchange::GhostExchange(const decomposition::DistributedMesh& dm, std::initializer_list<int> channel_widths)
    : impl_(new Impl{dm, {}, {}, {}}) {
  const auto& maps = dm.maps();
  for (int w : channel_widths) {
    impl_->send.push_back(Teuchos::rcp(new decomposition::multivector_type(maps.senders, w)));
    impl_->ghost.push_back(Teuchos::rcp(new decomposition::multivector_type(maps.ghosts, w)));
    impl_->width.push_back(w);
  }
}

GhostExchange::~GhostExchange() = default;

void GhostExchange::import_ghost_rows(int channel, std::initializer_list<RowBuffer> buffers) {
  auto& send = *impl_->send.at(channel);
  auto& ghost = *impl_->ghost.at(channel);
  int total = 0;
  for (const auto& b : buffers) total += b.width;
  SHELLFRAC_REQUIRE(total == impl_->width[channel], "ghost exchange: buffers of width " << total << " on a channel of "
                                                                                        << impl_->width[channel]);
  const auto& maps = impl_->dm.maps();
  {
    auto s = send.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (std::size_t r = 0; r < maps.send_rows.size(); ++r) {
      const LocalId le = maps.send_rows[r];
      int col = 0;
      for (const auto& b : buffers)
        for (int i = 0; i < b.width; ++i) s(r, col++) = b.data[std::size_t(le) * b.width + i];
    }
  }
  ghost.doImport(send, *maps.send_importer, Tpetra::INSERT);
  auto s = ghost.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto num_ghosts = static_cast<LocalId>(ghost.getLocalLength());
  const LocalId first = impl_->dm.num_owned();
  for (LocalId r = 0; r < num_ghosts; ++r) {
    int col = 0;
    for (const auto& b : buffers)
      for (int i = 0; i < b.width; ++i) b.data[std::size_t(first + r) * b.width + i] = s(r, col++);
  }
}

double GhostExchange::bytes() const {
  double total = 0;
  for (std::size_t c = 0; c < impl_->width.size(); ++c)
    total += sizeof(double) * double(impl_->width[c]) *
             double(impl_->dm.maps().send_rows.size() + std::size_t(impl_->dm.num_ghosts()));
  return total;
}

}  // namespace shellfrac::solver
