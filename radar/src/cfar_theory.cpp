// The CFAR's false-alarm theory: P_fa of CA, GO, SO and OS against the threshold factor, and the
// factor for a design P_fa.
#include <cmath>

#include "fogradar/core/error.hpp"
#include "fogradar/radar/cfar.hpp"
#include "solve_factor.hpp"

namespace fogradar::radar {

namespace {

// log Pfa of SO-CFAR, n cells per side, t = alpha / n (Gandhi & Kassam 1988):
//   Pfa_SO = 2 sum_{k=0}^{n-1} C(n-1+k, k) (2+t)^-(n+k).
double log_pfa_so(double n, double t) {
  const double log_base = std::log(2.0 + t);
  double log_term = -n * log_base;  // k = 0
  LogSum sum;
  for (double k = 0.0; k < n; k += 1.0) {
    sum.add(log_term);
    log_term += std::log((n + k) / (k + 1.0)) - log_base;
  }
  return std::log(2.0) + sum.log();
}

// log Pfa of GO-CFAR. The published form 2 (1+t)^-n - Pfa_SO cancels badly when Pfa is small
// (both terms ~ t^-n, the difference ~ t^-2n). Equivalent positive series, from
// Pfa_GO = E[exp(-t max(X, Y))] with X, Y ~ Gamma(n, 1) and P(max < m) = F(m)^2:
//   Pfa_GO = 2 sum_{j>=n} C(n-1+j, j) (2+t)^-(n+j).
// The term ratio r_j = (n+j) / ((j+1)(2+t)) is < 1 and decreasing for j >= n, so the tail after
// term j is bounded by term_j r_j / (1 - r_j).
double log_pfa_go(double n, double t) {
  const double log_base = std::log(2.0 + t);
  double log_term =
      std::lgamma(2.0 * n) - std::lgamma(n) - std::lgamma(n + 1.0) - 2.0 * n * log_base;  // j = n
  LogSum sum;
  for (double j = n;; j += 1.0) {
    sum.add(log_term);
    const double ratio = (n + j) / ((j + 1.0) * (2.0 + t));
    const double log_tail_bound = log_term + std::log(ratio / (1.0 - ratio));
    if (log_tail_bound < sum.log() - 45.0) break;  // tail < 3e-20 of the sum
    FOGRADAR_CHECK(j < n + 1e8);
    log_term += std::log(ratio);
  }
  return std::log(2.0) + sum.log();
}

// log Pfa of OS-CFAR, rank k of N (Rohling 1983): sum_{i<k} log((N-i) / (N-i+alpha)).
double log_pfa_os(double big_n, unsigned k, double alpha) {
  double result = 0.0;
  for (unsigned i = 0; i < k; ++i) result -= std::log1p(alpha / (big_n - i));
  return result;
}

double log_false_alarm_probability(const CfarConfig& config, double alpha) {
  const double n = config.training_cells;
  const double big_n = 2.0 * n;
  switch (config.kind) {
    case CfarKind::ca:
      return -big_n * std::log1p(alpha / big_n);
    case CfarKind::go:
      return log_pfa_go(n, alpha / n);
    case CfarKind::so:
      return log_pfa_so(n, alpha / n);
    case CfarKind::os:
      return log_pfa_os(big_n, config.effective_os_rank(), alpha);
  }
  FOGRADAR_CHECK(false && "unknown CfarKind");
  return 0.0;
}

}  // namespace

double cfar_false_alarm_probability(const CfarConfig& config, double alpha) {
  config.validate();
  require_non_negative("cfar.threshold_factor", alpha);
  return std::exp(log_false_alarm_probability(config, alpha));
}

double cfar_threshold_factor(const CfarConfig& config) {
  config.validate();
  const double log_pfa = std::log(config.false_alarm_probability);
  const double big_n = static_cast<double>(config.reference_cells());
  if (config.kind == CfarKind::ca) {
    // Closed form: alpha = N (Pfa^(-1/N) - 1), written with expm1 for small -log(Pfa)/N.
    return big_n * std::expm1(-log_pfa / big_n);
  }

  // GO, SO, OS: log Pfa(alpha) is continuous and strictly decreasing from 0 at alpha = 0.
  return solve_threshold_factor(
      [&](double alpha) { return log_false_alarm_probability(config, alpha); },
      config.false_alarm_probability, 1.0);
}

}  // namespace fogradar::radar
