#include "scenarios/output/output_file.hpp"

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

namespace {
// write(2) until all of it is written (a write may be partial, or interrupted by a signal).
void write_all(int fd, const char* p, std::size_t left, const std::filesystem::path& path) {
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_output_error(path, errno);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}
}  // namespace

void OutputFile::write(std::string_view bytes) {
  if (buffer_.size() + bytes.size() > kChunkBytes) flush();
  // Large pieces go straight to the file: no copy into the buffer first.
  if (bytes.size() >= kChunkBytes)
    write_all(fd_, bytes.data(), bytes.size(), path_);
  else
    buffer_.append(bytes.data(), bytes.data() + bytes.size());
}

void OutputFile::flush() {
  const std::size_t size = buffer_.size();
  buffer_.clear();  // a failed write throws: the buffer is not written twice
  write_all(fd_, buffer_.data(), size, path_);
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
