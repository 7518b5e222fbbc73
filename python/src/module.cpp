// fogradar._core: the compiled part of the Python module (docs/python.md). It reaches
// the sensors only through experiment/ and the sensor interface (sensor/sensor.hpp); the package's
// Python code (python/fogradar/) builds the API on it. The GIL is released while C++ computes;
// arrays are NumPy views of buffers C++ owns (a capsule keeps them alive), read-only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <complex>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/capture.hpp"
#include "fogradar/experiment/memory.hpp"
#include "fogradar/experiment/outputs.hpp"
#include "fogradar/experiment/runner.hpp"
#include "fogradar/experiment/scenario.hpp"
#include "fogradar/experiment/summary.hpp"
#include "fogradar/propagation/layer_model.hpp"
#include "fogradar/propagation/visibility.hpp"
#include "fogradar/sensor/origin.hpp"
#include "fogradar/stats/box_plot.hpp"
#include "fogradar/stats/line_plot.hpp"
#include "fogradar/stats/svg_plot.hpp"

namespace py = pybind11;

namespace fogradar::python {
namespace {

using experiment::Scenario;

// fogradar.InvalidParameter (a ValueError, python/fogradar/_errors.py) with the message word for
// word, the key and, for a scenario text, its line.
[[noreturn]] void raise_invalid(const InvalidParameter& e, std::string_view source = {}) {
  const py::object type = py::module_::import("fogradar._errors").attr("InvalidParameter");
  const InputLocation& at = e.location();
  const bool has_line = !source.empty() && at.source == source && at.line != 0;
  const py::object error =
      type(e.what(), e.field(), has_line ? py::object(py::int_(at.line)) : py::object(py::none()));
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

template <class F>
auto reading(std::string_view source, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InvalidParameter& e) {
    raise_invalid(e, source);
  }
}

// A read-only NumPy array over `count` values at `data` of shape `shape`, kept alive by `owner`.
template <class T>
py::array view(const T* data, const std::vector<std::size_t>& shape, py::object owner) {
  std::vector<py::ssize_t> dims(shape.begin(), shape.end());
  py::array array(py::dtype::of<T>(), dims, {}, data, owner);
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

py::object owner_of(std::shared_ptr<const experiment::RawCapture> capture) {
  return py::capsule(
      new std::shared_ptr<const experiment::RawCapture>(std::move(capture)),
      [](void* p) { delete static_cast<std::shared_ptr<const experiment::RawCapture>*>(p); });
}

// One item's kept kinds: an array kind as a NumPy array of the kind's shape, a table kind as
// {"rows": n, "columns": [{"name", "units", "values", "labels"}...]}.
py::dict kept_to_python(const std::shared_ptr<const experiment::RawCapture>& capture) {
  const py::object owner = owner_of(capture);
  py::dict out;
  for (const experiment::RawCapture::Kept& kept : capture->kept()) {
    const sensor::RawKind& kind = capture->kinds()[kept.kind];
    switch (kind.element) {
      case sensor::RawElement::complex128:
        out[py::str(kind.name)] = view(kept.complex128.data(), kind.shape, owner);
        break;
      case sensor::RawElement::float64:
        out[py::str(kind.name)] = view(kept.float64.data(), kind.shape, owner);
        break;
      case sensor::RawElement::uint8:
        out[py::str(kind.name)] = view(kept.uint8.data(), kind.shape, owner);
        break;
      case sensor::RawElement::int16:
        out[py::str(kind.name)] = view(kept.int16.data(), kind.shape, owner);
        break;
      case sensor::RawElement::table: {
        py::list columns;
        for (std::size_t c = 0; c < kind.columns.size(); ++c) {
          const sensor::RawColumn& column = kind.columns[c];
          const experiment::RawCapture::Column& values = kept.columns[c];
          py::dict entry;
          entry["name"] = column.name;
          entry["units"] = column.units;
          entry["labels"] = column.labels;
          if (!column.labels.empty()) {
            entry["values"] = view(values.codes.data(), {kept.rows}, owner);
          } else if (column.integer) {
            entry["values"] = view(values.integers.data(), {kept.rows}, owner);
          } else {
            entry["values"] = view(values.numbers.data(), {kept.rows}, owner);
          }
          columns.append(entry);
        }
        py::dict table;
        table["rows"] = kept.rows;
        table["columns"] = columns;
        out[py::str(kind.name)] = table;
        break;
      }
    }
  }
  return out;
}

// What a sensor offers: per kind its name, description, units, element, dimensions and axes.
py::list kinds_to_python(const std::vector<sensor::RawKind>& kinds) {
  static constexpr const char* elements[] = {"complex128", "float64", "uint8", "table", "int16"};
  py::list out;
  for (const sensor::RawKind& kind : kinds) {
    py::dict entry;
    entry["name"] = kind.name;
    entry["description"] = kind.description;
    entry["units"] = kind.units;
    entry["element"] = elements[static_cast<int>(kind.element)];
    entry["dimensions"] = kind.dimensions;
    entry["shape"] = kind.shape;
    entry["by_default"] = kind.by_default;
    entry["labels"] = kind.labels;
    py::dict axes;
    for (const sensor::RawAxis& axis : kind.axes) {
      if (axis.values.empty()) continue;
      py::dict a;
      a["units"] = axis.units;
      a["values"] =
          py::array_t<double>(static_cast<py::ssize_t>(axis.values.size()), axis.values.data());
      axes[py::str(axis.name)] = a;
    }
    entry["axes"] = axes;
    py::dict attributes;
    for (const auto& [name, value] : kind.attributes) attributes[py::str(name)] = value;
    entry["attributes"] = attributes;
    out.append(entry);
  }
  return out;
}

// Every sensor's step table, its CSV columns by header in their order: integers and numbers as
// NumPy arrays, texts as str, lists of numbers as lists.
py::list step_tables_to_python(const experiment::ExperimentSummary& summary) {
  py::list out;
  for (const experiment::SensorOutcome& s : summary.sensors) {
    py::dict columns;
    for (const sensor::Column& c : s.summary->step_table().columns()) {
      if (!c.csv) continue;
      const auto count = static_cast<py::ssize_t>(s.summary->step_table().steps());
      switch (c.type) {
        case sensor::ColumnType::integer:
          columns[py::str(c.header())] = py::array_t<std::int64_t>(count, c.integers.data());
          break;
        case sensor::ColumnType::number:
          columns[py::str(c.header())] = py::array_t<double>(count, c.numbers.data());
          break;
        case sensor::ColumnType::text:
          columns[py::str(c.header())] = py::cast(c.texts);
          break;
        case sensor::ColumnType::numbers:
          columns[py::str(c.header())] = py::cast(c.lists);
          break;
      }
    }
    py::dict entry;
    entry["sensor"] = s.name;
    entry["columns"] = columns;
    out.append(entry);
  }
  return out;
}

// A run's outcome: the scenario it ran and every sensor's summary.
struct Results {
  Scenario scenario;
  experiment::ExperimentResult result;
  experiment::ExperimentSummary summary;
};

// Runs `simulation` on a thread of its own while this one, holding the GIL only between waits,
// checks for signals: Ctrl-C stops the run's workers and raises KeyboardInterrupt, as SIGINT stops
// `fogradar run`.
std::shared_ptr<Results> run_simulation(const experiment::Simulation& simulation,
                                        unsigned threads) {
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::optional<experiment::ExperimentResult> result;
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      result = simulation.run({.threads = threads, .progress = {}, .stop = &stop, .raw = nullptr});
    } catch (...) {
      failure = std::current_exception();
    }
    const std::lock_guard lock(mutex);
    done = true;
    finished.notify_all();
  });
  const auto wait_for_end = [&](std::chrono::milliseconds timeout) {
    const py::gil_scoped_release release;
    std::unique_lock lock(mutex);
    return finished.wait_for(lock, timeout, [&] { return done; });
  };
  while (!wait_for_end(std::chrono::milliseconds(50))) {
    if (PyErr_CheckSignals() != 0) {
      stop = true;
      {
        const py::gil_scoped_release release;
        worker.join();
      }
      throw py::error_already_set();
    }
  }
  {
    const py::gil_scoped_release release;
    worker.join();
  }
  if (failure) std::rethrow_exception(failure);
  auto out = std::make_shared<Results>(Results{simulation.scenario(), std::move(*result), {}});
  out->summary = experiment::summarize(out->result);
  return out;
}

