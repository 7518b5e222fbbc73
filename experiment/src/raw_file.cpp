#include "fogradar/experiment/raw_file.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <sstream>

#include "fogradar/core/error.hpp"
#include "fogradar/experiment/files.hpp"
#include "raw_hdf5.hpp"

namespace fogradar::experiment {
namespace {

namespace fs = std::filesystem;

// The version of the file's layout (docs/data-out.md); the root attribute `raw_format` that also
// marks a file fogradar wrote, and may replace.
constexpr std::int64_t raw_format_version = 2;
// An item larger than this is chunked by rows of its first dimension (HDF5 chunks hold < 4 GiB).
constexpr std::size_t max_chunk_bytes = std::size_t{1} << 30;
constexpr hsize_t table_chunk_rows = 4096;

using detail::checked;
using detail::complex_type;
using detail::enum_type;
using detail::Handle;
using detail::Hdf5Error;
using detail::integer_attribute;
using detail::number_attribute;
using detail::property_list;
using detail::scale;
using detail::string_attribute;
using detail::untimed;

std::string joined(const std::vector<std::string>& parts, std::string_view separator) {
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : std::string(separator)) + part;
  return text;
}

}  // namespace

class RawFile::Impl {
 public:
  struct KindOut {
    std::size_t kind = 0;                   // index into the sensor's kinds
    Handle dataset;                         // array kinds
    Handle memory_type;                     // array kinds: the element as it is in memory
    std::vector<std::vector<double>> rows;  // table kinds: per (step position, item position)
  };
  struct SensorOut {
    const RawPlan::Sensor* plan = nullptr;
    Handle group;
    std::vector<KindOut> kinds;
    std::vector<std::ptrdiff_t> item_position;  // item index -> position, -1 when not kept
  };

  Impl(const RawPlan& plan, const Scenario& scenario) : plan_(plan) {
    // HDF5 would print its error stack on stderr; a failure here is reported once, as fogradar's.
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    const std::string given = plan.path.string();
    std::error_code error;
    final_ = fs::absolute(plan.path, error).lexically_normal();
    if (error || given.empty() || !final_.has_filename() || fs::is_directory(final_, error)) {
      throw_invalid("--raw", given, "a file name (not a directory)");
    }
    fs::create_directories(final_.parent_path(), error);
    if (error)
      throw_invalid("--raw", given,
                    "a file whose directory can be created (" + error.message() + ")");
    lock_ = std::make_unique<PathLock>(final_, "--raw", given, "a file");
    require_replaceable(given);
    const std::string name = final_.filename().string();
    std::string temporary =
        (final_.parent_path() / ('.' + name + ".tmp-" + std::to_string(::getpid()) + "-XXXXXX"))
            .string();
    const detail::Descriptor file(::mkstemp(temporary.data()));
    if (file.fd < 0) {
      throw_invalid("--raw", given,
                    "a file whose directory is writable (" + detail::errno_text() + ")");
    }
    // mkstemp makes it private; the result set's files are 0644.
    ::fchmod(file.fd, 0644);
    temporary_ = temporary;
    try {
      create(scenario);
    } catch (const Hdf5Error& e) {
      throw_invalid("--raw", given,
                    std::string("a file HDF5 can create (") + e.what() + " failed)");
    }
  }

  ~Impl() {
    if (!committed_) {
      sensors_.clear();
      file_.close();
      std::error_code ignored;
      if (!temporary_.empty()) fs::remove(temporary_, ignored);
    }
  }

  bool wanted(std::size_t sensor, std::size_t step, std::size_t index) const {
    return step_position_[step] >= 0 && index < sensors_[sensor].item_position.size() &&
           sensors_[sensor].item_position[index] >= 0 && !sensors_[sensor].kinds.empty();
  }

  KindOut* kind_out(std::size_t sensor, std::size_t kind) {
    for (KindOut& out : sensors_[sensor].kinds) {
      if (out.kind == kind) return &out;
    }
    return nullptr;
  }

