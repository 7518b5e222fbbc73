#include "fogradar/lidar/fog_return.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/detail/simd.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::lidar {
namespace {

// The pulse is evaluated within this many FWHM of a node: p(2 fwhm) = 2^-16 = 1.5e-5 of the peak,
// and the cut-off tails hold erfc(4 sqrt(ln 2)) = 3e-6 of the pulse's energy.
constexpr double support_fwhm = 2.0;
// The node step is at most sigma / 4 (the edge rule's 8 nodes span 2 sigma of the pulse), at most
// 0.4 / (alpha c) (the fog's two-way attenuation across a step, 2 alpha c h / 2, at most 0.4), and
// beyond the overlap range at most 0.15 r_start / c (the 4 nodes continued before the stretch stay
// within 0.3 r_start of its start, away from the 1/r^2 pole): with these the rule is within
// 2e-6 of the stretch's peak return in tests/lidar.
constexpr double max_step_sigma = 0.25;
constexpr double max_step_attenuation = 0.4;
constexpr double max_step_range_fraction = 0.15;
// Tables of the pulse at dt / S for S = 1, 2, 4, 8, 16, the finer ones while they hold at most this
// many values.
constexpr std::size_t max_fine_table = 1 << 16;
constexpr std::size_t fine_tables = 5;
constexpr long edge_before = 4;  // edge rule nodes -4..3 around the first node inside

// B_2k(1/2) / (2k)!, k = 1..4: the midpoint-form Euler-Maclaurin coefficients (B_n(1/2) =
// -(1 - 2^(1-n)) B_n; Abramowitz & Stegun 23.1.21).
constexpr std::array<double, 4> midpoint_euler_maclaurin = {
    -1.0 / 12.0 / 2.0, 7.0 / 240.0 / 24.0, -31.0 / 1344.0 / 720.0, 127.0 / 3840.0 / 40320.0};

// out[k - begin] += profile[m - m_lo] pulse[k - m coarse + half] for nodes m_lo..m_hi and samples
// k in [k_min, k_max] with |k - m coarse| <= half: the scatter of each node's pulse, each sample's
// sum in node order in every clone.
FOGRADAR_SIMD_CLONES
void scatter(double* __restrict out, long begin, long k_min, long k_max,
             const double* __restrict profile, long m_lo, long m_hi, long coarse,
             const double* __restrict pulse, long half) {
  for (long m = m_lo; m <= m_hi; ++m) {
    const double w = profile[m - m_lo];
    if (w == 0.0) continue;
    const long centre = m * coarse;
    const long from = std::max(k_min, centre - half);
    const long to = std::min(k_max, centre + half);
    double* o = out + (from - begin);
    const double* p = pulse + (from - centre + half);
    for (long i = 0; i <= to - from; ++i) o[i] += w * p[i];
  }
}

long floor_div(long a, long b) { return a / b - (a % b != 0 && (a < 0) != (b < 0) ? 1 : 0); }
long ceil_div(long a, long b) { return -floor_div(-a, b); }

}  // namespace

