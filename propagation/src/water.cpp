#include "fogradar/propagation/water.hpp"

#include <math.h>  // Boost 1.74 pchip.hpp calls unqualified isnan(): needs ::isnan

#include <algorithm>
#include <boost/math/interpolators/pchip.hpp>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fogradar/core/constants.hpp"
#include "fogradar/core/detail/text_fields.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::propagation {

namespace detail {
// Text of data/segelstein81_index.txt, embedded at build time by cmake/EmbedText.cmake.
std::string_view segelstein81_table_text();
}  // namespace detail

namespace {

using fogradar::detail::parse_number;
using fogradar::detail::take_field;

using Pchip = boost::math::interpolators::pchip<std::vector<double>>;

// Layout of data/segelstein81_index.txt: citation, blank line, column titles, then rows of
// wavelength (um), n, k separated by tabs.
constexpr std::size_t segelstein_header_lines = 4;
constexpr std::size_t segelstein_row_count = 1261;

// Validity of the Liebe/P.840 fit: below 1 THz (Liebe et al. 1991 title and abstract); the
// temperature span is the one water.hpp documents, -20..50 C, supercooled cloud water included.
// The kelvin bounds are converted as callers convert their Celsius values (-20 + 273.15 rounds
// below 253.15), so a temperature at a documented bound is accepted.
constexpr double liebe_max_frequency_hz = 1e12;
constexpr double liebe_min_temperature_k = celsius_to_kelvin(-20.0);
constexpr double liebe_max_temperature_k = celsius_to_kelvin(50.0);

// ---- Segelstein table parsing -------------------------------------------------------------

struct SegelsteinRows {
  std::vector<double> wavelength_m;
  std::vector<double> n;
  std::vector<double> k;
};

SegelsteinRows parse_segelstein_table(std::string_view text) {
  for (std::size_t line = 0; line < segelstein_header_lines; ++line) take_field(text, '\n');
  SegelsteinRows rows;
  while (!text.empty()) {
    std::string_view line = take_field(text, '\n');
    if (line.empty()) continue;
    // Division, not multiplication by 1e-6, so that 3800 um parses to the double nearest 3.8e-3 m.
    rows.wavelength_m.push_back(parse_number(take_field(line, '\t')) / 1e6);
    rows.n.push_back(parse_number(take_field(line, '\t')));
    rows.k.push_back(parse_number(line));
  }
  // The table is compiled in: a malformed one is a build defect, not bad user input.
  FOGRADAR_CHECK(rows.wavelength_m.size() == segelstein_row_count);
  FOGRADAR_CHECK(std::is_sorted(rows.wavelength_m.begin(), rows.wavelength_m.end()));
  FOGRADAR_CHECK(std::all_of(rows.n.begin(), rows.n.end(), [](double v) { return v > 0.0; }));
  FOGRADAR_CHECK(std::all_of(rows.k.begin(), rows.k.end(), [](double v) { return v > 0.0; }));
  return rows;
}

std::vector<double> logs_of(const std::vector<double>& values) {
  std::vector<double> logs(values.size());
  std::transform(values.begin(), values.end(), logs.begin(), [](double v) { return std::log(v); });
  return logs;
}

// ---- Liebe et al. 1991 double-Debye model, in the notation of ITU-R P.840-8 Annex 1 §2 -----
// Constants checked against three independent transcriptions of the same equations:
// ic-crc/crc-covlib python-wrapper/crc_covlib/helper/itur_p840.py (P.840-9 Annex 1 §2),
// lloda/prop-618 src/prop.f90 (P.840-7, whose equation numbers are quoted below) and atmlab
// eps_water_liebe93.m (Liebe et al. 1993, AGARD CP-542, the version P.840 reproduces).
// Maetzler's epswater.m (Liebe 1991, theta' = 1 - 300/T) has the same fit with 146.4 for 146.

// Inverse temperature variable: theta = 300 / T  (P.840 eq. 9).
double liebe_theta(double temperature_k) { return 300.0 / temperature_k; }

// Static permittivity: eps0 = 77.66 + 103.3 (theta - 1)  (P.840 eq. 6).
double liebe_static_permittivity(double theta) { return 77.66 + 103.3 * (theta - 1.0); }

// Intermediate high-frequency permittivity: eps1 = 0.0671 eps0  (P.840 eq. 7).
double liebe_eps1(double eps0) { return 0.0671 * eps0; }

// Optical-limit permittivity: eps2 = 3.52  (P.840 eq. 8; Liebe 1991 had 3.52 + 7.52 (1 - theta)).
constexpr double liebe_eps2 = 3.52;

// Principal relaxation frequency: fp = 20.20 - 146 (theta - 1) + 316 (theta - 1)^2 GHz (eq. 10).
double liebe_principal_relaxation_ghz(double theta) {
  const double x = theta - 1.0;
  return 20.20 - 146.0 * x + 316.0 * x * x;
}

// Secondary relaxation frequency: fs = 39.8 fp  (P.840 eq. 11).
double liebe_secondary_relaxation_ghz(double fp_ghz) { return 39.8 * fp_ghz; }

// One Debye term delta / (1 - i f/fr): real delta / (1 + (f/fr)^2), imaginary
// delta (f/fr) / (1 + (f/fr)^2): one term each of P.840's eps' (eq. 5) and eps'' (eq. 4) sums.
std::complex<double> debye_term(double delta, double frequency_ghz, double relaxation_ghz) {
  const double x = frequency_ghz / relaxation_ghz;
  const double denominator = 1.0 + x * x;
  return {delta / denominator, delta * x / denominator};
}

}  // namespace

// ---- Segelstein table -----------------------------------------------------------------------

