#include "fogradar/propagation/fog.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/propagation/droplet.hpp"
#include "fogradar/propagation/visibility.hpp"

namespace fogradar::propagation {
namespace {

// Densest fog accepted: 100 g/m^3 is far beyond natural fog (< 1 g/m^3) but lets users build the
// "artificially lossy" fogs that stress a radar chain; optical extinction and visibility limits
// are the matching optical orders of magnitude.
constexpr double max_lwc_g_per_m3 = 100.0;
constexpr double max_extinction_per_km = 1e6;
constexpr double min_visibility_m = 1e-3;
constexpr double max_visibility_m = 1e7;
// The Liebe model's temperatures (ITU-R P.840).
const Interval liebe_temperatures_c = closed(-20.0, 50.0);

}  // namespace

std::string segelstein_temperature_constraint(std::string_view with_segelstein,
                                              std::string_view with_liebe) {
  return "= " + message_number(segelstein_table_temperature_c) + " with " +
         std::string(with_segelstein) +
         " (a table for about 25 C without temperature dependence); " + std::string(with_liebe) +
         " takes " + liebe_temperatures_c.doc();
}

KeyTable<FogSpec> fog_keys(std::string prefix) {
  KeyTable<FogSpec> keys(prefix);
  const auto holds = [](auto alternative) {
    return
        [](const FogSpec& f) { return std::holds_alternative<decltype(alternative)>(f.density); };
  };
  const std::string one_density = "another density of " + prefix + "lwc_g_per_m3, " + prefix +
                                  "extinction_per_km, " + prefix + "visibility_m is given";
  keys.number(
          "lwc_g_per_m3",
          [](const FogSpec& f) { return std::get<LiquidWaterContent>(f.density).g_per_m3; },
          [](FogSpec& f, double v) { f.density = LiquidWaterContent{v}; },
          closed(0.0, max_lwc_g_per_m3), "liquid water content")
      .when(holds(LiquidWaterContent{}), one_density)
      .in_group("fog density");
  keys.number(
          "extinction_per_km",
          [](const FogSpec& f) { return std::get<OpticalExtinction>(f.density).per_km; },
          [](FogSpec& f, double v) { f.density = OpticalExtinction{v}; },
          closed(0.0, max_extinction_per_km),
          "or: optical extinction β at 550 nm (the study's fog: 900 /km)")
      .when(holds(OpticalExtinction{}), one_density)
      .in_group("fog density");
  keys.number(
          "visibility_m", [](const FogSpec& f) { return std::get<Visibility>(f.density).m; },
          [](FogSpec& f, double v) { f.density = Visibility{v}; },
          closed(min_visibility_m, max_visibility_m), "or: visibility, eq. 6 (2 % contrast)")
      .when(holds(Visibility{}), one_density)
      .in_group("fog density");
  // A table without temperature dependence cannot use any other temperature than its own:
  // refused rather than ignored.
  const std::string temperature_key = prefix + "temperature_c", model_key = prefix + "water_model";
  keys.number("temperature_c", FOGRADAR_KEY_FIELD(temperature_c), liebe_temperatures_c,
              "water temperature of the index at the radar frequency (20 °C: an assumed indoor "
              "hall, the study gives none)")
      .with_check([temperature_key, model_key](const FogSpec& f) {
        if (f.water_model == WaterModel::segelstein &&
            f.temperature_c != segelstein_table_temperature_c) {
          throw_invalid(temperature_key, f.temperature_c,
                        segelstein_temperature_constraint(model_key + " = \"segelstein\"",
                                                          model_key + " = \"liebe\""));
        }
      })
      .documented_as("[-20, 50] with `liebe`; only 25 with `segelstein`");
  keys.choice("water_model", FOGRADAR_KEY_FIELD(water_model), water_model_names,
              "water index at the radar frequency: `liebe` (Liebe 1991 / ITU-R P.840, "
              "temperature dependent, up to 1 THz) or `segelstein` (a table for about 25 °C "
              "without temperature dependence)");
  keys.include(droplet_keys(prefix + "droplets."), FOGRADAR_KEY_FIELD(droplets));
  return keys;
}

void FogSpec::validate() const { fog_keys("fog.").check(*this); }

Fog::Fog(const FogSpec& spec, const SegelsteinTable& table) : spec_(spec), table_(&table) {
  spec_.validate();
  struct ResolveLwc {
    const Fog& fog;
    double operator()(const LiquidWaterContent& d) const { return d.g_per_m3; }
    // Extinction is proportional to LWC at a fixed distribution: LWC = beta / beta(LWC = 1).
    double operator()(const OpticalExtinction& d) const {
      return per_km_to_per_m(d.per_km) / fog.unit_lwc_optical_extinction_per_m();
    }
    double operator()(const Visibility& d) const {
      return extinction_per_m_from_visibility(d.m) / fog.unit_lwc_optical_extinction_per_m();
    }
  };
  lwc_g_per_m3_ = std::visit(ResolveLwc{*this}, spec_.density);
}

double Fog::number_concentration_per_m3() const {
  return propagation::number_concentration_per_m3(spec_.droplets, lwc_g_per_m3_);
}

double Fog::unit_lwc_optical_extinction_per_m() const {
  return sum_cross_sections(visibility_wavelength_m,
                            table_->refractive_index(visibility_wavelength_m), 1.0)
      .extinction_m2;
}

FogOptics Fog::at_frequency(double frequency_hz) const {
  require_positive("frequency_hz", frequency_hz);
  const double wavelength_m = wavelength_from_frequency_m(frequency_hz);
  return bulk_optics(wavelength_m, spec_.water_model, spec_.temperature_c);
}

FogOptics Fog::at_optical_wavelength(double wavelength_m) const {
  return bulk_optics(wavelength_m, WaterModel::segelstein, segelstein_table_temperature_c);
}

double Fog::optical_extinction_per_km() const {
  return per_m_to_per_km(at_optical_wavelength(visibility_wavelength_m).extinction_per_m);
}

double Fog::visibility_m() const {
  const double extinction_per_m = at_optical_wavelength(visibility_wavelength_m).extinction_per_m;
  if (extinction_per_m == 0.0) return std::numeric_limits<double>::infinity();
  return visibility_m_from_extinction(extinction_per_m);
}

CrossSections Fog::sum_cross_sections(double wavelength_m, std::complex<double> index,
                                      double lwc_g_per_m3) const {
  // Bulk coefficient = N sum_j w_j sigma(D_j): the number-weighted mean cross section times N.
  CrossSections total;
  for (const QuadratureNode& node : quadrature_nodes(spec_.droplets)) {
    const CrossSections one = mie_cross_sections(node.diameter_m, wavelength_m, index);
    total.extinction_m2 += node.weight * one.extinction_m2;
    total.scattering_m2 += node.weight * one.scattering_m2;
    total.absorption_m2 += node.weight * one.absorption_m2;
    total.backscatter_m2 += node.weight * one.backscatter_m2;
  }
  const double n = propagation::number_concentration_per_m3(spec_.droplets, lwc_g_per_m3);
  total.extinction_m2 *= n;
  total.scattering_m2 *= n;
  total.absorption_m2 *= n;
  total.backscatter_m2 *= n;
  return total;
}

FogOptics Fog::bulk_optics(double wavelength_m, WaterModel model, double temperature_c) const {
  const std::complex<double> index =
      WaterOptics(model, celsius_to_kelvin(temperature_c), *table_).refractive_index(wavelength_m);
  const CrossSections per_volume = sum_cross_sections(wavelength_m, index, lwc_g_per_m3_);
  FogOptics optics;
  optics.wavelength_m = wavelength_m;
  optics.frequency_hz = frequency_from_wavelength_hz(wavelength_m);
  optics.refractive_index = index;
  optics.water_model = model;
  optics.water_temperature_c = temperature_c;
  optics.extinction_per_m = per_volume.extinction_m2;
  optics.absorption_per_m = per_volume.absorption_m2;
  optics.scattering_per_m = per_volume.scattering_m2;
  // Eq. 5 per metre, reported per km.
  optics.specific_attenuation_db_per_km =
      attenuation_db_per_km(per_m_to_per_km(optics.extinction_per_m));
  optics.volume_backscatter_m2_per_m3 = per_volume.backscatter_m2;
  return optics;
}

double bulk_optics_seconds(const DropSizeDistribution& droplets, double wavelength_m,
                           const MieCost& cost) {
  constexpr std::complex<double> optical_index{1.33, 0.0};
  double seconds = 0.0;
  for (const QuadratureNode& node : quadrature_nodes(droplets)) {
    const double x = size_parameter(node.diameter_m, wavelength_m);
    seconds += cost.seconds_per_node +
               cost.seconds_per_step * static_cast<double>(mie_recurrence_steps(x, optical_index));
  }
  return seconds;
}

double fog_resolution_seconds(const FogSpec& spec, const MieCost& cost) {
  if (std::holds_alternative<LiquidWaterContent>(spec.density)) return 0.0;
  return bulk_optics_seconds(spec.droplets, visibility_wavelength_m, cost);
}

}  // namespace fogradar::propagation
