#include "fogradar/radar/cfar_design.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "solve_factor.hpp"

namespace fogradar::radar {

namespace {

// Samples of the reference vector per reference geometry.
constexpr std::size_t kSamples = std::size_t{1} << 14;

// kSamples draws of N independent CN(0, 1) values (sample-major) from the stream of `seed`: the
// same draws serve every geometry of a design (common random numbers).
std::vector<std::complex<double>> standard_draws(std::size_t big_n, std::uint64_t seed) {
  RandomStream rng(seed);
  std::vector<std::complex<double>> draws(kSamples * big_n);
  for (auto& value : draws) value = rng.complex_normal(1.0);
  return draws;
}

using Matrix = Eigen::MatrixXd;

// R_ij = rho(p_i - p_j) for the cells at `positions`.
Matrix correlation_matrix(const NoiseCorrelation& noise,
                          std::span<const std::ptrdiff_t> positions) {
  const auto size = static_cast<Eigen::Index>(positions.size());
  Matrix r(size, size);
  for (Eigen::Index i = 0; i < size; ++i) {
    for (Eigen::Index j = 0; j < size; ++j) {
      r(i, j) =
          noise.at(positions[static_cast<std::size_t>(i)] - positions[static_cast<std::size_t>(j)]);
    }
  }
  return r;
}

// Lower Cholesky factor of a correlation matrix of distinct cells (positive definite: every window
// gives the cells' process a spectral density w[n]^2 that is positive on more than N points).
Matrix cholesky_factor(const Matrix& r) {
  const Eigen::LLT<Matrix> llt(r);
  FOGRADAR_CHECK(llt.info() == Eigen::Success);
  return llt.matrixL();
}

// log P_fa of CA at factor alpha for the cells at `offsets` around a cell under test at 0:
// log prod_{i>1} 1 / (1 + |lambda_i| / lambda_1), lambda the eigenvalues of L^T Q L
// (cfar_design.hpp). The solver resolves eigenvalues to ~eps max|lambda_i| ~ eps a: for a > ~1e12
// (P_fa < ~1e-200) lambda_1 ~ s^2 <= 1 is lost, and is taken from the product of all eigenvalues,
// det(L^T Q L) = det(R) det(Q) = det(R) (-a)^N: lambda_1 = det(R) a^N / prod_{i>1} |lambda_i|.
double log_pfa_ca_exact(const Matrix& cut_first_factor, double alpha) {
  const Eigen::Index size = cut_first_factor.rows();
  const double a = alpha / static_cast<double>(size - 1);
  Eigen::VectorXd q = Eigen::VectorXd::Constant(size, -a);
  q(0) = 1.0;
  const Matrix m = cut_first_factor.transpose() * q.asDiagonal() * cut_first_factor;
  const Eigen::SelfAdjointEigenSolver<Matrix> solver(m, Eigen::EigenvaluesOnly);
  FOGRADAR_CHECK(solver.info() == Eigen::Success);
  const Eigen::VectorXd& lambda = solver.eigenvalues();  // ascending
  double top = lambda(size - 1);
  if (!(top > 1e-6 * std::abs(lambda(0)))) {
    // log lambda_1 = log det R + N log a - sum_{i>1} log |lambda_i|
    double log_top = 2.0 * cut_first_factor.diagonal().array().log().sum() +
                     static_cast<double>(size - 1) * std::log(a);
    for (Eigen::Index i = 0; i + 1 < size; ++i) log_top -= std::log(std::abs(lambda(i)));
    top = std::exp(log_top);
  }
  FOGRADAR_CHECK(top > 0.0);
  double log_pfa = 0.0;
  for (Eigen::Index i = 0; i + 1 < size; ++i) log_pfa -= std::log1p(std::abs(lambda(i)) / top);
  return log_pfa;
}

// log P(|Y0|^2 > y s^2) for Y0 ~ CN(mu, s^2), lambda = |mu|^2 / s^2: log Marcum
// Q_1(sqrt(2 lambda), sqrt(2 y)), Q_1 = sum_j e^-lambda lambda^j/j! e^-y sum_{i<=j} y^i/i! (Poisson
// mixture of Gamma(j+1) tails), summed in log space (P_fa down to the smallest double). The gamma
// tails are <= 1, so the sum after term j is below the Poisson tail, which for j > lambda is below
// p_j r / (1 - r), r = lambda / (j + 1).
double log_cut_tail(double lambda, double y) {
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
  const double log_y = std::log(y);
  const double log_lambda = std::log(lambda);
  double log_poisson = -lambda;
  double log_gamma_term = -y;
  double log_gamma_tail = log_gamma_term;
  LogSum sum;
  sum.add(log_poisson + log_gamma_tail);
  for (double j = 1.0;; j += 1.0) {
    log_poisson += log_lambda - std::log(j);
    log_gamma_term += log_y - std::log(j);
    // log(e^tail + e^term), the larger first
    const double high = std::max(log_gamma_tail, log_gamma_term);
    const double low = std::min(log_gamma_tail, log_gamma_term);
    if (high > -std::numeric_limits<double>::infinity())
      log_gamma_tail = high + std::log1p(std::exp(low - high));
    sum.add(log_poisson + log_gamma_tail);
    const double ratio = lambda / (j + 1.0);
    if (ratio < 1.0 && log_poisson + std::log(ratio / (1.0 - ratio)) <= sum.log() - 39.2) break;
    if (log_poisson < -1e4) break;
  }
  return sum.log();
}

// The noise estimate Z of the kind (threshold alpha Z) from the N reference powers in range order;
// `scratch` holds N values.
double noise_estimate(const CfarConfig& config, std::span<const double> x,
                      std::vector<double>& scratch) {
  const std::size_t n = config.training_cells;
  double first = 0.0;
  double second = 0.0;
  for (std::size_t j = 0; j < n; ++j) first += x[j];
  for (std::size_t j = n; j < 2 * n; ++j) second += x[j];
  switch (config.kind) {
    case CfarKind::ca:
      return (first + second) / static_cast<double>(2 * n);
    case CfarKind::go:
      return std::max(first, second) / static_cast<double>(n);
    case CfarKind::so:
      return std::min(first, second) / static_cast<double>(n);
    case CfarKind::os: {
      scratch.assign(x.begin(), x.end());
      const auto kth = scratch.begin() + (config.effective_os_rank() - 1);
      std::nth_element(scratch.begin(), kth, scratch.end());
      return *kth;
    }
  }
  FOGRADAR_CHECK(false && "unknown CfarKind");
  return 0.0;
}

// A tilted version of the reference cells' law: density proportional to
// p(r) exp(-theta sum_{j in [begin, end)} |r_j|^2).
struct Tilt {
  std::size_t begin, end;
  double theta;
};

// The sampled P_fa estimate of one reference geometry (cfar_design.hpp): per sample its mixture
// weight p/q, its noise estimate over s^2 and lambda = |mu|^2/s^2.
class SampledPfa {
 public:
  SampledPfa(const CfarConfig& config, const NoiseCorrelation& noise,
             std::span<const std::ptrdiff_t> offsets, double tilt_alpha,
             std::span<const std::complex<double>> draws) {
    const std::size_t big_n = offsets.size();
    const auto size = static_cast<Eigen::Index>(big_n);
    std::vector<std::ptrdiff_t> positions(offsets.begin(), offsets.end());
    positions.push_back(0);  // the cell under test last: its row of L gives mu and s
    const Matrix factor = cholesky_factor(correlation_matrix(noise, positions));
    const Matrix lr = factor.topLeftCorner(size, size);
    const Eigen::RowVectorXd l = factor.block(size, 0, 1, size);
    const double s2 = factor(size, size) * factor(size, size);

    // Components: the noise itself, then tilts that make the noise estimate's cells small with the
    // independent-cell exponent of the estimate (alpha / N on all N cells, alpha / n on a half).
    const std::size_t n = config.training_cells;
    std::vector<Tilt> tilts;
    if (config.kind == CfarKind::so) {
      tilts = {{0, n, tilt_alpha / static_cast<double>(n)},
               {n, 2 * n, tilt_alpha / static_cast<double>(n)}};
    } else if (config.kind == CfarKind::os) {
      const double theta = tilt_alpha / static_cast<double>(big_n);
      tilts = {{0, big_n, theta}, {0, big_n, 0.5 * theta}, {0, big_n, 0.25 * theta}};
    } else {
      tilts = {{0, big_n, tilt_alpha / static_cast<double>(big_n)}};
    }
    const std::size_t components = tilts.size() + 1;
    // u ~ CN(0, A^-1), A = I + theta Lr^T D Lr, as u = H^-T z (A = H H^T), z ~ CN(0, I);
    // q/p = det(A) exp(-theta sum_D |r_j|^2).
    std::vector<Matrix> upper{Matrix::Identity(size, size)};
    std::vector<double> log_det{0.0};
    for (const Tilt& tilt : tilts) {
      Eigen::VectorXd d = Eigen::VectorXd::Zero(size);
      for (std::size_t j = tilt.begin; j < tilt.end; ++j)
        d(static_cast<Eigen::Index>(j)) = tilt.theta;
      // A = S^T S, S = [sqrt(D) Lr; I], so QR of S gives A = R^T R without forming A (whose
      // Cholesky fails at theta ~ 1e25, P_fa ~ 1e-300: A's condition number ~ theta).
      Matrix stacked = Matrix::Zero(2 * size, size);
      stacked.topRows(size) = d.cwiseSqrt().asDiagonal() * lr;
      stacked.bottomRows(size) = Matrix::Identity(size, size);
      const Eigen::HouseholderQR<Matrix> qr(stacked);
      Matrix r_factor = qr.matrixQR().topRows(size).triangularView<Eigen::Upper>();
      // Rows signed to a positive diagonal: the transposed Cholesky factor of A, to rounding.
      const Eigen::VectorXd signs = r_factor.diagonal().array().sign().matrix();
      r_factor = (signs.asDiagonal() * r_factor).eval();
      upper.push_back(r_factor);
      log_det.push_back(2.0 * r_factor.diagonal().array().log().sum());
    }

    log_weight_.resize(kSamples);
    scaled_noise_.resize(kSamples);
    lambda_.resize(kSamples);
    FOGRADAR_CHECK(draws.size() == kSamples * big_n);
    std::vector<std::complex<double>> u(big_n);
    std::vector<double> x(big_n), scratch;
    for (std::size_t i = 0; i < kSamples; ++i) {
      const std::size_t c = i * components / kSamples;  // contiguous blocks per component
      const std::complex<double>* z = draws.data() + i * big_n;
      // Back substitution H^T u = z (upper triangular).
      const Matrix& ht = upper[c];
      for (std::size_t jj = big_n; jj-- > 0;) {
        const auto j = static_cast<Eigen::Index>(jj);
        std::complex<double> value = z[jj];
        for (Eigen::Index k = j + 1; k < size; ++k)
          value -= ht(j, k) * u[static_cast<std::size_t>(k)];
        u[jj] = value / ht(j, j);
      }
      std::complex<double> mu = 0.0;
      for (Eigen::Index j = 0; j < size; ++j) {
        std::complex<double> r = 0.0;
        for (Eigen::Index k = 0; k <= j; ++k) r += lr(j, k) * u[static_cast<std::size_t>(k)];
        x[static_cast<std::size_t>(j)] = std::norm(r);
        mu += l(j) * u[static_cast<std::size_t>(j)];
      }
      // Balance-heuristic weight p / (sum_c q_c / components), in logs (q/p reaches e^900).
      LogSum mixture;
      mixture.add(0.0);
      for (std::size_t t = 0; t < tilts.size(); ++t) {
        double tilted = 0.0;
        for (std::size_t j = tilts[t].begin; j < tilts[t].end; ++j) tilted += x[j];
        mixture.add(log_det[t + 1] - tilts[t].theta * tilted);
      }
      log_weight_[i] = std::log(static_cast<double>(components)) - mixture.log();
      scaled_noise_[i] = noise_estimate(config, x, scratch) / s2;
      lambda_[i] = std::norm(mu) / s2;
    }
  }