// Items of one sensor measured one at a time; one Python thread at a time uses it (a mutex keeps
// a second one waiting, never racing).
class ItemRunner {
 public:
  ItemRunner(std::shared_ptr<const experiment::Simulation> simulation, const std::string& sensor)
      : simulation_(std::move(simulation)), run_(*simulation_, sensor) {}

  const experiment::ItemRun& run() const { return run_; }

  py::dict measure(std::size_t step, std::size_t index, const std::vector<std::string>& keep) {
    std::vector<std::size_t> wanted;
    const std::vector<sensor::RawKind>& kinds = run_.raw_kinds();
    for (const std::string& name : keep) {
      std::size_t k = 0;
      while (k < kinds.size() && kinds[k].name != name) ++k;
      if (k == kinds.size()) {
        std::string offered;
        for (const sensor::RawKind& kind : kinds)
          offered += (offered.empty() ? "" : ", ") + kind.name;
        throw_invalid("keep", name, "a raw data kind of the sensor: " + offered);
      }
      wanted.push_back(k);
    }
    auto capture = std::make_shared<experiment::RawCapture>(kinds, wanted);
    {
      const py::gil_scoped_release release;
      const std::lock_guard lock(mutex_);
      run_.measure(step, index, capture.get());
    }
    return kept_to_python(capture);
  }

