// Bottom loss against grazing angle as observations: read from the observation file, fitted with a
// sediment model's half-space through the reflection coefficient (docs/reflection.md), alone and
// jointly with attenuation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sedwave/inversion/fit.hpp"
#include "sedwave/inversion/setup.hpp"
#include "sedwave/sediment/catalog.hpp"
#include "sedwave/sediment/seabed_reflection.hpp"

namespace sedwave::inversion {
namespace {

constexpr double kWaterSpeed = 1500.0;
constexpr double kWaterDensity = 1025.0;
constexpr double kSigmaDb = 0.2;

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("sedwave_bottom_loss_" + name);
  std::ofstream(path) << text;
  return path;
}

/// Error text of reading `text` as an observation CSV.
std::string read_error(const std::string& text) {
  try {
    (void)read_observation_csv(write_file("bad.csv", text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

/// Noise-free bottom loss of EDFM with `truth` at the angles and frequencies, from the reflection
/// code directly, as an observation file; `attenuation` adds the model's attenuation at each
/// frequency (5 % sigma).
std::string synthetic_file(const Candidate& truth, bool attenuation) {
  const sediment::SeabedPart part{truth.model, truth.parameters.values(), 0.0};
  std::ostringstream out;
  out.precision(12);
  out << "# water_sound_speed_m_per_s: " << kWaterSpeed << "\n# water_density_kg_per_m3: " << kWaterDensity << "\n"
      << "quantity,frequency,frequency_unit,value,value_unit,sigma,grazing_angle_deg\n";
  for (double f : {2e3, 20e3}) {
    const sediment::LayeredHalfspace seabed{{kWaterSpeed, 0.0, 0.0, 0.0, kWaterDensity}, {},
                                            sediment::medium_of(part, f, false, "half-space")};
    for (double degrees = 4.0; degrees <= 88.0; degrees += 6.0) {
      const double loss =
          sediment::bottom_loss_db(sediment::reflection_coefficient(seabed, degrees * std::numbers::pi / 180.0, f));
      out << "bottom_loss," << f << ",Hz," << loss << ",dB," << kSigmaDb << ',' << degrees << '\n';
    }
    if (attenuation) {
      const double alpha = truth.model->evaluate(truth.parameters.values(), f, false).attenuation;
      out << "attenuation," << f << ",Hz," << alpha << ",Np/m," << 0.05 * alpha << ",\n";
    }
  }
  return out.str();
}

Candidate edfm(double porosity, double permeability) {
  ModelSetup setup;
  setup.model = "edfm";
  setup.free = "porosity,permeability";
  setup.values.push_back({"porosity", porosity, "test", ""});
  setup.values.push_back({"permeability", permeability, "test", ""});
  return make_candidate(setup);
}

const ParameterResult& parameter(const FitResult& r, const std::string& name) {
  for (const ParameterResult& p : r.parameters) {
    if (p.name == name) return p;
  }
  throw std::out_of_range(name);
}

void expect_recovered(const FitResult& r, double porosity, double permeability) {
  ASSERT_TRUE(r.converged) << r.solver_message;
  EXPECT_LT(r.chi2, 1e-6);  // noise-free data: the truth fits exactly
  for (const auto& [name, truth] : {std::pair{"porosity", porosity}, std::pair{"permeability", permeability}}) {
    const ParameterResult& p = parameter(r, name);
    EXPECT_TRUE(p.determined) << name;
    EXPECT_NEAR(p.value, truth, 1e-3 * truth) << name;
    EXPECT_GT(p.sigma, 0.0) << name;
    EXPECT_LT(std::abs(p.value - truth), p.sigma) << name;  // within its sigma
  }
}

FitOptions quick() {
  FitOptions o;
  o.method = FitMethod::Ceres;
  o.profile_likelihood = false;
  return o;
}

TEST(BottomLossFit, HalfSpaceRoundTripRecoversTheParameters) {
  const Candidate truth = edfm(0.42, 3e-11);
  const ObservationSet data = read_observation_csv(write_file("truth.csv", synthetic_file(truth, false)));
  ASSERT_EQ(data.observations.size(), 30U);
  EXPECT_EQ(data.observations.front().quantity, Quantity::BottomLoss);
  EXPECT_NEAR(data.observations.front().grazing_angle, 4.0 * std::numbers::pi / 180.0, 1e-15);
  const Candidate start = edfm(0.35, 1e-10);
  expect_recovered(fit(data, *start.model, start.parameters, quick()), 0.42, 3e-11);
}

TEST(BottomLossFit, JointFitWithAttenuation) {
  const Candidate truth = edfm(0.38, 1e-11);
  const ObservationSet data = read_observation_csv(write_file("joint.csv", synthetic_file(truth, true)));
  ASSERT_EQ(data.observations.size(), 32U);
  const Candidate start = edfm(0.45, 5e-11);
  const FitResult r = fit(data, *start.model, start.parameters, quick());
  expect_recovered(r, 0.38, 1e-11);
  int attenuation_rows = 0;
  for (const PointResidual& p : r.residuals) attenuation_rows += p.observation.quantity == Quantity::Attenuation;
  EXPECT_EQ(attenuation_rows, 2);
}

/// Rows repeated at one angle, frequency and sigma are fitted as their mean plus their scatter: two
/// rows 0.1 dB either side of the truth leave the truth as the best fit, with chi^2 = rows x (0.1 /
/// 0.2)^2 over the rows' own residuals.
TEST(BottomLossFit, RepeatedRowsFitAsTheirMeanWithTheirScatter) {
  const Candidate truth = edfm(0.42, 3e-11);
  std::istringstream single(synthetic_file(truth, false));
  std::ostringstream repeated;
  repeated.precision(12);
  int rows = 0;
  for (std::string line; std::getline(single, line);) {
    if (!line.starts_with("bottom_loss,")) {
      repeated << line << '\n';
      continue;
    }
    // quantity,frequency,unit,value,... : the value is the fourth field.
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
    for (double shift : {-0.1, 0.1}) {
      fields[3] = std::to_string(std::stod(fields[3]) + shift);
      std::string row;
      for (std::size_t i = 0; i < fields.size(); ++i) row += (i ? "," : "") + fields[i];
      repeated << row << '\n';
      fields[3] = std::to_string(std::stod(fields[3]) - shift);
      ++rows;
    }
  }
  const ObservationSet data = read_observation_csv(write_file("repeated.csv", repeated.str()));
  ASSERT_EQ(rows, 60);
  const Candidate start = edfm(0.35, 1e-10);
  const FitResult r = fit(data, *start.model, start.parameters, quick());
  ASSERT_TRUE(r.converged) << r.solver_message;
  EXPECT_EQ(r.residuals.size(), 60U);
  EXPECT_NEAR(r.chi2, 60 * 0.25, 1e-3);
  EXPECT_NEAR(parameter(r, "porosity").value, 0.42, 1e-3 * 0.42);
  EXPECT_NEAR(parameter(r, "permeability").value, 3e-11, 1e-3 * 3e-11);
}

TEST(BottomLossFit, ReflectionMagnitudeRoundTrip) {
  const Candidate truth = edfm(0.5, 2e-11);
  const sediment::SeabedPart part{truth.model, truth.parameters.values(), 0.0};
  std::ostringstream out;
  out.precision(12);
  out << "# water_sound_speed_m_per_s: " << kWaterSpeed << "\n"
      << "quantity,frequency,frequency_unit,value,value_unit,sigma,grazing_angle_deg\n";
  for (double f : {1e3, 8e3}) {
    const sediment::LayeredHalfspace seabed{{kWaterSpeed, 0.0, 0.0, 0.0, kWaterDensity}, {},
                                            sediment::medium_of(part, f, false, "half-space")};
    for (double degrees = 5.0; degrees <= 90.0; degrees += 5.0) {
      const double r = std::abs(sediment::reflection_coefficient(seabed, degrees * std::numbers::pi / 180.0, f));
      out << "reflection_magnitude," << f / 1e3 << ",kHz," << r << ",1,0.01," << degrees << '\n';
    }
  }
  const ObservationSet data = read_observation_csv(write_file("magnitude.csv", out.str()));
  ASSERT_EQ(data.observations.size(), 36U);
  EXPECT_EQ(data.observations.front().quantity, Quantity::ReflectionMagnitude);
  const Candidate start = edfm(0.4, 1e-10);
  expect_recovered(fit(data, *start.model, start.parameters, quick()), 0.5, 2e-11);
}

TEST(BottomLossFit, BadRowsNameFileLineAndField) {
  const std::string water = "# water_sound_speed_m_per_s: 1500\n";
  const std::string header = "quantity,frequency,frequency_unit,value,value_unit,sigma,grazing_angle_deg\n";
  const auto error = [&](const std::string& row, const std::string& head) { return read_error(head + row); };
  // The row under `head` is refused with `message` in its text.
  const auto refused = [&](const std::string& row, const std::string& head, const std::string& message) {
    const std::string text = error(row, head);
    EXPECT_NE(text.find(message), std::string::npos) << text;
  };
  refused("bottom_loss,1,kHz,-2,dB,0.5,30\n", water + header,
          "bad.csv:3:4: field 'value': bottom loss -2 dB is below 0 dB");
  EXPECT_EQ(error("bottom_loss,1,kHz,-1,dB,0.5,30\n", water + header), "(no error)");  // within its noise
  refused("reflection_magnitude,1,kHz,-0.1,1,0.05,30\n", water + header,
          ":3:4: field 'value': |R| must be >= 0");
  refused("bottom_loss,1,kHz,3,dB,,30\n", water + header,
          ":3:6: field 'sigma': a reflection row needs");
  refused("bottom_loss,1,kHz,3,dB,0.5,\n", water + header,
          ":3:7: field 'grazing_angle_deg': a reflection row needs");
  refused("bottom_loss,1,kHz,3,dB,0.5,95\n", water + header,
          ":3:7: field 'grazing_angle_deg': grazing angle must be in (0, 90]");
  refused("bottom_loss,1,kHz,3,Np/m,0.5,30\n", water + header,
          ":3:5: field 'value_unit': unknown unit 'Np/m'");
  refused("attenuation,1,kHz,3,dB/m,0.5,30\n", water + header,
          ":3:7: field 'grazing_angle_deg': only a reflection row");
  refused("bottom_loss,1,kHz,3,dB,0.5,30\n", header,
          ":2:5: field 'value_unit': reflection data need a water sound speed");
  // Without the angle column a bottom-loss row is missing its angle.
  refused("bottom_loss,1,kHz,3,dB,0.5\n", water + "quantity,frequency,frequency_unit,value,value_unit,sigma\n",
          ":3:7: field 'grazing_angle_deg'");
}

TEST(BottomLossFit, AModelWithoutDensityIsRefused) {
  ModelSetup setup;
  setup.model = "lattice";
  const Candidate dry = make_candidate(setup);
  const ObservationSet data = read_observation_csv(write_file(
      "dry.csv", "# water_sound_speed_m_per_s: 1500\n"
                 "quantity,frequency,frequency_unit,value,value_unit,sigma,grazing_angle_deg\n"
                 "bottom_loss,1,kHz,3,dB,0.5,30\n"));
  EXPECT_THROW((void)fit(data, *dry.model, dry.parameters, quick()), std::invalid_argument);
}

/// Shear-wave rows: the grain-shearing model's shear speed and attenuation beside its compressional
/// ones, noise-free, fitted back.
TEST(ShearObservations, RoundTripWithTheCompressionalWave) {
  ModelSetup setup;
  setup.model = "grain-shearing";
  const Candidate truth = make_candidate(setup);
  const std::vector<double> values = truth.parameters.values();
  std::ostringstream out;
  out.precision(12);
  out << "quantity,frequency,frequency_unit,value,value_unit,sigma\n";
  for (double f : {1e3, 10e3, 100e3}) {
    const sediment::Wave p = truth.model->evaluate(values, f, false);
    const sediment::Wave s = truth.model->evaluate_shear(values, f, false);
    out << "attenuation," << f << ",Hz," << p.attenuation << ",Np/m," << 0.05 * p.attenuation << '\n'
        << "sound_speed," << f << ",Hz," << p.speed << ",m/s,5\n"
        << "shear_speed," << f << ",Hz," << s.speed << ",m/s,5\n"
        << "shear_attenuation," << f << ",Hz," << s.attenuation * kDecibelPerNeper << ",dB/m,"
        << 0.05 * s.attenuation * kDecibelPerNeper << '\n';
  }
  const ObservationSet data = read_observation_csv(write_file("shear.csv", out.str()));
  ASSERT_EQ(data.observations.size(), 12U);
  EXPECT_EQ(data.observations[3].quantity, Quantity::ShearAttenuation);
  ModelSetup away = setup;
  const Candidate start_candidate = make_candidate(away);
  FitParameters start = start_candidate.parameters;
  for (int i : start.free_indices()) start.spec[static_cast<std::size_t>(i)].value *= 1.3;
  const FitResult r = fit(data, *truth.model, start, quick());
  ASSERT_TRUE(r.converged) << r.solver_message;
  EXPECT_LT(r.chi2, 1e-6);
  for (int i : start.free_indices()) {
    const ParameterResult& p = r.parameters[static_cast<std::size_t>(i)];
    EXPECT_NEAR(p.value, values[static_cast<std::size_t>(i)], 1e-4 * values[static_cast<std::size_t>(i)]) << p.name;
  }
  // A model without a shear wave cannot fit shear rows.
  const Candidate fluid = edfm(0.4, 1e-11);
  EXPECT_THROW((void)fit(data, *fluid.model, fluid.parameters, quick()), std::invalid_argument);
}

TEST(ShearObservations, DecibelPerWavelengthIsRefused) {
  EXPECT_NE(read_error("quantity,frequency,frequency_unit,value,value_unit,sigma\nshear_attenuation,1,kHz,3,dB/lambda,\n")
                .find(":2:5: field 'value_unit': unknown unit 'dB/lambda' for shear_attenuation"),
            std::string::npos);
}

/// A layered seabed (layered:edfm+edfm): noise-free bottom loss of a soft layer over a harder
/// half-space at 1-4 kHz, from the reflection code's own stack built part by part.
std::string layered_file(double layer_porosity, double thickness, double halfspace_porosity) {
  const auto model = sediment::make_sediment_model("edfm");
  std::vector<double> layer = model->default_values();
  std::vector<double> below = layer;
  layer[static_cast<std::size_t>(model->index_of("porosity"))] = layer_porosity;
  below[static_cast<std::size_t>(model->index_of("porosity"))] = halfspace_porosity;
  std::ostringstream out;
  out.precision(12);
  out << "# water_sound_speed_m_per_s: " << kWaterSpeed << "\n# water_density_kg_per_m3: " << kWaterDensity << "\n"
      << "quantity,frequency,frequency_unit,value,value_unit,sigma,grazing_angle_deg\n";
  for (double f : {1e3, 2e3, 4e3}) {
    const sediment::AcousticMedium water{kWaterSpeed, 0.0, 0.0, 0.0, kWaterDensity};
    const sediment::LayeredHalfspace seabed{water,
                                            {{sediment::medium_of({model, layer, thickness}, f, false, "l1"), thickness}},
                                            sediment::medium_of({model, below, 0.0}, f, false, "half-space")};
    for (double degrees = 5.0; degrees <= 85.0; degrees += 8.0) {
      const double loss =
          sediment::bottom_loss_db(sediment::reflection_coefficient(seabed, degrees * std::numbers::pi / 180.0, f));
      out << "bottom_loss," << f << ",Hz," << loss << ",dB," << kSigmaDb << ',' << degrees << '\n';
    }
  }
  return out.str();
}

Candidate layered(const std::string& free, double layer_porosity, double thickness, double halfspace_porosity) {
  ModelSetup setup;
  setup.model = "layered:edfm+edfm";
  setup.free = free;
  setup.values.push_back({"porosity", halfspace_porosity, "test", ""});
  setup.values.push_back({"l1.porosity", layer_porosity, "test", ""});
  setup.values.push_back({"l1.thickness", thickness, "test", ""});
  return make_candidate(setup);
}

TEST(LayeredSeabedFit, LayerThicknessAndPorositiesRecovered) {
  const ObservationSet data = read_observation_csv(write_file("layered.csv", layered_file(0.7, 0.5, 0.4)));
  const Candidate start = layered("porosity,l1.porosity,l1.thickness", 0.6, 0.4, 0.45);
  const FitResult r = fit(data, *start.model, start.parameters, quick());
  ASSERT_TRUE(r.converged) << r.solver_message;
  EXPECT_LT(r.chi2, 1e-6);
  for (const auto& [name, truth] : {std::pair{"porosity", 0.4}, std::pair{"l1.porosity", 0.7}, std::pair{"l1.thickness", 0.5}}) {
    const ParameterResult& p = parameter(r, name);
    EXPECT_TRUE(p.determined) << name;
    EXPECT_NEAR(p.value, truth, 1e-3 * truth) << name;
  }
}

/// A layer of the half-space's own material leaves the reflection unchanged whatever its thickness:
/// the data cannot see it, and the fit says so.
TEST(LayeredSeabedFit, AnInvisibleLayersThicknessIsNotDetermined) {
  const ObservationSet data = read_observation_csv(write_file("invisible.csv", layered_file(0.4, 0.5, 0.4)));
  const Candidate start = layered("porosity,l1.thickness", 0.4, 0.3, 0.45);
  const FitResult r = fit(data, *start.model, start.parameters, quick());
  ASSERT_TRUE(r.converged) << r.solver_message;
  EXPECT_LT(r.chi2, 1e-6);
  EXPECT_TRUE(parameter(r, "porosity").determined);
  EXPECT_NEAR(parameter(r, "porosity").value, 0.4, 1e-4);
  EXPECT_FALSE(parameter(r, "l1.thickness").determined);
}

}  // namespace
}  // namespace sedwave::inversion
