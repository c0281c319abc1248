#pragma once
// Plain records (trivially copyable: times, keys, ids, values) as bytes, and back: what parts of
// a partitioned run send each other between windows, across threads or MPI ranks
// (docs/decisions/0012-partitioned-runs.md). Both sides run the same build on the same kind of
// machine, so the bytes are the records' own.
#include <cstddef>
#include <cstring>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace masnet::sim {

template <class Record>
void append_records(std::vector<std::byte>& bytes, const Record* records, std::size_t count) {
  static_assert(std::is_trivially_copyable_v<Record>);
  const std::size_t at = bytes.size();
  bytes.resize(at + count * sizeof(Record));
  if (count > 0) std::memcpy(bytes.data() + at, records, count * sizeof(Record));
}

template <class Record>
std::vector<Record> records_from(const std::vector<std::byte>& bytes) {
  static_assert(std::is_trivially_copyable_v<Record>);
  std::vector<Record> records(bytes.size() / sizeof(Record));
  if (!records.empty()) std::memcpy(records.data(), bytes.data(), records.size() * sizeof(Record));
  return records;
}

/// Reads back, in order, what append_records wrote.
class PlainReader {
 public:
  explicit PlainReader(std::span<const std::byte> bytes) : bytes_(bytes) {}
  template <class Record>
  void read(Record* records, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<Record>);
    if (count > (bytes_.size() - at_) / sizeof(Record))
      throw std::runtime_error("plain records: fewer bytes than records");
    if (count > 0) std::memcpy(records, bytes_.data() + at_, count * sizeof(Record));
    at_ += count * sizeof(Record);
  }
  template <class Record>
  Record read() {
    Record record;
    read(&record, 1);
    return record;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  std::span<const std::byte> bytes_;
  std::size_t at_ = 0;
};

}  // namespace masnet::sim