 private:
  std::shared_ptr<const experiment::Simulation> simulation_;  // outlives run_'s sensor
  std::mutex mutex_;
  experiment::ItemRun run_;
};

stats::BoxPlot box_plot_of(const std::vector<double>& values) {
  try {
    return stats::box_plot(values);
  } catch (const InvalidParameter& e) {
    raise_invalid(e);
  }
}

py::dict box_plot_to_python(const stats::BoxPlot& b) {
  py::dict d;
  d["n"] = b.n;
  d["mean"] = b.mean;
  d["std"] = b.std_dev;
  d["min"] = b.min;
  d["q1"] = b.q1;
  d["median"] = b.median;
  d["q3"] = b.q3;
  d["max"] = b.max;
  d["whisker_low"] = b.whisker_low;
  d["whisker_high"] = b.whisker_high;
  d["outliers"] = b.outliers;
  return d;
}

}  // namespace
}  // namespace fogradar::python

PYBIND11_MODULE(_core, m) {
  using namespace fogradar;
  using namespace fogradar::python;
  m.doc() = "fogradar's compiled core (docs/python.md); use the fogradar package";
  m.attr("version") = FOGRADAR_VERSION;
  m.attr("origin_labels") = sensor::origin_labels();

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InvalidParameter& e) {
      try {
        raise_invalid(e);
      } catch (py::error_already_set& set) {
        set.restore();
      }
    }
  });

  py::class_<Scenario>(m, "Scenario")
      .def_static("paper",
                  [] { return reading("paper.toml", [] { return experiment::paper_scenario(); }); })
      .def_static("load",
                  [](const std::string& path) {
                    return reading(path, [&] { return experiment::load_scenario_file(path); });
                  })
      .def_static("parse",
                  [](const std::string& text, const std::string& source) {
                    return reading(source,
                                   [&] { return experiment::parse_scenario(text, source); });
                  })
      .def(
          "over",
          [](const Scenario& base, const std::string& text, const std::string& source,
             bool line_numbers) {
            return reading(source, [&] {
              return experiment::parse_scenario_over(
                  base, text, source,
                  line_numbers ? experiment::LineNumbers::shown : experiment::LineNumbers::hidden);
            });
          },
          py::arg("text"), py::arg("source"), py::arg("line_numbers") = true)
      .def("to_toml", [](const Scenario& s) { return experiment::to_toml(s); })
      .def_property_readonly("sensors", [](const Scenario& s) { return s.experiment.sensors; })
      .def_property_readonly("steps", [](const Scenario& s) { return s.steps(); })
      .def_property_readonly("seed", [](const Scenario& s) { return s.experiment.seed; })
      .def_property_readonly("target_range_m",
                             [](const Scenario& s) { return s.chamber_spec().target_range_m(); });

  py::class_<experiment::Simulation, std::shared_ptr<experiment::Simulation>>(m, "Simulation")
      .def(py::init([](const Scenario& scenario, unsigned threads,
                       std::optional<double> memory_limit_mib) {
             const std::size_t limit = memory_limit_mib
                                           ? static_cast<std::size_t>(*memory_limit_mib * 1048576.0)
                                           : experiment::default_memory_limit_bytes();
             experiment::require_memory_within(scenario, threads, limit);
             const py::gil_scoped_release release;
             return std::make_shared<experiment::Simulation>(scenario);
           }),
           py::arg("scenario"), py::arg("threads"), py::arg("memory_limit_mib"))
      .def_property_readonly("scenario", &experiment::Simulation::scenario)
      .def("run", [](const experiment::Simulation& sim, unsigned threads) {
        return run_simulation(sim, threads);
      });

  py::class_<Results, std::shared_ptr<Results>>(m, "Results")
      .def_property_readonly("scenario", [](const Results& r) { return r.scenario; })
      .def("files",
           [](const Results& r) {
             py::dict files;
             for (const sensor::ResultFile& f : experiment::result_files(r.scenario, r.summary)) {
               files[py::str(f.name)] = py::bytes(f.content);
             }
             return files;
           })
      .def("step_tables", [](const Results& r) { return step_tables_to_python(r.summary); })
      .def("tables",
           [](const Results& r) {
             return experiment::sensor_tables(r.summary) + experiment::benchmark_table(r.summary);
           })
      .def("limits",
           [](const Results& r) {
             py::list limits;
             for (const experiment::SensorOutcome& s : r.summary.sensors) {
               const sensor::Verdict v = s.summary->verdict();
               py::dict row;
               row["sensor"] = s.name;
               row["layers_to_failure"] = v.layers_to_failure
                                              ? py::object(py::int_(*v.layers_to_failure))
                                              : py::object(py::none());
               row["criterion"] = v.criterion;
               row["margin"] = v.margin;
               limits.append(row);
             }
             return limits;
           })
      .def("write", [](const Results& r, const std::string& dir) {
        const std::vector<sensor::ResultFile> files =
            experiment::result_files(r.scenario, r.summary);
        const py::gil_scoped_release release;
        experiment::OutputDirectory out(dir);
        out.replace(files);
      });

  py::class_<ItemRunner>(m, "ItemRun")
      .def(py::init([](std::shared_ptr<experiment::Simulation> sim, const std::string& sensor) {
        const py::gil_scoped_release release;
        return std::make_unique<ItemRunner>(std::move(sim), sensor);
      }))
      .def_property_readonly("steps", [](const ItemRunner& r) { return r.run().steps(); })
      .def_property_readonly("items_per_step",
                             [](const ItemRunner& r) { return r.run().items_per_step(); })
      .def_property_readonly(
          "kinds", [](const ItemRunner& r) { return kinds_to_python(r.run().raw_kinds()); })
      .def("measure", &ItemRunner::measure, py::arg("step"), py::arg("index"), py::arg("keep"));

  m.def(
      "optical_model_table",
      [](const std::vector<std::string>& models, double mie_extinction_per_km, double visibility_m,
         double wavelength_nm) {
        std::vector<propagation::OpticalModel> wanted;
        for (const std::string& name : models) {
          wanted.push_back(propagation::optical_model_names.parse(name, "models"));
        }
        py::list rows;
        for (const propagation::OpticalModelExtinction& row : propagation::optical_model_table(
                 wanted, mie_extinction_per_km, visibility_m, wavelength_nm)) {
          py::dict entry;
          entry["model"] = std::string(propagation::optical_model_names.name(row.model));
          entry["extinction_per_km"] = row.extinction_per_km;
          entry["q"] = row.q ? py::object(py::float_(*row.q)) : py::object(py::none());
          rows.append(std::move(entry));
        }
        return rows;
      },
      "The optical models at one wavelength (propagation/visibility.hpp optical_model_table)");
  m.def(
      "layer_model_table",
      [](double transmittance, double reflectance, unsigned max_layers,
         double object_reflectivity) {
        const propagation::VirtualLayer layer{transmittance, reflectance};
        layer.validate();
        require_in_range("object_reflectivity", object_reflectivity, 0.0, 1.0);
        py::list rows;
        for (const propagation::LayerModelRow& row :
             propagation::layer_model_table(layer, max_layers, object_reflectivity)) {
          py::dict entry;
          entry["layers"] = row.layers;
          entry["kappa"] = row.kappa;
          entry["fog_intensity_per_i0"] = row.fog_intensity_per_i0;
          entry["object_intensity_per_i0"] = row.object_intensity_per_i0;
          rows.append(std::move(entry));
        }
        return rows;
      },
      "Eq. 3, 4 for 0 .. max_layers layers (propagation/layer_model.hpp layer_model_table)");
  m.def("longest_layer_m", &propagation::longest_layer_m,
        "The longest layer with tau + rho <= 1 (propagation/layer_model.hpp)");
  m.def(
      "box_plot",
      [](const std::vector<double>& values) { return box_plot_to_python(box_plot_of(values)); },
      "Tukey box plot of the values (fogradar's statistics: type-7 quantiles)");
  m.def(
      "box_plot_svg",
      [](const std::vector<std::string>& labels, const std::vector<std::vector<double>>& values,
         const std::vector<double>& rates, const std::string& title,
         const std::vector<std::string>& caption, const std::string& x_label,
         const std::string& y_label, const std::string& rate_label,
         std::optional<std::size_t> marked, const std::string& mark_label) {
        std::vector<stats::BoxPlotSeries> series;
        for (std::size_t i = 0; i < labels.size(); ++i) {
          stats::BoxPlotSeries s;
          s.label = labels[i];
          s.box = box_plot_of(i < values.size() ? values[i] : std::vector<double>{});
          if (i < rates.size()) s.rate = rates[i];
          series.push_back(std::move(s));
        }
        stats::SvgPlotOptions options;
        options.title = title;
        options.caption = caption;
        options.x_label = x_label;
        options.y_label = y_label;
        options.rate_label = rate_label;
        options.marked_category = marked;
        options.mark_label = mark_label;
        try {
          return stats::box_plot_svg(series, options);
        } catch (const InvalidParameter& e) {
          raise_invalid(e);
        }
      },
      "fogradar's box plot (stats/svg_plot.hpp) as an SVG document");
  m.def(
      "line_plot_svg",
      [](const std::vector<std::string>& labels, const std::vector<std::vector<double>>& x,
         const std::vector<std::vector<double>>& y, const std::string& title,
         const std::vector<std::string>& caption, const std::string& x_label,
         const std::string& y_label) {
        std::vector<stats::LineSeries> series;
        for (std::size_t i = 0; i < labels.size(); ++i) {
          series.push_back(
              {.label = labels[i], .x = x.at(i), .y = y.at(i), .marker_x = {}, .marker_label = {}});
        }
        stats::LinePlotOptions options;
        options.title = title;
        options.caption = caption;
        options.x_label = x_label;
        options.y_label = y_label;
        options.x_integer_ticks = true;
        try {
          return stats::line_plot_svg(series, options);
        } catch (const InvalidParameter& e) {
          raise_invalid(e);
        }
      },
      "fogradar's line plot (stats/line_plot.hpp) as an SVG document");
}
