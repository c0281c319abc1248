#include "scenarios/live/live_watch.hpp"

#include <cmath>

namespace masnet::live {

LiveWatch::LiveWatch(Server& server, WatchOptions options)
    : server_(server), options_(options), speed_(options.speed) {
  paused_ = !options.start_running;
  waiting_for_viewer_ = !options.start_running;
  anchor_wall_ = Clock::now();
  server_.set_greeting([this] { return greeting(); });
  server_.set_command_handler([this](const nlohmann::json& c) { return command(c); });
  server_.set_viewers_handler([this](std::size_t n) { viewers_changed(n); });
}

LiveWatch::~LiveWatch() {
  // The server's thread may be about to call a handler it copied: stop it first.
  server_.stop();
  server_.set_greeting(nullptr);
  server_.set_command_handler(nullptr);
  server_.set_viewers_handler(nullptr);
}

std::string LiveWatch::status_locked() const {
  nlohmann::json status = {{"type", "status"},      {"t", t_s_},
                           {"paused", paused_},     {"waiting_for_viewer", waiting_for_viewer_},
                           {"speed", speed_},       {"to_end", to_end_},
                           {"finished", finished_}, {"viewers", viewers_}};
  return status.dump();
}

void LiveWatch::reanchor_locked(double t_s) {
  anchor_t_s_ = t_s;
  anchor_wall_ = Clock::now();
}

void LiveWatch::on_start(const nlohmann::json& header) {
  std::lock_guard lock(mutex_);
  hello_ = nlohmann::json{{"type", "hello"}, {"header", header}}.dump();
  // A viewer may have come while the world was being built: its greeting had no hello.
  if (greeted_without_hello_) server_.publish_control(hello_);
}

void LiveWatch::remember(const nlohmann::json& frame) {
  // Every stride-th frame: when full, drop every other point and double the stride.
  if (frames_seen_++ % history_stride_ != 0) return;
  nlohmann::json point = {{"t", frame["t"]}, {"p", frame["p"]}};
  if (frame.contains("metrics")) point["metrics"] = frame["metrics"];
  history_.push_back(std::move(point));
  if (history_.size() >= options_.max_history) {
    std::deque<nlohmann::json> thinned;
    for (std::size_t i = 0; i < history_.size(); i += 2)
      thinned.push_back(std::move(history_[i]));
    history_.swap(thinned);
    history_stride_ *= 2;
  }
}

void LiveWatch::on_frame(const nlohmann::json& frame) {
  std::string message = R"({"type":"frame","frame":)" + frame.dump() + "}";
  std::unique_lock lock(mutex_);
  t_s_ = frame.value("t", t_s_);
  remember(frame);
  latest_frame_ = message;
  server_.publish_frame(std::move(message));
  if (announce_pause_) {
    announce_pause_ = false;
    server_.publish_control(status_locked());
  }
  if (to_end_) return;
  if (step_requested_) return;  // on the way to the next update: no pacing
  const Clock::time_point hold_start = Clock::now();
  struct HeldTime {
    Clock::duration& held;
    Clock::time_point start;
    ~HeldTime() { held += Clock::now() - start; }
  } counted{held_, hold_start};
  const bool was_paused = paused_;
  changed_.wait(lock, [this] { return !paused_ || to_end_; });
  if (was_paused) reanchor_locked(t_s_);
  if (to_end_ || speed_ <= 0.0 || step_requested_) return;
  // Real time × speed from the anchor; a command (pause, speed) wakes the wait early.
  const auto due = anchor_wall_ + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>((t_s_ - anchor_t_s_) / speed_));
  changed_.wait_until(lock, due, [this] { return paused_ || to_end_ || step_requested_; });
  if (paused_ && !to_end_) {
    // Paused during the wait: hold here, then resume from this instant.
    changed_.wait(lock, [this] { return !paused_ || to_end_; });
    reanchor_locked(t_s_);
  }
}

bool LiveWatch::stop_after_update() {
  std::lock_guard lock(mutex_);
  if (!step_requested_) return false;
  step_requested_ = false;
  paused_ = true;
  announce_pause_ = true;  // by on_frame, with the time of the update
  return true;
}

void LiveWatch::on_end(const nlohmann::json& final_frame) {
  const std::string frame_text = final_frame.dump();
  std::lock_guard lock(mutex_);
  t_s_ = final_frame.value("t", t_s_);
  finished_ = true;
  paused_ = false;
  remember(final_frame);
  latest_frame_ = R"({"type":"frame","frame":)" + frame_text + "}";
  server_.publish_control(R"({"type":"end","frame":)" + frame_text + "}");
  server_.publish_control(status_locked());
}

std::string LiveWatch::command(const nlohmann::json& command) {
  const std::string name = command.value("cmd", "");
  std::lock_guard lock(mutex_);
  if (finished_) return "the run has finished";
  if (name == "pause") {
    paused_ = true;
  } else if (name == "play") {
    paused_ = false;
    waiting_for_viewer_ = false;
    reanchor_locked(t_s_);
  } else if (name == "step") {
    step_requested_ = true;
    paused_ = false;
    waiting_for_viewer_ = false;
  } else if (name == "speed") {
    const auto value = command.find("value");
    if (value == command.end() || !value->is_number() || !std::isfinite(value->get<double>()) ||
        value->get<double>() < 0.0 || value->get<double>() > 1000.0)
      return "speed takes a \"value\" from 0 (as fast as possible) to 1000 (× real time)";
    speed_ = value->get<double>();
    reanchor_locked(t_s_);
  } else if (name == "end") {
    to_end_ = true;
    paused_ = false;
    waiting_for_viewer_ = false;
  } else {
    return "unknown command '" + name + "' (pause, play, step, speed, end)";
  }
  changed_.notify_all();
  server_.publish_control(status_locked());
  return {};
}

void LiveWatch::viewers_changed(std::size_t viewers) {
  std::lock_guard lock(mutex_);
  viewers_ = viewers;
  if (waiting_for_viewer_ && viewers > 0) {
    waiting_for_viewer_ = false;
    paused_ = false;
    reanchor_locked(t_s_);
    changed_.notify_all();
  }
  server_.publish_control(status_locked());
}

double LiveWatch::held_s() const {
  std::lock_guard lock(mutex_);
  return std::chrono::duration<double>(held_).count();
}

std::vector<std::string> LiveWatch::greeting() {
  std::lock_guard lock(mutex_);
  std::vector<std::string> messages;
  if (hello_.empty())
    greeted_without_hello_ = true;
  else
    messages.push_back(hello_);
  nlohmann::json history = {{"type", "history"}, {"points", nlohmann::json::array()}};
  for (const nlohmann::json& point : history_)
    history["points"].push_back(point);
  messages.push_back(history.dump());
  if (!latest_frame_.empty()) messages.push_back(latest_frame_);
  messages.push_back(status_locked());
  return messages;
}

}  // namespace masnet::live
