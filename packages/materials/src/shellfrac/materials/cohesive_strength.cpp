#include "shellfrac/materials/cohesive_strength.hpp"

#include <cmath>

#include "shellfrac/core/error.hpp"

namespace shellfrac::materials {

namespace {

std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double standard_normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

}  // namespace

std::string distribution_name(StrengthDistribution d) {
  switch (d) {
    case StrengthDistribution::Constant: return "Constant";
    case StrengthDistribution::Uniform: return "Uniform";
    case StrengthDistribution::Normal: return "Normal";
    case StrengthDistribution::Weibull: return "Weibull";
  }
  return "?";
}

StrengthDistribution distribution_of(const std::string& name) {
  for (auto d : {StrengthDistribution::Constant, StrengthDistribution::Uniform, StrengthDistribution::Normal,
                 StrengthDistribution::Weibull})
    if (distribution_name(d) == name) return d;
  SHELLFRAC_REQUIRE(false, "unknown strength distribution '" << name << "'");
  return StrengthDistribution::Constant;
}

double unit_draw(std::uint64_t seed, std::uint64_t id) {
  const std::uint64_t bits = splitmix64(splitmix64(seed) ^ id);
  return (double(bits >> 11) + 0.5) * 0x1p-53;
}

double standard_normal_quantile(double p) {
  // Acklam's coefficients (central region |p - 1/2| <= 0.475, tails beyond).
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01,  -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double plow = 0.02425;
  double x;
  if (p < plow) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else if (p <= 1 - plow) {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  } else {
    const double q = std::sqrt(-2 * std::log1p(-p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  // One Halley step on Phi(x) - p (Acklam's refinement).
  const double e = standard_normal_cdf(x) - p;
  const double u = e * std::sqrt(2 * M_PI) * std::exp(0.5 * x * x);
  return x - u / (1 + 0.5 * x * u);
}

double edge_strength(const StrengthScatter& sc, double mean, double u, double edge_length) {
  switch (sc.type) {
    case StrengthDistribution::Constant:
      return mean;
    case StrengthDistribution::Uniform:
      return mean * (1 + sc.spread * (2 * u - 1));
    case StrengthDistribution::Normal: {
      const double tail = standard_normal_cdf(-normal_truncation);
      return mean * (1 + sc.spread * standard_normal_quantile(tail + u * (1 - 2 * tail)));
    }
    case StrengthDistribution::Weibull: {
      const double inv_m = 1 / sc.weibull_modulus;
      const double scale = mean / std::tgamma(1 + inv_m);
      return scale * std::pow(sc.reference_length / edge_length, inv_m) * std::pow(-std::log1p(-u), inv_m);
    }
  }
  return mean;
}

}  // namespace shellfrac::materials
