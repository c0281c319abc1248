// ZeroedArray (sim/zeroed_array.hpp): all zero from the start, and the pages of a large one that
// nobody writes are not in memory (mincore asks the kernel which pages are resident); the span of
// indices a reader must look at (WrittenSpan).
#include <sys/mman.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sim/zeroed_array.hpp"

using masnet::sim::ZeroedArray;

namespace {
// Whether each page of the array's storage is resident.
std::vector<bool> resident_pages(const ZeroedArray<std::uint64_t>& array) {
  const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  const std::size_t bytes = array.size() * sizeof(std::uint64_t);
  std::vector<unsigned char> flags((bytes + page - 1) / page);
  REQUIRE(::mincore(const_cast<std::uint64_t*>(array.data()), bytes, flags.data()) == 0);
  std::vector<bool> resident;
  for (const unsigned char f : flags)
    resident.push_back((f & 1u) != 0);
  return resident;
}
}  // namespace

TEST_CASE("A zeroed array reads zero everywhere, small or mapped, and keeps what is written",
          "[sim]") {
  for (const std::size_t size : {std::size_t{10}, std::size_t{1} << 20}) {
    INFO(size);
    ZeroedArray<std::uint64_t> array(size);
    REQUIRE(array.size() == size);
    std::uint64_t sum = 0;
    for (const std::uint64_t v : array)
      sum += v;
    CHECK(sum == 0);
    array[3] = 42;
    array[size - 1] = 7;
    array.fill_in(4, 9);
    array.fill_in(5, 0);
    CHECK(array[4] == 9);
    CHECK(array[5] == 0);
    array.zero(3, 4);
    CHECK(array[3] == 0);
    CHECK(array[size - 1] == 7);
    ZeroedArray<std::uint64_t> moved = std::move(array);
    CHECK(array.empty());  // NOLINT(bugprone-use-after-move): a moved-from array is empty
    CHECK(moved[size - 1] == 7);
  }
}

TEST_CASE("A large zeroed array takes memory only for the pages written", "[sim]") {
  ZeroedArray<std::uint64_t> array(std::size_t{1} << 21);  // 16 MiB
  const auto page_words = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE)) / 8;
  // The storage is marked for 2 MiB pages (sim/huge_pages.hpp): a write makes resident its small
  // page, or the whole huge page around it, never more.
  const std::size_t huge_page_pages = (std::size_t{2} << 20) / (page_words * 8);
  const std::vector<bool> before = resident_pages(array);
  CHECK(std::count(before.begin(), before.end(), true) == 0);
  const std::size_t written = 3 * huge_page_pages + 5;
  array[written * page_words + 1] = 1;
  const std::vector<bool> after = resident_pages(array);
  CHECK(after[written]);
  const auto resident = std::count(after.begin(), after.end(), true);
  CHECK((resident == 1 || resident == static_cast<std::ptrdiff_t>(huge_page_pages)));
  CHECK(std::count(after.begin() + 3 * huge_page_pages, after.begin() + 4 * huge_page_pages,
                   true) == resident);
}

TEST_CASE("A written span covers every index added and nothing outside them", "[sim]") {
  masnet::sim::WrittenSpan span;
  for (const std::size_t i : {std::size_t{0}, std::size_t{5}, std::size_t{1} << 31})
    CHECK_FALSE(span.covers(i));  // nothing written yet
  span.add(7);
  CHECK(span.covers(7));
  CHECK_FALSE(span.covers(6));
  CHECK_FALSE(span.covers(8));
  span.add(3);
  span.add(std::size_t{20}, std::size_t{25});  // [20, 25)
  for (std::size_t i = 0; i < 30; ++i) {
    INFO(i);
    CHECK(span.covers(i) == (i >= 3 && i < 25));
  }
  span.add(1);
  CHECK(span.first == 1);
  CHECK(span.end == 25);
}
