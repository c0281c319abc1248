#include <catch2/catch.hpp>

#include "scenarios/progress.hpp"

using masnet::scenarios::ProgressBar;

TEST_CASE("The progress line shows a bar, the share done, simulated time, speed and ETA",
          "[scenarios]") {
  CHECK(ProgressBar::line(2.5, 5.0, 1.5e6, 10.0, 10) ==
        "[#####     ]  50.0%  t = 2.500 / 5.000 s  1.50 M events/s  ETA 10 s");
  CHECK(ProgressBar::line(0.0, 5.0, 0.0, 0.0, 4) ==
        "[    ]   0.0%  t = 0.000 / 5.000 s  0.00 M events/s  ETA 0 s");
}

TEST_CASE("The progress bar rounds to the nearest cell and keeps its width", "[scenarios]") {
  // 1/3 of 10 cells is 3.33: three cells; 2/3 is 6.67: seven.
  CHECK(ProgressBar::line(1.0, 3.0, 2e5, 20.4, 10).rfind("[###       ]  33.3%", 0) == 0);
  CHECK(ProgressBar::line(2.0, 3.0, 2e5, 9.6, 10).rfind("[#######   ]  66.7%", 0) == 0);
  const std::string a = ProgressBar::line(0.1, 1.0, 1e6, 1, 30),
                    b = ProgressBar::line(0.9, 1.0, 1e6, 1, 30);
  CHECK(a.find(']') == 31);
  CHECK(b.find(']') == 31);
}

TEST_CASE("The progress bar is full, not overfull, past the end and for an empty run",
          "[scenarios]") {
  CHECK(ProgressBar::line(7.0, 5.0, 1e6, 0, 8).rfind("[########] 100.0%  t = 7.000 / 5.000 s", 0) ==
        0);
  CHECK(ProgressBar::line(0.0, 0.0, 0.0, 0, 8).rfind("[########] 100.0%", 0) == 0);
  CHECK(ProgressBar::line(-1.0, 5.0, 0.0, 0, 8).rfind("[        ]   0.0%", 0) == 0);
}
