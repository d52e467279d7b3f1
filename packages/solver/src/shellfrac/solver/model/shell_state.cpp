#include "shellfrac/solver/model/shell_state.hpp"

#include <algorithm>

namespace shellfrac::solver {

namespace {
template <class O, int P, int V>
double field_bytes(const Rows<O, P, V>& f) {
  return sizeof(double) * double(f.size());
}
double field_bytes(const std::vector<int>& f) { return sizeof(int) * double(f.size()); }
}  // namespace

double ShellState::bytes() const {
  double total = sizeof(materials::PlasticState) * double(plastic.size());
  visit_element_fields(*this, [&](const char*, const auto& f) { total += field_bytes(f); });
  visit_interface_fields(*this, [&](const char*, const auto& f) { total += field_bytes(f); });
  return total;
}

void pack_plastic_state(const materials::PlasticState& s, double out[plastic_state_values]) {
  std::copy(s.eps_p, s.eps_p + 3, out), std::copy(s.rho_p, s.rho_p + 3, out + 3), out[6] = s.alpha;
  std::copy(s.gam_p, s.gam_p + 2, out + 7);
}

void unpack_plastic_state(const double in[plastic_state_values], materials::PlasticState& s) {
  std::copy(in, in + 3, s.eps_p), std::copy(in + 3, in + 6, s.rho_p), s.alpha = in[6];
  std::copy(in + 7, in + 9, s.gam_p);
}

}  // namespace shellfrac::solver
