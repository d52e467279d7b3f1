#pragma once
/// \file shell_model.hpp
/// The discrete DG shell on one rank, built once from the distributed mesh and the deck: reference geometry
/// and element data (docs/theory.md §1, §5.3), the point-law parameters of each element, the lumped masses and
/// rotary inertias (§6), the interface elements with their penalty constants (§5.5) and the stable time step
/// (§8). Only the lifted-edge flags change afterwards: activation of an edge switches its lifting off (§9.6).
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "shellfrac/disc/dg_element.hpp"
#include "shellfrac/disc/dg_interface.hpp"
#include "shellfrac/materials/elastic_resultant.hpp"
#include "shellfrac/materials/material_params.hpp"
#include "shellfrac/materials/resultant_plasticity.hpp"
#include "shellfrac/mesh/serial_mesh.hpp"
#include "shellfrac/solver/input/dynamics_params.hpp"
#include "shellfrac/solver/model/mass_scaling.hpp"
#include "shellfrac/solver/model/shell_state.hpp"
#include "shellfrac/solver/model/time_step_survey.hpp"

namespace shellfrac::decomposition {
class DistributedMesh;
}

namespace shellfrac::solver {

/// What the model takes of the deck: the discretization constants, the time integration's rotary inertia and
/// mass scaling, and the files its messages name.
struct ModelParams {
  std::string deck_file;   ///< named in messages about deck parameters
  std::string mesh_label;  ///< named in messages about the mesh: its file, or the deck when the deck generates it
  DiscretizationParams discretization;
  TimeParams time;
  mesh::FileIds element_ids;  ///< the mesh file's element ids, for messages (empty: the positions)
};

/// The section of a mesh block: its thickness and its material, as the deck gives them.
struct BlockSection {
  double thickness = 0;
  materials::MaterialParams material;
};

/// The section of every block of the mesh, by block index, from the deck's Blocks and Materials. Every block has
/// an entry in `blocks` (checked when the model is set up).
std::vector<BlockSection> block_sections(const std::map<std::string, materials::BlockParams>& blocks,
                                         const std::map<std::string, materials::MaterialParams>& materials,
                                         const std::vector<std::string>& block_names);

/// An interface of an element and the element's side of it (0 = minus, 1 = plus).
struct IncidentInterface {
  int interface;
  int side;
};

/// The interfaces of each owned element, in increasing interface order, stored flat: element le's are
/// entries[offset[le]] .. entries[offset[le + 1] - 1].
struct IncidentInterfaces {
  std::vector<int> offset{0};
  std::vector<IncidentInterface> entries;
  struct Range {
    const IncidentInterface *first, *last;
    const IncidentInterface* begin() const { return first; }
    const IncidentInterface* end() const { return last; }
  };
  Range of(LocalId le) const { return {entries.data() + offset[le], entries.data() + offset[le + 1]}; }
};

/// The discrete DG shell on one rank.
struct ShellModel {
  /// Builds every reference quantity; the stable step is the global minimum (collective).
  ShellModel(const decomposition::DistributedMesh& dm, const ModelParams& params,
             const std::vector<BlockSection>& sections);

  const decomposition::DistributedMesh& dm;
  LocalId owned = 0, overlap = 0;
  std::vector<BlockSection> sections;        ///< by block index
  PositionRowsView X;                        ///< reference positions (overlap; the distributed mesh's, not copied)
  std::vector<disc::DgElementRef> element_refs;  ///< owned elements
  std::vector<std::array<bool, 3>> lifted;   ///< owned: the jump over edge k is lifted (an intact manifold edge)
  // The point laws' section data, by block index (an element's block: dm.element_block(le)).
  std::vector<materials::ElasticSection> block_elastic;
  std::vector<materials::PlasticSection> block_plastic;  ///< used where block_is_plastic
  std::vector<char> block_is_plastic;        ///< the block's material is Resultant Plasticity
  bool any_plastic = false;                  ///< some element of the mesh is plastic (the same on every rank)
  PositionNodeScalars mass;                  ///< HRZ lumped mass per position node (owned)
  DirectorNodeScalars inertia;               ///< lumped rotary inertia per director node (owned)
  double stable_dt = 0;                      ///< 2 / max omega over every element (before the safety factor)
  MassScaling mass_scaling;                  ///< what Target Time Step added (nothing without it)
  TimeStepSurvey time_step_survey;           ///< the smallest and the median element step (before scaling)
  // Interfaces: every local one (dm.interfaces() order).
  std::vector<disc::DgInterfaceRef> interface_refs;  ///< the minus side's reference edge data
  std::vector<double> interface_beta_x, interface_beta_t;  ///< penalty constants (mean of the two sides)
  /// Per owned element: its interfaces (local interface, side), in increasing interface id.
  IncidentInterfaces incident;
  /// Per owned element: its id in the mesh file (mesh::FileIds); empty when the file numbers by position.
  std::vector<std::int64_t> owned_file_ids;
  bool file_ids = false;  ///< the mesh file has its own element ids (the same on every rank)

  /// Element `gid` as messages name it: its id in the mesh file, and its number in the results when the two
  /// differ (mesh::element_label). The same on every rank; collective when the file has its own ids.
  std::string element_name(GlobalId gid) const;

  /// The elastic section of owned element le, and whether its material is plastic.
  const materials::ElasticSection& elastic(LocalId le) const;
  bool is_plastic(LocalId le) const;
  /// Kinetic energy of owned element le: 1/2 m |v|^2 over its position nodes plus 1/2 I |T-dot|^2 over its
  /// director nodes (the history's kinetic_energy, docs/theory.md §11).
  double element_kinetic(const ShellState& s, LocalId le) const {
    double k = 0;
    for (int A = 0; A < position_nodes; ++A)
      for (int c = 0; c < 3; ++c) k += 0.5 * *mass.at(le, A) * s.v.at(le, A)[c] * s.v.at(le, A)[c];
    for (int b = 0; b < director_nodes; ++b)
      for (int c = 0; c < 2; ++c)
        k += 0.5 * *inertia.at(le, b) * s.director_rate.at(le, b)[c] * s.director_rate.at(le, b)[c];
    return k;
  }
  /// Rotary kinetic energy 1/2 I |T-dot|^2 of director node b of owned element le.
  double rotary_kinetic(const ShellState& s, LocalId le, int b) const {
    const double* T = s.director_rate.at(le, b);
    return 0.5 * *inertia.at(le, b) * (T[0] * T[0] + T[1] * T[1]);
  }
  /// Bytes of reference data held on this rank.
  double bytes() const;

 private:
  /// The interface elements: reference edge data, penalty constants, each element's incident interfaces.
  void build_interfaces(const DiscretizationParams& discretization);
};

}  // namespace shellfrac::solver
