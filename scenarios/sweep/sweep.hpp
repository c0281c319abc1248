#pragma once
// Parameter sweeps (docs/sweeps.md): a sweep file names a base scenario, what to vary
// and which seeds; it expands into runs, each fully determined by (base, overrides, seed) and
// named by a stable id. Runs execute on worker threads (and MPI ranks, cli/sweep_command.cpp);
// only the calling thread writes results.sqlite, results.csv and report.html.
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/loader/reader.hpp"
#include "scenarios/sweep/sweep_report.hpp"

namespace masnet::scenarios {

/// The most runs a sweep may expand to (docs/sweeps.md, "Limits"), checked before expanding.
inline constexpr std::uint64_t kMaxSweepRuns = 100'000;

/// One override: a dotted scenario key and its value (given to the loader as "key=VALUE").
struct SweepOverride {
  std::string key;
  nlohmann::json value;
};

/// One position on an axis: the parameters it records and the overrides it applies.
struct AxisPoint {
  std::string label;                     ///< "0.1", "oracle", or "[3, 0.02]" for a zip group
  std::vector<SweepOverride> overrides;  ///< applied in order
};

/// One factor of the cartesian product: a varied key, a zip group, or the named variants.
struct SweepAxis {
  std::string name;               ///< "radio.loss", "variant", or the first key of a zip group
  std::vector<std::string> keys;  ///< the keys it sets (a variant's union of keys)
  std::vector<AxisPoint> points;
  bool numeric = false;  ///< every point is one number: charts use a linear x axis
};

struct SweepDef {
  std::string file;       ///< the sweep file as given
  std::string text;       ///< its content, stored in results.sqlite
  std::string base_path;  ///< the base scenario, resolved against the sweep file's folder
  std::string base_text;  ///< its content
  std::string base_key;   ///< hash of the base's YAML content (comments and layout ignored)
  std::vector<std::uint64_t> seeds;
  std::vector<SweepOverride> set;  ///< fixed overrides, applied first to every run
  std::vector<SweepAxis> axes;     ///< product order: variants, then vary keys in file order
  /// Every parameter recorded per run: "variant" when there are variants, then each key set by
  /// a variant or varied, in order of first appearance. One p_<key> column each.
  std::vector<std::string> parameters;
  std::string output_dir;  ///< relative to the working directory; --out replaces it
  bool keep_runs = false;  ///< write runs/<run_id>/ run directories
  /// `report.reference_lines`: each line's `x` resolved to an axis name.
  std::vector<SweepReferenceLine> reference_lines;
};

/// One run of a sweep.
struct RunSpec {
  std::size_t index = 0;  ///< position in the expansion (seeds vary fastest)
  std::string id;         ///< 16 hex digits of the hash of (base_key, overrides, seed)
  std::uint64_t seed = 1;
  std::vector<std::size_t> points;     ///< the point of each axis
  std::vector<std::string> overrides;  ///< "key=VALUE" for load_scenario, `set` first
  nlohmann::json parameters;           ///< parameter name -> value (absent: not set)
  std::string label;                   ///< "radio.loss=0.1 seed=3"
};

struct SweepLoad {
  std::optional<SweepDef> sweep;  ///< set when there is no diagnostic
  std::vector<Diagnostic> diagnostics;
};

/// Reads and checks a sweep file: structure, values, ranges, zip lengths, that every key is a
/// scenario key (one probe load per variant), that no two runs are the same. Never throws.
SweepLoad load_sweep(const std::string& path);
/// The same from text; `file_name` is used in messages and to resolve `base`.
SweepLoad load_sweep_text(const std::string& text, const std::string& file_name);

/// The runs of a sweep in a fixed order: axes in order (the last varies fastest), then seeds.
std::vector<RunSpec> expand_sweep(const SweepDef& sweep);

/// The id of a run: FNV-1a 64 (with a splitmix64 finish) of the canonical JSON {"base",
/// "overrides", "seed"} (keys sorted, later overrides of the same key win), as 16 hex digits.
std::string sweep_run_id(const std::string& base_key, const std::vector<SweepOverride>& overrides,
                         std::uint64_t seed);

/// The values of a {from, to, step} range, inclusive: from + k·step rounded to the most
/// decimals the three numbers are written with, so 0.1 steps give 0.3, not
/// 0.30000000000000004, and `to` is reached despite rounding. Integers stay integers. Empty
/// when step is 0 or points away from `to`; more than 100000 elements when the range is huge.
std::vector<nlohmann::json> sweep_range(double from, double to, double step, int decimals,
                                        bool integers);

/// What one run produced, sent between threads (and ranks, as JSON text).
struct RunResult {
  std::size_t index = 0;
  std::string id;
  bool ok = false;
  std::string error;       ///< loader diagnostics (one per line) or the exception
  nlohmann::json summary;  ///< summary.json without scenario.resolved; null when failed
  nlohmann::json to_json() const;
  static RunResult from_json(const nlohmann::json& j);
};

/// Loads, simulates and (keep_runs) publishes `out_dir`/runs/<id>/ for one run. Thread-safe:
/// runs share nothing. Never throws; failures come back in the result.
RunResult execute_sweep_run(const SweepDef& sweep, const RunSpec& run, const std::string& out_dir);

/// Runs on a Boost.Asio thread pool; finished results are collected by the owner's thread.
class SweepWorkers {
 public:
  SweepWorkers(const SweepDef& sweep, const std::vector<RunSpec>& runs, std::string out_dir,
               int threads);
  ~SweepWorkers();
  SweepWorkers(const SweepWorkers&) = delete;
  SweepWorkers& operator=(const SweepWorkers&) = delete;

