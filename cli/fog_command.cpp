// `fogradar fog`: the fog's water index, attenuation and backscatter at a (radar) frequency,
// optical extinction and visibility (docs/physics.md), the optical attenuation models of the
// study's eq. 1, 2 (Kruse, Kim) beside Mie at one wavelength, the virtual layer model of its eq. 3,
// 4, and one layer of the fog as each sensor of the paper scenario sees it
// (sensor::ConfiguredSensor::fog_report).
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "checks.hpp"
#include "commands.hpp"
#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/core/units.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/propagation/dsd.hpp"
#include "fogradar/propagation/fog.hpp"
#include "fogradar/propagation/layer_model.hpp"
#include "fogradar/propagation/visibility.hpp"
#include "fogradar/sensor/sensor.hpp"

namespace fogradar::cli {
namespace {

// The optical options' defaults, the command's own (it names no sensor): 905 nm, the band of the
// study's scanning lidar, and an object of unit reflectivity, so that eq. 4's column is the
// layers' two-way transmittance tau^(2k) itself.
constexpr double default_wavelength_nm = 905.0;
constexpr double default_object_reflectivity = 1.0;

struct FogOptions {
  double frequency_ghz = 77.0;
  std::string frequency_typed = "77";  // --frequency-ghz as typed, for the message that refuses it
  std::optional<double> lwc_g_per_m3;
  std::optional<double> extinction_per_km;
  std::optional<double> visibility_m;
  std::string lwc_from = "mie";
  // Absent: lognormal, or monodisperse where --diameter-um is given.
  std::optional<std::string> distribution;
  std::optional<double> diameter_um;
  std::optional<double> median_diameter_um;
  std::optional<double> geometric_std;
  std::optional<double> alpha;
  std::optional<double> gamma;
  std::optional<double> b_per_um_gamma;
  std::optional<double>
      temperature_c;  // absent: 20 C under Liebe, the table's own under Segelstein
  std::string water_model = "liebe";
  double layer_length_m = 1.0;  // the study's layer f_i
  std::vector<std::string> optical_models = propagation::optical_model_names.names();
  double wavelength_nm = default_wavelength_nm;
  std::optional<std::int64_t> layer_model;
  double object_reflectivity = default_object_reflectivity;
  bool json = false;
};

// A fog key's own range, under the options' prefix "--" (fog_keys).
Interval fog_key_range(std::string_view key) { return propagation::fog_keys("--").at(key).range; }

// The fogs behind the output. The radar-frequency values follow the LWC, the optical ones the
// extinction at 550 nm; under --lwc-from mie (the default) both are one fog, the LWC and the
// extinction tied by Mie over its droplets; under kunkel they are tied by Kunkel's empirical law
// instead, which no droplet distribution need obey, so the two are resolved as two fogs.
struct FogSpecs {
  propagation::FogSpec by_lwc;
  propagation::FogSpec by_extinction;
};

// An option and the fog key it sets (fog.hpp fog_keys, dsd.hpp droplet_keys, here under the prefix
// "--"), so that the bounds, the families, the presets and which key goes with which family are
// the scenario's. Diameters are typed in um, the keys hold m. The help states the key's range
// between `help` and `after`.
struct KeyOption {
  std::string_view option;
  std::string_view key;
  double key_per_option_unit;
  std::optional<double> FogOptions::*value;
  std::string_view help;
  std::string_view after;
};

const KeyOption density_options[] = {
    {"--lwc", "--lwc_g_per_m3", 1.0, &FogOptions::lwc_g_per_m3, "Liquid water content in g/m^3",
     ""},
    {"--extinction-per-km", "--extinction_per_km", 1.0, &FogOptions::extinction_per_km,
     "Optical extinction coefficient at 550 nm in 1/km", " (default 900, the study's fog)"},
    {"--visibility-m", "--visibility_m", 1.0, &FogOptions::visibility_m,
     "Visibility (eq. 6, 2 % contrast at 550 nm) in m", ""},
};

const KeyOption droplet_options[] = {
    {"--diameter-um", "--diameter_m", 1e-6, &FogOptions::diameter_um,
     "Monodisperse droplets of this diameter in um", " (default 1)"},
    {"--median-diameter-um", "--median_diameter_m", 1e-6, &FogOptions::median_diameter_um,
     "Lognormal median diameter in um", " (default 1)"},
    {"--geometric-std", "--geometric_std", 1.0, &FogOptions::geometric_std,
     "Lognormal geometric standard deviation sigma_g", " (default 1.5)"},
    {"--alpha", "--alpha", 1.0, &FogOptions::alpha,
     "Modified gamma n(r) = a r^alpha exp(-b r^gamma): alpha", " (default 3, or the preset's)"},
    {"--gamma", "--gamma", 1.0, &FogOptions::gamma, "Modified gamma: gamma",
     " (default 1, or the preset's)"},
    // The mean radius rule goes between the range and `after`.
    {"--b-per-um-gamma", "--b_per_um_gamma", 1.0, &FogOptions::b_per_um_gamma,
     "Modified gamma: b in um^-gamma,", " (default 0.3, or the preset's)"},
};

// The drop size distribution the options give, as the scenario's [fog.droplets] would: the family
// first (a preset with its published values), then its own parameters; a parameter of another
// family is refused, not ignored.
propagation::DropSizeDistribution droplets_from(const FogOptions& o) {
  KeyTable<propagation::DropSizeDistribution> keys = propagation::droplet_keys("--");
  propagation::DropSizeDistribution droplets = propagation::default_fog_droplets();
  keys.at("--distribution")
      .set_text(droplets, o.distribution.value_or(o.diameter_um ? "monodisperse" : "lognormal"));
  const KeyOption* gamma_option = nullptr;  // one given, for the message below
  for (const KeyOption& option : droplet_options) {
    const std::optional<double>& value = o.*option.value;
    if (!value) continue;
    const Key<propagation::DropSizeDistribution>& key = keys.at(option.key);
    if (!key.takes_effect(droplets)) {
      throw_invalid(option.option, *value, "given only " + key.applies_text);
    }
    key.set_number(droplets, *value * option.key_per_option_unit);
    if (std::holds_alternative<propagation::ModifiedGamma>(droplets)) {
      gamma_option = &option;
    }
  }
  // The one bound that involves several keys (droplet_keys: b_per_um_gamma); a preset meets it, so
  // a typed parameter broke it, and the message names that one.
  if (const auto* g = std::get_if<propagation::ModifiedGamma>(&droplets)) {
    const double mean_radius_um = propagation::mean_radius_um(*g);
    if (!(mean_radius_um <= propagation::max_mean_radius_um)) {
      std::ostringstream constraint;
      constraint << "such that " << propagation::mean_radius_rule() << " (here " << mean_radius_um
                 << " um with alpha = " << g->alpha << ", gamma = " << g->gamma
                 << ", b = " << g->b_per_um_gamma << ")";
      FOGRADAR_CHECK(gamma_option != nullptr);
      throw_invalid(gamma_option->option, *(o.*gamma_option->value), constraint.str());
    }
  }
  return droplets;
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
  KeyTable<propagation::FogSpec> keys = propagation::fog_keys("--");
  for (const KeyOption& option : density_options) {
    if (const std::optional<double>& value = o.*option.value) {
      keys.at(option.key).set_number(spec, *value * option.key_per_option_unit);
    }
  }
  spec.droplets = droplets_from(o);
  spec.water_model = propagation::water_model_names.parse(o.water_model, "--water-model");
  if (spec.water_model == propagation::WaterModel::segelstein) {
    spec.temperature_c = propagation::segelstein_table_temperature_c;
    if (o.temperature_c && *o.temperature_c != spec.temperature_c) {
      throw_invalid("--temperature-c", *o.temperature_c,
                    propagation::segelstein_temperature_constraint("--water-model segelstein",
                                                                   "--water-model liebe"));
    }
  } else if (o.temperature_c) {
    spec.temperature_c = *o.temperature_c;
  }
  return spec;
}

FogSpecs fog_specs_from(const FogOptions& o) {
  const propagation::FogSpec spec = fog_spec_from(o);
  if (o.lwc_from == "mie") return {spec, spec};
  double lwc_g_per_m3 = 0.0;
  double extinction_per_km = 0.0;
  if (o.lwc_g_per_m3) {
    lwc_g_per_m3 = *o.lwc_g_per_m3;
    extinction_per_km = propagation::kunkel_extinction_per_km(lwc_g_per_m3);
  } else {
    // Kunkel's LWC of a dense fog passes the LWC's own bound long before the extinction's: the
    // options are held to the extinction that bound allows.
    const double max_lwc_g_per_m3 = fog_key_range("--lwc_g_per_m3").high;
    const double max_extinction_per_km = propagation::kunkel_extinction_per_km(max_lwc_g_per_m3);
    const std::string kunkel = " with --lwc-from kunkel (Kunkel's LWC at most " +
                               message_number(max_lwc_g_per_m3) + " g/m^3); --lwc-from mie takes ";
    std::ostringstream constraint;
    if (o.visibility_m) {
      extinction_per_km =
          per_m_to_per_km(propagation::extinction_per_m_from_visibility(*o.visibility_m));
      const Interval visibilities_m = fog_key_range("--visibility_m");
      constraint << "in ["
                 << bound_text(propagation::visibility_m_from_extinction(
                                   per_km_to_per_m(max_extinction_per_km)),
                               false)
                 << ", " << doc_number(visibilities_m.high) << "]" << kunkel
                 << visibilities_m.doc();
    } else {
      extinction_per_km = std::get<propagation::OpticalExtinction>(spec.density).per_km;
      const Interval extinctions_per_km = fog_key_range("--extinction_per_km");
      constraint << "in [" << doc_number(extinctions_per_km.low) << ", "
                 << bound_text(max_extinction_per_km, true) << "]" << kunkel
                 << extinctions_per_km.doc();
    }
    if (extinction_per_km > max_extinction_per_km) {
      if (o.visibility_m) throw_invalid("--visibility-m", *o.visibility_m, constraint.str());
      throw_invalid("--extinction-per-km", extinction_per_km, constraint.str());
    }
    lwc_g_per_m3 = propagation::kunkel_lwc_g_per_m3(extinction_per_km);
  }
  FogSpecs specs{spec, spec};
  specs.by_lwc.density = propagation::LiquidWaterContent{lwc_g_per_m3};
  specs.by_extinction.density = propagation::OpticalExtinction{extinction_per_km};
  return specs;
}

// The fog through one layer of `layer_length_m` as each of the paper scenario's sensors sees it,
// resolved by the sensor modules themselves (the radar at its sweep centre, the lidar's Mie at its
// wavelength, the camera's band quadrature), so these are the numbers a run uses. A radio sensor
// sees the fog of the LWC, an optical one the fog of the 550 nm extinction (FogSpecs).
std::vector<std::pair<std::string, sensor::FogReport>> sensor_reports(
    const FogSpecs& specs, double layer_length_m, const propagation::SegelsteinTable& table) {
  const experiment::Scenario paper = experiment::paper_scenario();
  std::vector<std::pair<std::string, sensor::FogReport>> reports;
  for (const experiment::SensorSetting& setting : paper.sensors) {
    const bool radio = setting.kind->info().band == sensor::Band::radio;
    reports.emplace_back(setting.name, paper.configure(setting.name)
                                           ->fog_report(radio ? specs.by_lwc : specs.by_extinction,
                                                        layer_length_m, table));
  }
  return reports;
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

// A wavelength in the unit of its band: nm from the far infrared (below 0.1 mm) on, mm for radar.
std::string wavelength_text(double wavelength_m) {
  std::ostringstream text;
  text << std::setprecision(6);
  if (wavelength_m < 1e-4) {
    text << wavelength_m * 1e9 << " nm";
  } else {
    text << wavelength_m * 1e3 << " mm";
  }
  return text.str();
}

// The distribution's parameters under its [fog.droplets] keys' names, diameters in um as the
// options take them.
nlohmann::json droplet_parameters(const propagation::DropSizeDistribution& droplets) {
  struct Parameters {
    nlohmann::json operator()(const propagation::Monodisperse& d) const {
      return {{"diameter_um", d.diameter_m * 1e6}};
    }
    nlohmann::json operator()(const propagation::Lognormal& d) const {
      return {{"median_diameter_um", d.median_diameter_m * 1e6},
              {"geometric_std", d.geometric_std}};
    }
    nlohmann::json operator()(const propagation::ModifiedGamma& d) const {
      return {{"alpha", d.alpha}, {"gamma", d.gamma}, {"b_per_um_gamma", d.b_per_um_gamma}};
    }
  };
  return std::visit(Parameters{}, droplets);
}

std::string droplet_parameters_text(const propagation::DropSizeDistribution& droplets) {
  struct Text {
    std::string operator()(const propagation::Monodisperse& d) const {
      std::ostringstream text;
      text << "diameter " << d.diameter_m * 1e6 << " um";
      return text.str();
    }
    std::string operator()(const propagation::Lognormal& d) const {
      std::ostringstream text;
      text << "median " << d.median_diameter_m * 1e6 << " um, sigma_g " << d.geometric_std;
      return text.str();
    }
    std::string operator()(const propagation::ModifiedGamma& d) const {
      std::ostringstream text;
      text << "alpha " << d.alpha << ", gamma " << d.gamma << ", b " << d.b_per_um_gamma
           << " um^-gamma";
      return text.str();
    }
  };
  return std::visit(Text{}, droplets);
}

// An optical model's name in the text output.
std::string_view optical_model_label(propagation::OpticalModel model) {
  switch (model) {
    case propagation::OpticalModel::kruse:
      return "Kruse (eq. 1, 2)";
    case propagation::OpticalModel::kim:
      return "Kim (eq. 1)";
    case propagation::OpticalModel::mie:
      break;
  }
  return "Mie";
}

// The study's eq. 3, 4 for a stack of identical virtual layers, each one layer of `length_m` of
// the fog whose optics at the wavelength are `optics`.
propagation::VirtualLayer virtual_layer(const propagation::FogOptics& optics, double length_m,
                                        const FogOptions& o) {
  const double alpha = optics.extinction_per_m;
  const double eta = optics.volume_backscatter_m2_per_m3;
  if (std::exp(-alpha * length_m) + eta * length_m > 1.0) {
    std::ostringstream why;
    why << "for this fog at " << o.wavelength_nm << " nm (alpha = " << alpha
        << " 1/m, eta = " << eta << " m^2/m^3) the virtual layer's tau + rho = exp(-alpha d) + "
        << "eta d";
    if (eta >= alpha) {
      throw_invalid("--layer-model", static_cast<double>(*o.layer_model),
                    "left out: " + why.str() + " exceeds 1 at every layer length d");
    }
    std::ostringstream constraint;
    constraint << "at most " << bound_text(propagation::longest_layer_m(alpha, eta), true)
               << " with --layer-model: " << why.str() << " must not exceed 1";
    throw_invalid("--layer-length-m", length_m, constraint.str());
  }
  return propagation::virtual_layer_from_fog(alpha, eta, length_m);
}

void run_fog(const FogOptions& options) {
  const FogSpecs specs = fog_specs_from(options);
  const propagation::SegelsteinTable table;
  const propagation::Fog fog(specs.by_lwc, table);
  const propagation::Fog optical_fog(specs.by_extinction, table);
  const propagation::FogOptics at_frequency = fog.at_frequency(options.frequency_ghz * 1e9);
  const propagation::FogOptics optical =
      optical_fog.at_optical_wavelength(propagation::visibility_wavelength_m);
  const double optical_extinction_per_km = optical_fog.optical_extinction_per_km();
  const double visibility_m = optical_fog.visibility_m();
  const double meteorological_visibility_m =
      optical.extinction_per_m > 0.0
          ? propagation::meteorological_visibility_m(optical.extinction_per_m)
          : std::numeric_limits<double>::infinity();
  const propagation::FogOptics at_wavelength =
      optical_fog.at_optical_wavelength(options.wavelength_nm * 1e-9);
  std::vector<propagation::OpticalModel> wanted;
  for (const std::string& name : options.optical_models) {
    wanted.push_back(propagation::optical_model_names.parse(name, "--optical-model"));
  }
  const std::vector<propagation::OpticalModelExtinction> models = propagation::optical_model_table(
      wanted, per_m_to_per_km(at_wavelength.extinction_per_m), visibility_m, options.wavelength_nm);
  std::optional<propagation::VirtualLayer> layer;
  std::vector<propagation::LayerModelRow> layer_rows;
  if (options.layer_model) {
    layer = virtual_layer(at_wavelength, options.layer_length_m, options);
    layer_rows = propagation::layer_model_table(*layer, static_cast<unsigned>(*options.layer_model),
                                                options.object_reflectivity);
  }
  const auto reports = sensor_reports(specs, options.layer_length_m, table);

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
        {"droplets", propagation::distribution_name(specs.by_lwc.droplets)},
        {"droplet_parameters", droplet_parameters(specs.by_lwc.droplets)},
        {"lwc_from", options.lwc_from},
        {"lwc_g_per_m3", fog.lwc_g_per_m3()},
        {"number_concentration_per_cm3", fog.number_concentration_per_m3() * 1e-6},
        {"specific_attenuation_db_per_km", at_frequency.specific_attenuation_db_per_km},
        {"volume_backscatter_m2_per_m3", at_frequency.volume_backscatter_m2_per_m3},
        {"optical_extinction_per_km", optical_extinction_per_km},
        {"visibility_m", number_or_null(visibility_m)},
        {"meteorological_visibility_m", number_or_null(meteorological_visibility_m)},
        {"optical_wavelength_nm", options.wavelength_nm},
        {"layer_length_m", options.layer_length_m},
    };
    nlohmann::json& by_model = out["optical_models"] = nlohmann::json::object();
    for (const propagation::OpticalModelExtinction& row : models) {
      const std::string name(propagation::optical_model_names.name(row.model));
      nlohmann::json& entry =
          by_model[name] = {{"extinction_per_km", row.extinction_per_km},
                            {"specific_attenuation_db_per_km",
                             propagation::attenuation_db_per_km(row.extinction_per_km)}};
      if (row.model != propagation::OpticalModel::mie)
        entry["q"] = row.q ? nlohmann::json(*row.q) : nlohmann::json(nullptr);
    }
    if (layer) {
      nlohmann::json rows = nlohmann::json::array();
      for (const propagation::LayerModelRow& row : layer_rows) {
        rows.push_back({{"layers", row.layers},
                        {"kappa", row.kappa},
                        {"fog_intensity_per_i0", row.fog_intensity_per_i0},
                        {"object_intensity_per_i0", row.object_intensity_per_i0}});
      }
      out["layer_model"] = {
          {"wavelength_nm", options.wavelength_nm},
          {"layer_length_m", options.layer_length_m},
          {"extinction_per_m", at_wavelength.extinction_per_m},
          {"volume_backscatter_m2_per_m3", at_wavelength.volume_backscatter_m2_per_m3},
          {"transmittance_tau", layer->transmittance},
          {"reflectance_rho", layer->reflectance},
          {"object_reflectivity", options.object_reflectivity},
          {"rows", std::move(rows)}};
    }
    nlohmann::json& sensors = out["sensors"] = nlohmann::json::object();
    for (const auto& [name, report] : reports) sensors[name] = report.json;
    std::cout << out.dump(2) << '\n';
    return;
  }
  std::string lwc_source;
  if (options.lwc_from == "kunkel") {
    lwc_source = options.lwc_g_per_m3
                     ? " (gives the 550 nm extinction by Kunkel 1984: beta = 144.7 LWC^0.88)"
                     : " (from the 550 nm extinction by Kunkel 1984: beta = 144.7 LWC^0.88)";
  }
  std::cout << std::setprecision(6) << "frequency                 "
            << at_frequency.frequency_hz * 1e-9 << " GHz (wavelength "
            << wavelength_text(at_frequency.wavelength_m) << ")\n"
            << "water index m = n + ik    " << at_frequency.refractive_index.real() << " + "
            << at_frequency.refractive_index.imag() << "i (" << water_source(at_frequency) << ")\n"
            << "droplets                  " << propagation::distribution_name(specs.by_lwc.droplets)
            << " (" << droplet_parameters_text(specs.by_lwc.droplets) << "), "
            << fog.number_concentration_per_m3() * 1e-6 << " per cm^3\n"
            << "liquid water content      " << fog.lwc_g_per_m3() << " g/m^3" << lwc_source << '\n'
            << "specific attenuation      " << at_frequency.specific_attenuation_db_per_km
            << " dB/km\n"
            << "volume backscatter eta    " << at_frequency.volume_backscatter_m2_per_m3
            << " m^2/m^3\n"
            << "optical extinction 550 nm " << optical_extinction_per_km << " 1/km (water index "
            << water_source(optical) << ")\n"
            << "visibility (eq. 6, 2 %)   " << visibility_m << " m\n"
            << "CIE visibility (eq. 9)    " << meteorological_visibility_m
            << " m (meteorological optical range, 5 % contrast)\n"
            << "at " << options.wavelength_nm
            << " nm (Kruse and Kim from the eq. 6 visibility), eq. 5 for dB/km:\n";
  for (const propagation::OpticalModelExtinction& row : models) {
    std::cout << "  " << std::left << std::setw(24) << optical_model_label(row.model) << std::right
              << row.extinction_per_km << " 1/km, "
              << propagation::attenuation_db_per_km(row.extinction_per_km) << " dB/km";
    if (row.q) std::cout << " (q = " << *row.q << ")";
    std::cout << '\n';
  }
  if (layer) {
    std::cout << "virtual layer model (eq. 3, 4) at " << options.wavelength_nm
              << " nm, one layer = " << options.layer_length_m << " m of this fog:\n"
              << "  transmittance tau       " << layer->transmittance << " (exp(-alpha d))\n"
              << "  reflectance rho         " << layer->reflectance << " (eta d)\n"
              << "  layers k  fog echo I_kappa / I_0     object echo I_obj / I_0\n"
              << "            (eq. 3, kappa = 2k + 1)    (eq. 4, rho_obj = "
              << options.object_reflectivity << ")\n";
    for (const propagation::LayerModelRow& row : layer_rows) {
      std::cout << "  " << std::setw(8) << row.layers << "  " << std::left << std::setw(27)
                << row.fog_intensity_per_i0 << std::right << row.object_intensity_per_i0 << '\n';
    }
  }
  std::cout << "through one layer of " << options.layer_length_m
            << " m, as the paper scenario's sensors see it:\n";
  for (const auto& [name, report] : reports) std::cout << report.line << '\n';
}

}  // namespace

