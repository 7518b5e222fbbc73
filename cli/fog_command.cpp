// `fogradar fog`: the fog's water index, attenuation and backscatter at a (radar) frequency,
// optical extinction and visibility (docs/physics.md), and one layer of it as each sensor of the
// paper scenario sees it (sensor::SensorType::fog_report).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "checks.hpp"
#include "commands.hpp"
#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::cli {
namespace {

struct FogOptions {
  double frequency_ghz = 77.0;
  std::string frequency_typed = "77";  // --frequency-ghz as typed, for the message that refuses it
  std::optional<double> lwc_g_per_m3;
  std::optional<double> extinction_per_km;
  std::optional<double> visibility_m;
  std::optional<double> diameter_um;
  std::optional<double>
      temperature_c;  // absent: 20 C under Liebe, the table's own under Segelstein
  std::string water_model = "liebe";
  double layer_length_m = 1.0;  // the study's layer f_i
  bool json = false;
};

// The fog through one layer of `layer_length_m` as each of the paper scenario's sensors sees it,
// resolved by the sensor modules themselves (the radar at its sweep centre, the lidar's Mie at its
// wavelength, the camera's band quadrature), so these are the numbers a run uses.
std::vector<std::pair<std::string, sensor::FogReport>> sensor_reports(
    const propagation::FogSpec& spec, double layer_length_m,
    const propagation::SegelsteinTable& table) {
  const experiment::Scenario paper = experiment::paper_scenario();
  std::vector<std::pair<std::string, sensor::FogReport>> reports;
  for (const experiment::SensorSetting& setting : paper.sensors) {
    reports.emplace_back(setting.type->name(),
                         setting.type->fog_report(setting.params, spec, layer_length_m, table));
  }
  return reports;
}

// The argument names the user typed, so errors name them rather than internal fields.
propagation::FogSpec fog_spec_from(const FogOptions& o) {
  // The water table spans 10 nm .. 10 m, i.e. 0.03 GHz .. 3e7 GHz; Liebe's model ends at 1 THz.
  // The option's own check allows the table's span: beyond Liebe's the user is told the model
  // that covers the frequency.
  if (o.water_model == "liebe" && o.frequency_ghz > 1000.0) {
    throw_invalid("--frequency-ghz", o.frequency_typed,
                  "in [0.03, 1000] with --water-model liebe (Liebe 1991 ends at 1 THz); "
                  "--water-model segelstein covers [0.03, 2.99e7]");
  }
  propagation::FogSpec spec;
  if (o.lwc_g_per_m3) {
    require_in_range("--lwc", *o.lwc_g_per_m3, 0.0, 100.0);
    spec.density = propagation::LiquidWaterContent{*o.lwc_g_per_m3};
  } else if (o.extinction_per_km) {
    require_in_range("--extinction-per-km", *o.extinction_per_km, 0.0, 1e6);
    spec.density = propagation::OpticalExtinction{*o.extinction_per_km};
  } else if (o.visibility_m) {
    require_in_range("--visibility-m", *o.visibility_m, 1e-3, 1e7);
    spec.density = propagation::Visibility{*o.visibility_m};
  }
  if (o.diameter_um) {
    require_in_range("--diameter-um", *o.diameter_um, 0.01, 1000.0);
    spec.droplets = propagation::Monodisperse{*o.diameter_um * 1e-6};
  }
  spec.water_model = propagation::parse_water_model(o.water_model, "--water-model");
  if (spec.water_model == propagation::WaterModel::segelstein) {
    spec.temperature_c = propagation::segelstein_table_temperature_c;
    if (o.temperature_c && *o.temperature_c != spec.temperature_c) {
      throw_invalid(
          "--temperature-c", *o.temperature_c,
          "= 25 with --water-model segelstein (a table for about 25 C without temperature "
          "dependence); --water-model liebe takes [-20, 50]");
    }
  } else if (o.temperature_c) {
    require_in_range("--temperature-c", *o.temperature_c, -20.0, 50.0);
    spec.temperature_c = *o.temperature_c;
  }
  return spec;
}

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// The model and temperature that gave a water index, as the user should read them.
std::string water_source(const propagation::FogOptics& optics) {
  std::ostringstream text;
  if (optics.water_model == propagation::WaterModel::segelstein) {
    text << "Segelstein table, for its own " << optics.water_temperature_c << " C";
  } else {
    text << "Liebe 1991, " << optics.water_temperature_c << " C";
  }
  return text.str();
}

void run_fog(const FogOptions& options) {
  const propagation::FogSpec spec = fog_spec_from(options);
  const propagation::SegelsteinTable table;
  const propagation::Fog fog(spec, table);
  const propagation::FogOptics at_frequency = fog.at_frequency(options.frequency_ghz * 1e9);
  const propagation::FogOptics optical =
      fog.at_optical_wavelength(propagation::visibility_wavelength_m);
  const double optical_extinction_per_km = fog.optical_extinction_per_km();
  const double visibility_m = fog.visibility_m();
  const auto reports = sensor_reports(spec, options.layer_length_m, table);

  if (options.json) {
    nlohmann::json out = {
        {"frequency_hz", at_frequency.frequency_hz},
        {"wavelength_m", at_frequency.wavelength_m},
        {"refractive_index_n", at_frequency.refractive_index.real()},
        {"refractive_index_k", at_frequency.refractive_index.imag()},
        {"water_model", propagation::to_string(at_frequency.water_model)},
        {"temperature_c", at_frequency.water_temperature_c},
        {"optical_water_model", propagation::to_string(optical.water_model)},
        {"optical_water_temperature_c", optical.water_temperature_c},
        {"droplets", propagation::distribution_name(spec.droplets)},
        {"lwc_g_per_m3", fog.lwc_g_per_m3()},
        {"number_concentration_per_cm3", fog.number_concentration_per_m3() * 1e-6},
        {"specific_attenuation_db_per_km", at_frequency.specific_attenuation_db_per_km},
        {"volume_backscatter_m2_per_m3", at_frequency.volume_backscatter_m2_per_m3},
        {"optical_extinction_per_km", optical_extinction_per_km},
        {"visibility_m", number_or_null(visibility_m)},
        {"layer_length_m", options.layer_length_m},
    };
    nlohmann::json& sensors = out["sensors"] = nlohmann::json::object();
    for (const auto& [name, report] : reports) sensors[name] = report.json;
    std::cout << out.dump(2) << '\n';
    return;
  }
  std::cout << std::setprecision(6) << "frequency                 "
            << at_frequency.frequency_hz * 1e-9 << " GHz (wavelength "
            << at_frequency.wavelength_m * 1e3 << " mm)\n"
            << "water index m = n + ik    " << at_frequency.refractive_index.real() << " + "
            << at_frequency.refractive_index.imag() << "i (" << water_source(at_frequency) << ")\n"
            << "droplets                  " << propagation::distribution_name(spec.droplets) << ", "
            << fog.number_concentration_per_m3() * 1e-6 << " per cm^3\n"
            << "liquid water content      " << fog.lwc_g_per_m3() << " g/m^3\n"
            << "specific attenuation      " << at_frequency.specific_attenuation_db_per_km
            << " dB/km\n"
            << "volume backscatter eta    " << at_frequency.volume_backscatter_m2_per_m3
            << " m^2/m^3\n"
            << "optical extinction 550 nm " << optical_extinction_per_km << " 1/km (water index "
            << water_source(optical) << ")\n"
            << "visibility (eq. 6, 2 %)   " << visibility_m << " m\n"
            << "through one layer of " << options.layer_length_m
            << " m, as the paper scenario's sensors see it:\n";
  for (const auto& [name, report] : reports) std::cout << report.line << '\n';
}

}  // namespace

