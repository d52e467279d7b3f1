// Crack-face contact of the extrinsic cohesive law (theory.md §9.9).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "cohesive_law_test_cases.hpp"
#include "shellfrac/materials/cohesive_law.hpp"

using namespace shellfrac::materials;
using namespace shellfrac::materials::cohesive_test;

// With crack-face contact (Fracture->Crack Face Contact, theory.md §9.9) closing is not opening, and the crack
// faces resist interpenetration. References:
// the contact energy of a penalty k_c/h per unit thickness on the gap g(z) = d + z t over the part of
// z in [-h/2, h/2] where g < 0, integrated by hand: closed over the whole thickness
// U = 1/2 k_c (d^2 + h^2 t^2 / 12); touching at one face only (g(-h/2) < 0 < g(h/2), t > 0), with
// z0 = -d/t: U = k_c/(2h) (-(d - t h/2)^3 / (3 t)) (the integral of g^2 = (g^3/(3t)) from -h/2 to z0).
TEST(CrackFaceContact, ClosedFacesStoreThePenaltyEnergyAndPushApart) {
  const double kc = 3 * 70e9 * 2e-3 / 1e-3, h = 2e-3;  // beta_x / h_e with c_x = 3, E = 70 GPa, h_e = 1 mm
  double f, m;
  // Closed everywhere, no rotation.
  EXPECT_NEAR(crack_face_contact(kc, h, -1e-6, 0.0, f, m), 0.5 * kc * 1e-12, 1e-15 * 0.5 * kc * 1e-12 * 4);
  EXPECT_NEAR(f, -kc * 1e-6, 1e-14 * kc * 1e-6);
  EXPECT_EQ(m, 0.0);
  // Closed everywhere, with a director jump: U = 1/2 kc (d^2 + h^2 t^2/12), f = kc d, m = kc h^2 t/12.
  const double d = -2e-6, t = 1e-4;  // |t| h/2 = 1e-7 < |d|
  EXPECT_NEAR(crack_face_contact(kc, h, d, t, f, m), 0.5 * kc * (d * d + h * h * t * t / 12), 1e-12 * kc * d * d);
  EXPECT_NEAR(f, kc * d, 1e-12 * kc * std::abs(d));
  EXPECT_NEAR(m, kc * h * h * t / 12, 1e-9 * kc * h * h * t / 12);
  // Apart: no energy, no force.
  EXPECT_EQ(crack_face_contact(kc, h, 1e-6, 1e-4, f, m), 0.0);
  EXPECT_EQ(f, 0.0);
  EXPECT_EQ(m, 0.0);
  EXPECT_EQ(crack_face_contact(kc, h, 0.0, 0.0, f, m), 0.0);
  // Touching at one face: the closed form above.
  const double d1 = 2e-7, t1 = 4e-4;  // g(-h/2) = 2e-7 - 4e-7 < 0 < g(h/2)
  const double lo = d1 - t1 * h / 2;
  EXPECT_NEAR(crack_face_contact(kc, h, d1, t1, f, m), kc / (2 * h) * (-lo * lo * lo / (3 * t1)),
              1e-9 * kc / (2 * h) * (-lo * lo * lo / (3 * t1)));
}

TEST(CrackFaceContact, ForcesAreTheGradientOfTheEnergy) {
  const double kc = 4.2e11, h = 2e-3;
  for (const auto& [d, t] : {std::pair{-1e-6, 0.0}, {-1e-6, 3e-3}, {2e-7, 4e-4}, {2e-7, -4e-4}, {-3e-6, -1e-2}}) {
    double f, m, f1, m1;
    crack_face_contact(kc, h, d, t, f, m);
    const double ed = 1e-6 * std::max(std::abs(d), 1e-9), et = 1e-6 * std::max(std::abs(t), 1e-6);
    const double dUdd = (crack_face_contact(kc, h, d + ed, t, f1, m1) - crack_face_contact(kc, h, d - ed, t, f1, m1)) / (2 * ed);
    const double dUdt = (crack_face_contact(kc, h, d, t + et, f1, m1) - crack_face_contact(kc, h, d, t - et, f1, m1)) / (2 * et);
    EXPECT_NEAR(f, dUdd, 1e-6 * std::abs(f) + 1e-12) << d << " " << t;
    EXPECT_NEAR(m, dUdt, 1e-6 * std::abs(m) + 1e-12) << d << " " << t;
  }
}

TEST(CrackFaceContact, ClosingNeitherOpensNorDamages) {
  CohesiveParams p = beam_blast();
  p.contact = true;
  const double nu[3] = {1, 0, 0}, zero[3] = {0, 0, 0};
  // Open to a quarter of delta_f, then press the faces through each other: delta_max stays.
  double dmax = 0, n_c[3], m_c[3];
  const double open[3] = {0.25 * p.delta_f, 0, 0};
  cohesive_tractions(p, open, zero, nu, dmax, n_c, m_c);
  EXPECT_EQ(dmax, 0.25 * p.delta_f);
  const double closed[3] = {-0.5 * p.delta_f, 0, 0};
  const CohesiveResult r = cohesive_tractions(p, closed, zero, nu, dmax, n_c, m_c);
  EXPECT_EQ(dmax, 0.25 * p.delta_f);
  EXPECT_EQ(effective_opening(p, closed, zero, nu), 0.0);
  EXPECT_EQ(n_c[0], 0.0);  // the law carries no compression; the contact does
  EXPECT_EQ(r.stored, 0.0);
  // A compressive edge force does not count towards nucleation; shear under compression does.
  const double press[3] = {-2 * p.S0, 0, 0}, shear_press[3] = {-2 * p.S0, 0.5 * p.S0, 0};
  EXPECT_EQ(equivalent_traction(p, press, zero, nu), 0.0);
  EXPECT_NEAR(equivalent_traction(p, shear_press, zero, nu), 0.5 * p.S0, 1e-9 * p.S0);
  // Without contact (the default, the paper's law) a closing jump counts as opening.
  p.contact = false;
  double dmax2 = 0;
  cohesive_tractions(p, closed, zero, nu, dmax2, n_c, m_c);
  EXPECT_EQ(dmax2, 0.5 * p.delta_f);
  EXPECT_EQ(equivalent_traction(p, press, zero, nu), 2 * p.S0);
}
