// Scattering by one homogeneous sphere: Rayleigh closed forms and the Mie series.
//
// The Mie series is that of Bohren & Huffman (1983) ch. 4, written in the ratios
// rho_n(z) = psi_{n+1}(z)/psi_n(z) of Riccati-Bessel functions (as Du 2004, Appl. Opt. 43, 1951,
// does with their inverse) instead of BHMIE's D_n and upward psi_n, so that small droplets keep
// full precision without a separate small-particle branch:
//  * BHMIE's b_n numerator (m D_n(mx) + n/x) psi_n(x) - psi_{n-1}(x) cancels to relative order x^2
//    (its terms are x^n, the result x^(n+2)), and the upward recurrence psi_1 = sin x/x - cos x
//    cancels likewise; at x = 1e-6 both leave ~4 correct digits. With D_n(z) = (n+1)/z - rho_n(z)
//    the (n+1)/x parts cancel analytically, leaving psi_{n+1}(x) - m rho_n(mx) psi_n(x), whose
//    terms are both of the size of the result.
//  * Above n = x, psi_n(x) = psi_{n-1}(x) rho_{n-1}(x) involves no subtraction. Up to n = x the
//    upward recurrence is stable and is kept: anchoring the products at psi_0 = sin x instead
//    would fail near x = k pi (at x = fl(pi), sin x = 1.2e-16 and Qext comes out 3.5 % high).
// Orders above N are not stored, so |mx| >> N costs time, not memory.
#include "fogradar/propagation/droplet.hpp"

#include <algorithm>
#include <boost/container/small_vector.hpp>
#include <cmath>
#include <complex>
#include <cstddef>
#include <sstream>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"

