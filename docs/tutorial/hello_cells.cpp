// hello_cells: a robot protocol written against masnet's installed API (docs/tutorial-protocol.md).
// Every `period` each robot broadcasts a HELLO (a message type of its own) carrying its position
// at a fixed range, `hello_range`. At its next update it builds its Voronoi cell from the HELLOs
// heard since the last one, asks the sensors inside the cell for their readings with the paper's
// SENSE, and moves towards the density-weighted centroid. One round, no radius search: cheap,
// but a cell is only right when every Voronoi neighbour is within hello_range.
#include <masnet/protocols/registry.hpp>
#include <masnet/scenarios/cli/command_line.hpp>

#include <algorithm>
#include <memory>
#include <variant>
#include <vector>

namespace mp = masnet::protocols;
namespace mn = masnet::net;
using masnet::sim::seconds;

namespace {

struct Hello {  // what a HELLO carries; the radio never reads it
  mn::NodeId robot;
  mn::Vec2 position;
};

class HelloCells final : public mp::RobotProtocol {
 public:
  HelloCells(const mp::RobotSetup& setup, mn::MessageType hello)
      : host_(setup.host),
        context_(setup.context),
        hello_(hello),
        hello_range_(setup.params.real("hello_range")),
        period_s_(setup.params.real("period")),
        reply_timeout_s_(setup.params.real("reply_timeout")),
        phase_s_(setup.random.uniform(0.0, period_s_)) {}

  void start() override { host_.set_timer(seconds(phase_s_), kTick); }

  void on_frame(const mn::Frame& frame) override {
    if (frame.type == hello_) {
      const auto& message = std::get<mn::CustomMessage>(frame.payload);
      const auto& hello = *static_cast<const Hello*>(message.body.get());
      heard_.push_back({hello.robot, hello.position});
    } else if (const auto* reading = std::get_if<mn::Reading>(&frame.payload)) {
      if (reading->update != record_.update) return;  // an answer to an earlier SENSE
      readings_.push_back(*reading);
      record_.messages.add(frame.type, frame.size_bytes);
    }
  }

  void on_timer(std::uint32_t kind) override {
    if (kind == kTick) {
      host_.set_timer(seconds(period_s_), kTick);
      begin_update();
    } else if (kind == kSenseEnd) {
      finish_update();
    }
  }

  double radius() const override { return hello_range_; }
  const mp::ConvexPolygon& cell() const override { return cell_; }
  const std::vector<mp::CellReading>& cell_readings() const override { return cell_readings_; }

 private:
  enum Timer : std::uint32_t { kTick, kSenseEnd };

  void begin_update() {
    const std::uint32_t update = record_.update + 1;
    record_ = mp::UpdateRecord{};
    record_.robot = host_.id();
    record_.update = update;
    record_.started = host_.now();
    record_.position = host_.position();
    record_.rounds = 1;
    record_.radius = hello_range_;
    record_.heard = std::move(heard_);
    heard_.clear();
    readings_.clear();

    // The cell of this robot among the positions heard (site 0 is the robot itself).
    std::vector<mn::Vec2> sites{record_.position};
    std::vector<std::uint32_t> candidates;
    for (const mp::HeardRobot& robot : record_.heard) {
      candidates.push_back(static_cast<std::uint32_t>(sites.size()));
      sites.push_back(robot.position);
    }
    mp::Cell cell = mp::voronoi_cell(0, sites, candidates, context_.domain);
    for (std::uint32_t site : cell.neighbours)
      record_.neighbours.push_back(record_.heard[site - 1].robot);
    std::sort(record_.neighbours.begin(), record_.neighbours.end());
    record_.cell = std::move(cell.polygon);
    record_.extra = {static_cast<double>(record_.heard.size())};  // the column "robots_heard"

    // Tell the others where this robot is, then ask the sensors of the cell for readings.
    const mn::MessageSizes& sizes = host_.message_sizes();
    mn::CustomMessage hello{hello_, sizes.id_bytes + sizes.position_bytes,
                            std::make_shared<const Hello>(Hello{host_.id(), record_.position})};
    record_.messages.add(hello_, host_.broadcast(hello_range_, std::move(hello)));
    if (record_.cell.vertices.empty()) return finish_update();
    const double sense_range = mp::max_vertex_distance(record_.cell, record_.position);
    record_.messages.add(
        mn::MessageType::sense,
        host_.broadcast(sense_range, mn::Sense{host_.id(), record_.update, record_.cell.vertices}));
    host_.set_timer(seconds(reply_timeout_s_), kSenseEnd);
  }

  void finish_update() {
    mp::CentroidAccumulator accumulator(context_.scaling);
    cell_readings_.clear();
    for (const mn::Reading& r : readings_) {
      if (!mp::contains(record_.cell, r.position)) continue;
      accumulator.add(r.position, r.reading, host_.sensor_area(r.sensor));
      cell_readings_.push_back({r.position, r.reading});
    }
    record_.readings = static_cast<std::uint32_t>(cell_readings_.size());
    if (record_.update == 1) target_ = record_.position;
    target_ = mp::head_for_centroid(host_, accumulator, record_, target_);  // or keep the target
    cell_ = record_.cell;
    host_.update_finished(record_);
  }

  mp::RobotHost& host_;
  const mp::ProtocolContext& context_;
  mn::MessageType hello_;
  double hello_range_, period_s_, reply_timeout_s_, phase_s_;
  std::vector<mp::HeardRobot> heard_;
  std::vector<mn::Reading> readings_;
  mp::UpdateRecord record_;
  mp::ConvexPolygon cell_;
  std::vector<mp::CellReading> cell_readings_;
  mn::Vec2 target_{0, 0};
};

}  // namespace

int main(int argc, char** argv) {
  const mn::MessageType hello = mn::register_message_type("HELLO");

  mp::ProtocolDefinition definition;
  definition.name = "hello_cells";
  definition.summary = "one HELLO broadcast a period at a fixed range; cells from what was heard";
  definition.params = {mp::update_period_param(), mp::reply_timeout_param(),
                       mp::ParamSpec::real("hello_range", 0.4, mp::ParamRange::between(0.01, 10.0),
                                           "world units", "how far a HELLO reaches")};
  definition.robots_hear = {hello, mn::MessageType::reading};
  definition.sensors_hear = {mn::MessageType::sense};
  definition.update_columns = {"robots_heard"};
  definition.make_robot = [hello](const mp::RobotSetup& setup) {
    return std::make_unique<HelloCells>(setup, hello);
  };
  mp::register_protocol(std::move(definition));

  return masnet::cli::main(argc, argv);  // run, validate, render, sweep, protocols
}
