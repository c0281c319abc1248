// The results of a sweep, kept by one thread: results.sqlite (one transaction per run, so an
// interrupted sweep keeps what finished), results.csv, report.html and the progress line.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <sqlite3.h>
#include <unistd.h>

#include "scenarios/output/output_file.hpp"
#include "scenarios/run/run_directory.hpp"
#include "scenarios/sweep/sweep.hpp"
#include "scenarios/sweep/sweep_figures.hpp"
#include "scenarios/sweep/sweep_report.hpp"
#include "scenarios/sweep/sweep_statistics.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace

namespace {
void flatten_into(const json& j, const std::string& prefix,
                  std::vector<std::pair<std::string, double>>& out) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
      if (key == "scenario.resolved" || key == "seed") continue;
      flatten_into(it.value(), key, out);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      flatten_into(j[i], prefix + "." + std::to_string(i), out);
  } else if (j.is_boolean()) {
    out.emplace_back(prefix, j.get<bool>() ? 1.0 : 0.0);
  } else if (j.is_number()) {
    const double v = j.get<double>();
    if (std::isfinite(v)) out.emplace_back(prefix, v);
  }
}
}  // namespace

std::vector<std::pair<std::string, double>> flatten_metrics(const json& summary) {
  std::vector<std::pair<std::string, double>> out;
  flatten_into(summary, "", out);
  return out;
}

std::string sanitize_column(const std::string& key) {
  std::string c;
  for (char ch : key) {
    const auto u = static_cast<unsigned char>(ch);
    c += std::isalnum(u) ? static_cast<char>(std::tolower(u)) : '_';
  }
  if (c.empty() || std::isdigit(static_cast<unsigned char>(c.front()))) c = "_" + c;
  return c;
}

namespace {

// The fixed columns of `runs`, in order; then p_<parameter>, then one per metric.
const std::vector<std::string> kFixedColumns = {"run_id",     "run_index",   "seed",
                                                "status",     "error",       "label",
                                                "parameters", "fingerprint", "finished_at"};
// The totals of the contended radio levels (collision, csma): metric columns that every
// database has, so that queries over them work whatever the sweep ran; NULL for other levels.
const std::vector<std::string> kContentionColumns = {
    "messages_total_transmissions", "messages_total_delivered", "messages_total_collided",
    "messages_total_channel_lost",  "messages_total_dropped",   "messages_total_retries",
    "messages_total_backoffs",      "messages_total_acks",      "messages_total_latency_mean_s",
    "messages_total_latency_p99_s"};

std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s)
    q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      throw std::runtime_error(std::string("results.sqlite: ") + sqlite3_errmsg(db) +
                               " in: " + sql);
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  void bind(int i, const std::string& s) {
    sqlite3_bind_text(stmt_, i, s.c_str(), -1, SQLITE_TRANSIENT);
  }
  void bind(int i, double v) { sqlite3_bind_double(stmt_, i, v); }
  void bind(int i, std::int64_t v) { sqlite3_bind_int64(stmt_, i, v); }
  void bind_null(int i) { sqlite3_bind_null(stmt_, i); }
  void bind(int i, const json& v) {
    if (v.is_null())
      bind_null(i);
    else if (v.is_string())
      bind(i, v.get<std::string>());
    else if (v.is_boolean())
      bind(i, std::int64_t{v.get<bool>() ? 1 : 0});
    else if (v.is_number_integer())
      bind(i, v.get<std::int64_t>());
    else if (v.is_number())
      bind(i, v.get<double>());
    else
      bind(i, v.dump());
  }
  /// True while there is a row.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw std::runtime_error(std::string("results.sqlite: ") + sqlite3_errmsg(db_));
  }
  void reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  std::string text(int i) const {
    const unsigned char* t = sqlite3_column_text(stmt_, i);
    return t ? reinterpret_cast<const char*>(t) : std::string();
  }
  double number(int i) const { return sqlite3_column_double(stmt_, i); }
  bool is_null(int i) const { return sqlite3_column_type(stmt_, i) == SQLITE_NULL; }
  sqlite3_stmt* get() const { return stmt_; }

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace

struct SweepSession::Db {
  sqlite3* db = nullptr;
  std::int64_t invocation = 0;
  std::set<std::string> columns;                        // of `runs`
  std::map<std::string, std::string> column_of_metric;  // dotted key -> column
  ~Db() {
    if (db) sqlite3_close(db);
  }
  void exec(const std::string& sql) {
    char* message = nullptr;
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
      const std::string m = message ? message : "unknown error";
      sqlite3_free(message);
      throw std::runtime_error("results.sqlite: " + m + " in: " + sql);
    }
  }
  void add_column(const std::string& name) {
    if (columns.count(name)) return;
    exec("ALTER TABLE runs ADD COLUMN \"" + name + "\"");
    columns.insert(name);
  }
};