namespace fogradar::propagation {
namespace {

using Complex = std::complex<double>;

// One value per order n = 0..N. Up to N = 31 (x up to ~15) this needs no heap allocation: fog
// droplets at 77 GHz have N <= 4.
template <typename T>
using OrderBuffer = boost::container::small_vector<T, 32>;

void validate_refractive_index(Complex m) {
  const bool valid =
      std::isfinite(m.real()) && std::isfinite(m.imag()) && m.real() > 0.0 && m.imag() >= 0.0;
  if (!valid) {
    std::ostringstream value;
    value.precision(10);
    value << m.real() << (std::signbit(m.imag()) ? " - " : " + ") << std::abs(m.imag()) << "i";
    throw_invalid("refractive_index", value.str(), "finite with Re(m) > 0 and Im(m) >= 0");
  }
}

void validate_geometry(double diameter_m, double wavelength_m) {
  require_positive("diameter_m", diameter_m);
  require_positive("wavelength_m", wavelength_m);
}

// Number of terms N = x + 6 x^(1/3) + 2. Wiscombe 1980 (Appl. Opt. 19, 1505) uses
// x + 4.05 x^(1/3) + 2, where |a_N| ~ 1e-7: enough for Qext and Qsca, which converge like |a_n|^2,
// but the backscatter sum converges like |a_n| and keeps errors of 6e-7 (m = 1.33, x = 1e4).
// Past n = x + t x^(1/3), |a_n| falls like exp(-1.9 t^(3/2)), so t = 6 gives |a_N| ~ 1e-12 for
// 2 x^(1/3) more terms.
int series_length(double x) { return static_cast<int>(x + 6.0 * std::cbrt(x) + 2.0); }

// Order at which the downward recurrence for rho_n(z) starts from rho = 0. An error there shrinks
// by |psi_n(z)/psi_{n-1}(z)|^2 per step down, (psi_start/psi_n)^2 in all. Beyond the turning point
// n = |z| + t |z|^(1/3), psi_n(z) decays like Ai(2^(1/3) t) ~ exp(-0.94 t^(3/2)) (DLMF 10.20), so
// t = 8 leaves < 1e-18 at the turning point. BHMIE's fixed start max(N, |mx|) + 15 is too low
// for real m > 1 and large x: with it, Qext came out 4e-4 low at m = 1.5, x = 1000.
int recurrence_start(double abs_z, int n_max) {
  return static_cast<int>(std::max<double>(n_max, abs_z) + 8.0 * std::cbrt(abs_z)) + 15;
}

// rho_n(z) = psi_{n+1}(z)/psi_n(z) for n = 0..n_max by the downward recurrence
// rho_{n-1} = 1/((2n+1)/z - rho_n), from psi_{n-1} + psi_{n+1} = (2n+1)/z psi_n (DLMF 10.51.1).
template <typename T>
OrderBuffer<T> psi_ratios(T z, int n_max) {
  OrderBuffer<T> rho(static_cast<std::size_t>(n_max) + 1);
  T rho_n{0.0};
  for (int n = recurrence_start(std::abs(z), n_max); n > 0; --n) {
    rho_n = 1.0 / ((2.0 * n + 1.0) / z - rho_n);
    if (n <= n_max + 1) rho[static_cast<std::size_t>(n - 1)] = rho_n;
  }
  return rho;
}

struct MieCoefficients {
  Complex a;
  Complex b;
};

// Riccati-Bessel values at order n needed for a_n, b_n: psi = x j_n(x), chi = -x y_n(x).
struct RiccatiBessel {
  double psi_n;
  double psi_next;  // psi_{n+1}(x)
  double chi_n;
  double chi_prev;  // chi_{n-1}(x)
};

// psi_{n+1}(x) from psi_n, psi_{n-1}: the upward recurrence psi_{n+1} = (2n+1)/x psi_n - psi_{n-1}
// (DLMF 10.51.1) while n + 1 <= x, where it is stable, and psi_n rho_n(x) above (see top of file).
double next_psi(int n, double x, double psi_n, double psi_prev, double rho_x_n) {
  if (n + 1 <= x) return (2.0 * n + 1.0) / x * psi_n - psi_prev;
  return psi_n * rho_x_n;
}

// Mie coefficients (B&H eq. 4.88) with xi_n = psi_n - i chi_n, written a_n = A/(A - i U),
// b_n = B/(B - i V) where
//   A = (D_n(mx)/m + n/x) psi_n - psi_{n-1},  U = (D_n(mx)/m + n/x) chi_n - chi_{n-1},
//   B = (m D_n(mx) + n/x) psi_n - psi_{n-1},  V = (m D_n(mx) + n/x) chi_n - chi_{n-1}.
// With D_n(mx) = (n+1)/(mx) - rho_n(mx) and psi_{n-1} = (2n+1)/x psi_n - psi_{n+1}, A and B lose
// their cancelling parts (see top of file):
//   A = [(n+1)(1 - m^2)/(m^2 x) - rho_n(mx)/m] psi_n + psi_{n+1},
//   B = psi_{n+1} - m rho_n(mx) psi_n.
MieCoefficients mie_coefficients(int n, double x, Complex m, Complex rho_mx,
                                 const RiccatiBessel& f) {
  const double nd = n;
  const Complex m2 = m * m;
  const Complex d_over_m = (nd + 1.0) / (m2 * x) - rho_mx / m;  // D_n(mx)/m
  const Complex a_psi = ((nd + 1.0) * (1.0 - m2) / (m2 * x) - rho_mx / m) * f.psi_n + f.psi_next;
  const Complex b_psi = f.psi_next - m * rho_mx * f.psi_n;
  const Complex a_chi = (d_over_m + nd / x) * f.chi_n - f.chi_prev;
  const Complex b_chi = ((2.0 * nd + 1.0) / x - m * rho_mx) * f.chi_n - f.chi_prev;
  const Complex i{0.0, 1.0};
  return {a_psi / (a_psi - i * a_chi), b_psi / (b_psi - i * b_chi)};
}

// Running sums of the efficiency series (B&H ch. 4; Wiscombe 1980 §I; backscatter B&H §4.6).
struct EfficiencySums {
  double extinction = 0.0;   // sum (2n+1) Re(a_n + b_n)
  double scattering = 0.0;   // sum (2n+1) (|a_n|^2 + |b_n|^2)
  Complex backscatter{0.0};  // sum (2n+1) (-1)^n (a_n - b_n)
  double asymmetry = 0.0;    // the two sums in Wiscombe's g, = g Qsca x^2 / 4
};

// Adds order n; `previous` holds a_{n-1}, b_{n-1} (unused for n = 1).
void accumulate(EfficiencySums& sums, int n, const MieCoefficients& c,
                const MieCoefficients& previous) {
  const double nd = n;
  const double weight = 2.0 * nd + 1.0;
  sums.extinction += weight * (c.a.real() + c.b.real());
  sums.scattering += weight * (std::norm(c.a) + std::norm(c.b));
  sums.backscatter += (n % 2 == 0 ? weight : -weight) * (c.a - c.b);
  sums.asymmetry += weight / (nd * (nd + 1.0)) * (c.a * std::conj(c.b)).real();
  if (n > 1) {
    // n(n+2)/(n+1) Re(a_n a*_{n+1} + b_n b*_{n+1}) written for the pair (n-1, n).
    sums.asymmetry += (nd - 1.0) * (nd + 1.0) / nd *
                      (previous.a * std::conj(c.a) + previous.b * std::conj(c.b)).real();
  }
}

}  // namespace

std::complex<double> clausius_mossotti(std::complex<double> m) {
  validate_refractive_index(m);
  const Complex m2 = m * m;
  return (m2 - 1.0) / (m2 + 2.0);
}

double size_parameter(double diameter_m, double wavelength_m) {
  validate_geometry(diameter_m, wavelength_m);
  return pi * diameter_m / wavelength_m;
}

MieEfficiencies mie_efficiencies(double size_parameter, std::complex<double> m) {
  require_positive("size_parameter", size_parameter);
  validate_refractive_index(m);
  const double x = size_parameter;
  const int n_max = series_length(x);
  const OrderBuffer<Complex> rho_mx = psi_ratios(m * x, n_max);
  const OrderBuffer<double> rho_x = psi_ratios(x, n_max);

  // Orders 0 and 1: psi_0 = sin x, chi_0 = cos x, chi_1 = cos x/x + sin x. chi runs upward,
  // chi_{n+1} = (2n+1)/x chi_n - chi_{n-1}, stable because chi grows with n (BHMIE).
  double psi_prev = std::sin(x);
  double psi_n = next_psi(0, x, psi_prev, std::cos(x), rho_x[0]);
  double chi_prev = std::cos(x);
  double chi_n = chi_prev / x + std::sin(x);
  EfficiencySums sums;
  MieCoefficients previous{};
  for (int n = 1; n <= n_max; ++n) {
    const auto order = static_cast<std::size_t>(n);
    const double psi_next = next_psi(n, x, psi_n, psi_prev, rho_x[order]);
    const MieCoefficients c =
        mie_coefficients(n, x, m, rho_mx[order], {psi_n, psi_next, chi_n, chi_prev});
    accumulate(sums, n, c, previous);
    previous = c;
    const double chi_next = (2.0 * n + 1.0) / x * chi_n - chi_prev;
    psi_prev = psi_n;
    psi_n = psi_next;
    chi_prev = chi_n;
    chi_n = chi_next;
  }

  const double x2 = x * x;
  MieEfficiencies q;
  q.extinction = 2.0 / x2 * sums.extinction;
  q.scattering = 2.0 / x2 * sums.scattering;
  q.absorption = q.extinction - q.scattering;
  q.backscatter = std::norm(sums.backscatter) / x2;
  // An index-matched sphere (m = 1) scatters nothing; its g is 0 rather than 0/0.
  q.asymmetry = q.scattering > 0.0 ? 4.0 / (x2 * q.scattering) * sums.asymmetry : 0.0;
  return q;
}

std::size_t mie_recurrence_steps(double size_parameter, std::complex<double> m) {
  const int n_max = series_length(size_parameter);
  return static_cast<std::size_t>(recurrence_start(std::abs(m * size_parameter), n_max) + n_max);
}

CrossSections mie_cross_sections(double diameter_m, double wavelength_m, std::complex<double> m) {
  const MieEfficiencies q = mie_efficiencies(size_parameter(diameter_m, wavelength_m), m);
  const double area_m2 = pi * diameter_m * diameter_m / 4.0;
  return {q.extinction * area_m2, q.scattering * area_m2, q.absorption * area_m2,
          q.backscatter * area_m2};
}

CrossSections rayleigh_cross_sections(double diameter_m, double wavelength_m,
                                      std::complex<double> m) {
  validate_geometry(diameter_m, wavelength_m);
  const Complex k = clausius_mossotti(m);
  const double d3_over_lambda = std::pow(diameter_m, 3) / wavelength_m;
  const double d6_over_lambda4 = std::pow(diameter_m, 6) / std::pow(wavelength_m, 4);
  const double pi5 = std::pow(pi, 5);
  CrossSections s;
  s.absorption_m2 = pi * pi * d3_over_lambda * k.imag();
  s.scattering_m2 = 2.0 * pi5 / 3.0 * d6_over_lambda4 * std::norm(k);
  s.backscatter_m2 = pi5 * d6_over_lambda4 * std::norm(k);
  s.extinction_m2 = s.absorption_m2 + s.scattering_m2;
  return s;
}

}  // namespace fogradar::propagation
