#include <catch2/catch.hpp>

#include "scenarios/run/progress.hpp"

using masnet::scenarios::ProgressBar;

TEST_CASE("The progress line shows a bar, the share done, simulated time, speed and ETA",
          "[scenarios]") {
  CHECK(ProgressBar::line(2.5, 5.0, 1.5e6, 10.0, 10) ==
        "[#####     ]  50.0%  t = 2.500 / 5.000 s  1.50 M events/s  ETA 00:10");
  // Nothing simulated yet: no rate to extrapolate from.
  CHECK(ProgressBar::line(0.0, 5.0, 0.0, -1.0, 4) ==
        "[    ]   0.0%  t = 0.000 / 5.000 s  0.00 M events/s  ETA --:--");
}

TEST_CASE("The ETA reads mm:ss below an hour and h:mm:ss from an hour on, to the second",
          "[scenarios]") {
  CHECK(ProgressBar::clock_text(0.0) == "00:00");
  CHECK(ProgressBar::clock_text(0.4) == "00:00");
  CHECK(ProgressBar::clock_text(59.6) == "01:00");
  CHECK(ProgressBar::clock_text(754.0) == "12:34");
  CHECK(ProgressBar::clock_text(3599.4) == "59:59");
  CHECK(ProgressBar::clock_text(3600.0) == "1:00:00");
  CHECK(ProgressBar::clock_text(37230.0) == "10:20:30");
  CHECK(ProgressBar::line(1.0, 4.0, 1e6, 4000.0, 4).substr(53) == "ETA 1:06:40");
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