Action add_fog_command(CLI::App& app) {
  auto options = std::make_shared<FogOptions>();
  CLI::App* fog = app.add_subcommand("fog",
                                     "Water index, attenuation and backscatter at a frequency, "
                                     "optical extinction and visibility of "
                                     "a fog, and each sensor's view of one layer of it");
  fog->add_option("--frequency-ghz", options->frequency_ghz, "Radar frequency in GHz")
      ->capture_default_str()
      ->check(number_in("--frequency-ghz", 0.03, 2.99e7,
                        "in [0.03, 1000] with --water-model liebe, [0.03, 2.99e7] with segelstein"))
      ->check(CLI::Validator(
          [options](const std::string& text) {
            options->frequency_typed = text;
            return std::string();
          },
          "", ""));
  auto* lwc =
      fog->add_option("--lwc", options->lwc_g_per_m3, "Liquid water content in g/m^3 [0, 100]")
          ->check(number_in("--lwc", 0.0, 100.0, "in [0, 100]"));
  auto* ext = fog->add_option("--extinction-per-km", options->extinction_per_km,
                              "Optical extinction coefficient at 550 nm in 1/km [0, 1e6] (default "
                              "900, the study's fog)")
                  ->check(number_in("--extinction-per-km", 0.0, 1e6, "in [0, 1e6]"));
  auto* vis = fog->add_option("--visibility-m", options->visibility_m,
                              "Visibility (eq. 6, 2 % contrast at 550 nm) in m [1e-3, 1e7]")
                  ->check(number_in("--visibility-m", 1e-3, 1e7, "in [1e-3, 1e7]"));
  lwc->excludes(ext)->excludes(vis);
  ext->excludes(vis);
  fog->add_option("--diameter-um", options->diameter_um,
                  "Monodisperse droplets of this diameter in um [0.01, 1000] (default: lognormal, "
                  "median 1 um, "
                  "sigma_g 1.5)")
      ->check(number_in("--diameter-um", 0.01, 1000.0, "in [0.01, 1000]"));
  fog->add_option(
         "--temperature-c", options->temperature_c,
         "Water temperature in C: [-20, 50] with liebe (default 20); segelstein is a table for "
         "25 C and takes only 25")
      ->check(number_in("--temperature-c", -20.0, 50.0,
                        "in [-20, 50] with --water-model liebe, 25 with segelstein"));
  fog->add_option("--water-model", options->water_model,
                  "Water index at --frequency-ghz: liebe (temperature dependent, up to 1000 GHz) | "
                  "segelstein (25 C table); 550 nm always uses segelstein")
      ->capture_default_str();
  fog->add_option("--layer-length-m", options->layer_length_m,
                  "Layer length in m for each sensor's loss through one layer [0.001, 10000]")
      ->capture_default_str()
      ->check(number_in("--layer-length-m", 0.001, 1e4, "in [0.001, 10000]"));
  fog->add_flag("--json", options->json, "Print one JSON object");
  return [options] { run_fog(*options); };
}

}  // namespace fogradar::cli
