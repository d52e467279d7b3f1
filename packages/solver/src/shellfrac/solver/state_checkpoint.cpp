#include "shellfrac/solver/state_checkpoint.hpp"

#include <algorithm>

#include "shellfrac/core/error.hpp"
#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"

namespace shellfrac::solver {

namespace {

constexpr int nq = disc::num_area_points;

/// Width of a field in a checkpoint row.
template <int P, int V>
int field_width(const Rows<P, V>&) {
  return Rows<P, V>::width;
}
int field_width(const std::vector<int>&) { return 1; }

/// Appends row r of a field to `out`, and reads it back from `in` (advancing it).
template <int P, int V>
void append_row(const Rows<P, V>& f, LocalId r, std::vector<double>& out) {
  out.insert(out.end(), f.at(r), f.at(r) + Rows<P, V>::width);
}
void append_row(const std::vector<int>& f, LocalId r, std::vector<double>& out) { out.push_back(double(f[r])); }
template <int P, int V>
void read_row(Rows<P, V>& f, LocalId r, const double*& in) {
  std::copy(in, in + Rows<P, V>::width, f.at(r)), in += Rows<P, V>::width;
}
void read_row(std::vector<int>& f, LocalId r, const double*& in) { f[r] = int(*in++); }

int element_width() {
  ShellState s;
  int w = 0;
  ShellState::visit_element_fields(s, [&](const char*, const auto& f) { w += field_width(f); });
  return w;
}
int interface_width() {
  ShellState s;
  int w = 0;
  ShellState::visit_interface_fields(s, [&](const char*, const auto& f) { w += field_width(f); });
  return w;
}

}  // namespace

io::CheckpointData state_checkpoint(const ShellState& s, const decomposition::DistributedMesh& dm, bool plastic) {
  io::CheckpointData d;
  d.scalars["time"] = s.time, d.scalars["step"] = double(s.step);
  d.scalars["num_elements"] = double(dm.num_global_elements());
  auto& el = d.tables["elements"];
  el.width = element_width();
  for (LocalId le = 0; le < dm.num_owned(); ++le) {
    el.ids.push_back(dm.element_gid(le));
    ShellState::visit_element_fields(s, [&](const char*, const auto& f) { append_row(f, le, el.values); });
  }
  if (plastic) {
    auto& pl = d.tables["plastic"];
    pl.width = nq * plastic_state_values;
    for (LocalId le = 0; le < dm.num_owned(); ++le) {
      pl.ids.push_back(dm.element_gid(le));
      for (int q = 0; q < nq; ++q) {
        double v[plastic_state_values];
        pack_plastic_state(s.plastic[le * nq + q], v);
        pl.values.insert(pl.values.end(), v, v + plastic_state_values);
      }
    }
  }
  auto& it = d.tables["interfaces"];
  it.width = interface_width();
  const auto& ifs = dm.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    if (!ifs[i].owned) continue;
    it.ids.push_back(ifs[i].gid);
    ShellState::visit_interface_fields(s, [&](const char*, const auto& f) { append_row(f, LocalId(i), it.values); });
  }
  return d;
}

std::map<std::string, std::vector<GlobalId>> checkpoint_rows(const decomposition::DistributedMesh& dm, bool plastic) {
  std::map<std::string, std::vector<GlobalId>> rows;
  auto& el = rows["elements"];
  for (LocalId le = 0; le < dm.num_owned(); ++le) el.push_back(dm.element_gid(le));
  if (plastic) rows["plastic"] = el;
  auto& it = rows["interfaces"];
  for (const auto& f : dm.interfaces()) it.push_back(f.gid);
  std::sort(it.begin(), it.end());
  it.erase(std::unique(it.begin(), it.end()), it.end());
  return rows;
}

void restore_state(const io::CheckpointData& d, const std::string& file, const decomposition::DistributedMesh& dm,
                   bool plastic, ShellState& s) {
  const auto scalar = [&](const char* name) {
    const auto it = d.scalars.find(name);
    SHELLFRAC_INPUT_REQUIRE(it != d.scalars.end(), file << ": the checkpoint has no '" << name << "'");
    return it->second;
  };
  const auto table = [&](const char* name, int width) -> const io::CheckpointTable& {
    const auto it = d.tables.find(name);
    SHELLFRAC_INPUT_REQUIRE(it != d.tables.end() && it->second.width == width,
                            file << ": the checkpoint's table '" << name << "' is missing or has another width "
                                 << "(written by another version or for another model?)");
    return it->second;
  };
  SHELLFRAC_INPUT_REQUIRE(GlobalId(scalar("num_elements")) == dm.num_global_elements(),
                          file << ": the checkpoint has " << GlobalId(scalar("num_elements")) << " elements, the mesh "
                               << dm.num_global_elements());
  s.time = scalar("time"), s.step = long(scalar("step"));
  const auto& el = table("elements", element_width());
  const io::CheckpointTable* pl = plastic ? &table("plastic", nq * plastic_state_values) : nullptr;
  for (LocalId le = 0; le < dm.num_owned(); ++le) {
    const GlobalId gid = dm.element_gid(le);
    const double* r = el.row(gid);
    SHELLFRAC_INPUT_REQUIRE(r, file << ": the checkpoint has no state for element " << gid + 1);
    ShellState::visit_element_fields(s, [&](const char*, auto& f) { read_row(f, le, r); });
    if (!pl) continue;
    const double* p = pl->row(gid);
    SHELLFRAC_INPUT_REQUIRE(p, file << ": the checkpoint has no plastic state for element " << gid + 1);
    for (int q = 0; q < nq; ++q, p += plastic_state_values) unpack_plastic_state(p, s.plastic[le * nq + q]);
  }
  const auto& it = table("interfaces", interface_width());
  const auto& ifs = dm.interfaces();
  for (std::size_t i = 0; i < ifs.size(); ++i) {
    const double* r = it.row(ifs[i].gid);
    SHELLFRAC_INPUT_REQUIRE(r, file << ": the checkpoint has no state for interface " << ifs[i].gid + 1);
    ShellState::visit_interface_fields(s, [&](const char*, auto& f) { read_row(f, LocalId(i), r); });
  }
}

}  // namespace shellfrac::solver