  // log P_fa at factor alpha: log((1/K) sum_i w_i Q_1,i).
  double operator()(double alpha) const {
    LogSum sum;
    for (std::size_t i = 0; i < kSamples; ++i)
      sum.add(log_weight_[i] + log_cut_tail(lambda_[i], alpha * scaled_noise_[i]));
    return sum.log() - std::log(static_cast<double>(kSamples));
  }

 private:
  std::vector<double> log_weight_;
  std::vector<double> scaled_noise_;
  std::vector<double> lambda_;
};


// True when no two cells of a geometry spanning `span` cells are correlated.
bool white_within(const NoiseCorrelation& noise, std::size_t span) {
  for (std::size_t m = 1; m <= span && m < noise.coefficients.size(); ++m) {
    if (noise.coefficients[m] != 0.0) return false;
  }
  return true;
}

double log_pfa_ca_for(const NoiseCorrelation& noise, std::span<const std::ptrdiff_t> offsets,
                      double alpha) {
  std::vector<std::ptrdiff_t> positions{0};
  positions.insert(positions.end(), offsets.begin(), offsets.end());
  return log_pfa_ca_exact(cholesky_factor(correlation_matrix(noise, positions)), alpha);
}

double ca_factor(const CfarConfig& config, const NoiseCorrelation& noise,
                 std::span<const std::ptrdiff_t> offsets, double independent_factor) {
  std::vector<std::ptrdiff_t> positions{0};
  positions.insert(positions.end(), offsets.begin(), offsets.end());
  const Matrix factor = cholesky_factor(correlation_matrix(noise, positions));
  return solve_threshold_factor([&](double alpha) { return log_pfa_ca_exact(factor, alpha); },
                      config.false_alarm_probability, independent_factor);
}

// The factor whose tilts the sampled estimate uses: the kind's independent-cell factor scaled by
// what the correlation does to CA's exact factor in the same geometry (the sampled factors land
// within a few % of it, so the tilts sit where the estimate's mass is).
double tilt_factor(const CfarConfig& config, const NoiseCorrelation& noise,
                   std::span<const std::ptrdiff_t> offsets, double independent_factor) {
  CfarConfig ca = config;
  ca.kind = CfarKind::ca;
  const double ca_independent = cfar_threshold_factor(ca);
  return independent_factor * ca_factor(ca, noise, offsets, ca_independent) / ca_independent;
}

double correlated_factor(const CfarConfig& config, const NoiseCorrelation& noise,
                         std::span<const std::ptrdiff_t> offsets, double independent_factor,
                         std::span<const std::complex<double>> draws) {
  if (config.kind == CfarKind::ca) return ca_factor(config, noise, offsets, independent_factor);
  const double start = tilt_factor(config, noise, offsets, independent_factor);
  const SampledPfa pfa(config, noise, offsets, start, draws);
  return solve_threshold_factor([&](double alpha) { return pfa(alpha); },
                                config.false_alarm_probability, start);
}

}  // namespace

double correlated_false_alarm_probability(const CfarConfig& config, const NoiseCorrelation& noise,
                                          std::span<const std::ptrdiff_t> offsets, double alpha,
                                          CorrelatedPfaMethod method, std::uint64_t seed) {
  config.validate();
  noise.validate();
  require_non_negative("cfar.threshold_factor", alpha);
  FOGRADAR_CHECK(offsets.size() == config.reference_cells());
  if (config.kind == CfarKind::ca && method == CorrelatedPfaMethod::automatic) {
    return std::exp(log_pfa_ca_for(noise, offsets, alpha));
  }
  const std::vector<std::complex<double>> draws = standard_draws(offsets.size(), seed);
  return std::exp(SampledPfa(config, noise, offsets, alpha, draws)(alpha));
}

CfarThresholdFactors design_cfar_threshold_factors(const CfarConfig& config,
                                                   const NoiseCorrelation& noise) {
  config.validate();
  noise.validate();
  const double independent = cfar_threshold_factor(config);
  const std::size_t reach = std::size_t{config.guard_cells} + config.training_cells;
  CfarThresholdFactors factors{independent, std::vector<double>(reach, independent)};
  // The widest geometry, an edge cell's, spans guard + N cells.
  if (config.threshold_design == CfarThresholdDesign::independent ||
      white_within(noise, config.guard_cells + config.reference_cells())) {
    return factors;
  }
  const std::vector<std::complex<double>> draws =
      config.kind == CfarKind::ca ? std::vector<std::complex<double>>{}
                                  : standard_draws(config.reference_cells(), kCfarDesignSeed);
  // Cells 0..guard share one geometry (no cell on their left): solve each distinct one once.
  std::vector<std::pair<std::vector<std::ptrdiff_t>, double>> solved;
  const auto factor_for = [&](std::size_t cells_from_end) {
    std::vector<std::ptrdiff_t> offsets = cfar_reference_offsets(config, cells_from_end);
    for (const auto& [known, factor] : solved) {
      if (known == offsets) return factor;
    }
    const double factor = correlated_factor(config, noise, offsets, independent, draws);
    solved.emplace_back(std::move(offsets), factor);
    return factor;
  };
  factors.interior = factor_for(reach);
  for (std::size_t i = 0; i < reach; ++i) factors.edge[i] = factor_for(i);
  return factors;
}

}  // namespace fogradar::radar