Action add_fog_command(CLI::App& app) {
  auto options = std::make_shared<FogOptions>();
  CLI::App* fog = app.add_subcommand("fog",
                                     "Water index, attenuation and backscatter at a frequency, "
                                     "optical extinction, visibility and attenuation models of "
                                     "a fog, its virtual layer model, and each sensor's view of "
                                     "one layer of it");
  fog->add_option("--frequency-ghz", options->frequency_ghz, "Radar frequency in GHz")
      ->capture_default_str()
      ->check(number_in("--frequency-ghz", 0.03, 2.99e7,
                        "in [0.03, 1000] with --water-model liebe, [0.03, 2.99e7] with segelstein"))
      ->check(keep_text(&options->frequency_typed));
  // The options that set a fog key are checked by its own range (fog_keys, droplet_keys), in the
  // key's unit, and state it in theirs.
  KeyTable<propagation::FogSpec> fog_keys = propagation::fog_keys("--");
  KeyTable<propagation::DropSizeDistribution> droplet_keys = propagation::droplet_keys("--");
  const auto add_key_option = [fog, &options](const KeyOption& option, const Interval& range,
                                              const std::string& rule = "") {
    const std::string name(option.option);
    const std::string help = std::string(option.help) + " " +
                             option_range(range, option.key_per_option_unit).doc() +
                             (rule.empty() ? "" : " with " + rule) + std::string(option.after);
    return fog->add_option(name, (*options).*option.value, help)
        ->check(key_number(name, range, option.key_per_option_unit,
                           rule.empty() ? "" : ", with " + rule));
  };
  std::vector<CLI::Option*> density;
  for (const KeyOption& option : density_options) {
    density.push_back(add_key_option(option, fog_keys.at(option.key).range));
  }
  density[0]->excludes(density[1])->excludes(density[2]);
  density[1]->excludes(density[2]);
  fog->add_option("--lwc-from", options->lwc_from,
                  "What ties the LWC to the 550 nm extinction: mie (over the droplets) | kunkel "
                  "(Kunkel 1984, beta = 144.7 LWC^0.88; the radar sees the LWC, the optical "
                  "sensors the extinction)")
      ->capture_default_str()
      ->check(one_of("--lwc-from", {"mie", "kunkel"}));
  fog->add_option("--distribution", options->distribution,
                  "Drop size distribution: lognormal (default) | monodisperse (default with "
                  "--diameter-um) | advection | radiation (modified-gamma presets, Shettle & "
                  "Fenn) | modified_gamma");
  for (const KeyOption& option : droplet_options) {
    add_key_option(option, droplet_keys.at(option.key).range,
                   option.key == "--b_per_um_gamma" ? propagation::mean_radius_rule() : "");
  }
  const Interval temperatures_c = fog_keys.at("--temperature_c").range;
  const std::string table_c = message_number(propagation::segelstein_table_temperature_c);
  fog->add_option("--temperature-c", options->temperature_c,
                  "Water temperature in C: " + temperatures_c.doc() +
                      " with liebe (default 20); segelstein is a table for " + table_c +
                      " C and takes only " + table_c)
      ->check(key_number("--temperature-c", temperatures_c, 1.0,
                         " with --water-model liebe, " + table_c + " with segelstein"));
  fog->add_option("--water-model", options->water_model,
                  "Water index at --frequency-ghz: liebe (temperature dependent, up to 1000 GHz) | "
                  "segelstein (25 C table); 550 nm always uses segelstein")
      ->capture_default_str();
  fog->add_option("--layer-length-m", options->layer_length_m,
                  "Layer length in m for each sensor's loss through one layer and --layer-model's "
                  "virtual layer [0.001, 10000]")
      ->capture_default_str()
      ->check(number_in("--layer-length-m", 0.001, 1e4, "in [0.001, 10000]"));
  fog->add_option("--optical-model", options->optical_models,
                  "Optical attenuation models printed at --wavelength-nm beside Mie, comma "
                  "separated: mie | kruse (eq. 1, 2) | kim")
      ->delimiter(',')
      ->capture_default_str()
      ->check(one_of("--optical-model", propagation::optical_model_names.names()));
  // Kruse's and Kim's fits are of visible and near-infrared data; the lidar's key takes the same.
  fog->add_option("--wavelength-nm", options->wavelength_nm,
                  "Optical wavelength of --optical-model and --layer-model in nm [400, 2000] "
                  "(default 905, the study's lidar band)")
      ->capture_default_str()
      ->check(number_in("--wavelength-nm", 400.0, 2000.0, "in [400, 2000]"));
  auto* layer_model =
      fog->add_option("--layer-model", options->layer_model,
                      "Virtual layer model (eq. 3, 4) at --wavelength-nm for objects behind 0 .. "
                      "N layers of --layer-length-m [1, 1000]")
          ->check(integer_in("--layer-model", 1, 1000));
  fog->add_option("--object-reflectivity", options->object_reflectivity,
                  "Object reflectivity rho_obj of --layer-model's eq. 4 [0, 1] (default 1: the "
                  "object echo is the layers' two-way transmittance)")
      ->capture_default_str()
      ->check(number_in("--object-reflectivity", 0.0, 1.0, "in [0, 1]"))
      ->needs(layer_model);
  fog->add_flag("--json", options->json, "Print one JSON object");
  return [options] { run_fog(*options); };
}

}  // namespace fogradar::cli
