#include "scenarios/cli/run_command.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <utility>

#include <CLI/CLI.hpp>

#include "scenarios/cli/command_output.hpp"
#include "scenarios/cli/logging_setup.hpp"
#include "scenarios/cli/mpi_scope.hpp"
#include "scenarios/loader/scenario.hpp"
#include "scenarios/output/output_file.hpp"
#include "scenarios/report/report.hpp"
#include "scenarios/run/progress.hpp"
#include "scenarios/run/run.hpp"
#include "scenarios/run/run_directory.hpp"
#include "scenarios/run/sensors_csv.hpp"
#include "sim/cpus.hpp"

namespace masnet::cli {
using namespace masnet::scenarios;

namespace {

// --seed takes the same range as the scenario's `seed` key: 0 … 2^63 − 1.
std::optional<std::uint64_t> parse_seed(const std::string& text, Diagnostic& problem) {
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end ||
      value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
    problem = {"--seed " + shown_text(text),
               "expected a whole number between 0 and " +
                   std::to_string(std::numeric_limits<std::int64_t>::max())};
    return std::nullopt;
  }
  return value;
}

/// MASNET_OVERHEARING_THREAD=0 or 1 forces the radio's second thread off or on, to compare
/// the two (docs/performance.md); otherwise it runs when two processors are allowed.
bool overhearing_thread_wanted() {
  const char* forced = std::getenv("MASNET_OVERHEARING_THREAD");
  if (forced != nullptr && (std::strcmp(forced, "0") == 0 || std::strcmp(forced, "1") == 0))
    return forced[0] == '1';
  return masnet::sim::allowed_cpu_count() >= 2;
}

/// `masnet run`'s --log-level and --log-file. The file is opened (created, or appended to)
/// before anything is simulated; an empty string means done, otherwise the reason it failed.
std::string set_up_run_logging(const RunArgs& args, const std::string& out, Logging& logging) {
  const spdlog::level::level_enum level = args.log_level == "error" ? spdlog::level::err
                                          : args.log_level == "warn"
                                              ? spdlog::level::warn
                                              : spdlog::level::from_str(args.log_level);
  if (args.log_file.empty()) {
    spdlog::default_logger()->set_level(level);
    logging.shows_on_terminal = level < spdlog::level::warn;
    return {};
  }
  std::error_code ec;
  if (std::filesystem::is_directory(args.log_file, ec))
    return "cannot open the log file '" + args.log_file + "': it is a directory";
  // The run directory is replaced as a whole at the end: a log inside it would be lost.
  std::error_code log_ec, run_ec;
  const std::filesystem::path log_path =
      std::filesystem::weakly_canonical(std::filesystem::absolute(args.log_file), log_ec);
  const std::filesystem::path run_dir =
      std::filesystem::weakly_canonical(normalised_directory(out), run_ec);
  if (!log_ec && !run_ec &&
      std::mismatch(run_dir.begin(), run_dir.end(), log_path.begin(), log_path.end()).first ==
          run_dir.end())
    return "the log file '" + args.log_file + "' cannot be inside the run directory '" +
           run_dir.string() + "', which is replaced at the end of the run";
  try {
    logging.file = std::make_shared<masnet::sim::CheckedFileSink>(args.log_file);
  } catch (const std::system_error& e) {
    return "cannot open the log file '" + args.log_file + "': " + e.code().message();
  }
  spdlog::set_default_logger(make_logger(logging.file, level));
  return {};
}

}  // namespace

CLI::App* add_run_subcommand(CLI::App& app, RunArgs& args) {
  CLI::App* run = app.add_subcommand("run", "run a scenario and write its run directory");
  run->add_option("scenario", args.scenario, "scenario file (YAML)")->required();
  run->add_option("--out", args.out, "run directory (default: runs/<name>-seed<seed>)");
  run->add_option("--seed", args.seed, "override the scenario's seed (0 ... 2^63-1)");
  run->add_option("--set", args.sets, "override a key: --set radio.loss=0.2 (repeatable)");
  run->add_flag("--force", args.force, "replace a different run's directory");
  run->add_flag("--quiet", args.quiet, "no progress and no summary line");
  run->add_flag("--baseline", args.baseline,
                "diffusion runs: also run without dispensers and report both (control.baseline)");
  run->add_option("--log-level", args.log_level,
                  "protocol log on stderr (or --log-file): trace, debug, info, warn, error or off")
      ->check(CLI::IsMember(kLogLevels))
      ->default_str("warn");
  run->add_option("--log-file", args.log_file,
                  "write the log to this file (appended to) instead of stderr");
  run->add_option("--tiles", args.tiles,
                  "cut the run into this many bands of sensors, run side by side on the allowed "
                  "processors (under mpirun: one per rank): the same outputs, not faster yet "
                  "(needs tie_order: origin)")
      ->check(CLI::Range(1u, 1024u));
  add_serve_options(*run, args.serve);

  return run;
}

