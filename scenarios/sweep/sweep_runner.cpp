// Executing a sweep's runs: one run loaded, simulated and (keep_runs) published, runs spread
// over a Boost.Asio thread_pool, and the whole sweep in this process.
#include <algorithm>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <utility>

#include <boost/asio/post.hpp>
#include <boost/asio/thread_pool.hpp>

#include "scenarios/loader/scenario.hpp"
#include "scenarios/output/output_file.hpp"
#include "scenarios/run/run.hpp"
#include "scenarios/run/run_directory.hpp"
#include "scenarios/run/sensors_csv.hpp"
#include "scenarios/sweep/sweep.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;
using nlohmann::json;

json RunResult::to_json() const {
  return {{"index", index}, {"id", id}, {"ok", ok}, {"error", error}, {"summary", summary}};
}

RunResult RunResult::from_json(const json& j) {
  RunResult r;
  r.index = j.at("index").get<std::size_t>();
  r.id = j.at("id").get<std::string>();
  r.ok = j.at("ok").get<bool>();
  r.error = j.at("error").get<std::string>();
  r.summary = j.at("summary");
  return r;
}

RunResult execute_sweep_run(const SweepDef& sweep, const RunSpec& run, const std::string& out_dir) {
  RunResult result;
  result.index = run.index;
  result.id = run.id;
  try {
    LoadResult loaded = load_scenario(sweep.base_path, run.overrides, run.seed);
    if (!loaded.scenario) {
      for (const Diagnostic& d : loaded.diagnostics)
        result.error += (result.error.empty() ? "" : "\n") + d.text();
      return result;
    }
    Run simulation(std::move(*loaded.scenario));
    const ScenarioDef& def = simulation.def();
    simulation.execute();
    result.summary = simulation.summary();
    if (sweep.keep_runs) {
      publish_run_directory((fs::path(out_dir) / "runs" / run.id).string(),
                            [&](const std::string& dir) {
                              simulation.write_files(dir);
                              write_sensors_csv(fs::path(dir) / "sensors.csv", def.world.sensors);
                            });
    }
    // The resolved scenario is (base, overrides, seed) again: not worth a copy per row.
    if (result.summary.contains("scenario")) result.summary["scenario"].erase("resolved");
    // One number per robot would be a column per robot (10⁴ in the scaling benchmark).
    if (result.summary.contains("energy_j") && result.summary["energy_j"].contains("locomotion"))
      result.summary["energy_j"]["locomotion"].erase("per_robot");
    result.ok = true;
  } catch (const OutputError& e) {
    result.ok = false;
    result.summary = nullptr;
    result.error = e.what();
  } catch (const std::exception& e) {
    result.ok = false;
    result.summary = nullptr;
    result.error = std::string("internal error: ") + e.what();
  }
  return result;
}

struct SweepWorkers::Shared {
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<RunResult> done;
  // Last member: destroyed (stopped and joined) first, while the queue still exists.
  boost::asio::thread_pool pool;
  explicit Shared(std::size_t threads) : pool(threads) {}
  ~Shared() {
    pool.stop();  // on an early exit, queued runs are dropped; running ones finish
    pool.join();
  }
};

SweepWorkers::SweepWorkers(const SweepDef& sweep, const std::vector<RunSpec>& runs,
                           std::string out_dir, int threads)
    : sweep_(sweep),
      runs_(runs),
      out_dir_(std::move(out_dir)),
      shared_(std::make_unique<Shared>(static_cast<std::size_t>(std::max(1, threads)))) {}

SweepWorkers::~SweepWorkers() = default;

void SweepWorkers::submit(std::size_t index) {
  ++in_flight_;
  Shared* shared = shared_.get();
  boost::asio::post(shared->pool, [this, shared, index] {
    RunResult r = execute_sweep_run(sweep_, runs_.at(index), out_dir_);
    {
      std::lock_guard<std::mutex> lock(shared->mutex);
      shared->done.push_back(std::move(r));
    }
    shared->ready.notify_one();
  });
}

std::optional<RunResult> SweepWorkers::next(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(shared_->mutex);
  if (!shared_->ready.wait_for(lock, timeout, [&] { return !shared_->done.empty(); }))
    return std::nullopt;
  RunResult r = std::move(shared_->done.front());
  shared_->done.pop_front();
  --in_flight_;
  return r;
}

SweepCounts run_sweep_locally(const SweepDef& sweep, const SweepOptions& options,
                              const std::function<void(const RunResult&)>& on_result) {
  SweepSession results(sweep, expand_sweep(sweep), options);
  {
    SweepWorkers workers(sweep, results.runs(), options.out_dir, options.jobs);
    for (std::size_t index : results.pending())
      workers.submit(index);
    while (workers.in_flight() > 0)
      if (auto r = workers.next(std::chrono::milliseconds(500))) {
        results.record(*r);
        if (on_result) on_result(*r);
      }
  }
  return results.finish();
}

}  // namespace masnet::scenarios