SweepSession::SweepSession(const SweepDef& sweep, std::vector<RunSpec> runs, SweepOptions options)
    : sweep_(sweep),
      runs_(std::move(runs)),
      options_(std::move(options)),
      db_(std::make_unique<Db>()),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {
  const fs::path out(options_.out_dir);
  const fs::path db_path = out / "results.sqlite";
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    throw SweepOutputError("'" + out.string() + "' exists and is not a directory");
  // --force discards a sweep's own results only: a folder of other files is never emptied.
  if (fs::exists(out, ec) && !fs::is_empty(out, ec) && !fs::exists(db_path, ec)) {
    throw SweepOutputError("refusing to write into '" + out.string() +
                           "': it is not empty and holds no sweep results (results.sqlite); "
                           "choose another --out");
  }
  if (options_.force) {
    for (const char* name : {"results.sqlite", "results.sqlite-journal", "results.sqlite-wal",
                             "results.sqlite-shm", "results.csv", "report.html"})
      fs::remove(out / name, ec);
    fs::remove_all(out / "runs", ec);
  }
  fs::create_directories(out);
  if (sqlite3_open_v2(db_path.c_str(), &db_->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                      nullptr) != SQLITE_OK)
    throw SweepOutputError("cannot open '" + db_path.string() + "': " + sqlite3_errmsg(db_->db));
  sqlite3_busy_timeout(db_->db, 5000);
  try {
    db_->exec(
        "CREATE TABLE IF NOT EXISTS sweep (invocation INTEGER PRIMARY KEY, started_at TEXT, "
        "finished_at TEXT, sweep_file TEXT, sweep_text TEXT, base_file TEXT, base_text TEXT, "
        "masnet_version TEXT, jobs INTEGER, ranks INTEGER, runs_total INTEGER, runs_skipped "
        "INTEGER, runs_executed INTEGER, runs_failed INTEGER, wall_time_s REAL)");
    db_->exec(
        "CREATE TABLE IF NOT EXISTS runs (run_id TEXT PRIMARY KEY, run_index INTEGER, seed "
        "INTEGER, "
        "status TEXT, error TEXT, label TEXT, parameters TEXT, fingerprint TEXT, finished_at "
        "TEXT)");
    db_->exec(
        "CREATE TABLE IF NOT EXISTS metrics (run_id TEXT, key TEXT, value REAL, "
        "PRIMARY KEY (run_id, key)) WITHOUT ROWID");
  } catch (const std::runtime_error& e) {
    throw SweepOutputError("'" + db_path.string() + "' is not a sweep database: " + e.what());
  }
  {
    Statement info(db_->db, "PRAGMA table_info(runs)");
    while (info.step())
      db_->columns.insert(info.text(1));
  }
  for (const auto& c : kFixedColumns)
    if (!db_->columns.count(c))
      throw SweepOutputError("'" + db_path.string() + "' is not a sweep database (no column " + c +
                             ")");

  db_->exec("BEGIN");
  for (const auto& p : sweep_.parameters)
    db_->add_column(sanitize_column("p_" + p));
  for (const auto& c : kContentionColumns)
    db_->add_column(c);
  {
    Statement insert(db_->db,
                     "INSERT INTO sweep (started_at, sweep_file, sweep_text, base_file, base_text, "
                     "masnet_version, jobs, ranks, runs_total) VALUES (?,?,?,?,?,?,?,?,?)");
    insert.bind(1, now_utc());
    insert.bind(2, sweep_.file);
    insert.bind(3, sweep_.text);
    insert.bind(4, sweep_.base_path);
    insert.bind(5, sweep_.base_text);
    insert.bind(6, std::string(MASNET_VERSION));
    insert.bind(7, std::int64_t{options_.jobs});
    insert.bind(8, std::int64_t{options_.ranks});
    insert.bind(9, static_cast<std::int64_t>(runs_.size()));
    insert.step();
    db_->invocation = sqlite3_last_insert_rowid(db_->db);
  }
  // Finished runs are skipped, failed ones retried; rows of no current run lose their index.
  std::map<std::string, std::string> status;
  {
    Statement rows(db_->db, "SELECT run_id, status FROM runs");
    while (rows.step())
      status[rows.text(0)] = rows.text(1);
  }
  db_->exec("UPDATE runs SET run_index = NULL");
  Statement index(db_->db, "UPDATE runs SET run_index = ?, label = ? WHERE run_id = ?");
  std::set<std::string> current;
  for (const RunSpec& r : runs_) {
    current.insert(r.id);
    auto found = status.find(r.id);
    if (found != status.end()) {
      index.bind(1, static_cast<std::int64_t>(r.index));
      index.bind(2, r.label);
      index.bind(3, r.id);
      index.step();
      index.reset();
    }
    if (found != status.end() && found->second == "ok")
      ++counts_.skipped;
    else
      pending_.push_back(r.index);
  }
  for (const auto& [id, s] : status)
    counts_.foreign += current.count(id) ? 0 : 1;
  db_->exec("COMMIT");
  counts_.total = runs_.size();
}

