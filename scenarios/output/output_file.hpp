#pragma once
// Writing output files so that no failure goes unseen: every write and the close are checked,
// and a failure (a full disk, a read-only mount, a vanished folder) throws OutputError naming
// the file and the system's reason. Nothing throws from a destructor, so an error while
// unwinding never turns into an abort. See docs/outputs.md ("How files are written").
#include <cstddef>
#include <filesystem>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace masnet::scenarios {

/// An output file could not be written; what() names the file and the reason.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws OutputError "cannot write 'PATH': REASON" (REASON from errno `error_number`).
[[noreturn]] void throw_output_error(const std::filesystem::path& path, int error_number);

/// A file opened for writing (created or truncated), buffered in 64 KiB pieces.
class OutputFile {
 public:
  explicit OutputFile(std::filesystem::path path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(std::string_view bytes);
  template <class... Args>
  void print(fmt::format_string<Args...> format, Args&&... args) {
    fmt::format_to(std::back_inserter(buffer_), format, std::forward<Args>(args)...);
    if (buffer_.size() >= kChunkBytes) flush();
  }
  /// Writes what is buffered and closes; throws OutputError if any of it failed. A file that
  /// is never closed (an exception elsewhere) is closed by the destructor without a check.
  void close();
  const std::filesystem::path& path() const { return path_; }

 private:
  static constexpr std::size_t kChunkBytes = std::size_t{1} << 16;
  void flush();

  std::filesystem::path path_;
  int fd_ = -1;
  fmt::memory_buffer buffer_;
};

/// Writes `bytes` to `path` (created or truncated) and closes it, checked.
void write_file(const std::filesystem::path& path, std::string_view bytes);

}  // namespace masnet::scenarios
