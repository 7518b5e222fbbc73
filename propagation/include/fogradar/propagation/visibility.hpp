// Optical extinction, attenuation and visibility (paper eq. 1, 2, 5, 6, 9; Kunkel; Kim).
// beta is an extinction coefficient of power (1/km or 1/m as named). The study's eq. 1 prints
// "dB/km", but 3.91 = -ln(0.02) makes it an extinction coefficient beta in 1/km (power ~ exp(-beta
// d)): the Kruse functions below return beta in 1/km; multiply by 10 log10(e) (eq. 5) for dB/km.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "fogradar/core/enum_names.hpp"

namespace fogradar::propagation {

// Contrast thresholds: Koschmieder/visual range (paper eq. 6, epsilon = 0.02) and CIE
// meteorological optical range (paper eq. 9, 0.05).
inline constexpr double visual_range_contrast = 0.02;
inline constexpr double cie_contrast = 0.05;

// Eq. 5: specific attenuation A (dB/km) = 10 log10(e) beta (1/km).
double attenuation_db_per_km(double extinction_per_km);

// Eq. 6: V = -ln(0.02) / beta.
double visibility_m_from_extinction(double extinction_per_m);
double extinction_per_m_from_visibility(double visibility_m);

// Eq. 9: CIE meteorological visibility d_m = -ln(0.05) / beta.
double meteorological_visibility_m(double extinction_per_m);

// Kunkel 1984 (J. Climate Appl. Meteor. 23, 34): beta(550 nm) = 144.7 LWC^0.88, beta in 1/km,
// LWC in g/m^3.
double kunkel_extinction_per_km(double lwc_g_per_m3);
double kunkel_lwc_g_per_m3(double extinction_per_km);

// Kruse, McGlauchlin & McQuistan 1962, paper eq. 2: q = 1.6 (V > 50 km), 1.3 (6 < V <= 50 km),
// 0.585 V^(1/3) (V <= 6 km).
double kruse_q(double visibility_km);

// Kim, McArthur & Korevaar 2001 (Proc. SPIE 4214): q = 1.6 (V > 50), 1.3 (6 < V <= 50),
// 0.16 V + 0.34 (1 < V <= 6), V - 0.5 (0.5 < V <= 1), 0 (V <= 0.5), V in km.
double kim_q(double visibility_km);

// Paper eq. 1: beta(lambda) = (3.91 / V) (lambda / 550 nm)^(-q), V in km, beta in 1/km.
double kruse_extinction_per_km(double visibility_km, double wavelength_nm);
double kim_extinction_per_km(double visibility_km, double wavelength_nm);

// The study's optical attenuation models: Mie over the fog's droplets, eq. 1 with Kruse's q (eq. 2)
// and eq. 1 with Kim's q.
enum class OpticalModel { mie, kruse, kim };
inline constexpr auto optical_model_names = enum_names<OpticalModel>(
    {{OpticalModel::mie, "mie"}, {OpticalModel::kruse, "kruse"}, {OpticalModel::kim, "kim"}});

// One model's extinction at one wavelength.
struct OpticalModelExtinction {
  OpticalModel model = OpticalModel::mie;
  double extinction_per_km = 0.0;
  std::optional<double> q;  // eq. 1's wavelength exponent: Kruse's and Kim's, none without water
};

// The models' extinction at `wavelength_nm` for a fog whose Mie extinction there is
// `mie_extinction_per_km` and whose eq. 6 visibility is `visibility_m` (infinite without water):
// Mie first, then Kruse and Kim where `models` names them. Eq. 1's 3.91 is -ln 0.02, the 2 %
// contrast of eq. 6, so at 550 nm Kruse and Kim give the fog's own extinction; without water eq. 1
// gives none (its limit as V grows without bound) and no q.
std::vector<OpticalModelExtinction> optical_model_table(std::span<const OpticalModel> models,
                                                        double mie_extinction_per_km,
                                                        double visibility_m, double wavelength_nm);

}  // namespace fogradar::propagation
