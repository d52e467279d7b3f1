#include "shellfrac/solver/state_checkpoint.hpp"

#include <algorithm>
#include <memory>

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

/// Copies row r of a field to `out` (advancing it), and reads it back from `in` (advancing it).
template <int P, int V>
void copy_row(const Rows<P, V>& f, LocalId r, double*& out) {
  out = std::copy(f.at(r), f.at(r) + Rows<P, V>::width, out);
}
void copy_row(const std::vector<int>& f, LocalId r, double*& out) { *out++ = double(f[r]); }
template <int P, int V>
void read_row(Rows<P, V>& f, LocalId r, const double*& in) {
  std::copy(in, in + Rows<P, V>::width, f.at(r)), in += Rows<P, V>::width;
}
void read_row(std::vector<int>& f, LocalId r, const double*& in) { f[r] = int(*in++); }

std::string element_table(const char* field) { return std::string("element ") + field; }
std::string interface_table(const char* field) { return std::string("interface ") + field; }

}  // namespace

// One table per field, read from the state a block of rows at a time when the checkpoint is written
// (io::TableSource): the owned elements in ascending global id (row = local id), and the owned interfaces, which
// are listed by ascending gid (row k = the k-th owned interface).
io::CheckpointData state_checkpoint(const ShellState& s, const decomposition::DistributedMesh& dm, bool plastic) {
  io::CheckpointData d;
  d.scalars["time"] = s.time, d.scalars["step"] = double(s.step);
  d.scalars["num_elements"] = double(dm.num_global_elements());
  const auto* mesh = &dm;
  const auto element_ids = [mesh] {
    std::vector<GlobalId> ids(std::size_t(mesh->num_owned()));
    for (LocalId le = 0; le < mesh->num_owned(); ++le) ids[std::size_t(le)] = mesh->element_gid(le);
    return ids;
  };
  ShellState::visit_element_fields(s, [&](const char* name, const auto& f) {
    d.table_sources[element_table(name)] = {field_width(f), element_ids,
                                             [field = &f](std::size_t first, std::size_t count, double* out) {
                                               for (std::size_t le = first; le < first + count; ++le)
                                                 copy_row(*field, LocalId(le), out);
                                             }};
  });
  if (plastic)
    d.table_sources["plastic"] = {nq * plastic_state_values, element_ids,
                                  [state = &s](std::size_t first, std::size_t count, double* out) {
                                    for (std::size_t le = first; le < first + count; ++le)
                                      for (int q = 0; q < nq; ++q, out += plastic_state_values)
                                        pack_plastic_state(state->plastic[le * nq + std::size_t(q)], out);
                                  }};
  // The owned interfaces' local indices, in ascending gid (dm.interfaces() is sorted by gid).
  auto owned = std::make_shared<std::vector<LocalId>>();
  for (std::size_t i = 0; i < dm.interfaces().size(); ++i)
    if (dm.interfaces()[i].owned) owned->push_back(LocalId(i));
  const auto interface_ids = [mesh, owned] {
    std::vector<GlobalId> ids;
    for (const LocalId i : *owned) ids.push_back(mesh->interfaces()[std::size_t(i)].gid);
    return ids;
  };
  ShellState::visit_interface_fields(s, [&](const char* name, const auto& f) {
    d.table_sources[interface_table(name)] = {field_width(f), interface_ids,
                                               [field = &f, owned](std::size_t first, std::size_t count, double* out) {
                                                 for (std::size_t k = first; k < first + count; ++k)
                                                   copy_row(*field, (*owned)[k], out);
                                               }};
  });
  return d;
}

std::map<std::string, std::vector<GlobalId>> checkpoint_rows(const decomposition::DistributedMesh& dm, bool plastic) {
  std::vector<GlobalId> elements, interfaces;
  for (LocalId le = 0; le < dm.num_owned(); ++le) elements.push_back(dm.element_gid(le));
  for (const auto& f : dm.interfaces()) interfaces.push_back(f.gid);
  std::sort(interfaces.begin(), interfaces.end());
  interfaces.erase(std::unique(interfaces.begin(), interfaces.end()), interfaces.end());
  std::map<std::string, std::vector<GlobalId>> rows;
  ShellState none;
  ShellState::visit_element_fields(none, [&](const char* name, const auto&) { rows[element_table(name)] = elements; });
  if (plastic) rows["plastic"] = elements;
  ShellState::visit_interface_fields(none, [&](const char* name, const auto&) { rows[interface_table(name)] = interfaces; });
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
  ShellState::visit_element_fields(s, [&](const char* name, auto& f) {
    const auto& t = table(element_table(name).c_str(), field_width(f));
    for (LocalId le = 0; le < dm.num_owned(); ++le) {
      const double* r = t.row(dm.element_gid(le));
      SHELLFRAC_INPUT_REQUIRE(r, file << ": the checkpoint has no " << name << " for element " << dm.element_gid(le) + 1);
      read_row(f, le, r);
    }
  });
  if (plastic) {
    const auto& pl = table("plastic", nq * plastic_state_values);
    for (LocalId le = 0; le < dm.num_owned(); ++le) {
      const double* p = pl.row(dm.element_gid(le));
      SHELLFRAC_INPUT_REQUIRE(p, file << ": the checkpoint has no plastic state for element " << dm.element_gid(le) + 1);
      for (int q = 0; q < nq; ++q, p += plastic_state_values) unpack_plastic_state(p, s.plastic[le * nq + q]);
    }
  }
  const auto& ifs = dm.interfaces();
  ShellState::visit_interface_fields(s, [&](const char* name, auto& f) {
    const auto& t = table(interface_table(name).c_str(), field_width(f));
    for (std::size_t i = 0; i < ifs.size(); ++i) {
      const double* r = t.row(ifs[i].gid);
      SHELLFRAC_INPUT_REQUIRE(r, file << ": the checkpoint has no " << name << " for interface " << ifs[i].gid + 1);
      read_row(f, LocalId(i), r);
    }
  });
}

}  // namespace shellfrac::solver
