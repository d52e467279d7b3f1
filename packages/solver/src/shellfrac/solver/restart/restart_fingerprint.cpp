#include "shellfrac/solver/restart/restart_fingerprint.hpp"

#include <mpi.h>

#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "shellfrac/core/digest.hpp"
#include "shellfrac/core/error.hpp"
#include "shellfrac/decomposition/distributed_mesh.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/input/deck.hpp"

namespace shellfrac::solver {

namespace {

/// Parameters that may change on a restart, by path below the deck's root.
const std::set<std::string> free_on_restart = {
    "Mesh->File",
    "Time Integration->End Time",
    "Time Integration->Output Interval",
    "Time Integration->History Interval",
    "Time Integration->History Time Interval",
    "Time Integration->Exact Output Times",
    "Time Integration->Time Step",
    "Time Integration->Safety Factor",
    "Time Integration->Force Time Step",
    "Time Integration->Relaxation Tolerance",
    "Time Integration->Maximum Steps",
};
/// Sublists that may change as a whole (results, checkpoints, the partition; initial conditions act at t = 0 only).
const std::set<std::string> free_sublists = {"Output", "Checkpoint", "Partitioning", "Initial Conditions"};

std::string value_text(const Teuchos::ParameterEntry& e) {
  std::ostringstream os;
  os.precision(17);
  if (e.isType<double>()) {
    os << e.getValue<double>(static_cast<double*>(nullptr));
  } else if (e.isType<Teuchos::Array<double>>()) {
    const auto& a = e.getValue<Teuchos::Array<double>>(static_cast<Teuchos::Array<double>*>(nullptr));
    os << "{";
    for (long i = 0; i < static_cast<long>(a.size()); ++i) os << (i ? ", " : "") << a[i];
    os << "}";
  } else {
    e.leftshift(os, false);
  }
  return os.str();
}

void physics_lines(const Teuchos::ParameterList& pl, const std::string& prefix,
                   std::map<std::string, std::string>& out) {
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = prefix.empty() ? name : prefix + "->" + name;
    if (prefix.empty() && free_sublists.count(name)) continue;
    const auto& entry = pl.entry(it);
    if (entry.isList())
      physics_lines(Teuchos::getValue<Teuchos::ParameterList>(entry), path, out);
    else if (!free_on_restart.count(path))
      out[path] = value_text(entry);
  }
}

std::map<std::string, std::string> parse_lines(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream is(text);
  for (std::string line; std::getline(is, line);) {
    const auto eq = line.find(" = ");
    if (eq != std::string::npos) out[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return out;
}

std::string mesh_digest(const decomposition::DistributedMesh& dm) {
  std::uint64_t lanes[2] = {0, 0}, sums[2];
  for (LocalId le = 0; le < dm.num_owned(); ++le) {
    Digest d;
    d.add(std::int64_t(dm.element_gid(le)));
    d.add(std::int64_t(dm.element_block(le)));
    for (int a = 0; a < dm.nodes_per_element(); ++a) {
      d.add(std::int64_t(dm.mesh_node(le, a)));
      for (int k = 0; k < 3; ++k) d.add(dm.node_coords(le, a)[k]);
    }
    lanes[0] += d.lane(0), lanes[1] += d.lane(1);  // modulo 2^64: the order of the elements does not matter
  }
  SHELLFRAC_REQUIRE(MPI_Allreduce(lanes, sums, 2, MPI_UINT64_T, MPI_SUM, dm.comm()) == MPI_SUCCESS,
                    "MPI_Allreduce of the mesh digest failed");
  return Digest::from_lanes(sums[0], sums[1]).hex() + " (" + std::to_string(dm.num_global_elements()) + " elements)";
}

/// A digest of the mesh's named sets (node, side and element sets: names, ids and members, in file order): the
/// supports, loads and probes that name them act on these entities. The same on every rank (the whole mesh).
std::string sets_digest(const mesh::SerialMesh& m) {
  Digest d;
  for (const auto& s : m.node_sets) {
    d.add(std::string("node set ") + s.name), d.add(std::int64_t(s.id));
    for (const GlobalId n : s.nodes) d.add(std::int64_t(n));
  }
  for (const auto& s : m.side_sets) {
    d.add(std::string("side set ") + s.name), d.add(std::int64_t(s.id));
    for (std::size_t i = 0; i < s.elements.size(); ++i)
      d.add(std::int64_t(s.elements[i])), d.add(std::int64_t(s.local_edges[i]));
  }
  for (const auto& s : m.element_sets) {
    d.add(std::string("element set ") + s.name), d.add(std::int64_t(s.id));
    for (const GlobalId e : s.elements) d.add(std::int64_t(e));
  }
  return d.hex() + " (" + std::to_string(m.node_sets.size()) + " node sets, " + std::to_string(m.side_sets.size()) +
         " side sets, " + std::to_string(m.element_sets.size()) + " element sets)";
}

/// Sublists whose entries the user names (their valid parameters show one example entry).
const char* const named_lists[] = {"Blocks->", "Materials->", "Boundary Conditions->", "Initial Conditions->",
                                   "Loads->", "Regions->", "Contact->Rigid Walls->"};

/// Whether `path`, absent from a checkpoint's fingerprint, is a parameter this version added at its default value:
/// the run that wrote the checkpoint had the same physics. Inside a user-named entry (a material, a wall) only if
/// the checkpoint has that entry: a whole new entry is new physics.
bool added_at_default(const std::string& path, const std::string& value, const std::map<std::string, std::string>& ck) {
  static const auto valid = Deck::valid_parameters();
  std::string lookup = path;
  for (const char* list : named_lists) {
    const std::string prefix(list);
    if (path.compare(0, prefix.size(), prefix) != 0) continue;
    const auto arrow = path.find("->", prefix.size());
    if (arrow == std::string::npos) return false;
    const std::string entry = path.substr(0, arrow + 2);  // e.g. "Materials->al->"
    const auto it = ck.lower_bound(entry);
    if (it == ck.end() || it->first.compare(0, entry.size(), entry) != 0) return false;
    const Teuchos::ParameterList* example = &valid->sublist(prefix.substr(0, prefix.size() - 2));
    if (prefix == "Contact->Rigid Walls->") example = &valid->sublist("Contact").sublist("Rigid Walls");
    if (example->begin() == example->end()) return false;
    lookup = prefix + example->name(example->begin()) + path.substr(arrow);
  }
  const Teuchos::ParameterList* pl = valid.get();
  for (std::size_t start = 0;;) {
    const auto arrow = lookup.find("->", start);
    const std::string name = lookup.substr(start, arrow == std::string::npos ? std::string::npos : arrow - start);
    const Teuchos::ParameterEntry* e = pl->getEntryPtr(name);
    if (e == nullptr) return false;
    if (arrow == std::string::npos) return !e->isList() && value_text(*e) == value;
    if (!e->isList()) return false;
    pl = &Teuchos::getValue<Teuchos::ParameterList>(*e);
    start = arrow + 2;
  }
}

/// "'path' = deck value (checkpoint: value)" for every difference, at most `limit` of them.
std::string differences(const std::map<std::string, std::string>& deck, const std::map<std::string, std::string>& ck) {
  std::ostringstream os;
  int n = 0;
  const auto add = [&](const std::string& s) { os << (n++ ? "; " : "") << s; };
  for (const auto& [path, value] : deck) {
    const auto it = ck.find(path);
    if (it == ck.end()) {
      if (!added_at_default(path, value, ck)) add("'" + path + "' = " + value + " is new");
    } else if (it->second != value)
      add("'" + path + "' = " + value + " (checkpoint: " + it->second + ")");
  }
  for (const auto& [path, value] : ck)
    if (!deck.count(path)) add("'" + path + "' = " + value + " is gone");
  return os.str();
}

}  // namespace

RestartFingerprint RestartFingerprint::of(const Deck& deck, const decomposition::DistributedMesh& dm,
                                          const mesh::SerialMesh& whole) {
  RestartFingerprint f;
  f.mesh = mesh_digest(dm);
  f.sets = sets_digest(whole);
  std::map<std::string, std::string> lines;
  if (!deck.expanded.is_null()) physics_lines(*deck.expanded, "", lines);
  for (const auto& [path, value] : lines) f.physics += path + " = " + value + "\n";
  return f;
}

void RestartFingerprint::stamp(io::CheckpointData& data) const {
  data.strings["fingerprint mesh"] = mesh;
  data.strings["fingerprint physics"] = physics;
  data.strings["fingerprint sets"] = sets;
}

void RestartFingerprint::check(const io::CheckpointData& data, const std::string& file,
                               bool allow_physics_change) const {
  const auto get = [&](const char* key) {
    const auto it = data.strings.find(key);
    SHELLFRAC_INPUT_REQUIRE(it != data.strings.end(), file << ": the checkpoint has no '" << key << "'");
    return it->second;
  };
  SHELLFRAC_INPUT_REQUIRE(get("fingerprint mesh") == mesh,
                          file << ": the checkpoint was written for another mesh (digest " << get("fingerprint mesh")
                               << ", this deck's mesh " << mesh
                               << "): coordinates, connectivity, element blocks or refinement differ; a checkpoint "
                                  "restarts only on the mesh it was written for");
  // Checkpoints written before the sets were part of the fingerprint do not record them.
  const auto recorded_sets = data.strings.find("fingerprint sets");
  SHELLFRAC_INPUT_REQUIRE(recorded_sets == data.strings.end() || recorded_sets->second == sets,
                          file << ": the checkpoint was written for a mesh with other node, side or element sets ("
                               << recorded_sets->second << "; this deck's mesh: " << sets
                               << "): the supports, loads and probes that name them would act on other entities; a "
                                  "checkpoint restarts only on the mesh it was written for");
  if (allow_physics_change) return;
  get("fingerprint physics");
  const std::string diff = physics_differences(data);
  SHELLFRAC_INPUT_REQUIRE(diff.empty(),
                          file << ": the deck's physics differ from the run that wrote the checkpoint: " << diff
                               << ". To continue with changed physics on purpose, add --allow-physics-change (End "
                                  "Time, Output Interval, History Interval, History Time Interval, Exact Output Times, Time Step, Safety Factor and the Output, "
                                  "Checkpoint, Partitioning and Initial Conditions sublists may change freely)");
}

std::string RestartFingerprint::physics_differences(const io::CheckpointData& data) const {
  const auto recorded = data.strings.find("fingerprint physics");
  if (recorded == data.strings.end()) return "";
  return differences(parse_lines(physics), parse_lines(recorded->second));
}

}  // namespace shellfrac::solver
