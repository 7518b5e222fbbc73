// `fogradar fog`: the fog's water index, radar attenuation and backscatter, optical extinction and
// visibility (docs/physics.md), and its optics at the paper scenario's three sensors' bands with
// each sensor's loss through one layer.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "checks.hpp"
#include "commands.hpp"
#include "fogradar/camera/camera.hpp"
#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/lidar/lidar.hpp"
#include "fogradar/propagation/fog.hpp"

namespace fogradar::cli {
namespace {

struct FogOptions {
  double frequency_ghz = 77.0;
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
// resolved by the sensor modules themselves (the lidar's Mie at its wavelength, the camera's band
// quadrature), so these are the numbers a run uses.
struct SensorBands {
  double radar_two_way_loss_db = 0.0;  // 2 A L, A the specific attenuation
  double lidar_wavelength_m = 0.0;
  double lidar_extinction_per_m = 0.0;
  double lidar_backscatter_per_m_sr = 0.0;  // beta_pi = eta / (4 pi)
  double lidar_two_way_loss_db = 0.0;       // 10 log10 e x 2 alpha L (Beer-Lambert)
  std::string camera_band;
  double camera_transmittance = 0.0;     // band-weighted one-way t of the layer
  double camera_extinction_per_m = 0.0;  // -ln t / L: the band's effective beta
  double camera_one_way_loss_db = 0.0;   // -10 log10 t
};

SensorBands sensor_bands(const propagation::FogSpec& spec, const propagation::FogOptics& radar,
                         double layer_length_m, const propagation::SegelsteinTable& table) {
  const experiment::Scenario paper = experiment::paper_scenario();
  propagation::ChamberSpec chamber;
  chamber.layers = {propagation::FogLayerSpec{.length_m = layer_length_m, .fog = spec}};
  SensorBands b;
  b.radar_two_way_loss_db = 2.0 * radar.specific_attenuation_db_per_km * layer_length_m * 1e-3;
  const lidar::Lidar lidar(paper.lidar, chamber, table);
  b.lidar_wavelength_m = paper.lidar.wavelength_m;
  b.lidar_extinction_per_m = lidar.layer_extinction_per_m(0);
  b.lidar_backscatter_per_m_sr = lidar.layer_backscatter_per_m_sr(0);
  b.lidar_two_way_loss_db =
      10.0 * std::log10(std::exp(1.0)) * 2.0 * b.lidar_extinction_per_m * layer_length_m;
  const camera::Camera camera(paper.camera, chamber, table);
  b.camera_band = std::string(camera::to_string(paper.camera.band));
  b.camera_transmittance =
      camera.step_optics(propagation::ActiveLayers{true}).transmittance.front();
  b.camera_extinction_per_m = -std::log(b.camera_transmittance) / layer_length_m;
  b.camera_one_way_loss_db = -10.0 * std::log10(b.camera_transmittance);
  return b;
}

// The argument names the user typed, so errors name them rather than internal fields.
propagation::FogSpec fog_spec_from(const FogOptions& o) {
  // The water table spans 10 nm .. 10 m, i.e. 0.03 GHz .. 3e7 GHz; Liebe's model ends at 1 THz.
  const bool liebe = o.water_model == "liebe";
  require_in_range("--frequency-ghz", o.frequency_ghz, 0.03, liebe ? 1000.0 : 2.99e7);
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
  const propagation::FogOptics radar = fog.at_frequency(options.frequency_ghz * 1e9);
  const propagation::FogOptics optical =
      fog.at_optical_wavelength(propagation::visibility_wavelength_m);
  const double optical_extinction_per_km = fog.optical_extinction_per_km();
  const double visibility_m = fog.visibility_m();
  const SensorBands bands = sensor_bands(spec, radar, options.layer_length_m, table);

  if (options.json) {
    const nlohmann::json out = {
        {"frequency_hz", radar.frequency_hz},
        {"wavelength_m", radar.wavelength_m},
        {"refractive_index_n", radar.refractive_index.real()},
        {"refractive_index_k", radar.refractive_index.imag()},
        {"water_model", propagation::to_string(radar.water_model)},
        {"temperature_c", radar.water_temperature_c},
        {"optical_water_model", propagation::to_string(optical.water_model)},
        {"optical_water_temperature_c", optical.water_temperature_c},
        {"droplets", propagation::distribution_name(spec.droplets)},
        {"lwc_g_per_m3", fog.lwc_g_per_m3()},
        {"number_concentration_per_cm3", fog.number_concentration_per_m3() * 1e-6},
        {"specific_attenuation_db_per_km", radar.specific_attenuation_db_per_km},
        {"volume_backscatter_m2_per_m3", radar.volume_backscatter_m2_per_m3},
        {"optical_extinction_per_km", optical_extinction_per_km},
        {"visibility_m", number_or_null(visibility_m)},
        {"layer_length_m", options.layer_length_m},
        {"sensors",
         {{"radar",
           {{"frequency_hz", radar.frequency_hz},
            {"specific_attenuation_db_per_km", radar.specific_attenuation_db_per_km},
            {"volume_backscatter_m2_per_m3", radar.volume_backscatter_m2_per_m3},
            {"two_way_loss_db_per_layer", bands.radar_two_way_loss_db}}},
          {"lidar",
           {{"wavelength_m", bands.lidar_wavelength_m},
            {"extinction_per_m", bands.lidar_extinction_per_m},
            {"backscatter_per_m_sr", bands.lidar_backscatter_per_m_sr},
            {"lidar_ratio_sr",
             number_or_null(bands.lidar_extinction_per_m / bands.lidar_backscatter_per_m_sr)},
            {"two_way_loss_db_per_layer", bands.lidar_two_way_loss_db}}},
          {"camera",
           {{"band", bands.camera_band},
            {"extinction_per_m", number_or_null(bands.camera_extinction_per_m)},
            {"transmittance_per_layer", bands.camera_transmittance},
            {"one_way_loss_db_per_layer", number_or_null(bands.camera_one_way_loss_db)}}}}},
    };
    std::cout << out.dump(2) << '\n';
    return;
  }
  std::cout << std::setprecision(6) << "frequency                 " << radar.frequency_hz * 1e-9
            << " GHz (wavelength " << radar.wavelength_m * 1e3 << " mm)\n"
            << "water index m = n + ik    " << radar.refractive_index.real() << " + "
            << radar.refractive_index.imag() << "i (" << water_source(radar) << ")\n"
            << "droplets                  " << propagation::distribution_name(spec.droplets) << ", "
            << fog.number_concentration_per_m3() * 1e-6 << " per cm^3\n"
            << "liquid water content      " << fog.lwc_g_per_m3() << " g/m^3\n"
            << "specific attenuation      " << radar.specific_attenuation_db_per_km << " dB/km\n"
            << "volume backscatter eta    " << radar.volume_backscatter_m2_per_m3 << " m^2/m^3\n"
            << "optical extinction 550 nm " << optical_extinction_per_km << " 1/km (water index "
            << water_source(optical) << ")\n"
            << "visibility (eq. 6, 2 %)   " << visibility_m << " m\n"
            << "through one layer of " << options.layer_length_m
            << " m, as the paper scenario's sensors see it:\n"
            << "  radar 2-way loss        " << bands.radar_two_way_loss_db << " dB\n"
            << "  lidar (" << bands.lidar_wavelength_m * 1e9 << " nm)         extinction "
            << bands.lidar_extinction_per_m << " 1/m, backscatter beta_pi "
            << bands.lidar_backscatter_per_m_sr << " 1/(m sr), 2-way loss "
            << bands.lidar_two_way_loss_db << " dB\n"
            << "  camera (" << bands.camera_band << ")       transmittance "
            << bands.camera_transmittance << " (effective extinction "
            << bands.camera_extinction_per_m << " 1/m), 1-way loss " << bands.camera_one_way_loss_db
            << " dB\n";
}

}  // namespace

Action add_fog_command(CLI::App& app) {
  auto options = std::make_shared<FogOptions>();
  CLI::App* fog = app.add_subcommand(
      "fog",
      "Water index, radar attenuation and backscatter, optical extinction and visibility of a fog");
  fog->add_option("--frequency-ghz", options->frequency_ghz, "Radar frequency in GHz")
      ->capture_default_str()
      ->check(
          number_in("--frequency-ghz", 0.03, 2.99e7,
                    "in [0.03, 1000] with --water-model liebe, [0.03, 2.99e7] with segelstein"));
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
  fog->add_option(
         "--water-model", options->water_model,
         "Water index at the radar frequency: liebe (temperature dependent, up to 1000 GHz) | "
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
