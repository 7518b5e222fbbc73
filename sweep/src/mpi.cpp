// Sweeps on MPI (fogradar/sweep/mpi.hpp). Coded against the MPI-3.1 C API only.
#include "fogradar/sweep/mpi.hpp"

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numeric>
#include <thread>

#include "engine.hpp"
#include "fogradar/core/error.hpp"

#if FOGRADAR_WITH_MPI
#include <mpi.h>
#endif

namespace fogradar::sweep {
namespace {

std::optional<std::size_t> environment_number(std::initializer_list<const char*> names) {
  for (const char* name : names) {
    const char* text = std::getenv(name);
    if (text == nullptr || *text == '\0') continue;
    char* end = nullptr;
    const unsigned long long value = std::strtoull(text, &end, 10);
    if (*end == '\0') return static_cast<std::size_t>(value);
  }
  return std::nullopt;
}

}  // namespace

// Open MPI's mpirun sets OMPI_COMM_WORLD_*; srun and PMIx launchers PMIX_RANK; MPICH's PMI_*.
std::optional<std::size_t> launched_rank() {
  return environment_number({"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"});
}

std::optional<std::size_t> launched_size() {
  return environment_number({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"});
}

#if !FOGRADAR_WITH_MPI

bool built_with_mpi() { return false; }

MpiJob::MpiJob() {
  if (launched_rank().value_or(0) != 0) throw RefusedOnRankZero();
  throw InvalidParameter("mpirun",
                         "mpirun: this fogradar was built without MPI (FOGRADAR_WITH_MPI=OFF), so "
                         "every process would run the whole sweep: build it with MPI, or run the "
                         "shares of the sweep as separate processes with --shard i/N");
}

MpiJob::~MpiJob() = default;

void MpiJob::settle(const std::function<void()>&) {}

std::string MpiJob::share(const std::string& text) const { return text; }

SweepOutcome run_sweep(MpiJob&, const SweepSpec& spec, const std::vector<Point>& points,
                       const std::filesystem::path& dir, const SweepOptions& options) {
  return run_sweep(spec, points, dir, options);
}

#else

namespace {

using nlohmann::json;

// A worker's message to rank 0: "ready" (empty) or a point's result; rank 0's answer: the index of
// the next point, or -1 when there is none.
constexpr int tag_ready = 1;
constexpr int tag_result = 2;
constexpr int tag_assign = 3;

void require(int code, const char* call) {
  if (code != MPI_SUCCESS) throw InternalError(std::string(call) + " failed");
}

std::vector<std::uint8_t> receive(const MPI_Status& probed) {
  int count = 0;
  require(MPI_Get_count(&probed, MPI_BYTE, &count), "MPI_Get_count");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(count));
  require(MPI_Recv(bytes.data(), count, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE),
          "MPI_Recv");
  return bytes;
}

// A point's piece and kept files as one CBOR message (the files' bytes as CBOR byte strings).
std::vector<std::uint8_t> result_message(std::size_t index, const detail::Computed& computed) {
  json kept = json::array();
  for (const sensor::ResultFile& file : computed.kept) {
    kept.push_back({{"name", file.name},
                    {"content", json::binary(std::vector<std::uint8_t>(file.content.begin(),
                                                                       file.content.end()))}});
  }
  return json::to_cbor(json{{"index", index}, {"piece", computed.piece}, {"kept", kept}});
}

struct Result {
  std::size_t index = 0;
  detail::Computed computed;
};

Result read_result(const std::vector<std::uint8_t>& bytes) {
  json message = json::from_cbor(bytes);
  Result result;
  result.index = message["index"].get<std::size_t>();
  result.computed.piece = std::move(message["piece"]);
  for (const json& file : message["kept"]) {
    const std::vector<std::uint8_t>& content = file["content"].get_binary();
    result.computed.kept.push_back(
        {file["name"].get<std::string>(), std::string(content.begin(), content.end())});
  }
  return result;
}

}  // namespace

bool built_with_mpi() { return true; }

MpiJob::MpiJob() {
  int provided = 0;
  require(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw InternalError("MPI provides no MPI_THREAD_FUNNELED");
  }
  int rank = 0, size = 1;
  require(MPI_Comm_rank(MPI_COMM_WORLD, &rank), "MPI_Comm_rank");
  require(MPI_Comm_size(MPI_COMM_WORLD, &size), "MPI_Comm_size");
  rank_ = static_cast<std::size_t>(rank);
  size_ = static_cast<std::size_t>(size);
}

MpiJob::~MpiJob() {
  if (std::uncaught_exceptions() == 0 || refused_) MPI_Finalize();
}

void MpiJob::settle(const std::function<void()>& check) {
  int accepted = 1;
  std::exception_ptr refusal;
  if (rank_ == 0) {
    try {
      check();
    } catch (const InvalidParameter&) {
      accepted = 0;
      refusal = std::current_exception();
    }
  }
  require(MPI_Bcast(&accepted, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
  if (accepted) return;
  refused_ = true;
  if (refusal) std::rethrow_exception(refusal);
  throw RefusedOnRankZero();
}

std::string MpiJob::share(const std::string& text) const {
  std::uint64_t length = text.size();
  require(MPI_Bcast(&length, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
  std::string shared = rank_ == 0 ? text : std::string(length, '\0');
  require(MPI_Bcast(shared.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD),
          "MPI_Bcast");
  return shared;
}

SweepOutcome run_sweep(MpiJob& job, const SweepSpec& spec, const std::vector<Point>& points,
                       const std::filesystem::path& dir, const SweepOptions& options) {
  const propagation::SegelsteinTable water;
  experiment::SensorCache own_cache;
  experiment::SensorCache& cache = options.cache ? *options.cache : own_cache;
  const auto compute = [&](std::size_t index) {
    return detail::compute_point(spec, points[index],
                                 detail::definition_of(points[index], spec.replications), water,
                                 cache, options);
  };
  std::unique_ptr<detail::SweepDirectory> out;
  std::vector<std::string> definitions;  // rank 0's
  std::vector<std::optional<json> > pieces(points.size());
  job.settle([&] {
    using Mode = detail::SweepDirectory::Mode;
    definitions = detail::definitions_of(points, spec.replications);
    out = std::make_unique<detail::SweepDirectory>(dir, options.resume ? Mode::resume : Mode::fresh,
                                                   definitions);
    out->write_table("sweep.toml", spec.text);
    detail::write_origin(*out, spec.directory);
    if (options.opened) options.opened();
    if (!options.resume) return;
    std::vector<std::size_t> all(points.size());
    std::iota(all.begin(), all.end(), std::size_t{0});
    out->remove_stale_kept(points, all, true);
    for (const Point& point : points) {
      pieces[point.index] = out->committed(definitions[point.index]);
      // points/<index>/ of another point (before values were added to an axis): made again.
      if (options.keep_points && !out->holds_kept(point)) pieces[point.index].reset();
    }
  });
  SweepOutcome outcome;
  outcome.ranks = job.size();
  if (job.rank() != 0) {
    // A worker: ask, compute, send the piece back with the next request.
    std::vector<std::uint8_t> message;
    int tag = tag_ready;
    for (;;) {
      require(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, tag,
                       MPI_COMM_WORLD),
              "MPI_Send");
      std::int64_t next = -1;
      require(MPI_Recv(&next, 1, MPI_INT64_T, 0, tag_assign, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
      if (next < 0) return outcome;
      const auto index = static_cast<std::size_t>(next);
      message = result_message(index, compute(index));
      tag = tag_result;
      ++outcome.computed;
    }
  }

  // Rank 0: the queue, shared by a thread computing points here and the main thread answering the
  // workers (and calling MPI: MPI_THREAD_FUNNELED).
  std::deque<std::size_t> queue;
  for (const std::size_t index : detail::cost_order(spec, points)) {
    if (!pieces[index]) queue.push_back(index);
  }
  outcome.reused = points.size() - queue.size();
  std::mutex mutex;
  std::size_t done = outcome.reused;
  std::exception_ptr failure;
  bool own_finished = false, closing = false;
  const auto take = [&]() -> std::optional<std::size_t> {
    const std::lock_guard<std::mutex> lock(mutex);
    if (failure || closing || queue.empty()) return std::nullopt;
    const std::size_t index = queue.front();
    queue.pop_front();
    return index;
  };
  const auto store = [&](std::size_t index, detail::Computed computed) {
    if (options.keep_points) out->keep(index, computed.kept);
    out->commit(computed.piece);
    const std::lock_guard<std::mutex> lock(mutex);
    pieces[index] = std::move(computed.piece);
    ++done;
    ++outcome.computed;
  };
  std::thread own([&] {
    try {
      while (const std::optional<std::size_t> index = take()) store(*index, compute(*index));
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex);
      failure = std::current_exception();
    }
    const std::lock_guard<std::mutex> lock(mutex);
    own_finished = true;
  });
  // However the main thread leaves, the computing thread takes no further point and is joined.
  struct Join {
    std::thread& thread;
    std::mutex& mutex;
    bool& closing;
    ~Join() {
      {
        const std::lock_guard<std::mutex> lock(mutex);
        closing = true;
      }
      if (thread.joinable()) thread.join();
    }
  } join{own, mutex, closing};

  const auto start = std::chrono::steady_clock::now();
  const auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  std::size_t workers = job.size() - 1, reported = outcome.reused, messages = 0;
  double bookkeeping = 0.0;
  for (;;) {
    bool finished = false, failed = false;
    std::size_t now_done = 0;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      finished = own_finished;
      failed = failure != nullptr;
      now_done = done;
    }
    if (options.progress && now_done != reported) {
      options.progress(now_done, points.size(), seconds_since(start));
      reported = now_done;
    }
    if (failed || (finished && workers == 0)) break;
    // SIGINT or SIGTERM (the launcher ending the job after a rank died): stop waiting for workers.
    if (options.stop != nullptr && options.stop->load()) throw experiment::Interrupted();
    int arrived = 0;
    MPI_Status probed;
    require(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &probed),
            "MPI_Iprobe");
    if (!arrived) {
      // A worker waits up to this long for its answer, against points of 0.1 s and more; a shorter
      // period takes CPU from the points computed beside this thread.
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    const auto handled = std::chrono::steady_clock::now();
    const std::vector<std::uint8_t> bytes = receive(probed);
    if (probed.MPI_TAG == tag_result) {
      Result result = read_result(bytes);
      store(result.index, std::move(result.computed));
    }
    const std::optional<std::size_t> index = take();
    const std::int64_t next = index ? static_cast<std::int64_t>(*index) : -1;
    require(MPI_Send(&next, 1, MPI_INT64_T, probed.MPI_SOURCE, tag_assign, MPI_COMM_WORLD),
            "MPI_Send");
    if (!index) --workers;
    bookkeeping += seconds_since(handled);
    ++messages;
  }
  own.join();
  if (failure) std::rethrow_exception(failure);
  std::vector<json> all;
  for (std::optional<json>& piece : pieces) all.push_back(std::move(*piece));
  SweepOutcome tables = detail::write_tables(spec, points, all, *out);
  tables.computed = outcome.computed;
  tables.reused = outcome.reused;
  tables.ranks = job.size();
  tables.bookkeeping_seconds_per_message =
      messages ? bookkeeping / static_cast<double>(messages) : 0.0;
  return tables;
}

#endif

}  // namespace fogradar::sweep
