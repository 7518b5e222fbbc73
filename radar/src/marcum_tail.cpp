// log Marcum Q_1, the cell under test's conditional tail: its series and saddlepoint approximation.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "fogradar/radar/cfar_design.hpp"

namespace fogradar::radar {

namespace {

// Below this lambda log_cut_tail sums the exact series, from it on it takes the saddlepoint
// approximation (relative error below 3e-5 there: test_cfar_correlated.cpp against the series).
constexpr double kSaddlepointLambda = 10.0;

// log P(|Y0|^2 > y s^2) for Y0 ~ CN(mu, s^2), lambda = |mu|^2 / s^2 < kSaddlepointLambda: log
// Marcum Q_1(sqrt(2 lambda), sqrt(2 y)) = log e^{-lambda-y} sum_j a_j B_j, a_j = lambda^j/j!, B_j =
// sum_{i<=j} y^i/i! (Poisson mixture of Gamma(j+1) tails, all terms positive), summed in linear
// space with B and the sum rescaled together. The term ratio a_{k+1} B_{k+1} / (a_k B_k) is at most
// rho_k = lambda (k + 1 + y) / (k + 1)^2 (B_{k+1} / B_k <= 1 + y / (k + 1)), decreasing in k, so
// once rho_j < 1 the rest of the sum is below term_j rho_j / (1 - rho_j). 1/j for the series'
// terms, computed by the compiler (a multiplication instead of a division per term).
constexpr std::array<double, 1024> kInverses = [] {
  std::array<double, 1024> inverses{};
  for (std::size_t j = 1; j < inverses.size(); ++j) inverses[j] = 1.0 / static_cast<double>(j);
  return inverses;
}();

double log_cut_tail_series(double lambda, double y) {
  // The series' first-order term lambda (1 + y) e^-y below the rounding of e^-y: a cell under test
  // uncorrelated with its reference cells (lambda at rounding level, ~1e-30).
  if (lambda * (1.0 + y) < 1e-17) return -y;
  // Q_1(a, b) <= exp(-(b - a)^2 / 2) for b > a (Simon & Alouini 2000): below e^-1500 a sample
  // weighs nothing against any design P_fa (>= e^-745, sample weights <= 4); the bound stays
  // decreasing in y.
  if (y > lambda) {
    const double gap = std::sqrt(y) - std::sqrt(lambda);
    if (gap * gap > 1500.0) return -gap * gap;
  }
  constexpr double kRescale = 1e-250;
  double a = 1.0, b = 1.0, big_b = 1.0, sum = 1.0, log_scale = 0.0;
  for (std::size_t k = 1;; ++k) {
    const double j = static_cast<double>(k);
    const double inverse = k < kInverses.size() ? kInverses[k] : 1.0 / j;
    a *= lambda * inverse;
    b *= y * inverse;
    big_b += b;
    sum += a * big_b;
    if (big_b > 1e250) {
      b *= kRescale;
      big_b *= kRescale;
      sum *= kRescale;
      log_scale -= std::log(kRescale);
    }
    const double rho = lambda * (j + 1.0 + y) / ((j + 1.0) * (j + 1.0));
    if (rho < 1.0 && a * big_b * rho / (1.0 - rho) <= 1e-17 * sum) break;
  }
  return -lambda - y + log_scale + std::log(sum);
}

// Mills' ratio (1 - Phi(w)) / phi(w) for w >= 0: from erfc below w = 25, from there by its
// asymptotic series (1/w) sum_k (-1)^k (2k - 1)!! / w^{2k} (Abramowitz & Stegun 26.2.12), whose
// terms fall below 1e-17 of the first by k = 9 at w >= 25.
double mills_ratio(double w) {
  if (w < 25.0) {
    return 0.5 * std::erfc(w / std::numbers::sqrt2) * std::exp(0.5 * w * w) *
           std::sqrt(2.0 * std::numbers::pi);
  }
  const double z = 1.0 / (w * w);
  double series = 1.0;
  for (int k = 9; k >= 1; --k) series = 1.0 - static_cast<double>(2 * k - 1) * z * series;
  return series / w;
}

// The same tail for lambda >= kSaddlepointLambda. X = |Y0|^2 / s^2 = |sqrt(lambda) + W|^2, W ~
// CN(0, 1), has the cumulant generating function K(t) = lambda t / (1 - t) - log(1 - t), t < 1;
// with u = 1 / (1 - t): K' = lambda u^2 + u, K'' = 2 lambda u^3 + u^2, K''' = 6 lambda u^4 + 2 u^3,
// K'''' = 24 lambda u^5 + 6 u^4, and the saddlepoint K'(t) = y is u = 2 y / (1 + sqrt(1 + 4 lambda
// y)). Second-order Lugannani-Rice (Lugannani & Rice 1980, Adv. Appl. Prob. 12, 475-490; Daniels
// 1987, Int. Stat. Rev. 55, 37-48):
//   P(X > y) = 1 - Phi(w) + phi(w) [1/v - 1/w + (k4/8 - 5 k3^2/24)/v - 1/v^3 - k3/(2 v^2) + 1/w^3],
// w = sign(t) sqrt(2 (t y - K(t))), v = t sqrt(K''), k3 = K'''/K''^1.5, k4 = K''''/K''^2. The
// bracket is a difference of terms ~ 1/w^3 near the mean, so for |w| < 1 it is formed in long
// double (beyond, the double result agrees with it to 1e-10 for lambda = 10-1e7), and for
// |w| < 0.01 log P is interpolated (Lagrange's cubic in y) from the points w ~ -+0.015, -+0.03.
template <class Real>
double log_cut_tail_saddlepoint_at(double lambda_d, double y_d, Real& w) {
  const Real lambda = lambda_d, y = y_d;
  const Real u = Real{2} * y / (Real{1} + std::sqrt(Real{1} + Real{4} * lambda * y));
  const Real t = Real{1} - Real{1} / u;
  // t y - K(t), K(t) = lambda (u - 1) + log u = lambda t u - log1p(-t)
  const Real exponent = t * y - lambda * t * u + std::log1p(-t);
  w = std::copysign(std::sqrt(std::max(Real{0}, Real{2} * exponent)), t);
  const Real u2 = u * u;
  const Real k2 = Real{2} * lambda * u2 * u + u2;
  const Real k3 = (Real{6} * lambda * u2 * u2 + Real{2} * u2 * u) / (k2 * std::sqrt(k2));
  const Real k4 = (Real{24} * lambda * u2 * u2 * u + Real{6} * u2 * u2) / (k2 * k2);
  const Real v = t * std::sqrt(k2);
  const double bracket = static_cast<double>(
      Real{1} / v - Real{1} / w + (k4 / Real{8} - Real{5} * k3 * k3 / Real{24}) / v -
      Real{1} / (v * v * v) - k3 / (Real{2} * v * v) + Real{1} / (w * w * w));
  const double wd = static_cast<double>(w);
  const double log_phi = -0.5 * wd * wd - 0.5 * std::log(2.0 * std::numbers::pi);
  if (wd > 0.0) return log_phi + std::log(mills_ratio(wd) + bracket);
  return std::log(0.5 * std::erfc(wd / std::numbers::sqrt2) + std::exp(log_phi) * bracket);
}

double log_cut_tail_saddlepoint(double lambda, double y) {
  double w_double = 0.0;
  const double fast = log_cut_tail_saddlepoint_at(lambda, y, w_double);
  if (std::abs(w_double) >= 1.0) return fast;
  long double w = 0.0L;
  const double value = log_cut_tail_saddlepoint_at(lambda, y, w);
  if (std::abs(w) >= 0.01L) return value;
  const double mean = lambda + 1.0;
  const double sd = std::sqrt(2.0 * lambda + 1.0);
  constexpr std::array<double, 4> kNodes = {-0.03, -0.015, 0.015, 0.03};
  const double c = (y - mean) / sd;
  double result = 0.0;
  for (std::size_t k = 0; k < kNodes.size(); ++k) {
    double basis = 1.0;
    for (std::size_t m = 0; m < kNodes.size(); ++m) {
      if (m != k) basis *= (c - kNodes[m]) / (kNodes[k] - kNodes[m]);
    }
    long double node_w = 0.0L;
    result += basis * log_cut_tail_saddlepoint_at(lambda, mean + kNodes[k] * sd, node_w);
  }
  return result;
}

}  // namespace

// log P(|Y0|^2 > y s^2) for Y0 ~ CN(mu, s^2), lambda = |mu|^2 / s^2 (Marcum Q_1(sqrt(2 lambda),
// sqrt(2 y))): the series below kSaddlepointLambda, the saddlepoint approximation from it on.
double log_marcum_q1_tail(double lambda, double y) {
  return lambda < kSaddlepointLambda ? log_cut_tail_series(lambda, y)
                                     : log_cut_tail_saddlepoint(lambda, y);
}

}  // namespace fogradar::radar
