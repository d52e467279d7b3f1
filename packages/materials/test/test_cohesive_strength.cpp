// Scattered cohesive strength (docs/theory.md §9.8). References:
//  * SplitMix64 (Steele, Lea & Flood, OOPSLA 2014; Vigna's reference splitmix64.c): from the state 0 the first
//    output is 0xe220a8397b1dcdaf, i.e. the finaliser of 0 + 0x9e3779b97f4a7c15;
//  * the standard normal quantiles are those of Wichura's AS 241 (Applied Statistics 37, 1988) as Python's
//    statistics.NormalDist().inv_cdf prints them: Phi^-1(0.975) = 1.9599639845400536, Phi^-1(0.001) =
//    -3.090232306167813, Phi^-1(1e-10) = -6.361340902404056, Phi^-1(0.9) = 1.2815515655446008;
//  * the normal law truncated at +-a (a = 3) has mean 0 and standard deviation
//    sqrt(1 - 2 a phi(a) / (1 - 2 Phi(-a))) = 0.9865783925581086 (Johnson, Kotz & Balakrishnan, Continuous
//    Univariate Distributions 1, §10.1);
//  * Weibull (modulus m, scale s): mean s Gamma(1 + 1/m), median s (ln 2)^(1/m), coefficient of variation
//    sqrt(Gamma(1 + 2/m) / Gamma(1 + 1/m)^2 - 1);
//  * a sample mean of N independent draws lies within 5 standard errors of the mean except with probability
//    6e-7, and the Kolmogorov-Smirnov distance of N uniform draws exceeds 1.63/sqrt(N) with probability 1 %
//    (Massey, JASA 46, 1951). The draws are fixed by the hash, so these checks are deterministic: they fail only
//    if the hash or the transforms are wrong.
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "shellfrac/core/error.hpp"
#include "shellfrac/materials/cohesive_strength.hpp"
#include "shellfrac/materials/material_params.hpp"

using namespace shellfrac::materials;

namespace {

constexpr int N = 200000;

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}

double sd_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size() - 1));
}

std::vector<double> strengths(const StrengthScatter& sc, double mean, double length, std::uint64_t seed = 7) {
  std::vector<double> v(N);
  for (int i = 0; i < N; ++i) v[i] = edge_strength(sc, mean, unit_draw(seed, std::uint64_t(i)), length);
  return v;
}

}  // namespace

TEST(UnitDraw, IsTheSplitMix64FinaliserKeyedByTheSeed) {
  // splitmix64(seed 0) = 0xe220a8397b1dcdaf, so the id equal to it gives splitmix64(0) again.
  const std::uint64_t first = 0xe220a8397b1dcdafULL;
  EXPECT_EQ(unit_draw(0, first), (double(first >> 11) + 0.5) * 0x1p-53);
}

TEST(UnitDraw, IsUniformInTheOpenIntervalAndTheSameOnEveryCall) {
  std::vector<double> u(N);
  for (int i = 0; i < N; ++i) u[i] = unit_draw(3, std::uint64_t(i));
  for (int i = 0; i < N; i += 997) EXPECT_EQ(u[i], unit_draw(3, std::uint64_t(i)));
  EXPECT_GT(*std::min_element(u.begin(), u.end()), 0.0);
  EXPECT_LT(*std::max_element(u.begin(), u.end()), 1.0);
  EXPECT_NEAR(mean_of(u), 0.5, 5 * std::sqrt(1.0 / 12 / N));
  std::vector<double> sorted = u;
  std::sort(sorted.begin(), sorted.end());
  double ks = 0;
  for (int i = 0; i < N; ++i)
    ks = std::max({ks, std::abs(sorted[i] - double(i) / N), std::abs(sorted[i] - double(i + 1) / N)});
  EXPECT_LT(ks, 1.63 / std::sqrt(double(N)));
}

TEST(UnitDraw, OtherSeedsAreUncorrelated) {
  std::vector<double> a(N), b(N);
  for (int i = 0; i < N; ++i) a[i] = unit_draw(1, std::uint64_t(i)), b[i] = unit_draw(2, std::uint64_t(i));
  double c = 0;
  const double ma = mean_of(a), mb = mean_of(b);
  for (int i = 0; i < N; ++i) c += (a[i] - ma) * (b[i] - mb);
  const double r = c / (N - 1) / (sd_of(a) * sd_of(b));
  EXPECT_LT(std::abs(r), 5 / std::sqrt(double(N)));
  EXPECT_NE(a[0], b[0]);
}

TEST(NormalQuantile, MatchesAS241) {
  EXPECT_NEAR(standard_normal_quantile(0.975), 1.9599639845400536, 1e-15 * 2);
  EXPECT_NEAR(standard_normal_quantile(0.001), -3.090232306167813, 1e-15 * 4);
  EXPECT_NEAR(standard_normal_quantile(1e-10), -6.361340902404056, 1e-15 * 7);
  EXPECT_NEAR(standard_normal_quantile(0.9), 1.2815515655446008, 1e-15 * 2);
  EXPECT_NEAR(standard_normal_quantile(0.5), 0.0, 1e-16);
}

TEST(EdgeStrength, ConstantIsTheMean) {
  EXPECT_EQ(edge_strength(StrengthScatter{}, 300e6, 0.123, 0.01), 300e6);
}

