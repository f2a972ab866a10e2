// Observations: read with the command line's readers (the same messages), built from numpy arrays,
// written as the sedwave observation CSV. SI throughout: Hz, Np/m, m/s.
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "bindings.hpp"
#include "sedwave/inversion/observations.hpp"
#include "sedwave/inversion/setup.hpp"
#include "sedwave/inversion/synthetic.hpp"

namespace sedwave::python {
namespace {

using inversion::Observation;
using inversion::ObservationSet;
using inversion::Quantity;


template <typename Field>
py::array_t<double> column(const ObservationSet& set, Field field) {
  py::array_t<double> out(static_cast<py::ssize_t>(set.observations.size()));
  double* o = out.mutable_data();
  for (std::size_t i = 0; i < set.observations.size(); ++i) o[i] = field(set.observations[i]);
  return out;
}

/// One text per row from a str (every row) or a sequence of str.
std::vector<std::string> texts_of(const py::handle& given, std::size_t rows, const std::string& argument) {
  if (py::isinstance<py::str>(given)) return std::vector<std::string>(rows, given.cast<std::string>());
  std::vector<std::string> texts;
  try {
    texts = given.cast<std::vector<std::string>>();
  } catch (const py::cast_error&) {
    throw py::type_error(argument + ": expected a str or a sequence of str");
  }
  if (texts.size() != rows) {
    throw py::value_error(argument + ": " + std::to_string(texts.size()) + " entries for " + std::to_string(rows) +
                          " observations");
  }
  return texts;
}

DoubleArray flat_numbers(const py::handle& given, const std::string& argument) {
  DoubleArray array = DoubleArray::ensure(given);
  if (!array || array.ndim() != 1) throw py::value_error(argument + ": expected a 1-D array of numbers");
  return array;
}

/// Observations from arrays, each value converted to SI from its unit (the observation CSV's units).
/// A reflection row (bottom loss [dB] or |R|): its sigma and grazing angle [deg] are required, a
/// bottom loss may fall below 0 dB by its noise (down to -3 sigma), an |R| not below 0 (the
/// observation CSV's rules).
void set_reflection_row(Observation& o, std::size_t i, double raw, bool has_sigma, double raw_sigma,
                        const std::string& unit, const std::optional<DoubleArray>& angles) {
  const std::string at = "[" + std::to_string(i) + "]";
  const bool loss = o.quantity == Quantity::BottomLoss;
  o.unit = unit.empty() ? (loss ? "dB" : "1") : unit;
  if (o.unit != (loss ? "dB" : "1")) {
    throw py::value_error("unit" + at + ": '" + o.unit + "': a " + (loss ? "bottom loss is in dB" : "|R| is in 1"));
  }
  if (!has_sigma) throw py::value_error("sigma" + at + ": a reflection row needs its 1-sigma uncertainty");
  if (!angles) throw py::value_error("grazing_angle_deg: reflection rows need their grazing angles [deg]");
  const double degrees = angles->data()[i];
  if (!(degrees > 0.0 && degrees <= 90.0)) {
    throw py::value_error("grazing_angle_deg" + at + " = " + std::to_string(degrees) + ": must be in (0, 90] degrees");
  }
  if (!std::isfinite(raw) || (loss ? raw < -3.0 * raw_sigma : raw < 0.0)) {
    throw py::value_error("value" + at + ": " + (loss ? "a bottom loss below 0 dB by more than three sigmas" : "|R| must be >= 0"));
  }
  o.value = raw;
  o.sigma = raw_sigma;
  o.grazing_angle = degrees * std::numbers::pi / 180.0;
}

ObservationSet from_arrays(const py::handle& quantity, const py::handle& frequency_hz, const py::handle& value,
                           const py::object& sigma, const py::object& unit, std::optional<double> water_speed,
                           std::optional<double> sediment_speed, const std::string& source,
                           const py::object& grazing_angle_deg) {
  const DoubleArray f = flat_numbers(frequency_hz, "frequency_hz");
  const DoubleArray v = flat_numbers(value, "value");
  const auto n = static_cast<std::size_t>(f.size());
  if (static_cast<std::size_t>(v.size()) != n) {
    throw py::value_error("value: " + std::to_string(v.size()) + " entries for " + std::to_string(n) + " frequencies");
  }
  if (n == 0) throw py::value_error("frequency_hz: no observations");
  std::optional<DoubleArray> s;
  if (!sigma.is_none()) {
    s = flat_numbers(sigma, "sigma");
    if (static_cast<std::size_t>(s->size()) != n) {
      throw py::value_error("sigma: " + std::to_string(s->size()) + " entries for " + std::to_string(n) + " frequencies");
    }
  }
  std::optional<DoubleArray> angles;
  if (!grazing_angle_deg.is_none()) {
    angles = flat_numbers(grazing_angle_deg, "grazing_angle_deg");
    if (static_cast<std::size_t>(angles->size()) != n) {
      throw py::value_error("grazing_angle_deg: " + std::to_string(angles->size()) + " entries for " + std::to_string(n) +
                            " frequencies");
    }
  }
  const std::vector<std::string> quantities = texts_of(quantity, n, "quantity");
  std::vector<std::string> units;
  if (!unit.is_none()) units = texts_of(unit, n, "unit");
  ObservationSet set;
  set.water_sound_speed = water_speed;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string at = "[" + std::to_string(i) + "]";
    const std::string& q = quantities[i];
    Observation o;
    o.file = source;
    o.line = static_cast<int>(i);
    o.frequency_hz = f.data()[i];
    if (!(o.frequency_hz > 0.0) || !std::isfinite(o.frequency_hz)) {
      throw py::value_error("frequency_hz" + at + " = " + std::to_string(o.frequency_hz) +
                            ": a frequency must be positive and finite [Hz]");
    }
    const double raw = v.data()[i];
    // A plain double and a flag, not an optional: GCC 12 takes the optional's value for uninitialised.
    const bool has_sigma = s.has_value();
    const double raw_sigma = has_sigma ? s->data()[i] : 0.0;
    if (has_sigma && (!std::isfinite(raw_sigma) || !(raw_sigma > 0.0))) {
      throw py::value_error("sigma" + at + ": must be positive and finite (give None for no sigma)");
    }
    if (q == "bottom_loss" || q == "reflection_magnitude") {
      o.quantity = q == "bottom_loss" ? Quantity::BottomLoss : Quantity::ReflectionMagnitude;
      set_reflection_row(o, i, raw, has_sigma, raw_sigma, units.empty() ? std::string() : units[i], angles);
      set.observations.push_back(o);
      continue;
    }
    if (!std::isfinite(raw) || !(raw > 0.0)) throw py::value_error("value" + at + ": must be positive and finite");
    try {
      if (q == "shear_speed" || q == "shear_attenuation") {
        const bool speed = q == "shear_speed";
        o.quantity = speed ? Quantity::ShearSpeed : Quantity::ShearAttenuation;
        o.unit = units.empty() ? (speed ? "m/s" : "Np/m") : units[i];
        if (o.unit == "ratio" || o.unit == "dB/lambda") {
          throw std::invalid_argument("'" + o.unit + "' is not a unit of " + q + " (it would need the shear speed)");
        }
        const auto to_si = [&](double x) {
          return speed ? inversion::sound_speed_to_m_per_s(x, o.unit, water_speed)
                       : inversion::attenuation_to_np_per_m(x, o.unit, o.frequency_hz, sediment_speed);
        };
        o.value = to_si(raw);
        if (has_sigma) o.sigma = to_si(raw_sigma);
      } else if (q == "attenuation") {
        o.quantity = Quantity::Attenuation;
        o.unit = units.empty() ? "Np/m" : units[i];
        o.value = inversion::attenuation_to_np_per_m(raw, o.unit, o.frequency_hz, sediment_speed);
        if (has_sigma) o.sigma = inversion::attenuation_to_np_per_m(raw_sigma, o.unit, o.frequency_hz, sediment_speed);
      } else if (q == "sound_speed" || q == "sound_speed_ratio") {
        o.quantity = Quantity::SoundSpeed;
        o.unit = units.empty() ? (q == "sound_speed" ? "m/s" : "ratio") : units[i];
        o.value = inversion::sound_speed_to_m_per_s(raw, o.unit, water_speed);
        if (has_sigma) o.sigma = inversion::sound_speed_to_m_per_s(raw_sigma, o.unit, water_speed);
      } else {
        throw std::invalid_argument("'" + q + "': expected attenuation, sound_speed, sound_speed_ratio, "
                                    "shear_speed, shear_attenuation, bottom_loss or reflection_magnitude");
      }
    } catch (const std::invalid_argument& e) {
      const bool known = q == "attenuation" || q.starts_with("sound_speed") || q.starts_with("shear_");
      throw py::value_error((known ? "unit" : "quantity") + at + ": " + e.what());
    }
    if (angles && !std::isnan(angles->data()[i])) {  // reflection rows went on above
      throw py::value_error("grazing_angle_deg" + at + ": only a reflection row has a grazing angle (NaN for others)");
    }
    set.observations.push_back(o);
  }
  return set;
}

ObservationSet read_observations(const py::handle& paths, std::optional<double> water_speed,
                                 std::optional<double> sediment_speed) {
  std::vector<std::filesystem::path> files;
  if (py::isinstance<py::str>(paths) || py::hasattr(paths, "__fspath__")) {
    files.push_back(paths.cast<std::filesystem::path>());
  } else {
    files = paths.cast<std::vector<std::filesystem::path>>();
  }
  const inversion::ReadOptions read{water_speed, sediment_speed};
  ObservationSet all;
  for (const auto& f : files) all.append(inversion::read_observation_csv(f, read));
  if (!all.water_sound_speed) all.water_sound_speed = water_speed;
  return all;
}

}  // namespace

