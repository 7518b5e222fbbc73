// A Mie series written out for the tests independently of propagation/droplet.cpp: the reference
// fogradar's droplet and fog optics are checked against.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <vector>

namespace fogradar::testing {

struct Efficiencies {
  double extinction;
  double scattering;
};

// Bohren & Huffman 1983 Appendix A (BHMIE): a_n, b_n from the logarithmic derivative D_n(mx),
// recurred downwards from n = max(n_stop, |mx|) + 15, and the Riccati-Bessel functions of x
// recurred upwards; n_stop = x + 4 x^(1/3) + 2. Q_ext = 2/x^2 sum (2n+1) Re(a_n + b_n),
// Q_sca = 2/x^2 sum (2n+1) (|a_n|^2 + |b_n|^2). Index m = n + ik with k >= 0.
inline Efficiencies bhmie(double x, std::complex<double> m) {
  const int n_stop = static_cast<int>(x + 4.0 * std::cbrt(x) + 2.0);
  const std::complex<double> y = m * x;
  const int n_max = static_cast<int>(std::max<double>(n_stop, std::abs(y))) + 15;
  std::vector<std::complex<double>> d(static_cast<std::size_t>(n_max) + 1);
  for (int n = n_max; n > 0; --n) {
    const std::complex<double> n_over_y = static_cast<double>(n) / y;
    d[static_cast<std::size_t>(n) - 1] =
        n_over_y - 1.0 / (d[static_cast<std::size_t>(n)] + n_over_y);
  }
  double psi0 = std::cos(x), psi1 = std::sin(x), chi0 = -std::sin(x), chi1 = std::cos(x);
  std::complex<double> xi1{psi1, -chi1};
  double q_ext = 0.0, q_sca = 0.0;
  for (int n = 1; n <= n_stop; ++n) {
    const double fn = static_cast<double>(n);
    const double psi = (2.0 * fn - 1.0) / x * psi1 - psi0;
    const double chi = (2.0 * fn - 1.0) / x * chi1 - chi0;
    const std::complex<double> xi{psi, -chi};
    const std::complex<double> dn = d[static_cast<std::size_t>(n)];
    const std::complex<double> a =
        ((dn / m + fn / x) * psi - psi1) / ((dn / m + fn / x) * xi - xi1);
    const std::complex<double> b =
        ((dn * m + fn / x) * psi - psi1) / ((dn * m + fn / x) * xi - xi1);
    q_ext += (2.0 * fn + 1.0) * (a.real() + b.real());
    q_sca += (2.0 * fn + 1.0) * (std::norm(a) + std::norm(b));
    psi0 = psi1;
    psi1 = psi;
    chi0 = chi1;
    chi1 = chi;
    xi1 = xi;
  }
  return {2.0 / (x * x) * q_ext, 2.0 / (x * x) * q_sca};
}

}  // namespace fogradar::testing
