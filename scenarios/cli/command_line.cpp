// The `masnet` command line (docs/scenario-reference.md, docs/outputs.md). Exit codes: 0 success,
// 2 bad input, 1 internal error or a failed write.
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "scenarios/cli/command_line.hpp"
#include "scenarios/cli/sweep_command.hpp"
#include "scenarios/loader/scenario.hpp"
#include "scenarios/output/output_file.hpp"
#include "scenarios/report/figures.hpp"
#include "scenarios/report/report.hpp"
#include "scenarios/run/progress.hpp"
#include "scenarios/run/run.hpp"
#include "scenarios/run/run_directory.hpp"
#include "scenarios/run/sensors_csv.hpp"
#include "sim/cpus.hpp"
#include "sim/log.hpp"

using namespace masnet::scenarios;

namespace {

constexpr int kBadInput = 2;
constexpr int kInternalError = 1;

void print_warnings(const std::vector<Diagnostic>& warnings) {
  for (const Diagnostic& w : warnings)
    std::fprintf(stderr, "%s: warning: %s\n", w.location.c_str(), w.message.c_str());
}

int print_diagnostics(const std::vector<Diagnostic>& diagnostics) {
  for (const Diagnostic& d : diagnostics)
    std::fprintf(stderr, "%s\n", d.text().c_str());
  return kBadInput;
}

struct RunArgs {
  std::string scenario;
  std::string out;
  std::vector<std::string> sets;
  std::string seed;  ///< parsed here, not by CLI11, which clamps out-of-range numbers
  bool seed_given = false;
  bool force = false;
  bool quiet = false;
  bool baseline = false;
  std::string log_level = "warn";
  std::string log_file;
};

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

// ---- Logging (docs/logging.md) ----------------------------------------------------------------

const std::vector<std::string> kLogLevels{"trace", "debug", "info", "warn", "error", "off"};

/// Where the log goes: stderr (never stdout, which carries the summary lines) unless a file
/// was named. Nothing is logged below warn today, so the default leaves the terminal as it was.
struct Logging {
  std::shared_ptr<masnet::sim::CheckedFileSink> file;  // null: stderr
  bool shows_on_terminal = false;                      // lines may land on stderr
};

std::shared_ptr<spdlog::logger> make_logger(spdlog::sink_ptr sink,
                                            spdlog::level::level_enum level) {
  auto logger = std::make_shared<spdlog::logger>("masnet", std::move(sink));
  logger->set_pattern("%v");  // sim::Log writes the simulated-time prefix and the level itself
  logger->set_level(level);
  logger->flush_on(spdlog::level::warn);
  return logger;
}

/// Every command: the default logger writes to stderr at warn.
void log_to_stderr() {
  spdlog::set_default_logger(
      make_logger(std::make_shared<spdlog::sinks::stderr_sink_mt>(), spdlog::level::warn));
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

int command_run(const RunArgs& args) {
  std::optional<std::uint64_t> seed;
  if (!args.seed.empty() || args.seed_given) {
    Diagnostic problem;
    seed = parse_seed(args.seed, problem);
    if (!seed) return print_diagnostics({problem});
  }
  std::vector<std::string> sets = args.sets;
  if (args.baseline) sets.push_back("control.baseline=true");  // same as the scenario key
  LoadResult loaded = load_scenario(args.scenario, sets, seed);
  if (!loaded.scenario) return print_diagnostics(loaded.diagnostics);
  print_warnings(loaded.warnings);
  const ScenarioDef& def = *loaded.scenario;
  const std::string out =
      args.out.empty() ? "runs/" + def.name + "-seed" + std::to_string(def.seed) : args.out;
  // Refuse before simulating: a long run must not end in "cannot write".
  if (std::string problem = check_run_directory(out, run_key(def), args.force); !problem.empty()) {
    std::fprintf(stderr, "masnet run: %s\n", problem.c_str());
    return kBadInput;
  }
  Logging logging;
  if (std::string problem = set_up_run_logging(args, out, logging); !problem.empty()) {
    std::fprintf(stderr, "masnet run: %s\n", problem.c_str());
    return kBadInput;
  }
  // A lone run may use a second core for the radio's overhearing bookkeeping (the same results;
  // sweeps keep their cores for whole runs) when the process may run on two processors: pinned
  // to one (taskset, a cpuset), the two threads would only take turns.
  ScenarioDef run_def = def;
  run_def.world.radio.overhearing_thread = overhearing_thread_wanted();
  Run run(run_def);
  {
    // Log lines on the terminal would break into the progress line: one or the other.
    ProgressBar bar(def.duration_s,
                    !args.quiet && !logging.shows_on_terminal && ProgressBar::stderr_is_terminal());
    run.execute([&](double t, std::uint64_t events) { bar.update(t, events); });
  }
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
  return 0;
}

struct RenderArgs {
  std::string dir;
  bool no_oracle_cells = false;
  bool radius_circles = false;
  bool quiet = false;
};

int command_render(const RenderArgs& args) {
  RenderOptions options;
  options.figure.oracle_cells = !args.no_oracle_cells;
  options.figure.radius_circles = args.radius_circles;
  std::optional<RunData> data;
  try {
    data = load_run_data(args.dir);
  } catch (const std::exception& e) {
    // Missing or unreadable data files: the directory given is not a (complete) run.
    std::fprintf(stderr, "masnet render: %s\n", e.what());
    return kBadInput;
  }
  std::filesystem::path report;
  try {
    report = render_run(*data, options);
  } catch (const OutputError& e) {
    std::fprintf(stderr, "masnet render: %s\n", e.what());
    return kInternalError;
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "masnet render: %s\n", e.what());
    return kInternalError;
  }
  if (!args.quiet) std::printf("report: %s\n", report.string().c_str());
  return 0;
}

int command_validate(const std::string& scenario, const std::vector<std::string>& sets) {
  // The same checks as `run`, but the sensors are only counted, not built.
  LoadOptions options;
  options.build_sensors = false;
  LoadResult loaded = load_scenario(scenario, sets, std::nullopt, options);
  if (!loaded.scenario) return print_diagnostics(loaded.diagnostics);
  print_warnings(loaded.warnings);
  const ScenarioDef& def = *loaded.scenario;
  std::printf("%s: ok (%zu sensors, %zu robots, %.3f s)\n", scenario.c_str(), def.sensor_count,
              def.world.robots.size(), def.duration_s);
  return 0;
}

}  // namespace

