// Radar parameters: every invalid field rejected with its name, and the
// derived quantities against the textbook FMCW relations written out here:
//   [Ri14] M. A. Richards, Fundamentals of Radar Signal Processing, 2nd ed.: range resolution
//          c / (2B), Doppler 2v/lambda, velocity resolution lambda / (2 N_c T_i).
//   [PJ62] J. R. Probert-Jones, QJRMS 88, 485 (1962): two-way Gaussian-beam solid angle
//          pi theta_az theta_el / (8 ln 2).
// Tolerances: derived quantities 1e-12 relative (the same formulas in double precision).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>

#include "chain_test_support.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/radar/measurement.hpp"
#include "fogradar/radar/target.hpp"
#include "rejected_field.hpp"
#include "validation.hpp"

namespace fogradar::radar {
namespace {

using fogradar::testing::Tolerance;

constexpr double kC = 299'792'458.0;

// A number as check ids and conditions show it ("1", "55.5").
std::string id_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// A derived quantity of the paper radar against its textbook relation, 1e-12 relative.
void validate_derived(const std::string& name, const std::string& group,
                      const std::string& quantity, const std::string& unit,
                      const std::string& conditions, double reference, const std::string& source,
                      double value) {
  fogradar::testing::validate({.id = "radar.params." + name,
                               .group = group,
                               .quantity = quantity,
                               .unit = unit,
                               .conditions = conditions,
                               .reference = reference,
                               .source = source,
                               .value = value,
                               .tolerance = 1e-12,
                               .kind = Tolerance::relative});
}
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void expect_rejected(const std::function<void(RadarParams&)>& change, const std::string& field) {
  RadarParams p;
  change(p);
  try {
    p.validate();
    ADD_FAILURE() << "validate() accepted an invalid " << field;
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.field(), field) << error.what();
    EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
  }
  // The chain and derive() validate too.
  EXPECT_THROW(derive(p), InvalidParameter) << field;
  EXPECT_THROW(RadarChain{p}, InvalidParameter) << field;
}

// Every double field: below its range, above it, NaN (and infinity where the range is finite).
TEST(RadarParams, RejectsEveryInvalidField) {
  EXPECT_NO_THROW(RadarParams{}.validate());
  struct DoubleField {
    const char* name;
    double RadarParams::*member;
    double too_low;
    double too_high;
  };
  const DoubleField fields[] = {
      {"radar.centre_frequency_hz", &RadarParams::centre_frequency_hz, 0.5e9, 400e9},
      {"radar.sweep_bandwidth_hz", &RadarParams::sweep_bandwidth_hz, 0.0, 50e9},
      {"radar.chirp_duration_s", &RadarParams::chirp_duration_s, 0.0, 1.0},
      {"radar.chirp_interval_s", &RadarParams::chirp_interval_s, 50e-6, 2.0},  // < duration
      {"radar.sample_rate_hz", &RadarParams::sample_rate_hz, -1.0, 1e11},
      {"radar.tx_power_dbm", &RadarParams::tx_power_dbm, -40.0, 60.0},
      {"radar.tx_gain_dbi", &RadarParams::tx_gain_dbi, -1.0, 70.0},
      {"radar.rx_gain_dbi", &RadarParams::rx_gain_dbi, -1.0, 70.0},
      {"radar.azimuth_beamwidth_deg", &RadarParams::azimuth_beamwidth_deg, 0.0, 200.0},
      {"radar.elevation_beamwidth_deg", &RadarParams::elevation_beamwidth_deg, 0.0, 200.0},
      {"radar.noise_figure_db", &RadarParams::noise_figure_db, -1.0, 50.0},
      {"radar.reference_temperature_k", &RadarParams::reference_temperature_k, 0.0, 2000.0},
      {"radar.phase_noise_rms_rad", &RadarParams::phase_noise_rms_rad, -0.1, 4.0},
      {"radar.processing.association_gate_m", &RadarParams::association_gate_m, -1.0, 2e3},
  };
  for (const DoubleField& f : fields) {
    for (const double bad : {f.too_low, f.too_high, kNaN, -kInf, kInf}) {
      expect_rejected([&](RadarParams& p) { p.*(f.member) = bad; }, f.name);
    }
  }
  // The full scale counts only with an ADC (adc_bits > 0): without one it is no parameter at all.
  for (const double bad : {-200.0, 40.0, kNaN, -kInf, kInf}) {
    expect_rejected(
        [&](RadarParams& p) {
          p.adc_bits = 12;
          p.adc_full_scale_dbm = bad;
        },
        "radar.adc_full_scale_dbm");
  }
  // Counts.
  expect_rejected([](RadarParams& p) { p.samples_per_chirp = 8; }, "radar.samples_per_chirp");
  expect_rejected([](RadarParams& p) { p.chirps_per_frame = 0; }, "radar.chirps_per_frame");
  expect_rejected([](RadarParams& p) { p.adc_bits = 25; }, "radar.adc_bits");
  // The samples must fit in the chirp: 1024 samples at 10 MS/s need 102.4 us > 51.2 us.
  expect_rejected([](RadarParams& p) { p.samples_per_chirp = 1024; }, "radar.samples_per_chirp");
  // Every field is named by its scenario key (radar_param_keys), the CFAR's under
  // [radar.processing.cfar].
  expect_rejected([](RadarParams& p) { p.cfar.training_cells = 0; },
                  "radar.processing.cfar.training_cells");
  expect_rejected([](RadarParams& p) { p.cfar.false_alarm_probability = 1.0; },
                  "radar.processing.cfar.false_alarm_probability");
  expect_rejected([](RadarParams& p) { p.cfar.false_alarm_probability = kNaN; },
                  "radar.processing.cfar.false_alarm_probability");
  expect_rejected(
      [](RadarParams& p) {
        p.cfar.kind = CfarKind::os;
        p.cfar.os_rank = 17;
      },
      "radar.processing.cfar.os_rank");
  // The radome, [radar.radome]: a thickness or film below 0, a permittivity below 1 (vacuum), a
  // negative loss tangent, each beyond its range, and NaN.
  for (const double bad : {-1e-3, 0.06, kNaN}) {
    expect_rejected([&](RadarParams& p) { p.radome.thickness_m = bad; },
                    "radar.radome.thickness_m");
  }
  for (const double bad : {0.5, 101.0, kNaN}) {
    expect_rejected(
        [&](RadarParams& p) {
          p.radome.thickness_m = 0.005;
          p.radome.relative_permittivity = bad;
        },
        "radar.radome.relative_permittivity");
  }
  for (const double bad : {-0.01, 1.5, kNaN}) {
    expect_rejected(
        [&](RadarParams& p) {
          p.radome.thickness_m = 0.005;
          p.radome.loss_tangent = bad;
        },
        "radar.radome.loss_tangent");
  }
  for (const double bad : {-1e-4, 0.02, kNaN}) {
    expect_rejected([&](RadarParams& p) { p.radome.water_film_m = bad; },
                    "radar.radome.water_film_m");
  }
  // A CFAR window (2 (g + n) + 1 = 21 cells) longer than the range profile (16 samples).
  expect_rejected(
      [](RadarParams& p) {
        p.samples_per_chirp = 16;
        p.sample_rate_hz = 1e6;
      },
      "radar.processing.cfar.training_cells");
}

// Paper radar (examples/paper.toml): the derived quantities by the textbook relations [Ri14, PJ62].
TEST(RadarParams, DerivedQuantitiesOfThePaperRadar) {
  const RadarParams p;
  const RadarDerived d = derive(p);
  const double lambda = kC / 77e9;
  const double slope = 1e9 / 51.2e-6;
  const double max_range = kC * 10e6 / (2.0 * slope);
  const double deg = std::numbers::pi / 180.0;
  const std::string paper = "paper radar: 77 GHz, 1 GHz sweep in 51.2 us, 10 MS/s, 512 x 64";
  const std::string sp = "radar: signal processing";
  validate_derived("wavelength.up", sp, "wavelength", "m", paper + ", up-chirp", lambda,
                   "lambda = c / f_c", d.wavelength_m);
  // Default up-chirp centred on 77 GHz: 76.5 -> 77.5 GHz.
  EXPECT_EQ(p.sweep_direction, SweepDirection::up);
  EXPECT_EQ(d.sweep_sign, 1.0);
  validate_derived("start_frequency.up", sp, "sweep start frequency", "Hz", paper + ", up-chirp",
                   76.5e9, "f_c - B/2", d.start_frequency_hz);
  RadarParams down = p;
  down.sweep_direction = SweepDirection::down;
  EXPECT_EQ(derive(down).sweep_sign, -1.0);
  validate_derived("start_frequency.down", sp, "sweep start frequency", "Hz",
                   paper + ", down-chirp", 77.5e9, "f_c + B/2", derive(down).start_frequency_hz);
  validate_derived("wavelength.down", sp, "wavelength", "m", paper + ", down-chirp", lambda,
                   "lambda = c / f_c", derive(down).wavelength_m);
  validate_derived("chirp_slope", sp, "chirp slope", "Hz/s", paper, slope, "S = B / T_c",
                   d.chirp_slope_hz_per_s);
  validate_derived("range_resolution", sp, "range resolution", "m", paper, kC / 2e9,
                   "c / (2B) [Ri14]", d.range_resolution_m);
  validate_derived("max_range", sp, "maximum range", "m", paper, max_range, "c fs / (2 S) [Ri14]",
                   d.max_range_m);
  validate_derived("range_bin", sp, "range bin", "m", paper, max_range / 512.0,
                   "c fs / (2 S N) [Ri14]", d.range_bin_m);
  validate_derived("range_bin.reference_function", sp, "range bin", "m", paper,
                   test::reference_range_bin_m(p),
                   "c fs / (2 S N), reference_range_bin_m (chain_test_support.hpp)", d.range_bin_m);
  validate_derived("velocity_resolution", "radar: Doppler", "velocity resolution", "m/s", paper,
                   lambda / (2.0 * 64 * 51.2e-6), "lambda / (2 N_c T_i) [Ri14]",
                   d.velocity_resolution_m_per_s);
  validate_derived("max_unambiguous_velocity", "radar: Doppler", "maximum unambiguous |velocity|",
                   "m/s", paper, lambda / (4.0 * 51.2e-6), "lambda / (4 T_i) [Ri14]",
                   d.max_unambiguous_velocity_m_per_s);
  validate_derived("noise_power", "radar: SNR", "thermal noise power k T0 F fs", "W", paper,
                   test::reference_noise_power_w(p),
                   "k T0 F fs, reference_noise_power_w (chain_test_support.hpp)", d.noise_power_w);
  fogradar::testing::validate({.id = "radar.params.tx_power",
                               .group = "radar: SNR",
                               .quantity = "transmit power",
                               .unit = "W",
                               .conditions = paper + ", 10 dBm",
                               .reference = 0.01,
                               .source = "10 dBm = 1e-3 W x 10^(10/10)",
                               .value = d.tx_power_w,
                               .tolerance = 1e-15,
                               .kind = Tolerance::absolute});
  validate_derived("tx_gain", "radar: SNR", "transmit antenna gain", "1", paper + ", 25 dBi",
                   std::pow(10.0, 2.5), "10^(25/10)", d.tx_gain);
  validate_derived("rx_gain", "radar: SNR", "receive antenna gain", "1", paper + ", 25 dBi",
                   std::pow(10.0, 2.5), "10^(25/10)", d.rx_gain);
  validate_derived("beam_solid_angle", "radar: SNR", "two-way beam solid angle", "sr",
                   paper + ", 10 deg x 10 deg beam",
                   std::numbers::pi * 100.0 * deg * deg / (8.0 * std::log(2.0)),
                   "pi theta_az theta_el / (8 ln 2) [PJ62]", d.beam_solid_angle_sr);
  std::printf(
      "[ measured ] paper radar: lambda %.4f mm, range resolution %.4f m, range bin %.4f m, max "
      "range %.2f m, "
      "velocity resolution %.4f m/s, max |v| %.3f m/s, noise k T0 F fs %.2f dBm, beam solid angle "
      "%.5f sr\n",
      d.wavelength_m * 1e3, d.range_resolution_m, d.range_bin_m, d.max_range_m,
      d.velocity_resolution_m_per_s, d.max_unambiguous_velocity_m_per_s,
      10.0 * std::log10(d.noise_power_w / 1e-3), d.beam_solid_angle_sr);
}

// The sweep direction's names round-trip; anything else is refused naming the field.
TEST(RadarParams, SweepDirectionNames) {
  for (const SweepDirection direction : {SweepDirection::up, SweepDirection::down}) {
    EXPECT_EQ(sweep_direction_names.parse(to_string(direction), "radar.sweep_direction"),
              direction);
  }
  EXPECT_EQ(to_string(SweepDirection::up), "up");
  EXPECT_EQ(to_string(SweepDirection::down), "down");
  EXPECT_EQ(test_support::rejected_field(
                [] { sweep_direction_names.parse("Up", "radar.sweep_direction"); }),
            "radar.sweep_direction");
  EXPECT_EQ(test_support::rejected_field([] { sweep_direction_names.parse("sawtooth", "x.dir"); }),
            "x.dir");
}

// Radar equation round trip and against the reference form (Skolnik eq. 2.1): 1e-12 relative.
TEST(RadarParams, RadarEquationAndEq7AreInverse) {
  RadarParams p;
  p.tx_power_dbm = 3.0;
  p.tx_gain_dbi = 21.0;
  p.rx_gain_dbi = 14.0;
  p.centre_frequency_hz = 79e9;
  const RadarDerived d = derive(p);
  for (const double r : {1.0, 10.0, 55.5}) {
    const double pr = received_power_w(d.tx_power_w, d.tx_gain, d.rx_gain, d.wavelength_m, 3.3, r);
    const std::string conditions =
        "Pt 3 dBm, Gt 21 dBi, Gr 14 dBi, 79 GHz, RCS 3.3 m^2, R = " + id_number(r) + " m";
    validate_derived("received_power.R" + id_number(r) + "m", "radar: SNR", "received power", "W",
                     conditions, test::reference_received_power_w(p, 3.3, r),
                     "radar equation, Skolnik eq. 2.1 (reference_received_power_w)", pr);
    fogradar::testing::validate({.id = "radar.params.rcs_round_trip.R" + id_number(r) + "m",
                                 .group = "radar: RCS",
                                 .quantity = "RCS from the received power (paper eq. 7)",
                                 .unit = "m^2",
                                 .conditions = conditions,
                                 .reference = 3.3,
                                 .source = "the set RCS (eq. 7 inverts the radar equation)",
                                 .value = rcs_from_received_power_m2(pr, d.tx_power_w, d.tx_gain,
                                                                     d.rx_gain, d.wavelength_m, r),
                                 .tolerance = 3.3e-12,
                                 .kind = Tolerance::absolute});
  }
  fogradar::testing::validate({.id = "radar.params.beat_frequency",
                               .group = "radar: signal processing",
                               .quantity = "beat frequency of a 20 m two-way path",
                               .unit = "Hz",
                               .conditions = "path 20 m, slope 1 GHz / 51.2 us",
                               .reference = 20.0 * 1e9 / 51.2e-6 / kC,
                               .source = "f_b = S L / c",
                               .value = beat_frequency_hz(20.0, 1e9 / 51.2e-6),
                               .tolerance = 1e-6,
                               .kind = Tolerance::absolute});
}

// The Gaussian beam is 3 dB down at half the beamwidth off axis, and its two-way solid angle
// integral of g(az)^2 g(el)^2 over angles (small-angle, trapezoid on a fine grid here) equals the
// Probert-Jones closed form within 1e-6.
TEST(RadarParams, GaussianBeamAndTwoWaySolidAngle) {
  const double bw = 10.0 * std::numbers::pi / 180.0;
  for (const auto& [name, angle, expected, tolerance] :
       {std::tuple<const char*, double, double, double>{"plus_half_beamwidth", 0.5 * bw, 0.5,
                                                        1e-15},
        {"minus_half_beamwidth", -0.5 * bw, 0.5, 1e-15},
        {"boresight", 0.0, 1.0, 0.0}}) {
    fogradar::testing::validate(
        {.id = "radar.params.gaussian_beam." + std::string(name),
         .group = "radar: SNR",
         .quantity = "one-way Gaussian beam power pattern",
         .unit = "1",
         .conditions =
             "10 deg beamwidth, angle " + id_number(angle * 180.0 / std::numbers::pi) + " deg",
         .reference = expected,
         .source = "the beamwidth's definition: 3 dB down (0.5) at half the beamwidth, 1 on axis",
         .value = gaussian_beam_power(angle, bw),
         .tolerance = tolerance,
         .kind = Tolerance::absolute});
  }
  const double bw_el = 6.0 * std::numbers::pi / 180.0;
  const auto line_integral = [](double beam) {
    const int n = 20000;
    const double h = 8.0 * beam / n;
    double s = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double x = -4.0 * beam + i * h;
      const double g = gaussian_beam_power(x, beam);
      s += (i == 0 || i == n ? 0.5 : 1.0) * g * g;
    }
    return s * h;
  };
  EXPECT_NEAR(two_way_beam_solid_angle_sr(bw, bw_el) / (line_integral(bw) * line_integral(bw_el)),
              1.0, 1e-6);
}

