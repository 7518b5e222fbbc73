#include "fogradar/propagation/visibility.hpp"

#include <algorithm>
#include <cmath>

#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"

namespace fogradar::propagation {
namespace {

constexpr double visibility_reference_wavelength_nm = 550.0;
// -ln(0.02) = 3.912; the study's eq. 1 rounds it to 3.91.
const double koschmieder_constant = -std::log(visual_range_contrast);

// q above 6 km, common to Kruse and Kim (paper eq. 2 context; Kim et al. 2001 eq. 3).
double q_clear_air(double visibility_km) { return visibility_km > 50.0 ? 1.6 : 1.3; }

double wavelength_scaled_extinction_per_km(double visibility_km, double wavelength_nm, double q) {
  require_positive("wavelength_nm", wavelength_nm);
  return koschmieder_constant / visibility_km *
         std::pow(wavelength_nm / visibility_reference_wavelength_nm, -q);
}

}  // namespace

// Eq. 5.
double attenuation_db_per_km(double extinction_per_km) {
  require_non_negative("extinction_per_km", extinction_per_km);
  return db_per_neper_power * extinction_per_km;
}

// Eq. 6.
double visibility_m_from_extinction(double extinction_per_m) {
  require_positive("extinction_per_m", extinction_per_m);
  return koschmieder_constant / extinction_per_m;
}

double extinction_per_m_from_visibility(double visibility_m) {
  require_positive("visibility_m", visibility_m);
  return koschmieder_constant / visibility_m;
}

// Eq. 9.
double meteorological_visibility_m(double extinction_per_m) {
  require_positive("extinction_per_m", extinction_per_m);
  return -std::log(cie_contrast) / extinction_per_m;
}

// Kunkel 1984: beta = 144.7 LWC^0.88.
double kunkel_extinction_per_km(double lwc_g_per_m3) {
  require_non_negative("lwc_g_per_m3", lwc_g_per_m3);
  return 144.7 * std::pow(lwc_g_per_m3, 0.88);
}

double kunkel_lwc_g_per_m3(double extinction_per_km) {
  require_non_negative("extinction_per_km", extinction_per_km);
  return std::pow(extinction_per_km / 144.7, 1.0 / 0.88);
}

// Paper eq. 2 and its clear-air branches.
double kruse_q(double visibility_km) {
  require_positive("visibility_km", visibility_km);
  if (visibility_km > 6.0) return q_clear_air(visibility_km);
  return 0.585 * std::cbrt(visibility_km);
}

// Kim et al. 2001.
double kim_q(double visibility_km) {
  require_positive("visibility_km", visibility_km);
  if (visibility_km > 6.0) return q_clear_air(visibility_km);
  if (visibility_km > 1.0) return 0.16 * visibility_km + 0.34;
  if (visibility_km > 0.5) return visibility_km - 0.5;
  return 0.0;
}

// Paper eq. 1, read as an extinction coefficient (see header).
double kruse_extinction_per_km(double visibility_km, double wavelength_nm) {
  return wavelength_scaled_extinction_per_km(visibility_km, wavelength_nm, kruse_q(visibility_km));
}

double kim_extinction_per_km(double visibility_km, double wavelength_nm) {
  return wavelength_scaled_extinction_per_km(visibility_km, wavelength_nm, kim_q(visibility_km));
}

std::vector<OpticalModelExtinction> optical_model_table(std::span<const OpticalModel> models,
                                                        double mie_extinction_per_km,
                                                        double visibility_m, double wavelength_nm) {
  std::vector<OpticalModelExtinction> rows = {
      {OpticalModel::mie, mie_extinction_per_km, std::nullopt}};
  const bool clear = !std::isfinite(visibility_m);
  const double visibility_km = visibility_m * 1e-3;
  const auto eq1 = [&](OpticalModel model, double (*extinction_per_km)(double, double),
                       double (*q)(double)) {
    if (std::find(models.begin(), models.end(), model) == models.end()) return;
    rows.push_back({model, clear ? 0.0 : extinction_per_km(visibility_km, wavelength_nm),
                    clear ? std::nullopt : std::optional(q(visibility_km))});
  };
  eq1(OpticalModel::kruse, kruse_extinction_per_km, kruse_q);
  eq1(OpticalModel::kim, kim_extinction_per_km, kim_q);
  return rows;
}

}  // namespace fogradar::propagation