TEST(EdgeStrength, UniformSpansMeanPlusMinusSpread) {
  StrengthScatter sc{StrengthDistribution::Uniform, 0.1, 0, 0};
  const auto v = strengths(sc, 100.0, 1.0);
  EXPECT_GE(*std::min_element(v.begin(), v.end()), 90.0);
  EXPECT_LE(*std::max_element(v.begin(), v.end()), 110.0);
  EXPECT_LT(*std::min_element(v.begin(), v.end()), 90.01);
  EXPECT_GT(*std::max_element(v.begin(), v.end()), 109.99);
  const double sd = 10 / std::sqrt(3.0);  // half-width / sqrt(3)
  EXPECT_NEAR(mean_of(v), 100.0, 5 * sd / std::sqrt(double(N)));
  EXPECT_NEAR(sd_of(v), sd, 0.01 * sd);
}

TEST(EdgeStrength, NormalIsTruncatedAtThreeStandardDeviations) {
  StrengthScatter sc{StrengthDistribution::Normal, 0.1, 0, 0};
  const auto v = strengths(sc, 100.0, 1.0);
  EXPECT_GE(*std::min_element(v.begin(), v.end()), 70.0 - 1e-9);
  EXPECT_LE(*std::max_element(v.begin(), v.end()), 130.0 + 1e-9);
  const double sd = 10 * 0.9865783925581086;
  EXPECT_NEAR(mean_of(v), 100.0, 5 * sd / std::sqrt(double(N)));
  EXPECT_NEAR(sd_of(v), sd, 0.01 * sd);
  // u = 1/2 is the mean; the extremes of u map onto the truncation points.
  EXPECT_NEAR(edge_strength(sc, 100.0, 0.5, 1.0), 100.0, 1e-12);
  EXPECT_NEAR(edge_strength(sc, 100.0, 1e-300, 1.0), 70.0, 1e-9);
}

TEST(EdgeStrength, WeibullHasTheMeanAtTheReferenceLengthAndTheSizeEffect) {
  const double m = 8, mean = 100.0;
  StrengthScatter sc{StrengthDistribution::Weibull, 0, m, 0.01};
  const double g1 = std::tgamma(1 + 1 / m), g2 = std::tgamma(1 + 2 / m);
  const double cv = std::sqrt(g2 / (g1 * g1) - 1);
  const auto v = strengths(sc, mean, 0.01);
  EXPECT_NEAR(mean_of(v), mean, 5 * cv * mean / std::sqrt(double(N)));
  EXPECT_NEAR(sd_of(v) / mean_of(v), cv, 0.01 * cv);
  std::vector<double> sorted = v;
  std::nth_element(sorted.begin(), sorted.begin() + N / 2, sorted.end());
  EXPECT_NEAR(sorted[N / 2], mean / g1 * std::pow(std::log(2.0), 1 / m), 0.005 * mean);
  // Four times the length: every draw weaker by 4^(-1/m) (weakest link of four links).
  for (int i = 0; i < 1000; ++i) {
    const double u = unit_draw(7, std::uint64_t(i));
    EXPECT_NEAR(edge_strength(sc, mean, u, 0.04) / edge_strength(sc, mean, u, 0.01), std::pow(4.0, -1 / m), 1e-14);
  }
}

namespace {

Teuchos::ParameterList material(const std::string& distribution) {
  Teuchos::ParameterList pl;
  pl.set("Cohesive Strength", 300e6);
  pl.set("Fracture Energy", 10e3);
  pl.set("Strength Distribution", distribution);
  return pl;
}

MaterialParams read(Teuchos::ParameterList pl) {
  return MaterialParams::from_parameters("al", pl, {"deck.xml", "Materials->al"});
}

}  // namespace

TEST(StrengthDistributionInput, ReadsEachDistributionsOwnParameters) {
  auto w = material("Weibull");
  w.set("Weibull Modulus", 12.0), w.set("Weibull Reference Length", 0.005);
  const auto mw = read(w);
  EXPECT_EQ(mw.strength_scatter.type, StrengthDistribution::Weibull);
  EXPECT_EQ(mw.strength_scatter.weibull_modulus, 12.0);
  EXPECT_EQ(mw.strength_scatter.reference_length, 0.005);
  auto u = material("Uniform");
  u.set("Strength Spread", 0.1);
  EXPECT_EQ(read(u).strength_scatter.spread, 0.1);
  EXPECT_FALSE(read(material("Constant")).strength_scatter.scattered());
}

TEST(StrengthDistributionInput, RefusesParametersOfAnotherDistributionAndMissingOnes) {
  const auto refused = [](Teuchos::ParameterList pl, const std::string& words) {
    try {
      read(pl);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const shellfrac::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("deck.xml"), std::string::npos) << e.what();
    }
  };
  auto c = material("Constant");
  c.set("Strength Spread", 0.1);
  refused(c, "only the Uniform and Normal distributions use");
  auto u = material("Uniform");
  u.set("Weibull Modulus", 10.0);
  refused(u, "which only the Weibull distribution uses");
  refused(material("Uniform"), "must be in (0, 1)");
  auto n = material("Normal");
  n.set("Strength Spread", 0.4);
  refused(n, "must be in (0, 0.333");
  auto w = material("Weibull");
  w.set("Weibull Modulus", 10.0);
  refused(w, "no positive 'Weibull Modulus' and 'Weibull Reference Length'");
  Teuchos::ParameterList none;
  none.set("Strength Distribution", "Weibull");
  none.set("Weibull Modulus", 10.0), none.set("Weibull Reference Length", 0.01);
  refused(none, "but no 'Cohesive Strength'");
}