// --- Scene ------------------------------------------------------------------------------------

void expect_scene_rejected(const std::function<void(Scene&)>& change, const std::string& field) {
  Scene scene;
  change(scene);
  EXPECT_EQ(test_support::rejected_field([&] { scene.validate(); }), field);
}

TEST(Scene, RejectsEveryInvalidField) {
  EXPECT_NO_THROW(Scene{}.validate());
  EXPECT_NO_THROW(evt_rear_scene().validate());
  EXPECT_NO_THROW(point_target_scene(10.0).validate());
  expect_scene_rejected([](Scene& s) { s.centres.clear(); }, "target.centres");
  for (const double bad : {-200.0, 200.0, kNaN}) {
    expect_scene_rejected([&](Scene& s) { s.centres[0].range_offset_m = bad; },
                          "target.centres[0].range_offset_m");
    expect_scene_rejected([&](Scene& s) { s.centres[0].lateral_m = bad; },
                          "target.centres[0].lateral_m");
    expect_scene_rejected([&](Scene& s) { s.centres[0].height_m = bad; },
                          "target.centres[0].height_m");
    expect_scene_rejected([&](Scene& s) { s.centres[0].radial_velocity_m_per_s = bad * 10.0; },
                          "target.centres[0].radial_velocity_m_per_s");
    expect_scene_rejected([&](Scene& s) { s.sensor_height_m = bad; }, "radar.height_m");
  }
  for (const double bad : {-1.0, 2e6, kNaN}) {
    expect_scene_rejected([&](Scene& s) { s.centres[0].rcs_m2 = bad; }, "target.centres[0].rcs_m2");
  }
  // The index names the offending centre.
  expect_scene_rejected(
      [](Scene& s) {
        s = evt_rear_scene();
        s.centres[3].rcs_m2 = -1.0;
      },
      "target.centres[3].rcs_m2");
  for (const double bad : {-1.5, 1.5, kNaN}) {
    expect_scene_rejected([&](Scene& s) { s.surfaces = {coefficient_floor(bad)}; },
                          "chamber.room.floor.reflection_coefficient");
  }
  for (const double bad : {-1e-3, 0.2, kNaN}) {
    expect_scene_rejected([&](Scene& s) { s.micro_motion_std_m = bad; },
                          "target.micro_motion_std_m");
  }
  expect_scene_rejected([](Scene& s) { s.clutter_scatterers_per_bin = 0; },
                        "radar.clutter_scatterers_per_bin");
  expect_scene_rejected([](Scene& s) { s.clutter_scatterers_per_bin = 65; },
                        "radar.clutter_scatterers_per_bin");
  for (const double bad : {-0.1, 1.1, kNaN}) {
    expect_scene_rejected([&](Scene& s) { s.radome_two_way_transmittance = bad; },
                          "radome_two_way_transmittance");
    expect_scene_rejected([&](Scene& s) { s.target_film_reflectance = bad; },
                          "target_film_reflectance");
  }
}