FogReturn::FogReturn(const WaveformGrid& grid) : grid_(grid) {
  FOGRADAR_CHECK(grid.sample_interval_s > 0.0 && grid.pulse_fwhm_s > 0.0);
  sigma_s_ = grid.pulse_fwhm_s / std::sqrt(8.0 * std::numbers::ln2);
  const double a = 4.0 * std::numbers::ln2 / (grid.pulse_fwhm_s * grid.pulse_fwhm_s);
  for (std::size_t i = 0; i < fine_tables; ++i) {
    const double step = grid.sample_interval_s / static_cast<double>(1 << i);
    const auto half = static_cast<long>(std::floor(support_fwhm * grid.pulse_fwhm_s / step));
    if (i > 0 && static_cast<std::size_t>(2 * half + 1) > max_fine_table) break;
    std::vector<double> table(static_cast<std::size_t>(2 * half + 1));
    for (long n = -half; n <= half; ++n) {
      const double t = static_cast<double>(n) * step;
      table[static_cast<std::size_t>(n + half)] = std::exp(-a * t * t);
    }
    pulse_.push_back(std::move(table));
    half_.push_back(half);
  }
  // Edge weights on nodes l = -4..3 (in node steps from the first node inside, the edge theta
  // before it): sum_l w_l P(l) = integral_-theta^-1/2 P + sum_k c_k P^(2k-1)(-1/2) for every
  // polynomial P of degree <= 7, the part of integral_edge^end P that the plain sum over the inside
  // nodes, read as the midpoint rule from -1/2 on, misses (Euler-Maclaurin, midpoint form).
  constexpr auto n = static_cast<Eigen::Index>(edge_nodes);
  Eigen::Matrix<double, edge_nodes, edge_nodes> vandermonde;
  Eigen::Matrix<double, edge_nodes, 1> moments;
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index l = 0; l < n; ++l) {
      vandermonde(j, l) = std::pow(static_cast<double>(l - edge_before), static_cast<double>(j));
    }
    // integral_0^-1/2 u^j du; the theta part, -integral_0^-theta u^j du, is edge_theta_.
    double moment = std::pow(-0.5, static_cast<double>(j + 1)) / static_cast<double>(j + 1);
    for (Eigen::Index k = 1; 2 * k - 1 <= j; ++k) {
      // d^(2k-1) u^j / du^(2k-1) at u = -1/2.
      double derivative = std::pow(-0.5, static_cast<double>(j - 2 * k + 1));
      for (Eigen::Index f = j - 2 * k + 2; f <= j; ++f) derivative *= static_cast<double>(f);
      moment += midpoint_euler_maclaurin[static_cast<std::size_t>(k - 1)] * derivative;
    }
    moments(j) = moment;
  }
  const Eigen::Matrix<double, edge_nodes, edge_nodes> inverse = vandermonde.inverse();
  const Eigen::Matrix<double, edge_nodes, 1> constant = inverse * moments;
  for (Eigen::Index l = 0; l < n; ++l) {
    edge_constant_[static_cast<std::size_t>(l)] = constant(l);
    for (Eigen::Index j = 0; j < n; ++j) {
      // -integral_0^-theta u^j du = (-1)^j theta^(j+1) / (j+1).
      edge_theta_[static_cast<std::size_t>(l)][static_cast<std::size_t>(j)] =
          inverse(l, j) * (j % 2 == 0 ? 1.0 : -1.0) / static_cast<double>(j + 1);
    }
  }
}

