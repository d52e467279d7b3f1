#include "shellfrac/solver/restart/state_checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <sstream>
#include <utility>

#include "shellfrac/core/error.hpp"
#include "shellfrac/core/parallel.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/disc/dg_element.hpp"

namespace shellfrac::solver {

namespace {

constexpr int nq = disc::num_area_points;

/// Width of a field in a checkpoint row.
template <class O, int P, int V>
int field_width(const Rows<O, P, V>&) {
  return Rows<O, P, V>::width;
}
int field_width(const std::vector<int>&) { return 1; }

/// Copies row r of a field to `out` (advancing it), and reads it back from `in` (advancing it).
template <class O, int P, int V>
void copy_row(const Rows<O, P, V>& f, LocalId r, double*& out) {
  out = std::copy(f.at(r), f.at(r) + Rows<O, P, V>::width, out);
}
void copy_row(const std::vector<int>& f, LocalId r, double*& out) { *out++ = double(f[r]); }
template <class O, int P, int V>
void read_row(Rows<O, P, V>& f, LocalId r, const double*& in) {
  std::copy(in, in + Rows<O, P, V>::width, f.at(r)), in += Rows<O, P, V>::width;
}
void read_row(std::vector<int>& f, LocalId r, const double*& in) { f[r] = int(*in++); }

std::string element_table(const char* field) { return std::string("element ") + field; }

/// The checkpoint scalars of a rigid body's motion: "rigid body <name> <x|v|a|force> <x|y|z>", with the values'
/// places in RigidBodyState, in that order.
template <class Body, class Visit>
void visit_body_scalars(Body& b, Visit&& visit) {
  const std::pair<const char*, decltype(&b.x)> fields[] = {{"x", &b.x}, {"v", &b.v}, {"a", &b.a}, {"force", &b.force}};
  for (const auto& [field, values] : fields)
    for (int c = 0; c < 3; ++c)
      visit("rigid body " + b.name + " " + field + " " + char('x' + c), (*values)[std::size_t(c)]);
}
std::string interface_table(const char* field) { return std::string("interface ") + field; }

/// Whether a table is one that older checkpoints do not have and whose rows then stay as the initial state made them
/// (zero): the friction account, which a checkpoint written before friction existed cannot have needed (the deck
/// had no friction then, and one with friction is new physics to the fingerprint).
bool added_since_checkpoints_began(const std::string& table) { return table == element_table("friction_dissipation"); }

}  // namespace

// One table per field, read from the state a block of rows at a time when the checkpoint is written
// (io::TableSource): the owned elements in ascending global id (row = local id), and the owned interfaces, which
// are listed by ascending gid (row k = the k-th owned interface).
io::CheckpointData state_checkpoint(const ShellState& s, const decomposition::DistributedMesh& dm, bool plastic) {
  io::CheckpointData d;
  d.scalars["time"] = s.time, d.scalars["step"] = double(s.step);
  d.scalars["num_elements"] = double(dm.num_global_elements());
  for (const auto& b : s.bodies) visit_body_scalars(b, [&](const std::string& key, double v) { d.scalars[key] = v; });
  RelaxationProgress::visit(s.relaxation, [&](const std::string& key, double v) { d.scalars[key] = v; });
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

CheckpointRows::CheckpointRows(const decomposition::DistributedMesh& dm, bool plastic) {
  for (LocalId le = 0; le < dm.num_owned(); ++le) elements_.push_back(dm.element_gid(le));
  for (const auto& f : dm.interfaces()) interfaces_.push_back(f.gid);
  SHELLFRAC_REQUIRE(std::adjacent_find(interfaces_.begin(), interfaces_.end(), std::greater_equal<>()) ==
                        interfaces_.end(),
                    "the local interfaces are not sorted by global id");  // row k = local interface k
  ShellState none;
  ShellState::visit_element_fields(none, [&](const char* name, const auto&) { of_[element_table(name)] = &elements_; });
  if (plastic) of_["plastic"] = &elements_;
  ShellState::visit_interface_fields(none, [&](const char* name, const auto&) { of_[interface_table(name)] = &interfaces_; });
}

const std::vector<GlobalId>* CheckpointRows::operator()(const std::string& table) const {
  const auto it = of_.find(table);
  return it == of_.end() ? nullptr : it->second;
}

std::vector<std::string> CheckpointRows::tables() const {
  std::vector<std::string> names;
  for (const auto& [name, ids] : of_) names.push_back(name);
  return names;
}

StateRestore::StateRestore(std::string file, const decomposition::DistributedMesh& dm, bool plastic, ShellState& s)
    : file_(std::move(file)), dm_(dm), s_(s), needed_(dm, plastic) {}

void StateRestore::header(const io::CheckpointData& d) {
  const auto scalar = [&](const char* name) {
    const auto it = d.scalars.find(name);
    SHELLFRAC_INPUT_REQUIRE(it != d.scalars.end(), file_ << ": the checkpoint has no '" << name << "'");
    return it->second;
  };
  SHELLFRAC_INPUT_REQUIRE(GlobalId(scalar("num_elements")) == dm_.num_global_elements(),
                          file_ << ": the checkpoint has " << GlobalId(scalar("num_elements")) << " elements, the mesh "
                                << dm_.num_global_elements());
  const double time = scalar("time"), step = scalar("step");
  SHELLFRAC_INPUT_REQUIRE(step >= 0 && step <= 9.0e15 && step == std::floor(step),
                          file_ << ": the checkpoint's step " << step << " is not a whole number >= 0: the file was "
                                << "not written by a shellfrac run");
  SHELLFRAC_INPUT_REQUIRE(std::isfinite(time) && time >= 0 && (time == 0) == (step == 0),
                          file_ << ": the checkpoint's time " << time << " at step " << step << " is not finite and "
                                << "positive after step 0 (0 at step 0): the file was not written by a shellfrac run");
  s_.time = time, s_.step = long(step);
  // A checkpoint from before static relaxations were checkpointed starts its relaxation's tracking anew.
  RelaxationProgress::visit(s_.relaxation, [&](const std::string& key, double& v) {
    const auto it = d.scalars.find(key);
    if (it != d.scalars.end()) v = it->second;
  });
  for (auto& b : s_.bodies)
    visit_body_scalars(b, [&](const std::string& key, double& v) {
      v = scalar(key.c_str());
      SHELLFRAC_INPUT_REQUIRE(std::isfinite(v), file_ << ": the checkpoint's '" << key << "' is " << v
                                                      << ", not finite: the file was not written by a shellfrac run");
    });
}

// The first value of a block that no run can have written, in words; "" if none. Every value finite; a director
// of unit length (the exponential map keeps it so to round-off); a mode intact, cohesive or separated.
std::string StateRestore::implausible(const std::string& name, const io::CheckpointTable& rows) const {
  std::ostringstream os;
  const int width = rows.width;
  for (std::size_t k = 0; k < rows.ids.size(); ++k) {
    const double* r = rows.values.data() + k * std::size_t(width);
    const std::string where = (name.rfind("interface ", 0) == 0 ? "interface " : "element ") +
                              std::to_string(rows.ids[k] + 1);
    for (int c = 0; c < width; ++c)
      if (!std::isfinite(r[c])) {
        os << "its table '" << name << "' holds " << r[c] << " for " << where;
        return os.str();
      }
    if (name == interface_table("mode") && r[0] != intact && r[0] != cohesive && r[0] != separated) {
      os << "its table '" << name << "' holds the mode " << r[0] << " for " << where
         << " (0 intact, 1 cohesive, 2 separated)";
      return os.str();
    }
    if (name == element_table("t"))
      for (int a = 0; a < width / 3; ++a) {
        const double length = std::sqrt(r[3 * a] * r[3 * a] + r[3 * a + 1] * r[3 * a + 1] + r[3 * a + 2] * r[3 * a + 2]);
        if (std::abs(length - 1) > 1e-6) {
          os << "its director " << a + 1 << " of " << where << " has the length " << length << ", not 1";
          return os.str();
        }
      }
  }
  return {};
}

void StateRestore::table(const std::string& name, const io::CheckpointTable& rows) {
  const std::vector<GlobalId>* ids = needed_(name);
  if (!ids) return;  // a table of no state field
  if (name != current_) {
    finish_table();
    current_ = name, restored_.insert(name), seen_.assign(ids->size(), 0);
  }
  if (invalid_.empty()) invalid_ = implausible(name, rows);  // remembered, not thrown: the read is collective
  // The row's local index: an owned element, or a local interface (both lists are sorted by global id).
  const auto local = [&](GlobalId gid) -> LocalId {
    const auto it = std::lower_bound(ids->begin(), ids->end(), gid);
    return it != ids->end() && *it == gid ? LocalId(it - ids->begin()) : -1;
  };
  const auto fill = [&](int width, const auto& read) {
    SHELLFRAC_INPUT_REQUIRE(rows.width == width, file_ << ": the checkpoint's table '" << name << "' has another width ("
                                                       << rows.width << ", expected " << width
                                                       << "; written by another version or for another model?)");
    for (std::size_t k = 0; k < rows.ids.size(); ++k) {
      const LocalId row = local(rows.ids[k]);
      if (row < 0) continue;
      seen_[std::size_t(row)] = 1;
      read(row, rows.values.data() + k * std::size_t(width));
    }
  };
  ShellState::visit_element_fields(s_, [&](const char* field, auto& f) {
    if (name == element_table(field))
      fill(field_width(f), [&](LocalId le, const double* r) { read_row(f, le, r); });
  });
  if (name == "plastic")
    fill(nq * plastic_state_values, [&](LocalId le, const double* p) {
      for (int q = 0; q < nq; ++q, p += plastic_state_values) unpack_plastic_state(p, s_.plastic[le * nq + q]);
    });
  ShellState::visit_interface_fields(s_, [&](const char* field, auto& f) {
    if (name == interface_table(field))
      fill(field_width(f), [&](LocalId i, const double* r) { read_row(f, i, r); });
  });
}

// A missing row is remembered, not thrown, while the tables are read (the read is collective); finish() reports it.
void StateRestore::finish_table() {
  if (current_.empty() || !missing_.empty()) return;
  const std::vector<GlobalId>& ids = *needed_(current_);
  const auto k = std::find(seen_.begin(), seen_.end(), 0);
  if (k == seen_.end()) return;
  std::ostringstream os;
  os << file_ << ": the checkpoint's table '" << current_ << "' has no row for "
     << (current_.rfind("interface ", 0) == 0 ? "interface " : "element ") << ids[std::size_t(k - seen_.begin())] + 1
     << " (written for another model?)";
  missing_ = os.str();
}

void StateRestore::finish() {
  finish_table();
  current_.clear();
  parallel::on_all_then_agree(
      [&] {
        SHELLFRAC_INPUT_REQUIRE(invalid_.empty(), file_ << ": " << invalid_ << ": the file was not written by a "
                                                                    "shellfrac run (its checksum only proves it unchanged)");
        SHELLFRAC_INPUT_REQUIRE(missing_.empty(), missing_);
        for (const auto& name : needed_.tables())
          SHELLFRAC_INPUT_REQUIRE(restored_.count(name) || added_since_checkpoints_began(name), file_ << ": the checkpoint's table '" << name
                                                               << "' is missing (written by another version or for "
                                                                  "another model?)");
      },
      dm_.comm());
}

}  // namespace shellfrac::solver