// [target] water_film_m: a film below 0, beyond 10 mm, or NaN is refused by its key's name.
TEST(TargetKeys, RejectsAnInvalidWaterFilm) {
  const KeyTable<sensor::TargetWorld> keys = sensor::target_world_keys();
  EXPECT_NO_THROW(keys.check(sensor::TargetWorld{.water_film_m = 0.01}));
  for (const double bad : {-1e-4, 0.011, kNaN}) {
    EXPECT_EQ(
        test_support::rejected_field([&] { keys.check(sensor::TargetWorld{.water_film_m = bad}); }),
        "target.water_film_m")
        << bad;
  }
}

TEST(Scene, SwerlingNamesRoundTrip) {
  for (const Swerling s : {Swerling::zero, Swerling::one, Swerling::three})
    EXPECT_EQ(swerling_names.parse(to_string(s), "radar.target.swerling"), s);
  try {
    swerling_names.parse("2", "target.centres[1].swerling");
    ADD_FAILURE() << "accepted Swerling 2";
  } catch (const InvalidParameter& error) {
    EXPECT_EQ(error.field(), "target.centres[1].swerling");
  }
}

// The chain rejects a chamber resolved at another frequency, a target beyond the unambiguous
// range (c fs / (2 S) - 1 m = 75.8 m for the paper radar) and a centre at or behind the radar.
TEST(RadarChain, CheckCompatibleNamesTheField) {
  const RadarChain chain(RadarParams{});
  const propagation::Chamber at_77 = test::make_chamber(test::paper_chamber_spec(), 77e9);
  const propagation::Chamber at_79 = test::make_chamber(test::paper_chamber_spec(), 79e9);
  EXPECT_NO_THROW(chain.check_compatible(evt_rear_scene(), at_77));
  const auto expect_field = [&](const Scene& scene, const propagation::Chamber& chamber,
                                const std::string& field) {
    EXPECT_EQ(test_support::rejected_field([&] { chain.check_compatible(scene, chamber); }), field);
  };
  expect_field(evt_rear_scene(), at_79, "chamber.frequency_hz");
  Scene far = point_target_scene(10.0);
  far.centres[0].range_offset_m = 70.0;  // 80 m
  expect_field(far, at_77, "chamber.target_range_m");
  Scene invalid = point_target_scene(10.0);
  invalid.centres[0].rcs_m2 = kNaN;
  expect_field(invalid, at_77, "target.centres[0].rcs_m2");
  Scene behind = point_target_scene(10.0);
  behind.centres[0].range_offset_m = -10.0;  // at the radar
  expect_field(behind, at_77, "target.centres[0].range_offset_m");
  behind.centres[0].range_offset_m = -12.0;  // behind it
  expect_field(behind, at_77, "target.centres[0].range_offset_m");
}

}  // namespace
}  // namespace fogradar::radar
