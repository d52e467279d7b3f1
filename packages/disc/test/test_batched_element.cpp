// The element functions on a batch of elements in lock-step (lanes.hpp, element_lanes.hpp; docs/performance.md,
// "The batched element kernel") against the same functions on one element. Reference: exact equality. Every
// operation on a Batch is the IEEE operation of the same expression on a double on each lane (the build never
// contracts or reassociates), and an edge lifted on some lanes only is computed on all and selected per lane, so
// the energy, forces, lifting fluxes and edge tractions of each element must be bit for bit those it gets on its
// own, whichever elements share its batch and whichever lane it takes. Checked on a curved panel (boundary edges
// not lifted, so batches mix lifted and unlifted edges and same- and opposite-direction neighbours) with a random
// discontinuous state, with per-lane sections, with and without the P1 membrane projection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "dg_test_model.hpp"
#include "shellfrac/disc/element_lanes.hpp"

using namespace shellfrac;
using namespace shellfrac::disc;
using shellfrac::disc::test::Model;

namespace {

Model perturbed_panel(const StrainTreatment& strains) {
  auto m = mesh::make_cylindrical_panel(1.0, 1.2, 1.0, 4, 3, mesh::DiagonalPattern::Alternating);
  mesh::promote_to_p2(m);
  Model model(std::move(m));
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  for (double& v : model.x) v += u(rng);  // every DG copy on its own: jumps on every interface
  for (double& v : model.t) v += u(rng);
  for (std::size_t e = 0; e < model.refs.size(); ++e) {
    model.refs[e].strains = strains;  // the membrane remainder differs between lanes
    model.refs[e].membrane_remainder = strains.membrane == StrainSpace::p0 ? 0.2 + 0.1 * double(e % 3) : 0.0;
  }
  return model;
}

/// A different section for each element (Young's modulus and Poisson's ratio vary), so that lanes differ.
materials::ElasticSection section_of(GlobalId e) {
  return materials::make_elastic_section(1.0e3 * (1 + 0.1 * double(e % 5)), 0.25 + 0.01 * double(e % 3), 0.05);
}

struct OneElement {
  double energy;
  DgElementForces out;
  EdgeTractions at;
};

OneElement on_its_own(const Model& model, GlobalId e) {
  const materials::ElasticSection sc = section_of(e);
  auto law = [&sc](int, const double eps[3], const double gam[2], const double rho[3], double N[3], double Q[2],
                   double M[3]) {
    materials::elastic_resultants(sc, eps, gam, rho, N, Q, M);
    return materials::elastic_energy(sc, eps, gam, rho);
  };
  OneElement r;
  r.energy = dg_element_forces(model.refs[e], model.element_nodes(e), law, r.out, &r.at);
  return r;
}

std::vector<OneElement> in_a_batch(const Model& model, const GlobalId (&elements)[batch_width]) {
  DgElementRefOf<Batch> R;
  DgElementNodesOf<Batch> in;
  materials::ElasticSectionOf<Batch> sc;
  for (int i = 0; i < batch_width; ++i) {
    lanes::load(R, model.refs[elements[i]], i);
    lanes::load(in, model.element_nodes(elements[i]), i);
    const materials::ElasticSection s = section_of(elements[i]);
    sc.Dn.set(i, s.Dn), sc.Dm.set(i, s.Dm), sc.Ds.set(i, s.Ds), sc.nu.set(i, s.nu);
  }
  auto law = [&sc](int, const Batch eps[3], const Batch gam[2], const Batch rho[3], Batch N[3], Batch Q[2],
                   Batch M[3]) {
    materials::elastic_resultants(sc, eps, gam, rho, N, Q, M);
    return materials::elastic_energy(sc, eps, gam, rho);
  };
  DgElementForcesOf<Batch> out;
  EdgeTractionsOf<Batch> at;
  const Batch energy = dg_element_forces(R, in, law, out, &at);
  std::vector<OneElement> r(batch_width);
  for (int i = 0; i < batch_width; ++i) {
    r[i].energy = energy[i];
    lanes::store(out, r[i].out, i);
    lanes::store(at, r[i].at, i);
  }
  return r;
}

template <class S>
bool same_bits(const S& a, const S& b) {
  return std::memcmp(&a, &b, sizeof(S)) == 0;
}

void expect_batches_bitwise(const StrainTreatment& strains) {
  const Model model = perturbed_panel(strains);
  const GlobalId ne = model.mesh.num_elements();
  ASSERT_GE(ne, 4 * batch_width);
  int unlifted = 0;
  for (const auto& l : model.lift) unlifted += int(std::count(l.begin(), l.end(), false));
  ASSERT_GT(unlifted, 0) << "the mesh must have edges that are not lifted";
  std::vector<OneElement> own;
  for (GlobalId e = 0; e < ne; ++e) own.push_back(on_its_own(model, e));
  // Batches of consecutive elements, then three random shuffles: each element in several lanes and company.
  std::vector<GlobalId> order(static_cast<std::size_t>(ne));
  for (GlobalId e = 0; e < ne; ++e) order[std::size_t(e)] = e;
  std::mt19937 rng(7);
  for (int pass = 0; pass < 4; ++pass) {
    if (pass > 0) std::shuffle(order.begin(), order.end(), rng);
    for (std::size_t b = 0; b + batch_width <= order.size(); b += batch_width) {
      GlobalId members[batch_width];
      for (int i = 0; i < batch_width; ++i) members[i] = order[b + std::size_t(i)];
      const auto batch = in_a_batch(model, members);
      for (int i = 0; i < batch_width; ++i) {
        const OneElement& one = own[std::size_t(members[i])];
        EXPECT_TRUE(same_bits(batch[i].energy, one.energy)) << "element " << members[i] << " lane " << i;
        EXPECT_TRUE(same_bits(batch[i].out, one.out)) << "element " << members[i] << " lane " << i;
        EXPECT_TRUE(same_bits(batch[i].at, one.at)) << "element " << members[i] << " lane " << i;
      }
    }
  }
  // The state is not trivial: the forces and fluxes are far from zero.
  double largest = 0;
  for (const auto& o : own) largest = std::max(largest, std::abs(o.out.neighbour[0].f[2][1]));
  EXPECT_GT(largest, 1e-3);
}

}  // namespace

TEST(BatchedElement, BitwiseTheSameAsEachElementOnItsOwn) { expect_batches_bitwise({}); }

TEST(BatchedElement, BitwiseTheSameWithTheMembraneProjection) { expect_batches_bitwise({StrainSpace::p1}); }

TEST(BatchedElement, BitwiseTheSameWithStabilizedMeanMembraneAndProjectedShear) {
  expect_batches_bitwise({StrainSpace::p0, StrainSpace::p1});
}