void FogReturn::add(std::span<double> waveform, std::span<const FogStretch> stretches,
                    std::size_t first_sample) const {
  const double c = speed_of_light_m_per_s;
  const double dt = grid_.sample_interval_s;
  const double kink = grid_.full_overlap_range_m;
  // The smooth pieces: each stretch split at the overlap function's kink.
  struct Piece {
    const FogStretch* fog;
    double start_m;
    double end_m;
    bool inside_overlap;
  };
  std::array<Piece, 2> split{};
  std::vector<Piece> pieces;
  pieces.reserve(2 * stretches.size());
  double target_s = max_step_sigma * sigma_s_;
  for (const FogStretch& fog : stretches) {
    if (!(fog.end_m > fog.start_m) || fog.backscatter_per_m_sr == 0.0) continue;
    std::size_t count = 1;
    if (kink > fog.start_m && kink < fog.end_m) {
      split = {Piece{&fog, fog.start_m, kink, true}, Piece{&fog, kink, fog.end_m, false}};
      count = 2;
    } else {
      split[0] = {&fog, fog.start_m, fog.end_m, fog.end_m <= kink};
    }
    for (std::size_t i = 0; i < count; ++i) {
      const Piece& piece = split[i];
      if (fog.extinction_per_m > 0.0) {
        target_s = std::min(target_s, max_step_attenuation / (fog.extinction_per_m * c));
      }
      if (!piece.inside_overlap) {
        target_s = std::min(target_s, max_step_range_fraction * piece.start_m / c);
      }
      pieces.push_back(piece);
    }
  }
  if (pieces.empty()) return;
  // Node m at tau_m = m h, h = coarse dt / fine; table index n = k fine - m coarse for sample k.
  long coarse = 1;
  std::size_t level = 0;
  if (target_s >= dt) {
    coarse = static_cast<long>(std::floor(target_s / dt));
  } else {
    while (level + 1 < pulse_.size() && dt / static_cast<double>(1 << level) > target_s) ++level;
  }
  const long fine = 1L << level;
  const double h = dt * static_cast<double>(coarse) / static_cast<double>(fine);
  const double r_step = c * h / 2.0;

  // The nodes' weights times the profile beta_pi T^2(r) O(r) / r^2 dr/dtau h, piece by piece
  // (pieces that share a node add their parts in order).
  const auto node_range = [&](const Piece& piece) {
    const double first_inside = std::ceil(2.0 * piece.start_m / c / h);
    const double last_inside = std::floor(2.0 * piece.end_m / c / h);
    return std::pair{static_cast<long>(first_inside) - edge_before,
                     static_cast<long>(last_inside) + edge_before};
  };
  long m_lo = node_range(pieces.front()).first;
  long m_hi = m_lo;
  for (const Piece& piece : pieces) {
    const auto [lo, hi] = node_range(piece);
    m_lo = std::min(m_lo, lo);
    m_hi = std::max(m_hi, hi);
  }
  std::vector<double> profile(static_cast<std::size_t>(m_hi - m_lo + 1), 0.0);
  const double inside_factor = 1.0 / (grid_.full_overlap_range_m * grid_.full_overlap_range_m);
  double k_first = std::numeric_limits<double>::infinity();
  double k_last = -k_first;
  const double support_s = support_fwhm * grid_.pulse_fwhm_s;
  for (const Piece& piece : pieces) {
    const FogStretch& fog = *piece.fog;
    const double tau_a = 2.0 * piece.start_m / c;
    const double tau_b = 2.0 * piece.end_m / c;
    k_first = std::min(k_first, std::ceil((tau_a - support_s) / dt));
    k_last = std::max(k_last, std::floor((tau_b + support_s) / dt));
    const double first_inside = std::ceil(tau_a / h);
    const double last_inside = std::floor(tau_b / h);
    const auto m0 = static_cast<long>(first_inside);
    const auto m1 = static_cast<long>(last_inside);
    const long lo = m0 - edge_before;
    const long hi = m1 + edge_before;
    // Weight 1 on the nodes inside, plus the edge rule's on the 8 nodes around either edge.
    const auto edge_weights = [&](double theta) {
      std::array<double, edge_nodes> power{}, w{};
      double p = theta;
      for (std::size_t j = 0; j < edge_nodes; ++j, p *= theta) power[j] = p;
      for (std::size_t l = 0; l < edge_nodes; ++l) {
        w[l] = edge_constant_[l];
        for (std::size_t j = 0; j < edge_nodes; ++j) w[l] += edge_theta_[l][j] * power[j];
      }
      return w;
    };
    const std::array<double, edge_nodes> left = edge_weights(first_inside - tau_a / h);
    const std::array<double, edge_nodes> right = edge_weights(tau_b / h - last_inside);
    // T^2 by the exact multiplicative recurrence of exp(-2 alpha (r - start)) along the nodes.
    const double scale = fog.backscatter_per_m_sr * fog.transmittance_at_start * r_step;
    double attenuation =
        std::exp(-2.0 * fog.extinction_per_m * (static_cast<double>(lo) * r_step - fog.start_m));
    const double attenuation_step = std::exp(-2.0 * fog.extinction_per_m * r_step);
    for (long m = lo; m <= hi; ++m, attenuation *= attenuation_step) {
      double weight = m >= m0 && m <= m1 ? 1.0 : 0.0;
      if (m - m0 < edge_before) weight += left[static_cast<std::size_t>(m - lo)];
      if (m1 - m < edge_before) weight += right[static_cast<std::size_t>(hi - m)];
      const double r = static_cast<double>(m) * r_step;
      // Before a piece beyond the overlap range its 1/r^2 is continued (r > 0.7 r_start > 0
      // there). A piece starting at r = 0 beyond it would have no finite return: the lidar's
      // checks refuse fog at the aperture without an overlap function, so r = 0 is no node's.
      const double geometry =
          piece.inside_overlap ? inside_factor : (r > 0.0 ? 1.0 / (r * r) : 0.0);
      profile[static_cast<std::size_t>(m - m_lo)] += weight * scale * attenuation * geometry;
    }
  }

  // Samples within 2 fwhm of the stretches, and of the record.
  const auto begin = static_cast<long>(first_sample);
  const long end = begin + static_cast<long>(waveform.size());
  const long k_min = std::max(static_cast<long>(k_first), begin);
  const long k_max = std::min(static_cast<long>(k_last), end - 1);
  if (k_max < k_min) return;
  const std::vector<double>& pulse = pulse_[level];
  const long half = half_[level];
  double* out = waveform.data();  // out[k - begin] is sample k
  if (fine == 1) {
    scatter(out, begin, k_min, k_max, profile.data(), m_lo, m_hi, coarse, pulse.data(), half);
    return;
  }
  for (long m = m_lo; m <= m_hi; ++m) {
    const double w = profile[static_cast<std::size_t>(m - m_lo)];
    if (w == 0.0) continue;
    // Samples k with |k fine - m| <= half.
    const long from = std::max(k_min, ceil_div(m - half, fine));
    const long to = std::min(k_max, floor_div(m + half, fine));
    for (long k = from; k <= to; ++k) {
      out[k - begin] += w * pulse[static_cast<std::size_t>(k * fine - m + half)];
    }
  }
}

}  // namespace fogradar::lidar
