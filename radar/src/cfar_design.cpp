#include "fogradar/radar/cfar_design.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
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

namespace {

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
  SampledPfa(const CfarConfig& config, const NoiseCorrelation& noise,
             std::span<const std::ptrdiff_t> offsets, double tilt_alpha,
             std::span<const std::complex<double>> draws, const StopToken& stop)
      : stop_(stop) {
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
                 std::span<const std::ptrdiff_t> offsets, double independent_factor,
                 const StopToken& stop) {
  std::vector<std::ptrdiff_t> positions{0};
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
double tilt_factor(const CfarConfig& config, const NoiseCorrelation& noise,
                   std::span<const std::ptrdiff_t> offsets, double independent_factor,
                   const StopToken& stop) {
  CfarConfig ca = config;
  ca.kind = CfarKind::ca;
  const double ca_independent = cfar_threshold_factor(ca);
  return independent_factor * ca_factor(ca, noise, offsets, ca_independent, stop) / ca_independent;
}

double correlated_factor(const CfarConfig& config, const NoiseCorrelation& noise,
                         std::span<const std::ptrdiff_t> offsets, double independent_factor,
                         std::span<const std::complex<double>> draws, const StopToken& stop) {
  if (config.kind == CfarKind::ca)
    return ca_factor(config, noise, offsets, independent_factor, stop);
  const double start = tilt_factor(config, noise, offsets, independent_factor, stop);
  const SampledPfa pfa(config, noise, offsets, start, draws, stop);
  // The start lies within a few % of the root, and the estimate's own standard error is >= 0.1 %.
  return solve_smooth_threshold_factor([&](double alpha) { return pfa(alpha); },
                                       config.false_alarm_probability, start, 1e-9);
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
  return std::exp(SampledPfa(config, noise, offsets, alpha, draws, StopToken())(alpha));
}

namespace {

// A lag's correlation counts towards a geometry's structure from this magnitude on (its square, the
// correlation of the cells' powers, is then 1e-4; for CA exact, geometries that differ beyond it
// differ in their factors by < 1e-4: test_cfar_correlated.cpp).
constexpr double kReachCorrelation = 1e-2;

// The lags a geometry's structure may reach. Every window of the chain reaches at most 4 (Hann and
// Hamming 2, Blackman-Harris and the 80 dB Chebyshev 4 and 3: docs/radar.md §7).
constexpr std::size_t kStructureLags = 16;

// Cells on each side of a structure point (the cell under test's window, the end of a block, the
// boundary of the GO/SO halves) within which two geometries must agree to share a factor: the
// largest lag with |rho| >= kReachCorrelation, plus one. A correlation that has not decayed beyond
// kStructureLags (the last kStructureLags lags aside: the DFT's correlation is circular, rho(m) =
// rho(L - m) for a window of L samples) shares nothing: every geometry is its own, at n.
std::size_t structure_cells(const NoiseCorrelation& noise) {
  const std::size_t size = noise.coefficients.size();
  std::size_t reach = 0;
  for (std::size_t m = 1; m < size; ++m) {
    if (std::abs(noise.coefficients[m]) < kReachCorrelation) continue;
    if (m > kStructureLags && m + kStructureLags < size) {
      return std::numeric_limits<std::size_t>::max() / 4;
    }
    if (m <= kStructureLags) reach = m;
  }
  return reach + 1;
}

// A reference geometry by its number of reference cells on the left of the cell under test, L in
// [0, n] (n: the interior). Geometries whose L and n - L both reach K = structure_cells are the
// same cells near every structure point and differ only in where the far cells lie: one of them, L
// = n / 2, is solved for all (for CA exact they agree to 1e-5 at n = 24: test_cfar_correlated.cpp).
std::size_t solved_left(std::size_t left, std::size_t n, std::size_t k) {
  if (left < k || left + k >= n) return left;
  return n / 2;
}

// The edge cell i of a profile (i < guard + n) has L = max(0, i - guard) cells on its left.
std::size_t left_cells(std::size_t cell, const CfarConfig& config) {
  return cell > config.guard_cells ? cell - config.guard_cells : 0;
}

// The config at training cells m: an explicit OS rank scaled to keep its place k / N.
CfarConfig with_training(const CfarConfig& config, std::size_t m) {
  CfarConfig result = config;
  result.training_cells = static_cast<unsigned>(m);
  if (config.kind == CfarKind::os && config.os_rank != 0) {
    const double place =
        static_cast<double>(config.os_rank) / static_cast<double>(config.reference_cells());
    result.os_rank = static_cast<unsigned>(std::clamp<double>(
        std::round(place * static_cast<double>(2 * m)), 1.0, static_cast<double>(2 * m)));
  }
  return result;
}

// Modelled CPU seconds of solving every distinct geometry of `config` (no anchor).
double solve_seconds(const CfarConfig& config, const NoiseCorrelation& noise, std::size_t k) {
  const std::size_t n = config.training_cells;
  const std::size_t big_n = config.reference_cells();
  const double geometries = static_cast<double>(n <= 2 * k + 1 ? n + 1 : 2 * k + 2);
  const double cells = static_cast<double>(big_n) + 1.0;
  // Per geometry ~12 symmetric eigenvalue solves of (N + 1)^2 (CA's factor, and for GO/SO/OS the
  // tilt factor and the quadratic tilts) and a fixed overhead.
  const double exact = geometries * (2.2e-5 + 12.0 * 3.8e-10 * cells * cells * cells);
  if (config.kind == CfarKind::ca) return exact;
  // Per sample: the reference vector and ~15 evaluations of the conditional tail: Marcum
  // evaluations where the cell under test is correlated with a reference cell (a lag in
  // [guard + 1, guard + N]), else the closed form e^-y.
  bool correlated_cut = false;
  for (std::size_t m = std::size_t{config.guard_cells} + 1;
       m <= config.guard_cells + big_n && m < noise.coefficients.size(); ++m)
    correlated_cut = correlated_cut || noise.coefficients[m] != 0.0;
  // The reference vector's products, averaged over the mixture's components (SampledPfa): the
  // noise itself one banded product (N x the band, at most N^2 / 2), each tilt a dense back
  // substitution (N^2 / 2) and the banded product, each quadratic tilt a dense product (N^2 / 2).
  const double n_cells = static_cast<double>(big_n);
  const double lags = static_cast<double>(noise.coefficients.size());
  const double banded = n_cells * std::min(lags, 0.5 * (n_cells + 1.0));
  const double dense = 0.5 * n_cells * n_cells;
  const double tilts = config.kind == CfarKind::so ? 2.0 : config.kind == CfarKind::os ? 3.0 : 1.0;
  const double quadratic = correlated_cut ? tilts : 0.0;
  const double products =
      (banded + tilts * (dense + banded) + quadratic * dense) / (1.0 + tilts + quadratic);
  const double per_sample = 0.75e-9 * products + (correlated_cut ? 0.7e-6 : 1.7e-7);
  return exact + geometries * static_cast<double>(kSamples) * per_sample;
}

// The training cells the design solves at (cfar_design.hpp): n itself when that fits the budget,
// else the largest m in [2 K + 1, n) that does (at least 2 K + 1, so that every kind of geometry
// exists at the anchor).
std::size_t anchor_training(const CfarConfig& config, const NoiseCorrelation& noise,
                            std::size_t k) {
  const std::size_t n = config.training_cells;
  const std::size_t least = std::min(n, 2 * k + 1);
  if (solve_seconds(config, noise, k) <= kCfarDesignBudgetSeconds) return n;
  // The modelled cost rises with m: bisection for the last m within the budget.
  std::size_t low = least, high = n;  // solve_seconds(high) > budget
  while (high - low > 1) {
    const std::size_t middle = low + (high - low) / 2;
    if (solve_seconds(with_training(config, middle), noise, k) <= kCfarDesignBudgetSeconds) {
      low = middle;
    } else {
      high = middle;
    }
  }
  return low;
}

// GO and SO take the larger or smaller of two half sums, each S/n = 1 + sigma xi with sigma^2 =
// c2/n, c2 = sum_m rho(m)^2 the variance per cell of a sum of correlated cells' powers (1 for
// independent cells): their mean shifts by +-sigma E[max(xi_1, xi_2)] = +-sigma / sqrt(pi) for
// independent standard normal xi. The factor that keeps the design P_fa scales inversely, so its
// ratio to the independent-cell factor carries -+(sqrt(c2) - 1) / sqrt(pi n) to first order, a
// 1/sqrt(n) term beside the 1/n ones the variance of the noise estimate brings (CA and OS: none).
double half_sum_bias_term(CfarKind kind, const NoiseCorrelation& noise) {
  if (kind != CfarKind::go && kind != CfarKind::so) return 0.0;
  // Over the lags of the structure (the first half of a circular correlation at most): the rest
  // is a floor below 2e-4 or the same lags again around the window.
  const std::size_t lags = std::min(kStructureLags, (noise.coefficients.size() - 1) / 2);
  double c2 = 1.0;
  for (std::size_t m = 1; m <= lags; ++m) c2 += 2.0 * noise.coefficients[m] * noise.coefficients[m];
  const double term = (std::sqrt(c2) - 1.0) / std::sqrt(std::numbers::pi);
  return kind == CfarKind::go ? -term : term;
}

bool designs_for_correlation(const CfarConfig& config, const NoiseCorrelation& noise) {
  return config.threshold_design == CfarThresholdDesign::correlated &&
         !white_within(noise, config.guard_cells + config.reference_cells());
}

}  // namespace

std::size_t cfar_correlation_lags(const CfarConfig& config) {
  return std::min<std::size_t>(std::size_t{config.guard_cells} + config.reference_cells(),
                               kCfarCorrelationLags);
}

std::size_t cfar_design_training_cells(const CfarConfig& config, const NoiseCorrelation& noise) {
  config.validate();
  noise.validate();
  if (!designs_for_correlation(config, noise)) return config.training_cells;
  return anchor_training(config, noise, structure_cells(noise));
}

CfarThresholdFactors design_cfar_threshold_factors(const CfarConfig& config,
                                                   const NoiseCorrelation& noise,
                                                   const StopToken& stop) {
  config.validate();
  noise.validate();
  const double independent = cfar_threshold_factor(config);
  const std::size_t n = config.training_cells;
  const std::size_t reach = std::size_t{config.guard_cells} + n;
  CfarThresholdFactors factors{independent, std::vector<double>(reach, independent)};
  if (!designs_for_correlation(config, noise)) return factors;
  const std::size_t k = structure_cells(noise);
  const std::size_t anchor = anchor_training(config, noise, k);
  const CfarConfig solved_config = with_training(config, anchor);
  const double solved_independent = cfar_threshold_factor(solved_config);
  const std::vector<std::complex<double>> draws =
      config.kind == CfarKind::ca
          ? std::vector<std::complex<double>>{}
          : standard_draws(solved_config.reference_cells(), kCfarDesignSeed);
  // The factor of the geometry with `left` cells on the left at the anchor, solved once.
  std::vector<std::pair<std::size_t, double>> solved;
  const auto solved_factor = [&](std::size_t left) {
    const std::size_t representative = solved_left(left, anchor, k);
    for (const auto& [known, factor] : solved) {
      if (known == representative) return factor;
    }
    const std::size_t cell =
        representative == 0 ? 0 : std::size_t{solved_config.guard_cells} + representative;
    const double factor =
        correlated_factor(solved_config, noise, cfar_reference_offsets(solved_config, cell),
                          solved_independent, draws, stop);
    solved.emplace_back(representative, factor);
    return factor;
  };
  // A geometry of n training cells takes its anchor twin's factor (the same cells near every
  // structure point) with its ratio r to the independent factor brought towards 1: r - 1 =
  // a / sqrt(n) + b / n, a the halves' term of GO/SO (0 for CA and OS), b from the anchor.
  const double half_sum_term = half_sum_bias_term(config.kind, noise);
  const auto factor_at = [&](std::size_t left) {
    if (anchor == n) return solved_factor(left);
    std::size_t twin = anchor / 2;
    if (left == n) {
      twin = anchor;
    } else if (left < k) {
      twin = left;
    } else if (left + k >= n) {
      twin = anchor - (n - left);
    }
    const double ratio = solved_factor(twin) / solved_independent;
    return independent * (1.0 + half_sum_term * (1.0 / std::sqrt(static_cast<double>(n))) +
                          (ratio - 1.0 - half_sum_term / std::sqrt(static_cast<double>(anchor))) *
                              static_cast<double>(anchor) / static_cast<double>(n));
  };
  factors.interior = factor_at(n);
  for (std::size_t i = 0; i < reach; ++i) factors.edge[i] = factor_at(left_cells(i, config));
  return factors;
}

double cfar_design_seconds(const CfarConfig& config, const NoiseCorrelation& noise) {
  if (!designs_for_correlation(config, noise)) return 0.0;
  const std::size_t k = structure_cells(noise);
  return solve_seconds(with_training(config, anchor_training(config, noise, k)), noise, k);
}

}  // namespace fogradar::radar
