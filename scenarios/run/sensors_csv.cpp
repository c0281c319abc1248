#include "scenarios/run/sensors_csv.hpp"

#include <iterator>
#include <string_view>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "scenarios/output/output_file.hpp"

namespace masnet::scenarios {

void write_sensors_csv(const std::filesystem::path& path, const agents::SensorList& sensors) {
  OutputFile out(path);
  out.print("index,x,y,area\n");
  // Compiled formats into a buffer written in large pieces (a million sensors: 27 MB).
  fmt::memory_buffer rows;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    fmt::format_to(std::back_inserter(rows), FMT_COMPILE("{},{},{},{}\n"), i,
                   sensors[i].position.x(), sensors[i].position.y(), sensors[i].area);
    if (rows.size() >= std::size_t{1} << 16) {
      out.write(std::string_view(rows.data(), rows.size()));
      rows.clear();
    }
  }
  out.write(std::string_view(rows.data(), rows.size()));
  out.close();
}

}  // namespace masnet::scenarios
