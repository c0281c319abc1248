#include "scenarios/run/run_directory.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <fcntl.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "scenarios/output/output_file.hpp"

namespace masnet::scenarios {
namespace fs = std::filesystem;

fs::path normalised_directory(const std::string& dir) {
  fs::path p = fs::absolute(dir).lexically_normal();
  while (!p.has_filename() && p.has_relative_path())
    p = p.parent_path();
  return p;
}

namespace {

// Whether `outer` is `inner` or one of its ancestors (both canonical).
bool contains_or_equals(const fs::path& outer, const fs::path& inner) {
  auto o = outer.begin(), i = inner.begin();
  for (; o != outer.end(); ++o, ++i) {
    if (i == inner.end() || *o != *i) return false;
  }
  return true;
}

fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(p, ec);
  if (ec) return p;
  while (!r.has_filename() && r.has_relative_path())
    r = r.parent_path();
  return r;
}

}  // namespace

std::string forbidden_output_directory(const std::string& dir, std::string_view what) {
  const std::string option(what);
  if (dir.empty()) return option + ": the directory name is empty";
  const fs::path target = resolved(normalised_directory(dir));
  const std::string shown = "'" + dir + "'";
  if (target == target.root_path())
    return option + " " + shown + ": the root folder cannot be an output directory";
  std::error_code ec;
  const fs::path cwd = resolved(fs::current_path(ec));
  if (!ec && contains_or_equals(target, cwd))
    return option + " " + shown +
           ": an output directory cannot be the working directory or a folder that contains "
           "it (masnet replaces the whole directory); name a new folder, e.g. runs/NAME";
  if (const char* home = std::getenv("HOME"); home && *home) {
    const fs::path h = resolved(fs::path(home));
    if (h.has_relative_path() && contains_or_equals(target, h))
      return option + " " + shown +
             ": an output directory cannot be the home folder or a folder that contains it";
  }
  return {};
}

std::string probe_writable(const std::string& dir) {
  std::error_code ec;
  fs::path p = normalised_directory(dir);
  while (!fs::exists(p, ec) && p.has_relative_path())
    p = p.parent_path();
  if (!fs::is_directory(p, ec))
    return "cannot create '" + dir + "': '" + p.string() + "' is not a directory";
  // A real file, not access(2): root passes every permission check, not a read-only mount.
  const fs::path probe = p / (".masnet-probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int error_number = errno;
    return "cannot write in '" + p.string() + "': " + std::strerror(error_number);
  }
  ::close(fd);
  ::unlink(probe.c_str());
  return {};
}

std::string check_run_directory(const std::string& dir, const std::string& key, bool force) {
  if (std::string problem = forbidden_output_directory(dir, "--out"); !problem.empty())
    return problem;
  const fs::path target = normalised_directory(dir);
  std::error_code ec;
  if (fs::exists(target, ec)) {
    if (!fs::is_directory(target, ec)) return "'" + dir + "' exists and is not a directory";
    if (!fs::is_empty(target, ec)) {
      std::ifstream in(target / "summary.json");
      std::string other;
      try {
        const nlohmann::json j = nlohmann::json::parse(in);
        if (j.value("run_key", std::string()) == key) {
          other.clear();  // the same run again: replace it
        } else {
          other = "scenario '" + j.at("scenario").value("name", std::string("?")) + "', seed " +
                  j.value("seed", nlohmann::json()).dump();
        }
      } catch (const nlohmann::json::exception&) {
        return "refusing to replace '" + dir +
               "': it is not empty and holds no masnet run (no readable summary.json), so "
               "--force does not apply; choose another --out";
      }
      if (!other.empty() && !force)
        return "refusing to overwrite '" + dir + "': it holds a different run (" + other +
               "); choose another --out or add --force";
    }
  }
  return probe_writable(target.parent_path().string());
}

void publish_run_directory(const std::string& dir,
                           const std::function<void(const std::string&)>& write) {
  const fs::path target = normalised_directory(dir);
  const fs::path parent = target.parent_path();
  const std::string name = target.filename().string();
  const std::string pid = std::to_string(::getpid());
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw OutputError("cannot create '" + parent.string() + "': " + ec.message());
  const fs::path staging = parent / (name + ".partial-" + pid);
  fs::remove_all(staging, ec);
  fs::create_directory(staging, ec);
  if (ec) throw OutputError("cannot create '" + staging.string() + "': " + ec.message());
  try {
    write(staging.string());
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  // The old directory is moved aside, not deleted, until the new one is in place: a failed
  // rename puts it back.
  const fs::path replaced = parent / (name + ".replaced-" + pid);
  const bool had_target = fs::symlink_status(target, ec).type() != fs::file_type::not_found;
  if (had_target) {
    fs::rename(target, replaced, ec);
    if (ec) {
      std::error_code ignored;
      fs::remove_all(staging, ignored);
      throw OutputError("cannot replace '" + target.string() + "': " + ec.message());
    }
  }
  fs::rename(staging, target, ec);
  if (ec) {
    std::error_code ignored;
    if (had_target) fs::rename(replaced, target, ignored);
    fs::remove_all(staging, ignored);
    throw OutputError("cannot rename '" + staging.string() + "' to '" + target.string() +
                      "': " + ec.message());
  }
  if (had_target) fs::remove_all(replaced, ec);
}

}  // namespace masnet::scenarios
