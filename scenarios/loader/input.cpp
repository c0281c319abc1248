#include "scenarios/loader/input.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <map>
#include <sstream>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

namespace masnet::scenarios {

bool read_regular_file(const std::string& path, std::uint64_t max_bytes, std::string& text,
                       std::string& problem) {
  text.clear();
  // stat first: opening a FIFO would block, and /dev/zero never ends.
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    problem = std::strerror(errno);
    return false;
  }
  if (S_ISDIR(info.st_mode)) {
    problem = std::strerror(EISDIR);
    return false;
  }
  if (!S_ISREG(info.st_mode)) {
    problem = "not a regular file";
    return false;
  }
  const auto too_large = [&] {
    problem = "larger than the limit of " + std::to_string(max_bytes) + " bytes";
    return false;
  };
  if (static_cast<std::uint64_t>(info.st_size) > max_bytes) return too_large();
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    problem = std::strerror(errno);
    return false;
  }
  text.reserve(static_cast<std::size_t>(info.st_size));
  char buffer[1 << 16];
  bool ok = true;
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      problem = std::strerror(errno);
      ok = false;
      break;
    }
    if (n == 0) break;
    // The file may have grown since stat.
    if (text.size() + static_cast<std::size_t>(n) > max_bytes) {
      ok = too_large();
      break;
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  if (!ok) text.clear();
  return ok;
}

std::string line_column(std::string_view text, std::size_t offset) {
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i)
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  return std::to_string(line) + ":" + std::to_string(offset - line_start + 1);
}

namespace {

// Stops the event pass once a limit is passed or a second document begins.
struct StopScan {};

// One pass over the parser's events: counts the nodes each alias repeats, and finds tags and a
// second document, without building the tree.
class YamlScan : public YAML::EventHandler {
 public:
  YamlScan(std::string file, std::string fixed_location)
      : file_(std::move(file)), fixed_(std::move(fixed_location)) {}

  std::vector<Diagnostic> diagnostics;

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents_ > 1) {
      report(mark,
             "a second YAML document starts here (the file must hold a single document; "
             "remove the '---' and what follows)");
      throw StopScan{};
    }
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t anchor) override { leaf(anchor); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    const auto found = sizes_.find(anchor);
    if (found == sizes_.end()) {
      report(mark, "an alias inside the node it refers to (a cycle) is not allowed");
      throw StopScan{};
    }
    repeated_ = std::min(repeated_ + found->second, kMaxAliasNodes + 1);
    if (repeated_ > kMaxAliasNodes) {
      report(mark, "the aliases (*name) repeat more than " + std::to_string(kMaxAliasNodes) +
                       " nodes in all (docs/scenario-reference.md, \"Limits\")");
      throw StopScan{};
    }
    add(found->second);
  }
  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string&) override {
    check_tag(mark, tag);
    leaf(anchor);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    check_tag(mark, tag);
    open_.push_back({anchor, 1});
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    check_tag(mark, tag);
    open_.push_back({anchor, 1});
  }
  void OnMapEnd() override { close(); }

 private:
  struct Open {
    YAML::anchor_t anchor;
    std::uint64_t nodes;  // this node and everything below it, aliases expanded (saturated)
  };

  void report(const YAML::Mark& mark, std::string message) {
    std::string location = fixed_;
    if (!file_.empty())
      location =
          file_ + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
    diagnostics.push_back({std::move(location), std::move(message)});
  }
  void check_tag(const YAML::Mark& mark, const std::string& tag) {
    // "?" is an untagged plain node, "!" a quoted scalar: everything else was written as a tag.
    if (tag.empty() || tag == "?" || tag == "!") return;
    std::string written = tag;
    const std::string core = "tag:yaml.org,2002:";
    if (written.rfind(core, 0) == 0) written = "!!" + written.substr(core.size());
    report(mark, "YAML tags are not supported (got '" + shown_text(written) +
                     "'); write the value alone, quoted if it must stay a text");
    if (++tags_ >= 10) throw StopScan{};
  }
  void add(std::uint64_t nodes) {
    if (!open_.empty())
      open_.back().nodes = std::min(open_.back().nodes + nodes, kMaxAliasNodes + 1);
  }
  void leaf(YAML::anchor_t anchor) {
    if (anchor != YAML::NullAnchor) sizes_[anchor] = 1;
    add(1);
  }
  void close() {
    const Open done = open_.back();
    open_.pop_back();
    if (done.anchor != YAML::NullAnchor) sizes_[done.anchor] = done.nodes;
    add(done.nodes);
  }

  std::string file_, fixed_;
  int documents_ = 0, tags_ = 0;
  std::uint64_t repeated_ = 0;
  std::vector<Open> open_;
  std::map<YAML::anchor_t, std::uint64_t> sizes_;
};

}  // namespace

std::vector<Diagnostic> check_yaml_text(const std::string& text, const std::string& file,
                                        const std::string& fixed_location) {
  if (const std::size_t bad = first_invalid_utf8(text); bad != std::string::npos) {
    const std::string location =
        file.empty() ? fixed_location : file + ":" + line_column(text, bad);
    static const char* hex = "0123456789ABCDEF";
    const auto byte = static_cast<unsigned char>(text[bad]);
    return {{location, std::string("the text is not valid UTF-8 (byte 0x") + hex[byte >> 4] +
                           hex[byte & 15] + " here); save the file as UTF-8"}};
  }
  YamlScan scan(file, fixed_location);
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    while (parser.HandleNextDocument(scan)) {
    }
  } catch (const StopScan&) {
  } catch (const YAML::Exception&) {
    // A syntax error: the loader reports it where yaml-cpp finds it.
  }
  return scan.diagnostics;
}

bool valid_name(std::string_view name) {
  if (name.empty() || name.size() > kMaxNameChars || name.front() == '.' || name.front() == '-')
    return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-';
  });
}

std::string name_rule() {
  return "use 1 to " + std::to_string(kMaxNameChars) +
         " of the characters A-Z a-z 0-9 . _ -, not starting with '.' or '-'";
}

std::string sanitized_name(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (out.size() == kMaxNameChars) break;
    const bool allowed = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                         (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
    if (out.empty() && (c == '.' || c == '-')) continue;
    out += allowed ? c : '_';
  }
  return out.empty() ? "scenario" : out;
}

}  // namespace masnet::scenarios
