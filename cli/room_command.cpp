// `fogradar room`: a surface material's complex permittivity at a radio frequency (or its complex
// index at an optical wavelength) and the Fresnel amplitude reflection coefficients of a smooth
// half-space of it at a grazing angle (propagation/materials.hpp, docs/physics.md).
#include <cmath>
#include <complex>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "checks.hpp"
#include "commands.hpp"
#include "fogradar/core/constants.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/propagation/materials.hpp"
#include "fogradar/propagation/water.hpp"

namespace fogradar::cli {
namespace {

using complex = std::complex<double>;

struct RoomOptions {
  std::string material;
  std::optional<double> frequency_ghz;
  std::string frequency_typed;
  std::optional<double> wavelength_nm;
  std::string wavelength_typed;
  double grazing_deg = 0.0;
  bool json = false;
};

std::string number(double value) {
  std::ostringstream text;
  text << std::setprecision(6) << value;
  return text.str();
}

std::string complex_text(complex value) {
  return number(value.real()) + (value.imag() < 0 ? " - " : " + ") +
         number(std::abs(value.imag())) + "i";
}

double phase_deg(complex value) { return std::arg(value) * 180.0 / pi; }

nlohmann::json complex_json(complex value) {
  return {{"real", value.real()}, {"imag", value.imag()}};
}

nlohmann::json coefficient_json(complex value) {
  return {{"real", value.real()},
          {"imag", value.imag()},
          {"magnitude", std::abs(value)},
          {"phase_deg", phase_deg(value)}};
}

void run_room(const RoomOptions& o) {
  if (o.frequency_ghz.has_value() == o.wavelength_nm.has_value()) {
    throw InvalidParameter("--frequency-ghz",
                           "--frequency-ghz / --wavelength-nm: give exactly one of them (a radio "
                           "frequency in GHz or an optical wavelength in nm)");
  }
  const propagation::Material material =
      propagation::material_names.parse(o.material, "--material");
  nlohmann::json out;
  out["material"] = o.material;
  std::ostringstream text;
  text << "material           " << o.material << '\n';
  complex permittivity;
  if (o.frequency_ghz) {
    const propagation::FrequencyRangeGhz range = propagation::radio_frequency_range(material);
    if (!(*o.frequency_ghz >= range.min_ghz && *o.frequency_ghz <= range.max_ghz)) {
      throw_invalid("--frequency-ghz", o.frequency_typed,
                    "in [" + message_number(range.min_ghz) + ", " + message_number(range.max_ghz) +
                        "] for material '" + o.material + "' (" +
                        std::string(propagation::radio_permittivity_source(material)) + ")");
    }
    permittivity = propagation::radio_permittivity(material, *o.frequency_ghz * 1e9);
    const std::string source(propagation::radio_permittivity_source(material));
    out["frequency_ghz"] = *o.frequency_ghz;
    out["source"] = source;
    out["valid_frequency_ghz"] = {range.min_ghz, range.max_ghz};
    text << "frequency          " << number(*o.frequency_ghz) << " GHz\n"
         << "source             " << source << ", valid " << number(range.min_ghz) << "-"
         << number(range.max_ghz) << " GHz\n";
    if (const std::optional<propagation::ItuP2040Fit> fit = propagation::itu_p2040_fit(material)) {
      const double sigma = propagation::itu_p2040_conductivity_s_per_m(*fit, *o.frequency_ghz);
      out["p2040_fit"] = {{"a", fit->a}, {"b", fit->b}, {"c", fit->c}, {"d", fit->d}};
      out["conductivity_s_per_m"] = sigma;
      text << "fit                eps' = " << number(fit->a) << " f^" << number(fit->b)
           << ", sigma = " << number(fit->c) << " f^" << number(fit->d)
           << " S/m, eps'' = 17.98 sigma / f (f in GHz)\n"
           << "conductivity       " << number(sigma) << " S/m\n";
    }
  } else {
    const propagation::SegelsteinTable table;
    const std::optional<propagation::WavelengthRangeNm> range =
        propagation::optical_wavelength_range(material, table);
    if (!range) {
      throw_invalid("--material", o.material,
                    "one of " + propagation::optical_material_names() +
                        " with --wavelength-nm (the materials with optical "
                        "data)");
    }
    if (!(*o.wavelength_nm >= range->min_nm && *o.wavelength_nm <= range->max_nm)) {
      throw_invalid("--wavelength-nm", o.wavelength_typed,
                    "in [" + message_number(range->min_nm) + ", " + message_number(range->max_nm) +
                        "] for material '" + o.material + "' (" +
                        std::string(propagation::optical_index_source(material)) + ")");
    }
    const complex index =
        propagation::optical_refractive_index(material, *o.wavelength_nm * 1e-9, table);
    permittivity = index * index;
    const std::string source(propagation::optical_index_source(material));
    out["wavelength_nm"] = *o.wavelength_nm;
    out["source"] = source;
    out["valid_wavelength_nm"] = {range->min_nm, range->max_nm};
    out["refractive_index"] = complex_json(index);
    text << "wavelength         " << number(*o.wavelength_nm) << " nm\n"
         << "source             " << source << ", valid " << number(range->min_nm) << "-"
         << number(range->max_nm) << " nm\n"
         << "refractive index   " << complex_text(index) << '\n';
  }
  const propagation::FresnelCoefficients gamma =
      propagation::fresnel_reflection(permittivity, o.grazing_deg * pi / 180.0);
  out["permittivity"] = complex_json(permittivity);
  out["grazing_deg"] = o.grazing_deg;
  out["te"] = coefficient_json(gamma.te);
  out["tm"] = coefficient_json(gamma.tm);
  if (o.json) {
    std::cout << out.dump(2) << '\n';
    return;
  }
  text << "permittivity       " << complex_text(permittivity)
       << " (eps' + i eps'', time dependence exp(-i w t))\n"
       << "grazing angle      " << number(o.grazing_deg) << " deg\n"
       << "Gamma TE (horiz.)  |G| = " << number(std::abs(gamma.te))
       << ", phase = " << number(phase_deg(gamma.te)) << " deg\n"
       << "Gamma TM (vert.)   |G| = " << number(std::abs(gamma.tm))
       << ", phase = " << number(phase_deg(gamma.tm)) << " deg\n";
  std::cout << text.str();
}

}  // namespace

Action add_room_command(CLI::App& app) {
  auto options = std::make_shared<RoomOptions>();
  CLI::App* room = app.add_subcommand(
      "room",
      "A surface material's complex permittivity (ITU-R P.2040-3 fits, water, plastic) or optical "
      "index, and its Fresnel TE and TM amplitude reflection coefficients at a grazing angle");
  room->add_option("--material", options->material,
                   "Material: " + propagation::material_names.allowed())
      ->required()
      ->check(CLI::Validator(
          [](const std::string& text) {
            propagation::material_names.parse(text, "--material");
            return std::string();
          },
          "", ""));
  auto* frequency =
      room->add_option("--frequency-ghz", options->frequency_ghz,
                       "Radio frequency in GHz, inside the material's fit (e.g. concrete [1, 100])")
          ->check(number_in("--frequency-ghz", 1e-3, 1e3,
                            "in [0.001, 1000], and inside the material's own range"))
          ->check(keep_text(&options->frequency_typed));
  auto* wavelength =
      room->add_option("--wavelength-nm", options->wavelength_nm,
                       "Optical wavelength in nm, for water, glass or metal (e.g. 905, 1550)")
          ->check(number_in("--wavelength-nm", 1.0, 1e10,
                            "in [1, 1e10], and inside the material's own range"))
          ->check(keep_text(&options->wavelength_typed));
  frequency->excludes(wavelength);
  room->add_option("--grazing-deg", options->grazing_deg,
                   "Grazing angle from the surface in degrees (0, 90]")
      ->required()
      ->check(CLI::Validator(
          [](const std::string& text) {
            const std::optional<double> value = parse_whole<double>(text);
            if (!value || !(*value > 0.0 && *value <= 90.0)) {
              throw_invalid("--grazing-deg", text, "in (0, 90]");
            }
            return std::string();
          },
          "", ""));
  room->add_flag("--json", options->json, "Print one JSON object");
  return [options] { run_room(*options); };
}

}  // namespace fogradar::cli
