// ExactSum (sim/exact_sum.hpp): the same bits whatever the order of the terms, and the exact
// sum wherever the terms are multiples of 2^-64.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "sim/exact_sum.hpp"
#include "sim/random.hpp"

using masnet::sim::ExactSum;

namespace {

double sum_in_order(const std::vector<double>& terms) {
  ExactSum s;
  for (double x : terms)
    s.add(x);
  return s.value();
}

}  // namespace

TEST_CASE("an exact sum does not depend on the order of its terms where doubles do", "[sim]") {
  // Left to right in doubles, 1 + 1e-16 rounds back to 1 twice; the small terms first add up to
  // something 1 does not swallow.
  const std::vector<double> big_first{1.0, 1e-16, 1e-16}, small_first{1e-16, 1e-16, 1.0};
  REQUIRE((1.0 + 1e-16) + 1e-16 != (1e-16 + 1e-16) + 1.0);
  CHECK(std::bit_cast<std::uint64_t>(sum_in_order(big_first)) ==
        std::bit_cast<std::uint64_t>(sum_in_order(small_first)));

  // Radio-like terms (microjoules with every bit of a double used), shuffled many times, and
  // split between two partial sums added together.
  masnet::sim::RandomStream rng(11);
  std::vector<double> terms;
  for (int i = 0; i < 5000; ++i)
    terms.push_back(1e-6 * (1.0 + rng.uniform01()));
  const double reference = sum_in_order(terms);
  for (int round = 0; round < 20; ++round) {
    for (std::size_t i = terms.size() - 1; i > 0; --i)
      std::swap(terms[i], terms[rng.next_u64() % (i + 1)]);
    CHECK(sum_in_order(terms) == reference);
    ExactSum first, second;
    for (std::size_t i = 0; i < terms.size(); ++i)
      (i % 3 == 0 ? first : second).add(terms[i]);
    first.add(second);
    CHECK(first.value() == reference);
  }
  // Within the truncation of each term (2^-64 J) of the long-double sum.
  long double exact = 0;
  for (double x : terms)
    exact += x;
  CHECK(std::fabs(static_cast<double>(exact) - reference) < 1e-12);
}

TEST_CASE("an exact sum of multiples of 2^-64 is exact", "[sim]") {
  ExactSum s;
  s.add(3.0);
  s.add(0.5);
  s.add(0x1p-64);
  s.add(0x1p-64);
  s.add(1e15);                     // large whole parts carry into the upper word
  CHECK(s.value() == 1e15 + 3.5);  // 2^-63 is below a double's resolution at 1e15 ...
  ExactSum small;
  small.add(0x1p-64);
  small.add(0x1p-64);
  small.add(0x1p-63);
  CHECK(small.value() == 0x1p-62);  // ... but not on its own
  ExactSum carried;                 // fractions that carry into the whole part
  carried.add(0.75);
  carried.add(0.75);
  CHECK(carried.value() == 1.5);
  CHECK(ExactSum{}.value() == 0.0);
}
