#include "scenarios/output_file.hpp"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <unistd.h>

namespace masnet::scenarios {

void throw_output_error(const std::filesystem::path& path, int error_number) {
  throw OutputError("cannot write '" + path.string() + "': " + std::strerror(error_number));
}

OutputFile::OutputFile(std::filesystem::path path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw_output_error(path_, errno);
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::write(std::string_view bytes) {
  if (buffer_.size() + bytes.size() > kChunkBytes) flush();
  if (bytes.size() >= kChunkBytes) {
    // Large pieces go straight to the file: no copy into the buffer first.
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        throw_output_error(path_, errno);
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    return;
  }
  buffer_.append(bytes.data(), bytes.data() + bytes.size());
}

void OutputFile::flush() {
  const char* p = buffer_.data();
  std::size_t left = buffer_.size();
  buffer_.clear();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_output_error(path_, errno);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void OutputFile::close() {
  if (fd_ < 0) return;
  flush();
  const int fd = fd_;
  fd_ = -1;
  // close() may be the first to report a failed delayed write (network file systems).
  if (::close(fd) != 0) throw_output_error(path_, errno);
}

void write_file(const std::filesystem::path& path, std::string_view bytes) {
  OutputFile out(path);
  out.write(bytes);
  out.close();
}

}  // namespace masnet::scenarios