void bind_data(py::module_& m) {
  static py::exception<inversion::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<inversion::SetupError> setup_error(m, "SetupError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const inversion::InputError& e) {
      // A file that is not there is an OSError (FileNotFoundError), as open() raises.
      if (e.line() == 0 && !e.file().empty() && !std::filesystem::exists(e.file())) {
        py::object error = py::module_::import("builtins").attr("FileNotFoundError")(2, e.what(), e.file());
        PyErr_SetObject(error.get_type().ptr(), error.ptr());
        return;
      }
      py::object error = py::handle(input_error.ptr())(e.what());
      error.attr("file") = e.file();
      error.attr("line") = e.line();
      error.attr("column") = e.column();
      error.attr("field") = e.field();
      PyErr_SetObject(input_error.ptr(), error.ptr());
    } catch (const inversion::SetupError& e) {
      setup_error(e.what());
    }
  });

  py::class_<ObservationSet>(m, "Observations", R"doc(
Observations in SI: quantity ("attenuation" [Np/m], "sound_speed" [m/s] (sound-speed ratios are
converted with the water sound speed), "shear_speed" [m/s], "shear_attenuation" [Np/m],
"bottom_loss" [dB], "reflection_magnitude" [1]), frequency_hz [Hz], value, sigma (NaN where none
was given), grazing_angle_deg (of reflection rows; NaN for others).

Observations(quantity, frequency_hz, value, sigma=None, unit=None, water_speed=None,
sediment_speed=None, grazing_angle_deg=None): from arrays. quantity: one of the names above or
"sound_speed_ratio", one for all rows or one per row; unit: the values' unit as the observation
CSV spells it ("Np/m", "dB/m", "dB/kHz/m", "dB/lambda", "m/s", "km/s", "ratio", "dB", "1");
default SI (ratio for ratios). sigma is in the value's unit. Reflection rows need their sigma, their
grazing angle [deg] and water_speed (the water above the seabed).)doc")
      .def(py::init(&from_arrays), py::arg("quantity"), py::arg("frequency_hz"), py::arg("value"),
           py::arg("sigma") = py::none(), py::arg("unit") = py::none(), py::arg("water_speed") = py::none(),
           py::arg("sediment_speed") = py::none(), py::arg("source") = "arrays",
           py::arg("grazing_angle_deg") = py::none())
      .def("__len__", [](const ObservationSet& s) { return s.observations.size(); })
      .def_property_readonly("frequency_hz", [](const ObservationSet& s) {
        return column(s, [](const Observation& o) { return o.frequency_hz; });
      })
      .def_property_readonly("value", [](const ObservationSet& s) {
        return column(s, [](const Observation& o) { return o.value; });
      })
      .def_property_readonly("sigma", [](const ObservationSet& s) {
        return column(s, [](const Observation& o) { return o.sigma.value_or(std::nan("")); });
      })
      .def_property_readonly("grazing_angle_deg", [](const ObservationSet& s) {
        return column(s, [](const Observation& o) {
          return is_reflection(o.quantity) ? o.grazing_angle * 180.0 / std::numbers::pi : std::nan("");
        });
      })
      .def_property_readonly("quantity", [](const ObservationSet& s) {
        std::vector<std::string> q;
        for (const Observation& o : s.observations) q.emplace_back(inversion::quantity_name(o.quantity));
        return py::array(py::cast(q));
      })
      .def_property_readonly("unit", [](const ObservationSet& s) {
        std::vector<std::string> u;
        for (const Observation& o : s.observations) u.push_back(o.unit);
        return u;
      }, "each value's unit as given (before conversion to SI)")
      .def_property_readonly("source", [](const ObservationSet& s) {
        std::vector<std::pair<std::string, int>> where;
        for (const Observation& o : s.observations) where.emplace_back(o.file, o.line);
        return where;
      }, "(file, line) of each observation")
      .def_readwrite("water_sound_speed", &ObservationSet::water_sound_speed, "[m/s] or None")
      .def_readonly("metadata", &ObservationSet::metadata)
      .def("append", &ObservationSet::append, py::arg("other"))
      .def("write", [](const ObservationSet& s, const std::filesystem::path& path, const std::vector<std::string>& header) {
             inversion::write_observation_csv(path, s, header);
           }, py::arg("path"), py::arg("header") = std::vector<std::string>{},
           "write as a sedwave observation CSV in SI units, header lines as '# ' comments")
      .def("__repr__", [](const ObservationSet& s) {
        return "<sedwave.Observations: " + std::to_string(s.observations.size()) + " observations>";
      });

  m.def("read_observations", &read_observations, py::arg("path"), py::arg("water_speed") = py::none(),
        py::arg("sediment_speed") = py::none(), R"doc(
Reads one or more sedwave observation CSV files (docs/file-formats.md), as `sedwave invert FILE...`
does: every value converted to SI. water_speed [m/s] converts sound-speed ratios where a file gives
none; sediment_speed [m/s] converts dB/lambda. Raises sedwave.InputError (a ValueError with file,
line, column and field) for bad input, FileNotFoundError for a missing file.)doc");
  m.def("read_digitized",
        [](const std::filesystem::path& path, const std::string& quantity, const std::string& frequency_unit,
           const std::string& value_unit, std::optional<double> relative_sigma, std::optional<double> water_speed,
           std::optional<double> sediment_speed) {
          const inversion::ReadOptions read{water_speed, sediment_speed};
          ObservationSet set =
              inversion::read_digitized_csv(path, {quantity, frequency_unit, value_unit, relative_sigma}, read);
          if (!set.water_sound_speed) set.water_sound_speed = water_speed;
          return set;
        },
        py::arg("path"), py::arg("quantity"), py::arg("frequency_unit"), py::arg("value_unit"),
        py::arg("relative_sigma") = py::none(), py::arg("water_speed") = py::none(),
        py::arg("sediment_speed") = py::none(), R"doc(
Reads a WebPlotDigitizer "x,y" export, as `sedwave invert --digitized-file PATH --digitized
QUANTITY:FREQ_UNIT:VALUE_UNIT[:REL_SIGMA]`: quantity "attenuation", "sound_speed" or
"sound_speed_ratio"; frequency_unit "Hz", "kHz" or "MHz"; relative_sigma the 1-sigma relative
uncertainty of every point.)doc");
}

}  // namespace sedwave::python