int run_run_command(const RunArgs& args) {
  // Started by mpirun with N ranks: one run in N tiles, one per rank; only the first speaks and
  // writes (docs/decisions/0012-partitioned-runs.md).
  MpiScope mpi(true);
  const bool root = mpi.rank() == 0, over_ranks = mpi.size() > 1;
  // Every rank checks the command and the scenario alone; over ranks they refuse together (a
  // rank that stopped alone would leave the others waiting in the run's first exchange).
  std::optional<LoadResult> loaded;
  const auto ranks = static_cast<unsigned>(mpi.size());
  const unsigned wanted_tiles = over_ranks ? ranks : args.tiles;
  const std::vector<std::string> refusal = [&]() -> std::vector<std::string> {
    auto lines = [](const std::vector<Diagnostic>& diagnostics) {
      std::vector<std::string> text;
      for (const Diagnostic& d : diagnostics)
        text.push_back(d.text());
      return text;
    };
    std::optional<std::uint64_t> seed;
    if (!args.seed.empty() || args.seed_given) {
      Diagnostic problem;
      seed = parse_seed(args.seed, problem);
      if (!seed) return lines({problem});
    }
    std::vector<std::string> sets = args.sets;
    if (args.baseline) sets.push_back("control.baseline=true");  // same as the scenario key
    loaded = load_scenario(args.scenario, sets, seed);
    if (!loaded->scenario) return lines(loaded->diagnostics);
    if (over_ranks && args.tiles != 1 && args.tiles != ranks)
      return {"masnet run: --tiles " + std::to_string(args.tiles) + " under " +
              std::to_string(ranks) + " MPI ranks: each rank runs one tile (give --tiles " +
              std::to_string(ranks) + " or leave it out)"};
    if (std::string problem = tiles_problem(*loaded->scenario, wanted_tiles); !problem.empty())
      return {"masnet run: --tiles " + std::to_string(wanted_tiles) + ": " + problem};
    if (wanted_tiles > 1 && args.serve.serve)
      return {"masnet run: --tiles and --serve cannot be used together"};
    return {};
  }();
  if (!mpi.all(refusal.empty())) {
    // The first rank speaks; another only when the first had nothing to say (a file that only
    // it cannot read).
    const bool first_refused = mpi.first_rank_says(!refusal.empty());  // every rank asks
    if (root || !first_refused)
      for (const std::string& line : refusal)
        std::fprintf(stderr, "%s\n", line.c_str());
    return kBadInput;
  }
  if (root) print_warnings(loaded->warnings);
  // Moved into the run below: a million sensors' definitions are tens of megabytes a copy.
  ScenarioDef& scenario = *loaded->scenario;
  const std::string out = args.out.empty()
                              ? "runs/" + scenario.name + "-seed" + std::to_string(scenario.seed)
                              : args.out;
  // Refuse before simulating: a long run must not end in "cannot write". Over ranks the first
  // checks and every rank stops if it refuses.
  Logging logging;
  std::string refused;
  if (root) refused = check_run_directory(out, run_key(scenario), args.force);
  if (root && refused.empty()) refused = set_up_run_logging(args, out, logging);
  if (!refused.empty()) std::fprintf(stderr, "masnet run: %s\n", refused.c_str());
  if (!mpi.all(refused.empty())) return kBadInput;
  // Bound before anything is simulated: a taken port must not cost a run.
  std::unique_ptr<LiveSession> live;
  if (args.serve.serve) {
    int exit_code = kInternalError;
    live = start_live_session(args.serve, exit_code);
    if (!live) return exit_code;
  }
  // A lone run may use a second core for the radio's overhearing bookkeeping (the same results;
  // sweeps keep their cores for whole runs) when the process may run on two processors: pinned
  // to one (taskset, a cpuset), the two threads would only take turns.
  scenario.world.radio.overhearing_thread = overhearing_thread_wanted();
  // With one allowed processor the tiles would only take turns on it, each running every robot:
  // the run in one piece gives the same outputs sooner (ranks bring their own processors).
  const unsigned tiles = over_ranks || masnet::sim::allowed_cpu_count() >= 2 ? wanted_tiles : 1;
  // More ranks than processors on a host: a rank that waits for a window polls, and each window
  // then costs milliseconds instead of microseconds (docs/performance.md, "Windows on MPI ranks").
  if (over_ranks) {
    const MpiScope::Host host = mpi.this_host();
    if (!mpi.all(host.ranks <= host.processors) && root)
      std::fprintf(stderr,
                   "masnet run: warning: more MPI ranks than processors on a host (here %d "
                   "ranks, %d processors): every window waits on OpenMPI's polling; start at "
                   "most one rank per processor\n",
                   host.ranks, host.processors);
  }
  const std::unique_ptr<TileLink> link = mpi.tile_link();
  Run run(std::move(scenario), tiles, 0, link.get());
  const ScenarioDef& def = run.def();
  try {
    // Log lines on the terminal would break into the progress line: one or the other.
    // The twins run first, each for the whole duration: the line counts them in.
    ProgressBar bar(def.duration_s * run.passes(), root && !args.quiet &&
                                                       !logging.shows_on_terminal &&
                                                       ProgressBar::stderr_is_terminal());
    run.execute([&](double t, std::uint64_t events) { bar.update(t, events); },
                live ? &live->watcher() : nullptr);
  } catch (const std::exception& e) {
    // The other ranks wait in the window loop for this one: end them all.
    if (!over_ranks) throw;
    std::fprintf(stderr, "masnet run: rank %d: %s\n", mpi.rank(), e.what());
    mpi.abort(kInternalError);
  }
  if (!root) return 0;
  // Figures and report are drawn into the staging folder too, so the published directory is
  // complete or absent. A drawing failure that is not a write failure keeps the run's data
  // (published without figures) and `masnet render` can finish the job.
  std::string render_error;
  std::filesystem::path report;
  try {
    publish_run_directory(out, [&](const std::string& dir) {
      run.write_files(dir);
      write_sensors_csv(std::filesystem::path(dir) / "sensors.csv", def.world.sensors);
      if (!def.output.figures && !def.output.report) return;
      RenderOptions render;
      render.figures = def.output.figures;
      render.report = def.output.report;
      try {
        if (!render_run_directory(dir, render).empty()) report = "report.html";
      } catch (const OutputError&) {
        throw;
      } catch (const std::filesystem::filesystem_error&) {
        throw;
      } catch (const std::exception& e) {
        render_error = e.what();
        std::error_code ignored;
        std::filesystem::remove_all(std::filesystem::path(dir) / "figures", ignored);
        std::filesystem::remove(std::filesystem::path(dir) / "report.html", ignored);
      }
    });
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "masnet: cannot write the run directory '%s': %s\n"
                 "masnet: nothing was written (the partial copy was removed)\n",
                 out.c_str(), e.what());
    return kInternalError;
  }
  // A degenerate run says so even with --quiet: its numbers would mislead otherwise.
  const nlohmann::json summary = run.summary();
  for (const auto& warning : summary.at("warnings"))
    std::fprintf(stderr, "masnet: warning: %s\n", warning.get<std::string>().c_str());
  if (!args.quiet) {
    std::printf("%s: %.3f s simulated in %.3f s wall, %llu events, fingerprint %s, traffic %s\n",
                def.name.c_str(), def.duration_s, run.wall_time_s(),
                static_cast<unsigned long long>(run.events()), run.fingerprint().c_str(),
                run.traffic_fingerprint().c_str());
    std::printf("run directory: %s\n", normalised_directory(out).string().c_str());
  }
  if (logging.file) {
    if (std::string problem = logging.file->error(); !problem.empty()) {
      std::fprintf(stderr, "masnet: the log file is incomplete: %s\n", problem.c_str());
      return kInternalError;
    }
  }
  if (!render_error.empty()) {
    std::fprintf(stderr,
                 "masnet: the run's data are in '%s', but its figures or report failed: %s\n",
                 out.c_str(), render_error.c_str());
    return kInternalError;
  }
  if (!args.quiet && !report.empty())
    std::printf("report: %s\n", (normalised_directory(out) / report).string().c_str());
  if (live) live->serve_until_interrupted(run.wall_time_s());
  return 0;
}

}  // namespace masnet::cli
