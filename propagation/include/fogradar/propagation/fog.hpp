// A fog: its density (LWC, optical extinction at 550 nm, or visibility), droplets and temperature,
// resolved into bulk optical properties at any frequency by quadrature over the drop sizes.
#pragma once

#include <complex>
#include <string>
#include <string_view>
#include <variant>

#include "fogradar/propagation/droplet.hpp"
#include "fogradar/propagation/dsd.hpp"
#include "fogradar/propagation/water.hpp"

namespace fogradar::propagation {

// Wavelength at which fog density and visibility are defined (paper sec. I).
inline constexpr double visibility_wavelength_m = 550e-9;

struct LiquidWaterContent {
  double g_per_m3 = 0.1;
  bool operator==(const LiquidWaterContent&) const = default;
};
// Optical (550 nm) extinction coefficient beta.
struct OpticalExtinction {
  double per_km = 900.0;
  bool operator==(const OpticalExtinction&) const = default;
};
// Visual range, eq. 6 (2 % contrast at 550 nm).
struct Visibility {
  double m = 100.0;
  bool operator==(const Visibility&) const = default;
};
using FogDensity = std::variant<LiquidWaterContent, OpticalExtinction, Visibility>;

struct FogSpec {
  FogDensity density = OpticalExtinction{};
  DropSizeDistribution droplets = default_fog_droplets();
  // Water temperature of the index at radar frequencies: 20 C (an assumed indoor hall; the study
  // gives none) under Liebe, the temperature-dependent model of ITU-R P.840. With the Segelstein
  // table only its own 25 C is accepted. Optical wavelengths always use the table at 25 C (Liebe
  // ends at 1 THz; docs/physics.md §2 quantifies what the optical temperature dependence would
  // change).
  double temperature_c = 20.0;
  WaterModel water_model = WaterModel::liebe;
  void validate() const;  // throws InvalidParameter naming the key under "fog." (fog_keys)
  bool operator==(const FogSpec&) const = default;
};

// The scenario keys of a fog under `prefix` ("fog."): one density of the group lwc_g_per_m3,
// extinction_per_km, visibility_m (the one given replaces the others), the temperature and water
// model of the index at radar frequencies, and the droplets under "droplets." (droplet_keys).
KeyTable<FogSpec> fog_keys(std::string prefix);

// The temperatures the water index takes, as a message states them after "must be ": only the
// Segelstein table's own under `with_segelstein` (the water model named as the user writes it:
// "fog.water_model = \"segelstein\"", "--water-model segelstein"), Liebe's range under
// `with_liebe`.
std::string segelstein_temperature_constraint(std::string_view with_segelstein,
                                              std::string_view with_liebe);

// Bulk properties of a fog at one frequency (sums over the drop size distribution, Mie per
// droplet).
struct FogOptics {
  double frequency_hz = 0.0;
  double wavelength_m = 0.0;
  std::complex<double> refractive_index;            // of water at this frequency
  WaterModel water_model = WaterModel::segelstein;  // the model and temperature that gave the index
  double water_temperature_c = segelstein_table_temperature_c;
  double extinction_per_m = 0.0;  // power extinction coefficient
  double absorption_per_m = 0.0;
  double scattering_per_m = 0.0;
  double specific_attenuation_db_per_km = 0.0;  // 10 log10(e) * 1000 * extinction_per_m
  double volume_backscatter_m2_per_m3 = 0.0;    // eta = N <sigma_b>
};

// The cost model of a Fog's Mie sums, for the run-time estimate (experiment/run_time.hpp): each
// quadrature node of the droplets costs a fixed part and its recurrence steps
// (mie_recurrence_steps at water's optical index, 1.33: at radio wavelengths the droplets are too
// small for the index to change the count). Per-unit constants measured by bench/
// estimate_calibration (docs/scenario.md, "Time limit").
struct MieCost {
  double seconds_per_node = 0.0;
  double seconds_per_step = 0.0;
};
inline constexpr MieCost mie_cost{.seconds_per_node = 1.49e-8, .seconds_per_step = 2.28e-8};
// CPU seconds of one bulk evaluation (Fog::at_frequency, Fog::at_optical_wavelength) of these
// droplets at `wavelength_m`.
double bulk_optics_seconds(const DropSizeDistribution& droplets, double wavelength_m,
                           const MieCost& cost = mie_cost);
// CPU seconds of constructing a Fog of `spec`: one bulk evaluation at 550 nm unless its density
// is an LWC.
double fog_resolution_seconds(const FogSpec& spec, const MieCost& cost = mie_cost);

// A fog with its LWC resolved: for OpticalExtinction or Visibility the LWC follows from Mie at
// 550 nm over the drop size distribution (Segelstein index).
class Fog {
 public:
  Fog(const FogSpec& spec, const SegelsteinTable& table);

  double lwc_g_per_m3() const { return lwc_g_per_m3_; }
  double number_concentration_per_m3() const;
  const FogSpec& spec() const { return spec_; }

  // Bulk properties at a frequency, water index from the spec's water model and temperature.
  FogOptics at_frequency(double frequency_hz) const;
  // Bulk properties at an optical wavelength (always the Segelstein table, at its own 25 C).
  FogOptics at_optical_wavelength(double wavelength_m) const;

  double optical_extinction_per_km() const;  // beta at 550 nm
  double visibility_m() const;               // eq. 6; infinite without water

 private:
  // Water index from `model` at `temperature_c`.
  FogOptics bulk_optics(double wavelength_m, WaterModel model, double temperature_c) const;
  // Per-volume cross sections (1/m) of the distribution holding lwc_g_per_m3 of water.
  CrossSections sum_cross_sections(double wavelength_m, std::complex<double> index,
                                   double lwc_g_per_m3) const;
  double unit_lwc_optical_extinction_per_m() const;

  FogSpec spec_;
  const SegelsteinTable* table_;
  double lwc_g_per_m3_ = 0.0;
};

}  // namespace fogradar::propagation
