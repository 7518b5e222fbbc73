// P_fa of CFAR cells the range window correlates (CA exact, others sampled); one geometry's factor.
#include "cfar_correlated.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/core/random.hpp"
#include "fogradar/radar/cfar_design.hpp"
#include "solve_factor.hpp"

namespace fogradar::radar {

std::vector<std::complex<double>> standard_draws(std::size_t big_n, std::uint64_t seed) {
  RandomStream rng(seed);
  std::vector<std::complex<double>> draws(kSamples * big_n);
  for (auto& value : draws) value = rng.complex_normal(1.0);
  return draws;
}

namespace {

using Matrix = Eigen::MatrixXd;

// R_ij = rho(p_i - p_j) for the cells at `positions`.
Matrix correlation_matrix(const CellNoise& noise, std::span<const CfarCellOffset> positions) {
  const auto size = static_cast<Eigen::Index>(positions.size());
  Matrix r(size, size);
  for (Eigen::Index i = 0; i < size; ++i) {
    for (Eigen::Index j = 0; j < size; ++j) {
      r(i, j) =
          noise.at(positions[static_cast<std::size_t>(i)], positions[static_cast<std::size_t>(j)]);
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

// The law of the reference cells r under the exponential tilt e^{theta q} of the quadratic form q =
// |Y0|^2 - a sum_{j in D} |r_j|^2 (a = tilt.theta on the tilt's cells D): the cell under test and
// its reference cells v = (r, Y0) ~ CN(0, R), R = L L^T, become CN(0, L (I - theta M)^-1 L^T),
// M = L^T Q L = V diag(m) V^T, for theta < 1 / max(m), with normaliser E[e^{theta q}] =
// prod_i 1 / (1 - theta m_i). theta is the Chernoff exponent of P(q > 0): sum_i m_i / (1 - theta
// m_i) = 0 (Bucklew 2004, Introduction to Rare Event Simulation, ch. 5: the tilt that centres q at
// 0). r's marginal is drawn as G z, G the lower Cholesky factor of its covariance.
struct QuadraticTilt {
  Tilt tilt;
  double theta = 0.0;
  double log_mgf = 0.0;  // log E[e^{theta q}]
  Matrix lower;          // G
};

// The tilt of `factor` (R's lower Cholesky factor, the cell under test last); none where q's mean
// is not negative (then theta <= 0) or M's eigenvalues do not resolve the positive one.
std::optional<QuadraticTilt> quadratic_tilt(const Matrix& factor, const Tilt& tilt) {
  const Eigen::Index size = factor.rows() - 1;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(size + 1);
  for (std::size_t j = tilt.begin; j < tilt.end; ++j) q(static_cast<Eigen::Index>(j)) = -tilt.theta;
  q(size) = 1.0;
  const Matrix m = factor.transpose() * q.asDiagonal() * factor;
  const Eigen::SelfAdjointEigenSolver<Matrix> solver(m);
  if (solver.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXd& eigen = solver.eigenvalues();  // ascending
  const double top = eigen(size);
  if (!(top > 1e-6 * std::abs(eigen(0))) || !(eigen.sum() < 0.0)) return std::nullopt;
  // sum_i m_i / (1 - theta m_i) rises from sum m_i < 0 to +inf as theta -> 1 / top: bisection.
  double low = 0.0, high = 1.0 / top;
  for (int step = 0; step < 200 && high - low > 1e-15 * high; ++step) {
    const double middle = 0.5 * (low + high);
    const double slope = (eigen.array() / (1.0 - middle * eigen.array())).sum();
    (slope < 0.0 ? low : high) = middle;
  }
  QuadraticTilt result{tilt, low, 0.0, {}};
  result.log_mgf = -(1.0 - low * eigen.array()).log().sum();
  // The reference rows of L V diag(1 / sqrt(1 - theta m)) are F_r, r = F_r z'; QR of F_r^T gives
  // F_r F_r^T = R^T R, G = R^T with its diagonal made positive.
  const Eigen::VectorXd scale = (1.0 - low * eigen.array()).rsqrt().matrix();
  const Matrix f_r = (factor * solver.eigenvectors() * scale.asDiagonal()).topRows(size);
  const Eigen::HouseholderQR<Matrix> qr(f_r.transpose());
  Matrix upper = qr.matrixQR().topRows(size).triangularView<Eigen::Upper>();
  const Eigen::VectorXd signs = upper.diagonal().array().sign().matrix();
  result.lower = (signs.asDiagonal() * upper).transpose();
  if (!(result.lower.diagonal().minCoeff() > 0.0) || !std::isfinite(result.log_mgf))
    return std::nullopt;
  return result;
}

// The sampled P_fa estimate of one reference geometry (cfar_design.hpp): per sample its mixture
// weight p/q, its noise estimate over s^2 and lambda = |mu|^2/s^2.
class SampledPfa {
 public:
  SampledPfa(const CfarConfig& config, const CellNoise& noise,
             std::span<const CfarCellOffset> offsets, double tilt_alpha,
             std::span<const std::complex<double>> draws, const StopToken& stop)
      : stop_(stop) {
    const std::size_t big_n = offsets.size();
    const auto size = static_cast<Eigen::Index>(big_n);
    std::vector<CfarCellOffset> positions(offsets.begin(), offsets.end());
    positions.push_back({});  // the cell under test last: its row of L gives mu and s
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
    // Where the cell under test is correlated with its reference cells, a sample of small cells
    // also predicts a small cell under test: the alarms come from reference vectors whose
    // prediction mu is large against the noise estimate, which the tilts above rarely draw. One
    // more component per tilt follows them (quadratic_tilt).
    std::vector<QuadraticTilt> quadratic;
    if (l.cwiseAbs().maxCoeff() > 1e-9) {
      for (const Tilt& tilt : tilts) {
        if (auto q = quadratic_tilt(factor, tilt)) quadratic.push_back(std::move(*q));
      }
    }
    // mu = l u = g r, g = l Lr^-1 (the cell under test's regression on the reference cells).
    const Eigen::RowVectorXd g =
        lr.transpose().triangularView<Eigen::Upper>().solve(l.transpose()).transpose();
    const std::size_t components = tilts.size() + quadratic.size() + 1;
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
    // The products below skip the exact zeros outside each row's nonzero span: the noise itself
    // has H = I, and Lr, the Cholesky factor of a correlation matrix of finite lag, is banded. A
    // skipped term is +-0, so the sums' values are the same.
    std::vector<std::vector<Eigen::Index>> upper_end(upper.size());
    for (std::size_t c = 0; c < upper.size(); ++c) {
      for (Eigen::Index j = 0; j < size; ++j) {
        Eigen::Index end = size;
        while (end > j + 1 && upper[c](j, end - 1) == 0.0) --end;
        upper_end[c].push_back(end);
      }
    }
    std::vector<Eigen::Index> lr_begin;
    for (Eigen::Index j = 0; j < size; ++j) {
      Eigen::Index begin = 0;
      while (begin < j && lr(j, begin) == 0.0) ++begin;
      lr_begin.push_back(begin);
    }
    std::vector<std::complex<double>> u(big_n);
    std::vector<double> x(big_n), scratch;
    for (std::size_t i = 0; i < kSamples; ++i) {
      stop.check();
      const std::size_t c = i * components / kSamples;  // contiguous blocks per component
      const std::complex<double>* z = draws.data() + i * big_n;
      std::complex<double> mu = 0.0;
      if (c < upper.size()) {
        // Back substitution H^T u = z (upper triangular).
        const Matrix& ht = upper[c];
        for (std::size_t jj = big_n; jj-- > 0;) {
          const auto j = static_cast<Eigen::Index>(jj);
          std::complex<double> value = z[jj];
          for (Eigen::Index k = j + 1; k < upper_end[c][jj]; ++k)
            value -= ht(j, k) * u[static_cast<std::size_t>(k)];
          u[jj] = value / ht(j, j);
        }
        for (Eigen::Index j = 0; j < size; ++j) {
          std::complex<double> r = 0.0;
          for (Eigen::Index k = lr_begin[static_cast<std::size_t>(j)]; k <= j; ++k)
            r += lr(j, k) * u[static_cast<std::size_t>(k)];
          x[static_cast<std::size_t>(j)] = std::norm(r);
          mu += l(j) * u[static_cast<std::size_t>(j)];
        }
      } else {
        // r = G z (lower triangular), mu = g r.
        const Matrix& lower = quadratic[c - upper.size()].lower;
        for (Eigen::Index j = 0; j < size; ++j) {
          std::complex<double> r = 0.0;
          for (Eigen::Index k = 0; k <= j; ++k) r += lower(j, k) * z[k];
          x[static_cast<std::size_t>(j)] = std::norm(r);
          mu += g(j) * r;
        }
      }
      // Balance-heuristic weight p / (sum_c q_c / components), in logs (q/p reaches e^900).
      LogSum mixture;
      mixture.add(0.0);
      for (std::size_t t = 0; t < tilts.size(); ++t) {
        double tilted = 0.0;
        for (std::size_t j = tilts[t].begin; j < tilts[t].end; ++j) tilted += x[j];
        mixture.add(log_det[t + 1] - tilts[t].theta * tilted);
      }
      for (const QuadraticTilt& q : quadratic) {
        double tilted = 0.0;
        for (std::size_t j = q.tilt.begin; j < q.tilt.end; ++j) tilted += x[j];
        // log q/p = -theta a sum_D |r_j|^2 + log E[e^{theta |Y0|^2} | r] - log M(theta), with
        // Y0 | r ~ CN(mu, s^2): E[e^{theta |Y0|^2} | r] = e^{theta |mu|^2 / (1 - theta s^2)} /
        // (1 - theta s^2).
        const double shrink = 1.0 - q.theta * s2;
        mixture.add(-q.theta * q.tilt.theta * tilted + q.theta * std::norm(mu) / shrink -
                    std::log(shrink) - q.log_mgf);
      }
      log_weight_[i] = std::log(static_cast<double>(components)) - mixture.log();
      scaled_noise_[i] = noise_estimate(config, x, scratch) / s2;
      lambda_[i] = std::norm(mu) / s2;
    }
  }

  // log P_fa at factor alpha: log((1/K) sum_i w_i Q_1,i).
  double operator()(double alpha) const {
    stop_.check();
    LogSum sum;
    for (std::size_t i = 0; i < kSamples; ++i)
      sum.add(log_weight_[i] + log_marcum_q1_tail(lambda_[i], alpha * scaled_noise_[i]));
    return sum.log() - std::log(static_cast<double>(kSamples));
  }

 private:
  StopToken stop_;
  std::vector<double> log_weight_;
  std::vector<double> scaled_noise_;
  std::vector<double> lambda_;
};

double log_pfa_ca_for(const CellNoise& noise, std::span<const CfarCellOffset> offsets,
                      double alpha) {
  std::vector<CfarCellOffset> positions{{}};
  positions.insert(positions.end(), offsets.begin(), offsets.end());
  return log_pfa_ca_exact(cholesky_factor(correlation_matrix(noise, positions)), alpha);
}

double ca_factor(const CfarConfig& config, const CellNoise& noise,
                 std::span<const CfarCellOffset> offsets, double independent_factor,
                 const StopToken& stop) {
  std::vector<CfarCellOffset> positions{{}};
  positions.insert(positions.end(), offsets.begin(), offsets.end());
  const Matrix factor = cholesky_factor(correlation_matrix(noise, positions));
  return solve_threshold_factor(
      [&](double alpha) {
        stop.check();
        return log_pfa_ca_exact(factor, alpha);
      },
      config.false_alarm_probability, independent_factor);
}

// The factor whose tilts the sampled estimate uses: the kind's independent-cell factor scaled by
// what the correlation does to CA's exact factor in the same geometry (the sampled factors land
// within a few % of it, so the tilts sit where the estimate's mass is).
double tilt_factor(const CfarConfig& config, const CellNoise& noise,
                   std::span<const CfarCellOffset> offsets, double independent_factor,
                   const StopToken& stop) {
  CfarConfig ca = config;
  ca.kind = CfarKind::ca;
  const double ca_independent = cfar_threshold_factor(ca);
  return independent_factor * ca_factor(ca, noise, offsets, ca_independent, stop) / ca_independent;
}

}  // namespace

bool white_within(const NoiseCorrelation& noise, std::size_t span) {
  for (std::size_t m = 1; m <= span && m < noise.coefficients.size(); ++m) {
    if (noise.coefficients[m] != 0.0) return false;
  }
  return true;
}

std::vector<CfarCellOffset> along_range(std::span<const std::ptrdiff_t> offsets) {
  std::vector<CfarCellOffset> cells;
  cells.reserve(offsets.size());
  for (const std::ptrdiff_t offset : offsets) cells.push_back({offset, 0});
  return cells;
}

double correlated_factor(const CfarConfig& config, const NoiseCorrelation& noise,
                         std::span<const std::ptrdiff_t> offsets, double independent_factor,
                         std::span<const std::complex<double>> draws, const StopToken& stop) {
  const NoiseCorrelation one_row;
  return correlated_factor(config, CellNoise{noise, one_row}, along_range(offsets),
                           independent_factor, draws, stop);
}

double correlated_factor(const CfarConfig& config, const CellNoise& noise,
                         std::span<const CfarCellOffset> offsets, double independent_factor,
                         std::span<const std::complex<double>> draws, const StopToken& stop) {
  if (config.kind == CfarKind::ca)
    return ca_factor(config, noise, offsets, independent_factor, stop);
  const double start = tilt_factor(config, noise, offsets, independent_factor, stop);
  const SampledPfa pfa(config, noise, offsets, start, draws, stop);
  // The start lies within a few % of the root, and the estimate's own standard error is >= 0.1 %.
  return solve_smooth_threshold_factor([&](double alpha) { return pfa(alpha); },
                                       config.false_alarm_probability, start, 1e-9);
}

double correlated_false_alarm_probability(const CfarConfig& config, const NoiseCorrelation& noise,
                                          std::span<const std::ptrdiff_t> offsets, double alpha,
                                          CorrelatedPfaMethod method, std::uint64_t seed) {
  const NoiseCorrelation one_row;
  return correlated_cell_false_alarm_probability(config, noise, one_row, along_range(offsets),
                                                 alpha, method, seed);
}

double correlated_cell_false_alarm_probability(const CfarConfig& config,
                                               const NoiseCorrelation& range_noise,
                                               const NoiseCorrelation& doppler_noise,
                                               std::span<const CfarCellOffset> offsets,
                                               double alpha, CorrelatedPfaMethod method,
                                               std::uint64_t seed) {
  config.validate();
  range_noise.validate();
  doppler_noise.validate();
  require_non_negative("cfar.threshold_factor", alpha);
  FOGRADAR_CHECK(offsets.size() == config.reference_cells());
  const CellNoise noise{range_noise, doppler_noise};
  if (config.kind == CfarKind::ca && method == CorrelatedPfaMethod::automatic) {
    return std::exp(log_pfa_ca_for(noise, offsets, alpha));
  }
  const std::vector<std::complex<double>> draws = standard_draws(offsets.size(), seed);
  return std::exp(SampledPfa(config, noise, offsets, alpha, draws, StopToken())(alpha));
}

}  // namespace fogradar::radar
