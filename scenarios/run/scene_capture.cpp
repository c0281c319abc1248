#include "scenarios/run/scene_capture.hpp"

#include <algorithm>
#include <cmath>

#include <boost/archive/iterators/base64_from_binary.hpp>
#include <boost/archive/iterators/transform_width.hpp>

#include "scenarios/run/recorder.hpp"

namespace masnet::scenarios {

std::string base64(const std::vector<std::uint8_t>& bytes) {
  using namespace boost::archive::iterators;
  using Encoder = base64_from_binary<transform_width<const std::uint8_t*, 6, 8>>;
  std::string out(Encoder(bytes.data()), Encoder(bytes.data() + bytes.size()));
  out.append((3 - bytes.size() % 3) % 3, '=');
  return out;
}

SceneCapture::SceneCapture(agents::World& world, const ScenarioDef& def)
    : world_(world), def_(def) {
  const auto& domain = world.def().domain.vertices;
  if (!domain.empty()) {
    x0_ = x1_ = domain.front().x();
    y0_ = y1_ = domain.front().y();
    for (const Vec2& v : domain) {
      x0_ = std::min(x0_, v.x());
      x1_ = std::max(x1_, v.x());
      y0_ = std::min(y0_, v.y());
      y1_ = std::max(y1_, v.y());
    }
  }
  // About one bin per sensor (a sensor grid maps onto itself), at most kMaxRasterBins along the
  // long side, the bins square.
  const std::size_t sensors = world.sensor_count();
  const double width = x1_ - x0_, height = y1_ - y0_;
  if (sensors == 0 || !(width > 0) || !(height > 0)) return;
  const double bin_size = std::max(std::sqrt(width * height / static_cast<double>(sensors)),
                                   std::max(width, height) / kMaxRasterBins);
  raster_nx_ = std::clamp<std::size_t>(static_cast<std::size_t>(std::lround(width / bin_size)), 1,
                                       kMaxRasterBins);
  raster_ny_ = std::clamp<std::size_t>(static_cast<std::size_t>(std::lround(height / bin_size)), 1,
                                       kMaxRasterBins);
  sensor_bin_.resize(sensors);
  bin_sensor_count_.assign(raster_nx_ * raster_ny_, 0);
  for (std::size_t s = 0; s < sensors; ++s) {
    const Vec2 p = world.def().sensors[s].position;
    const auto column = std::min<std::size_t>(
        raster_nx_ - 1, static_cast<std::size_t>(std::max(0.0, (p.x() - x0_) / width) *
                                                 static_cast<double>(raster_nx_)));
    const auto row = std::min<std::size_t>(
        raster_ny_ - 1, static_cast<std::size_t>(std::max(0.0, (p.y() - y0_) / height) *
                                                 static_cast<double>(raster_ny_)));
    sensor_bin_[s] = static_cast<std::uint32_t>(row * raster_nx_ + column);
    ++bin_sensor_count_[sensor_bin_[s]];
  }
}

std::int64_t SceneCapture::qx(double x) const {
  return std::llround((x - x0_) / (x1_ - x0_) * kCoordinateSteps);
}
std::int64_t SceneCapture::qy(double y) const {
  return std::llround((y - y0_) / (y1_ - y0_) * kCoordinateSteps);
}

nlohmann::json SceneCapture::polygon(const std::vector<Vec2>& vertices) const {
  nlohmann::json flat = nlohmann::json::array();
  for (const Vec2& v : vertices) {
    flat.push_back(qx(v.x()));
    flat.push_back(qy(v.y()));
  }
  return flat;
}

nlohmann::json SceneCapture::header() const {
  nlohmann::json domain = nlohmann::json::array();
  for (const Vec2& v : world_.def().domain.vertices)
    domain.push_back({qx(v.x()), qy(v.y())});
  return {{"format", "masnet-scene-1"},
          {"name", def_.name},
          {"duration_s", def_.duration_s},
          {"bbox", {x0_, y0_, x1_, y1_}},
          {"steps", kCoordinateSteps},
          {"domain", domain},
          {"robots", world_.robot_count()},
          {"sensors", world_.sensor_count()},
          {"targets", world_.source_positions().size()},
          {"diffusion", world_.diffusion() != nullptr},
          {"raster", {{"nx", raster_nx_}, {"ny", raster_ny_}}}};
}

std::string SceneCapture::raster(double& max_value) {
  bin_sum_.assign(raster_nx_ * raster_ny_, 0.0);
  for (std::size_t s = 0; s < sensor_bin_.size(); ++s)
    bin_sum_[sensor_bin_[s]] += world_.true_density(s);
  max_value = 0.0;
  for (std::size_t b = 0; b < bin_sum_.size(); ++b) {
    if (bin_sensor_count_[b] > 0) bin_sum_[b] /= bin_sensor_count_[b];
    max_value = std::max(max_value, bin_sum_[b]);
  }
  std::vector<std::uint8_t> bytes(bin_sum_.size(), 0);
  if (max_value > 0)
    for (std::size_t b = 0; b < bin_sum_.size(); ++b)
      bytes[b] = static_cast<std::uint8_t>(std::lround(255.0 * bin_sum_[b] / max_value));
  return base64(bytes);
}

nlohmann::json SceneCapture::sent_since_last(std::size_t stream) {
  if (robot_sent_.size() <= stream) robot_sent_.resize(stream + 1);
  std::vector<std::uint64_t>& previous = robot_sent_[stream];
  previous.resize(world_.robot_count(), 0);
  nlohmann::json sent = nlohmann::json::array();
  for (std::size_t i = 0; i < world_.robot_count(); ++i) {
    const std::uint64_t frames_sent = world_.radio().frames_sent(world_.robot_node(i));
    sent.push_back(frames_sent - previous[i]);
    previous[i] = frames_sent;
  }
  return sent;
}

nlohmann::json SceneCapture::frame(const Sample* latest) {
  nlohmann::json f;
  f["t"] = sim::to_seconds(world_.simulator().now());
  nlohmann::json positions = nlohmann::json::array(), radii = nlohmann::json::array(),
                 down = nlohmann::json::array(), cells = nlohmann::json::array(),
                 oracle = nlohmann::json::array();
  for (std::size_t i = 0; i < world_.robot_count(); ++i) {
    const Vec2 p = world_.robot_state(i).position;
    positions.push_back(qx(p.x()));
    positions.push_back(qy(p.y()));
    radii.push_back(
        std::llround(world_.robot_protocol(i).radius() / (x1_ - x0_) * kCoordinateSteps));
    cells.push_back(polygon(world_.robot_protocol(i).cell().vertices));
    if (world_.node_alive(world_.robot_node(i))) {
      oracle.push_back(polygon(world_.oracle_cell(i).polygon.vertices));
    } else {
      down.push_back(i);
      oracle.push_back(nlohmann::json::array());
    }
  }
  f["p"] = std::move(positions);
  f["r"] = std::move(radii);
  f["down"] = std::move(down);
  f["cells"] = std::move(cells);
  f["oracle"] = std::move(oracle);
  nlohmann::json targets = nlohmann::json::array();
  for (const Vec2& s : world_.source_positions()) {
    targets.push_back(qx(s.x()));
    targets.push_back(qy(s.y()));
  }
  f["targets"] = std::move(targets);
  if (world_.follower_count() > 0) {  // robot groups: each follower with its group (= leader)
    nlohmann::json followers = nlohmann::json::array();
    for (std::size_t k = 0; k < world_.follower_count(); ++k) {
      const Vec2 p = world_.follower_state(k).position;
      followers.push_back(qx(p.x()));
      followers.push_back(qy(p.y()));
      followers.push_back(world_.follower_group(k));
    }
    f["followers"] = std::move(followers);
  }
  if (raster_nx_ > 0) {
    double max_value = 0.0;
    f["raster"] = raster(max_value);
    f["raster_max"] = max_value;
  }
  if (latest != nullptr) {
    nlohmann::json metrics = {{"t", latest->t_s},
                              {"coverage_cost", latest->coverage_cost},
                              {"messages", latest->messages},
                              {"energy_j", latest->energy_j},
                              {"cell_correctness", latest->cell_correctness}};
    if (!world_.def().field.targets.empty()) metrics["tracking_mean"] = latest->tracking_mean;
    if (world_.diffusion() != nullptr) metrics["pollution_total"] = latest->pollution_total;
    f["metrics"] = std::move(metrics);
  }
  return f;
}

}  // namespace masnet::scenarios
