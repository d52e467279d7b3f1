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

std::string element_table(const char* field) { return std::string("element ") + field; }
std::string interface_table(const char* field) { return std::string("interface ") + field; }

}  // namespace

// One table per field, each built only when the checkpoint is written (CheckpointData::table_sources).
io::CheckpointData state_checkpoint(const ShellState& s, const decomposition::DistributedMesh& dm, bool plastic) {
  io::CheckpointData d;
  d.scalars["time"] = s.time, d.scalars["step"] = double(s.step);
  d.scalars["num_elements"] = double(dm.num_global_elements());
  const auto* mesh = &dm;
  ShellState::visit_element_fields(s, [&](const char* name, const auto& f) {
    d.table_sources[element_table(name)] = [field = &f, mesh] {
      io::CheckpointTable t;
      t.width = field_width(*field);
      for (LocalId le = 0; le < mesh->num_owned(); ++le) t.ids.push_back(mesh->element_gid(le)), append_row(*field, le, t.values);
      return t;
    };
  });
  if (plastic)
    d.table_sources["plastic"] = [state = &s, mesh] {
      io::CheckpointTable t;
      t.width = nq * plastic_state_values;
      for (LocalId le = 0; le < mesh->num_owned(); ++le) {
        t.ids.push_back(mesh->element_gid(le));
        for (int q = 0; q < nq; ++q) {
          double v[plastic_state_values];
          pack_plastic_state(state->plastic[le * nq + q], v);
          t.values.insert(t.values.end(), v, v + plastic_state_values);
        }
      }
      return t;
    };
  ShellState::visit_interface_fields(s, [&](const char* name, const auto& f) {
    d.table_sources[interface_table(name)] = [field = &f, mesh] {
      io::CheckpointTable t;
      t.width = field_width(*field);
      const auto& ifs = mesh->interfaces();
      for (std::size_t i = 0; i < ifs.size(); ++i)
        if (ifs[i].owned) t.ids.push_back(ifs[i].gid), append_row(*field, LocalId(i), t.values);
      return t;
    };
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
