#pragma once
// Where a run or a sweep writes, checked before any simulation and published all at once
// (docs/outputs.md, "How files are written"): a run directory is written into a staging
// sibling and renamed into place, so it is either complete or absent; a folder that is not
// a run's (the working directory, the home folder, a folder of the user's own files) is
// never emptied.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace masnet::scenarios {

/// `dir` made absolute and lexically normal, without a trailing separator ("runs/x/" and
/// "runs/x" name the same directory).
std::filesystem::path normalised_directory(const std::string& dir);

/// Why `dir` can never be an output directory, or "" when it may be one: ".", "..", "/", the
/// home folder, the working directory or any folder that contains it (after resolving
/// symbolic links). `what` names the option in the message ("--out").
std::string forbidden_output_directory(const std::string& dir, std::string_view what);

/// Whether files can be created where `dir` is or would be: a probe file is created and
/// removed in `dir` if it exists, else in its nearest existing ancestor. Returns "" or a
/// message naming the folder and the system's reason (read-only file system, permission).
std::string probe_writable(const std::string& dir);

/// Checks that `dir` may receive this run: absent, empty, or holding the same run (the same
/// run key); with `force`, also a different masnet run. A non-empty folder that holds no
/// masnet run is refused even with `force`. Also applies forbidden_output_directory and
/// probe_writable. Returns an error message, "" when fine.
std::string check_run_directory(const std::string& dir, const std::string& key, bool force);

/// Writes the run into a staging sibling "<dir>.partial-<pid>" with `write`, then replaces
/// `dir` with it by renames. If `write` throws, the staging folder is removed and `dir` is
/// left as it was; the exception propagates.
void publish_run_directory(const std::string& dir,
                           const std::function<void(const std::string&)>& write);

}  // namespace masnet::scenarios
