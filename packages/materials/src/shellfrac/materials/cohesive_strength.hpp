#pragma once
/// \file cohesive_strength.hpp
/// Scattered cohesive strength (docs/theory.md §9.8): each breakable interface draws its own strength from a
/// distribution of its material, through a counter-based hash of (seed, interface id). The draw of an interface
/// depends on nothing else: not on the loop order, the partition, the rank or thread count, or a restart.
#include <cstdint>
#include <string>

namespace shellfrac::materials {

/// The distributions of `Materials-><name>->Strength Distribution`. `Cohesive Strength` is the mean strength
/// (for Weibull: the mean of an edge of the reference length).
enum class StrengthDistribution { Constant, Uniform, Normal, Weibull };

/// Normal strengths are drawn from the normal law truncated at this many standard deviations from the mean.
constexpr double normal_truncation = 3.0;

struct StrengthScatter {
  StrengthDistribution type = StrengthDistribution::Constant;
  double spread = 0;            ///< Uniform: half-width / mean; Normal: standard deviation / mean (before truncation)
  double weibull_modulus = 0;   ///< Weibull: m (> 0)
  double reference_length = 0;  ///< Weibull: L_ref, the edge length whose mean strength is `Cohesive Strength`
  bool scattered() const { return type != StrengthDistribution::Constant; }
};

/// The drawn strengths of a mesh's breakable interfaces, over all ranks.
struct StrengthSummary {
  std::int64_t interfaces = 0;        ///< breakable interfaces
  std::int64_t scattered = 0;         ///< ... of which drew from a distribution other than Constant
  double min = 0, mean = 0, max = 0;  ///< of their strengths sigma_c (mean: exact sum over the interfaces)
};

/// The distribution's name as the deck spells it.
std::string distribution_name(StrengthDistribution d);
/// StrengthDistribution of a deck name (one of the four; a precondition the deck's validator checks).
StrengthDistribution distribution_of(const std::string& name);

/// A number uniformly distributed in the open interval (0, 1), a function of (seed, id) only: the SplitMix64
/// finaliser keyed by the seed, applied to the id (Steele, Lea & Flood, OOPSLA 2014), top 53 bits, centred on
/// its cell of width 2^-53 (so never 0 or 1).
double unit_draw(std::uint64_t seed, std::uint64_t id);

/// The standard normal quantile Phi^-1(p), 0 < p < 1: Acklam's rational approximation refined by one Halley step
/// on erfc (relative error below 1e-15 in double precision).
double standard_normal_quantile(double p);

/// The strength of an edge of reference length `edge_length` for the uniform draw u in (0, 1), `mean` being the
/// material's Cohesive Strength (docs/theory.md §9.8):
///   Constant  mean
///   Uniform   mean (1 + s (2u - 1))
///   Normal    mean (1 + s z),  z = Phi^-1(Phi(-a) + u (1 - 2 Phi(-a))),  a = normal_truncation
///   Weibull   mean / Gamma(1 + 1/m) (L_ref / L)^(1/m) (-ln(1 - u))^(1/m)
/// The Weibull strength is that of a weakest link of length L whose probability of failure below sigma is
/// 1 - exp(-(L/L_ref) (sigma/sigma_0)^m): a finer mesh has more, stronger edges along the same crack path.
double edge_strength(const StrengthScatter& scatter, double mean, double u, double edge_length);

}  // namespace shellfrac::materials