SweepSession::~SweepSession() {
  if (drawn_) std::fprintf(stderr, "\r\033[K");
}

void SweepSession::record(const RunResult& result) {
  const RunSpec& spec = runs_.at(result.index);
  const auto metrics =
      result.ok ? flatten_metrics(result.summary) : std::vector<std::pair<std::string, double>>{};
  db_->exec("BEGIN");
  try {
    std::vector<std::string> names = kFixedColumns;
    std::vector<json> values = {
        spec.id,
        static_cast<std::int64_t>(spec.index),
        static_cast<std::int64_t>(spec.seed),
        result.ok ? "ok" : "failed",
        result.ok ? json(nullptr) : json(result.error),
        spec.label,
        spec.parameters.dump(),
        result.ok ? result.summary.value("fingerprint", json(nullptr)) : json(nullptr),
        now_utc()};
    for (const auto& p : sweep_.parameters) {
      names.push_back(sanitize_column("p_" + p));
      values.push_back(spec.parameters.contains(p) ? spec.parameters[p] : json(nullptr));
    }
    std::set<std::string> used(names.begin(), names.end());
    for (const auto& [key, value] : metrics) {
      auto column = db_->column_of_metric.find(key);
      if (column == db_->column_of_metric.end()) {
        std::string name = sanitize_column(key);
        if (std::find(kFixedColumns.begin(), kFixedColumns.end(), name) != kFixedColumns.end() ||
            name.rfind("p_", 0) == 0)
          name = "m_" + name;
        column = db_->column_of_metric.emplace(key, name).first;
      }
      if (!used.insert(column->second).second) continue;  // two keys, one column: keep the first
      db_->add_column(column->second);
      names.push_back(column->second);
      // Counts stay integers in SQL (and in results.csv).
      if (value == std::floor(value) && std::abs(value) < 9e15)
        values.emplace_back(static_cast<std::int64_t>(value));
      else
        values.emplace_back(value);
    }
    std::string sql = "INSERT OR REPLACE INTO runs (", marks;
    for (std::size_t i = 0; i < names.size(); ++i) {
      sql += (i ? ",\"" : "\"") + names[i] + "\"";
      marks += i ? ",?" : "?";
    }
    sql += ") VALUES (" + marks + ")";
    Statement insert(db_->db, sql);
    for (std::size_t i = 0; i < values.size(); ++i)
      insert.bind(static_cast<int>(i + 1), values[i]);
    insert.step();
    Statement clear(db_->db, "DELETE FROM metrics WHERE run_id = ?");
    clear.bind(1, spec.id);
    clear.step();
    Statement metric(db_->db, "INSERT INTO metrics (run_id, key, value) VALUES (?,?,?)");
    for (const auto& [key, value] : metrics) {
      metric.bind(1, spec.id);
      metric.bind(2, key);
      metric.bind(3, value);
      metric.step();
      metric.reset();
    }
    db_->exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_->db, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  ++counts_.executed;
  if (!result.ok) ++counts_.failed;
  draw_progress(false);
}

void SweepSession::draw_progress(bool final) {
  if (!options_.progress) return;
  const auto now = std::chrono::steady_clock::now();
  if (!final && now - last_draw_ < std::chrono::milliseconds(200)) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::size_t todo = pending_.size();
  const std::size_t done = counts_.executed;
  const double eta =
      done > 0 ? elapsed * static_cast<double>(todo - done) / static_cast<double>(done) : 0.0;
  auto clock = [](double s) {
    const auto t = static_cast<long long>(std::llround(s));
    return fmt::format("{}:{:02d}", t / 60, t % 60);
  };
  std::string line = fmt::format("sweep: {}/{} runs", done, todo);
  if (counts_.skipped) line += fmt::format(" ({} done before)", counts_.skipped);
  if (counts_.failed) line += fmt::format(", {} failed", counts_.failed);
  line += ", " + clock(elapsed) + " elapsed";
  if (done > 0 && done < todo) line += ", ETA " + clock(eta);
  std::fprintf(stderr, "\r\033[K%s", line.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

SweepCounts SweepSession::finish() {
  if (drawn_) {
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    drawn_ = false;
  }
  counts_.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  {
    Statement update(
        db_->db,
        "UPDATE sweep SET finished_at = ?, runs_skipped = ?, runs_executed = ?, runs_failed = ?, "
        "wall_time_s = ? WHERE invocation = ?");
    update.bind(1, now_utc());
    update.bind(2, static_cast<std::int64_t>(counts_.skipped));
    update.bind(3, static_cast<std::int64_t>(counts_.executed));
    update.bind(4, static_cast<std::int64_t>(counts_.failed));
    update.bind(5, counts_.wall_time_s);
    update.bind(6, db_->invocation);
    update.step();
  }
  const fs::path out(options_.out_dir);
  std::error_code ec;
  write_statistics_table(db_->db, runs_);

  // results.csv: the rows of this sweep's runs, columns fixed, parameters, metrics by name.
  {
    Statement rows(db_->db, "SELECT * FROM runs WHERE run_index IS NOT NULL ORDER BY run_index");
    const int n = sqlite3_column_count(rows.get());
    std::vector<std::string> names;
    for (int i = 0; i < n; ++i)
      names.emplace_back(sqlite3_column_name(rows.get(), i));
    std::vector<int> order;
    auto position = [&](const std::string& name) {
      return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    for (const auto& c : kFixedColumns)
      order.push_back(position(c));
    for (const auto& p : sweep_.parameters)
      order.push_back(position(sanitize_column("p_" + p)));
    std::vector<std::string> rest;
    for (const auto& name : names)
      if (std::find(kFixedColumns.begin(), kFixedColumns.end(), name) == kFixedColumns.end() &&
          name.rfind("p_", 0) != 0)
        rest.push_back(name);
    std::sort(rest.begin(), rest.end());
    for (const auto& name : rest)
      order.push_back(position(name));
    // Parameter columns of an earlier version of the sweep file are kept after the metrics.
    for (const auto& name : names)
      if (name.rfind("p_", 0) == 0 &&
          std::find(order.begin(), order.end(), position(name)) == order.end())
        order.push_back(position(name));
    const fs::path tmp = out / "results.csv.partial";
    try {
      OutputFile csv(tmp);
      for (std::size_t i = 0; i < order.size(); ++i)
        csv.print("{}{}", i ? "," : "", names[order[i]]);
      csv.write("\n");
      while (rows.step()) {
        for (std::size_t i = 0; i < order.size(); ++i) {
          const int c = order[i];
          if (i) csv.write(",");
          switch (sqlite3_column_type(rows.get(), c)) {
            case SQLITE_NULL:
              break;
            case SQLITE_INTEGER:
              csv.print("{}", sqlite3_column_int64(rows.get(), c));
              break;
            case SQLITE_FLOAT:
              csv.write(shortest(rows.number(c)));
              break;
            default:
              csv.write(csv_cell(rows.text(c)));
          }
        }
        csv.write("\n");
      }
      csv.close();
    } catch (...) {
      fs::remove(tmp, ec);
      throw;
    }
    fs::rename(tmp, out / "results.csv");
  }

  // report.html: configurations over seeds, from the database (runs of earlier invocations too).
  SweepReportInput report;
  report.title = fs::path(sweep_.file).stem().string();
  report.sweep_file = sweep_.file;
  report.base_file = sweep_.base_path;
  report.seeds = sweep_.seeds.size();
  for (const auto& axis : sweep_.axes) {
    SweepReportAxis a;
    a.name = axis.name;
    a.numeric = axis.numeric;
    for (const auto& p : axis.points) {
      a.labels.push_back(p.label);
      a.x.push_back(axis.numeric && !p.overrides.empty() ? p.overrides.front().value.get<double>()
                                                         : 0.0);
    }
    report.axes.push_back(std::move(a));
  }
  {
    std::map<std::string, std::pair<std::string, std::string>> rows;  // id -> status, error
    Statement s(db_->db, "SELECT run_id, status, error FROM runs WHERE run_index IS NOT NULL");
    while (s.step())
      rows[s.text(0)] = {s.text(1), s.text(2)};
    Statement m(db_->db, "SELECT key, value FROM metrics WHERE run_id = ?");
    for (const RunSpec& r : runs_) {
      auto row = rows.find(r.id);
      if (row == rows.end()) continue;
      SweepReportRun rr;
      rr.index = r.index;
      rr.id = r.id;
      rr.seed = r.seed;
      rr.label = r.label;
      rr.points = r.points;
      rr.ok = row->second.first == "ok";
      rr.error = row->second.second;
      m.bind(1, r.id);
      while (m.step())
        rr.metrics[m.text(0)] = m.number(1);
      m.reset();
      add_derived_metrics(rr.metrics);
      report.runs.push_back(std::move(rr));
    }
  }
  report.total_runs = runs_.size();
  report.reference_lines = sweep_.reference_lines;
  report.figures = write_sensitivity_figures(report, out);
  report.figures_dir = out;
  const fs::path tmp = out / "report.html.partial";
  try {
    write_file(tmp, render_sweep_report(report));
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, out / "report.html");
  return counts_;
}

}  // namespace masnet::scenarios