  void submit(std::size_t index);
  /// The next finished result, waiting at most `timeout`.
  std::optional<RunResult> next(std::chrono::milliseconds timeout);
  /// Submitted and not yet returned by next().
  std::size_t in_flight() const { return in_flight_; }

 private:
  struct Shared;
  const SweepDef& sweep_;
  const std::vector<RunSpec>& runs_;
  std::string out_dir_;
  std::size_t in_flight_ = 0;
  std::unique_ptr<Shared> shared_;
};

/// Summary numbers flattened to dotted keys: numbers, booleans as 0/1, arrays as key.0, key.1…;
/// scenario.resolved, texts and `seed` left out. The `metrics` table, and (sanitised) the
/// columns of `runs`.
std::vector<std::pair<std::string, double>> flatten_metrics(const nlohmann::json& summary);
/// A SQL column name: lower case, [a-z0-9_], "messages.total.count" -> "messages_total_count".
std::string sanitize_column(const std::string& key);

struct SweepOptions {
  std::string out_dir;    ///< results folder
  int jobs = 1;           ///< worker threads in this process
  int ranks = 1;          ///< MPI ranks taking part (recorded)
  bool force = false;     ///< discard earlier results in out_dir
  bool progress = false;  ///< a progress line on stderr
};

struct SweepCounts {
  std::size_t total = 0;     ///< runs in the expansion
  std::size_t skipped = 0;   ///< already ok in results.sqlite
  std::size_t executed = 0;  ///< run now
  std::size_t failed = 0;    ///< failed now (earlier failures are always retried)
  std::size_t foreign = 0;   ///< rows of results.sqlite that are no run of this sweep
  double wall_time_s = 0;
  /// 0 when every run is ok, else the number of failed runs, capped at 125.
  int exit_code() const {
    return failed == 0 ? 0 : static_cast<int>(std::min<std::size_t>(failed, 125));
  }
};

/// Thrown when the output folder cannot be used (the message says why and what to do).
struct SweepOutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The results side of a sweep, owned by one thread (rank 0): results.sqlite, results.csv,
/// report.html and the progress line.
class SweepSession {
 public:
  /// Creates out_dir, opens (or creates) results.sqlite, records this invocation, and finds
  /// the runs still to do. Throws SweepOutputError when out_dir holds something else.
  SweepSession(const SweepDef& sweep, std::vector<RunSpec> runs, SweepOptions options);
  ~SweepSession();
  SweepSession(const SweepSession&) = delete;
  SweepSession& operator=(const SweepSession&) = delete;

  const std::vector<RunSpec>& runs() const { return runs_; }
  /// Indices of the runs to execute, ascending.
  const std::vector<std::size_t>& pending() const { return pending_; }
  /// Stores one result in its own transaction (an interrupted sweep keeps what finished).
  void record(const RunResult& result);
  /// Writes results.csv and report.html; returns the counts.
  SweepCounts finish();

 private:
  struct Db;
  const SweepDef& sweep_;
  std::vector<RunSpec> runs_;
  SweepOptions options_;
  std::unique_ptr<Db> db_;
  std::vector<std::size_t> pending_;
  SweepCounts counts_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool drawn_ = false;
  void draw_progress(bool final);
};

/// The whole sweep in this process: results + workers. `on_result`, if given, is called after
/// each record (tests count executed runs with it).
SweepCounts run_sweep_locally(const SweepDef& sweep, const SweepOptions& options,
                              const std::function<void(const RunResult&)>& on_result = {});

}  // namespace masnet::scenarios