  void write(std::size_t sensor, std::size_t step, std::size_t index, std::size_t kind,
             const void* data, std::size_t values) {
    KindOut* out = kind_out(sensor, kind);
    FOGRADAR_CHECK(out != nullptr && out->dataset.get() >= 0);
    const sensor::RawKind& spec = sensors_[sensor].plan->kinds[kind];
    FOGRADAR_CHECK(values == spec.item_values());
    std::vector<hsize_t> start = {static_cast<hsize_t>(step_position_[step]),
                                  static_cast<hsize_t>(sensors_[sensor].item_position[index])};
    std::vector<hsize_t> count = {1, 1};
    for (const std::size_t n : spec.shape) {
      start.push_back(0);
      count.push_back(n);
    }
    const std::lock_guard lock(mutex_);
    try {
      const Handle file_space(checked(H5Dget_space(out->dataset.get()), "H5Dget_space"), H5Sclose);
      checked(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                  count.data(), nullptr),
              "H5Sselect_hyperslab");
      const Handle memory_space(
          checked(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr),
                  "H5Screate_simple"),
          H5Sclose);
      checked(H5Dwrite(out->dataset.get(), out->memory_type.get(), memory_space.get(),
                       file_space.get(), H5P_DEFAULT, data),
              "H5Dwrite");
    } catch (const Hdf5Error& e) {
      throw_invalid("--raw", plan_.path.string(),
                    std::string("a writable file (") + e.what() + " failed)");
    }
  }

  void append(std::size_t sensor, std::size_t step, std::size_t index, std::size_t kind,
              std::span<const double> rows) {
    KindOut* out = kind_out(sensor, kind);
    FOGRADAR_CHECK(out != nullptr);
    const std::size_t columns = sensors_[sensor].plan->kinds[kind].columns.size();
    FOGRADAR_CHECK(columns > 0 && rows.size() % columns == 0);
    const std::size_t slot =
        static_cast<std::size_t>(step_position_[step]) * sensors_[sensor].plan->items.size() +
        static_cast<std::size_t>(sensors_[sensor].item_position[index]);
    // Each item's rows go to a slot of their own; commit() writes the slots in order.
    std::vector<double>& stored = out->rows[slot];
    stored.insert(stored.end(), rows.begin(), rows.end());
  }

  void finish() {
    try {
      for (SensorOut& s : sensors_) {
        for (KindOut& out : s.kinds) {
          if (s.plan->kinds[out.kind].element == sensor::RawElement::table) write_table(s, out);
        }
      }
      sensors_.clear();
      if (!file_.close()) throw Hdf5Error("H5Fclose");
    } catch (const Hdf5Error& e) {
      throw_invalid("--raw", plan_.path.string(),
                    std::string("a writable file (") + e.what() + " failed)");
    }
    if (!detail::sync_path(temporary_, false)) {
      throw_invalid("--raw", plan_.path.string(),
                    "a file that can be synced (" + detail::errno_text() + ")");
    }
  }

  void publish() {
    if (::rename(temporary_.c_str(), final_.c_str()) != 0) {
      throw_invalid("--raw", plan_.path.string(),
                    "a file that can be renamed into place (" + detail::errno_text() + ")");
    }
    committed_ = true;
    detail::sync_path(final_.parent_path(), true);
  }

 private:
  // An existing file is replaced only when fogradar wrote it (its root attribute raw_format).
  void require_replaceable(const std::string& given) const {
    std::error_code error;
    const fs::file_status status = fs::symlink_status(final_, error);
    if (!fs::exists(status)) return;
    const std::string refusal =
        "a new file or one fogradar wrote (it would be replaced; fogradar never overwrites a file "
        "of yours)";
    if (!fs::is_regular_file(status) || H5Fis_hdf5(final_.c_str()) <= 0) {
      throw_invalid("--raw", given, refusal);
    }
    const Handle file(H5Fopen(final_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (file.get() < 0 || H5Aexists(file.get(), "raw_format") <= 0) {
      throw_invalid("--raw", given, refusal);
    }
  }

  void create(const Scenario& scenario) {
    const Handle creation = property_list(H5P_FILE_CREATE);
    file_ =
        Handle(checked(H5Fcreate(temporary_.c_str(), H5F_ACC_TRUNC, creation.get(), H5P_DEFAULT),
                       "H5Fcreate"),
               H5Fclose);
    integer_attribute(file_.get(), "raw_format", raw_format_version);
    string_attribute(file_.get(), "fogradar_version", FOGRADAR_VERSION);
    string_attribute(file_.get(), "description",
                     "fogradar run's raw data: a group per sensor, each dataset indexed "
                     "[active_layers, item, ...] (docs/data-out.md)");
    string_attribute(file_.get(), "scenario", to_toml(scenario));
    integer_attribute(file_.get(), "seed", static_cast<std::int64_t>(scenario.experiment.seed));

    const std::size_t steps = scenario.steps();
    step_position_.assign(steps, -1);
    for (std::size_t p = 0; p < plan_.steps.size(); ++p) {
      step_position_[plan_.steps[p]] = static_cast<std::ptrdiff_t>(p);
    }
    for (const RawPlan::Sensor& plan : plan_.sensors) {
      SensorOut& out = sensors_.emplace_back();
      out.plan = &plan;
      if (plan.chosen.empty()) continue;
      const std::size_t largest = plan.items.empty() ? 0 : plan.items.back() + 1;
      out.item_position.assign(largest, -1);
      for (std::size_t p = 0; p < plan.items.size(); ++p) {
        out.item_position[plan.items[p]] = static_cast<std::ptrdiff_t>(p);
      }
      const Handle group_creation = untimed(H5P_GROUP_CREATE);
      out.group = Handle(checked(H5Gcreate2(file_.get(), ("/" + plan.name).c_str(), H5P_DEFAULT,
                                            group_creation.get(), H5P_DEFAULT),
                                 "H5Gcreate2"),
                         H5Gclose);
      std::vector<std::int64_t> layers(plan_.steps.begin(), plan_.steps.end());
      std::vector<std::int64_t> items(plan.items.begin(), plan.items.end());
      const Handle step_scale = scale(out.group.get(), "active_layers", H5T_STD_I64LE,
                                      H5T_NATIVE_INT64, layers.data(), layers.size(), "layers");
      const Handle item_scale = scale(out.group.get(), "item", H5T_STD_I64LE, H5T_NATIVE_INT64,
                                      items.data(), items.size(), "");
      std::vector<std::pair<std::string, Handle>> axes;
      for (const std::size_t k : plan.chosen) {
        KindOut& kind = out.kinds.emplace_back();
        kind.kind = k;
        const sensor::RawKind& spec = plan.kinds[k];
        if (spec.element == sensor::RawElement::table) {
          kind.rows.resize(plan_.steps.size() * plan.items.size());
          continue;
        }
        create_array(out, kind, spec, step_scale.get(), item_scale.get(), axes);
      }
    }
  }

  void create_array(SensorOut& out, KindOut& kind, const sensor::RawKind& spec, hid_t step_scale,
                    hid_t item_scale, std::vector<std::pair<std::string, Handle>>& axes) {
    Handle file_type;
    switch (spec.element) {
      case sensor::RawElement::complex128:
        file_type = complex_type(H5T_IEEE_F64LE);
        kind.memory_type = complex_type(H5T_NATIVE_DOUBLE);
        break;
      case sensor::RawElement::float64:
        file_type = Handle(checked(H5Tcopy(H5T_IEEE_F64LE), "H5Tcopy"), H5Tclose);
        kind.memory_type = Handle(checked(H5Tcopy(H5T_NATIVE_DOUBLE), "H5Tcopy"), H5Tclose);
        break;
      case sensor::RawElement::uint8:
        if (!spec.labels.empty()) {
          file_type = enum_type(H5T_STD_U8LE, spec.labels);
          kind.memory_type = enum_type(H5T_NATIVE_UINT8, spec.labels);
          break;
        }
        file_type = Handle(checked(H5Tcopy(H5T_STD_U8LE), "H5Tcopy"), H5Tclose);
        kind.memory_type = Handle(checked(H5Tcopy(H5T_NATIVE_UINT8), "H5Tcopy"), H5Tclose);
        break;
      case sensor::RawElement::int16:
        file_type = Handle(checked(H5Tcopy(H5T_STD_I16LE), "H5Tcopy"), H5Tclose);
        kind.memory_type = Handle(checked(H5Tcopy(H5T_NATIVE_INT16), "H5Tcopy"), H5Tclose);
        break;
      case sensor::RawElement::table:
        return;
    }
    std::vector<hsize_t> dims = {plan_.steps.size(), out.plan->items.size()};
    std::vector<hsize_t> chunk = {1, 1};
    for (const std::size_t n : spec.shape) {
      dims.push_back(n);
      chunk.push_back(n);
    }
    // One item per chunk, unless an item is too large for one.
    const std::size_t item_bytes = spec.item_bytes();
    if (item_bytes > max_chunk_bytes && !spec.shape.empty()) {
      const std::size_t row_bytes = item_bytes / spec.shape.front();
      chunk[2] = std::max<hsize_t>(1, max_chunk_bytes / row_bytes);
    }
    const Handle space(
        checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                "H5Screate_simple"),
        H5Sclose);
    const Handle creation = untimed(H5P_DATASET_CREATE);
    checked(H5Pset_chunk(creation.get(), static_cast<int>(chunk.size()), chunk.data()),
            "H5Pset_chunk");
    // Every chunk placed when the dataset is made, none filled: the items' writes in any order then
    // give the same bytes.
    checked(H5Pset_alloc_time(creation.get(), H5D_ALLOC_TIME_EARLY), "H5Pset_alloc_time");
    checked(H5Pset_fill_time(creation.get(), H5D_FILL_TIME_NEVER), "H5Pset_fill_time");
    kind.dataset = Handle(checked(H5Dcreate2(out.group.get(), spec.name.c_str(), file_type.get(),
                                             space.get(), H5P_DEFAULT, creation.get(), H5P_DEFAULT),
                                  "H5Dcreate2"),
                          H5Dclose);
    std::vector<std::string> dimensions = {"active_layers", "item"};
    dimensions.insert(dimensions.end(), spec.dimensions.begin(), spec.dimensions.end());
    string_attribute(kind.dataset.get(), "units", spec.units);
    string_attribute(kind.dataset.get(), "description", spec.description);
    string_attribute(kind.dataset.get(), "dimensions", joined(dimensions, ", "));
    for (const auto& [name, value] : spec.attributes) {
      number_attribute(kind.dataset.get(), name.c_str(), value);
    }
    checked(H5DSattach_scale(kind.dataset.get(), step_scale, 0), "H5DSattach_scale");
    checked(H5DSattach_scale(kind.dataset.get(), item_scale, 1), "H5DSattach_scale");
    for (std::size_t d = 0; d < spec.axes.size(); ++d) {
      const sensor::RawAxis& axis = spec.axes[d];
      if (axis.values.empty()) continue;
      auto found = std::find_if(axes.begin(), axes.end(),
                                [&](const auto& a) { return a.first == axis.name; });
      if (found == axes.end()) {
        axes.emplace_back(axis.name,
                          scale(out.group.get(), axis.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                                axis.values.data(), axis.values.size(), axis.units));
        found = axes.end() - 1;
      }
      checked(
          H5DSattach_scale(kind.dataset.get(), found->second.get(), static_cast<unsigned>(d + 2)),
          "H5DSattach_scale");
    }
  }

  // A compound dataset of every kept item's rows, in (step, item) order: active_layers and item,
  // then the kind's columns.
  void write_table(SensorOut& s, KindOut& out) {
    const sensor::RawKind& spec = s.plan->kinds[out.kind];
    std::vector<sensor::RawColumn> columns = {{"active_layers", "layers", true, {}},
                                              {"item", "", true, {}}};
    columns.insert(columns.end(), spec.columns.begin(), spec.columns.end());
    std::vector<std::size_t> offsets;
    std::size_t row_bytes = 0;
    for (const sensor::RawColumn& c : columns) {
      offsets.push_back(row_bytes);
      row_bytes += c.labels.empty() ? 8 : 1;
    }
    std::vector<Handle> enums;
    Handle file_type(checked(H5Tcreate(H5T_COMPOUND, row_bytes), "H5Tcreate"), H5Tclose);
    Handle memory_type(checked(H5Tcreate(H5T_COMPOUND, row_bytes), "H5Tcreate"), H5Tclose);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      hid_t file_part = columns[c].integer ? H5T_STD_I64LE : H5T_IEEE_F64LE;
      hid_t memory_part = columns[c].integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
      if (!columns[c].labels.empty()) {
        for (const hid_t base : {H5T_STD_U8LE, H5T_NATIVE_UINT8}) {
          enums.push_back(enum_type(base, columns[c].labels));
        }
        file_part = enums[enums.size() - 2].get();
        memory_part = enums.back().get();
      }
      checked(H5Tinsert(file_type.get(), columns[c].name.c_str(), offsets[c], file_part),
              "H5Tinsert");
      checked(H5Tinsert(memory_type.get(), columns[c].name.c_str(), offsets[c], memory_part),
              "H5Tinsert");
    }
    // The rows, packed as the memory type lays them out.
    const std::size_t own = spec.columns.size();
    std::vector<unsigned char> buffer;
    hsize_t count = 0;
    for (std::size_t slot = 0; slot < out.rows.size(); ++slot) {
      const std::int64_t layers =
          static_cast<std::int64_t>(plan_.steps[slot / s.plan->items.size()]);
      const std::int64_t item =
          static_cast<std::int64_t>(s.plan->items[slot % s.plan->items.size()]);
      const std::vector<double>& rows = out.rows[slot];
      for (std::size_t r = 0; r < rows.size() / own; ++r, ++count) {
        const std::size_t at = buffer.size();
        buffer.resize(at + row_bytes);
        std::memcpy(&buffer[at + offsets[0]], &layers, 8);
        std::memcpy(&buffer[at + offsets[1]], &item, 8);
        for (std::size_t c = 0; c < own; ++c) {
          const sensor::RawColumn& column = columns[c + 2];
          const double value = rows[r * own + c];
          unsigned char* field = &buffer[at + offsets[c + 2]];
          if (!column.labels.empty()) {
            *field = static_cast<std::uint8_t>(value);
          } else if (column.integer) {
            const auto integer = static_cast<std::int64_t>(value);
            std::memcpy(field, &integer, 8);
          } else {
            std::memcpy(field, &value, 8);
          }
        }
      }
    }
    const hsize_t unlimited = H5S_UNLIMITED;
    const Handle space(checked(H5Screate_simple(1, &count, &unlimited), "H5Screate_simple"),
                       H5Sclose);
    const Handle creation = untimed(H5P_DATASET_CREATE);
    const hsize_t chunk = std::clamp<hsize_t>(count, 1, table_chunk_rows);
    checked(H5Pset_chunk(creation.get(), 1, &chunk), "H5Pset_chunk");
    const Handle dataset(checked(H5Dcreate2(s.group.get(), spec.name.c_str(), file_type.get(),
                                            space.get(), H5P_DEFAULT, creation.get(), H5P_DEFAULT),
                                 "H5Dcreate2"),
                         H5Dclose);
    if (count > 0) {
      checked(
          H5Dwrite(dataset.get(), memory_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
          "H5Dwrite");
    }
    std::vector<std::string> described;
    for (const sensor::RawColumn& c : columns) {
      std::string text = c.name;
      if (!c.units.empty()) text += " (" + c.units + ")";
      if (!c.labels.empty()) text += " (" + joined(c.labels, " | ") + ")";
      described.push_back(text);
    }
    string_attribute(dataset.get(), "columns", joined(described, ", "));
    string_attribute(dataset.get(), "description", spec.description);
    for (const auto& [name, value] : spec.attributes) {
      number_attribute(dataset.get(), name.c_str(), value);
    }
  }

 public:
  // One item's raw data, into the file.
  class Sink : public sensor::RawSink {
   public:
    Sink(Impl& file, const RawPlan::Sensor& plan, std::size_t sensor, std::size_t step,
         std::size_t index)
        : file_(file), plan_(plan), sensor_(sensor), step_(step), index_(index) {}

    bool wants(std::size_t kind) const override {
      return std::find(plan_.chosen.begin(), plan_.chosen.end(), kind) != plan_.chosen.end();
    }
    void write(std::size_t kind, std::span<const std::complex<double>> values) override {
      check(kind, sensor::RawElement::complex128);
      file_.write(sensor_, step_, index_, kind, values.data(), values.size());
    }
    void write(std::size_t kind, std::span<const double> values) override {
      check(kind, sensor::RawElement::float64);
      file_.write(sensor_, step_, index_, kind, values.data(), values.size());
    }
    void write(std::size_t kind, std::span<const std::uint8_t> values) override {
      check(kind, sensor::RawElement::uint8);
      file_.write(sensor_, step_, index_, kind, values.data(), values.size());
    }
    void write(std::size_t kind, std::span<const std::int16_t> values) override {
      check(kind, sensor::RawElement::int16);
      file_.write(sensor_, step_, index_, kind, values.data(), values.size());
    }
    void append_rows(std::size_t kind, std::span<const double> rows) override {
      check(kind, sensor::RawElement::table);
      file_.append(sensor_, step_, index_, kind, rows);
    }

   private:
    void check(std::size_t kind, sensor::RawElement element) const {
      FOGRADAR_CHECK(wants(kind) && plan_.kinds[kind].element == element);
    }
    Impl& file_;
    const RawPlan::Sensor& plan_;
    std::size_t sensor_, step_, index_;
  };

  const RawPlan::Sensor& plan_of(std::size_t sensor) const { return *sensors_[sensor].plan; }

 private:
  const RawPlan& plan_;
  fs::path final_, temporary_;
  std::unique_ptr<PathLock> lock_;
  Handle file_;
  std::vector<std::ptrdiff_t> step_position_;  // step -> position in plan_.steps, -1: not kept
  std::vector<SensorOut> sensors_;             // in the plan's order
  std::mutex mutex_;                           // HDF5 calls, one at a time
  bool committed_ = false;
};

RawFile::RawFile(const RawPlan& plan, const Scenario& scenario)
    : impl_(std::make_unique<Impl>(plan, scenario)) {}

RawFile::~RawFile() = default;

std::unique_ptr<sensor::RawSink> RawFile::sink(std::size_t sensor, std::size_t step,
                                               std::size_t index) {
  if (!impl_->wanted(sensor, step, index)) return nullptr;
  return std::make_unique<Impl::Sink>(*impl_, impl_->plan_of(sensor), sensor, step, index);
}

void RawFile::finish() { impl_->finish(); }
void RawFile::publish() { impl_->publish(); }

}  // namespace fogradar::experiment