namespace masnet::cli {

int main(int argc, char** argv) {
  CLI::App app{"masnet — discrete-event simulator of mobile actuator/sensor networks"};
  app.require_subcommand(1);
  app.set_version_flag("--version", MASNET_VERSION);

  RunArgs run_args;
  CLI::App* run = app.add_subcommand("run", "run a scenario and write its run directory");
  run->add_option("scenario", run_args.scenario, "scenario file (YAML)")->required();
  run->add_option("--out", run_args.out, "run directory (default: runs/<name>-seed<seed>)");
  CLI::Option* seed_option =
      run->add_option("--seed", run_args.seed, "override the scenario's seed (0 ... 2^63-1)");
  run->add_option("--set", run_args.sets, "override a key: --set radio.loss=0.2 (repeatable)");
  run->add_flag("--force", run_args.force, "replace a different run's directory");
  run->add_flag("--quiet", run_args.quiet, "no progress and no summary line");
  run->add_flag("--baseline", run_args.baseline,
                "diffusion runs: also run without dispensers and report both (control.baseline)");
  run->add_option("--log-level", run_args.log_level,
                  "protocol log on stderr (or --log-file): trace, debug, info, warn, error or off")
      ->check(CLI::IsMember(kLogLevels))
      ->default_str("warn");
  run->add_option("--log-file", run_args.log_file,
                  "write the log to this file (appended to) instead of stderr");

  std::string validate_file;
  std::vector<std::string> validate_sets;
  CLI::App* validate =
      app.add_subcommand("validate", "check a scenario file and report every problem");
  validate->add_option("scenario", validate_file, "scenario file (YAML)")->required();
  validate->add_option("--set", validate_sets, "override a key before checking (repeatable)");

  RenderArgs render_args;
  CLI::App* render = app.add_subcommand(
      "render", "redraw a run directory's figures and report from its data files");
  render->add_option("run_dir", render_args.dir, "run directory written by masnet run")->required();
  render->add_flag("--no-oracle-cells", render_args.no_oracle_cells,
                   "leave out the oracle's cells (dashed)");
  render->add_flag("--radius-circles", render_args.radius_circles,
                   "draw each robot's radius R_i as a circle");
  render->add_flag("--quiet", render_args.quiet, "print nothing");

  SweepArgs sweep_args;
  CLI::App* sweep = add_sweep_subcommand(app, sweep_args);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kBadInput;
  }
  run_args.seed_given = seed_option->count() > 0;
  log_to_stderr();
  try {
    if (*run) return command_run(run_args);
    if (*validate) return command_validate(validate_file, validate_sets);
    if (*render) return command_render(render_args);
    if (*sweep) return run_sweep_command(sweep_args);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "masnet: internal error: %s\n", e.what());
    return kInternalError;
  }
  return kInternalError;
}

}  // namespace masnet::cli