// Interpolators are built once here and only read afterwards, so concurrent const calls are safe.
struct SegelsteinTable::Impl {
  SegelsteinRows rows;
  double log_min_wavelength;
  double log_max_wavelength;
  Pchip log_n;
  Pchip log_k;

  explicit Impl(SegelsteinRows parsed)
      : rows(std::move(parsed)),
        log_min_wavelength(std::log(rows.wavelength_m.front())),
        log_max_wavelength(std::log(rows.wavelength_m.back())),
        log_n(logs_of(rows.wavelength_m), logs_of(rows.n)),
        log_k(logs_of(rows.wavelength_m), logs_of(rows.k)) {}
};

SegelsteinTable::SegelsteinTable()
    : impl_(new Impl(parse_segelstein_table(detail::segelstein81_table_text()))) {}

SegelsteinTable::~SegelsteinTable() { delete impl_; }

std::complex<double> SegelsteinTable::refractive_index(double wavelength_m) const {
  require_in_range("wavelength_m", wavelength_m, min_wavelength_m(), max_wavelength_m());
  // Clamp guards against log() rounding a bound-inclusive wavelength just outside the grid.
  const double log_wavelength =
      std::clamp(std::log(wavelength_m), impl_->log_min_wavelength, impl_->log_max_wavelength);
  return {std::exp(impl_->log_n(log_wavelength)), std::exp(impl_->log_k(log_wavelength))};
}

double SegelsteinTable::min_wavelength_m() const { return impl_->rows.wavelength_m.front(); }
double SegelsteinTable::max_wavelength_m() const { return impl_->rows.wavelength_m.back(); }
std::span<const double> SegelsteinTable::wavelengths_m() const { return impl_->rows.wavelength_m; }
std::span<const double> SegelsteinTable::real_index() const { return impl_->rows.n; }
std::span<const double> SegelsteinTable::imag_index() const { return impl_->rows.k; }

// ---- Liebe permittivity and P.840 attenuation coefficient -----------------------------------

std::complex<double> liebe1991_permittivity(double frequency_hz, double temperature_k) {
  if (!(frequency_hz > 0.0 && frequency_hz <= liebe_max_frequency_hz)) {
    throw_invalid("frequency_hz", frequency_hz, "in (0, 1e12] (Liebe 1991 model, up to 1 THz)");
  }
  require_in_range("temperature_k", temperature_k, liebe_min_temperature_k,
                   liebe_max_temperature_k);
  const double frequency_ghz = frequency_hz * 1e-9;
  const double theta = liebe_theta(temperature_k);
  const double eps0 = liebe_static_permittivity(theta);
  const double eps1 = liebe_eps1(eps0);
  const double fp_ghz = liebe_principal_relaxation_ghz(theta);
  const double fs_ghz = liebe_secondary_relaxation_ghz(fp_ghz);
  // eps = eps2 + (eps0 - eps1)/(1 - i f/fp) + (eps1 - eps2)/(1 - i f/fs)  (P.840 eqs. 4-5).
  return liebe_eps2 + debye_term(eps0 - eps1, frequency_ghz, fp_ghz) +
         debye_term(eps1 - liebe_eps2, frequency_ghz, fs_ghz);
}

std::complex<double> refractive_index_from_permittivity(std::complex<double> permittivity) {
  // The principal root has Re(m) >= 0, hence Im(m) >= 0 whenever eps'' >= 0 (a passive medium);
  // the sign flip keeps the header's Im(m) >= 0 contract for any input.
  const std::complex<double> m = std::sqrt(permittivity);
  return m.imag() < 0.0 ? -m : m;
}

double itu_p840_specific_attenuation_coefficient(double frequency_hz, double temperature_k) {
  const std::complex<double> eps = liebe1991_permittivity(frequency_hz, temperature_k);
  const double frequency_ghz = frequency_hz * 1e-9;
  // eta = (2 + eps') / eps'' (eq. 3); K_l = 0.819 f / (eps'' (1 + eta^2)) (dB/km)/(g/m^3) (eq. 2).
  const double eta = (2.0 + eps.real()) / eps.imag();
  return 0.819 * frequency_ghz / (eps.imag() * (1.0 + eta * eta));
}

// ---- Model selection ------------------------------------------------------------------------

WaterOptics::WaterOptics(WaterModel model, double temperature_k, const SegelsteinTable& table)
    : model_(model), temperature_k_(temperature_k), table_(&table) {
  require_in_range("temperature_k", temperature_k, liebe_min_temperature_k,
                   liebe_max_temperature_k);
  if (model == WaterModel::segelstein &&
      temperature_k != celsius_to_kelvin(segelstein_table_temperature_c)) {
    throw_invalid("temperature_k", temperature_k,
                  "= " + std::to_string(celsius_to_kelvin(segelstein_table_temperature_c)) +
                      " with the segelstein model (a table for about 25 C without temperature "
                      "dependence); the liebe model takes [253.15, 323.15]");
  }
}

std::complex<double> WaterOptics::refractive_index(double wavelength_m) const {
  switch (model_) {
    case WaterModel::segelstein:
      return table_->refractive_index(wavelength_m);
    case WaterModel::liebe: {
      require_positive("wavelength_m", wavelength_m);
      const double frequency_hz = frequency_from_wavelength_hz(wavelength_m);
      if (frequency_hz > liebe_max_frequency_hz) {
        throw_invalid("wavelength_m", wavelength_m,
                      ">= 2.99792458e-4 (c / 1 THz, upper frequency limit of the Liebe model)");
      }
      return refractive_index_from_permittivity(
          liebe1991_permittivity(frequency_hz, temperature_k_));
    }
  }
  check_failed("WaterModel has a value outside the enum", __FILE__, __LINE__);
}

}  // namespace fogradar::propagation
