#include "freeplay/web/web_session.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <future>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>

#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/recording/camera_topics.hpp"
#include "freeplay/runner/camera_rig.hpp"
#include "freeplay/runner/frame_sink.hpp"
#include "freeplay/runner/live_episode.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen_renderer.hpp"
#include "freeplay/web/components.hpp"
#include "freeplay/web/experiment.hpp"
#include "freeplay/web/foxglove.hpp"
#include "freeplay/web/state_frame.hpp"

namespace freeplay::web {

namespace {

constexpr int kBackgroundJpegQuality = 85;
constexpr int kItemPicturePx = 160;
constexpr double kCameraRateHz = 1.0;  // the 3-D view is a glance, not a video: rendering runs on the sim thread
constexpr int kCameraWidthPx = 480;
constexpr int kCameraHeightPx = 270;  // the page scales the game's item pictures down to their on-screen size
constexpr const char* kStartingFrame = R"({"type":"state","stage":"starting","items":[],"events":[]})";

double unix_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
}

HttpReply json_reply(int status, const nlohmann::json& body) { return {status, "application/json", body.dump()}; }
HttpReply error_reply(int status, const std::string& message) { return json_reply(status, {{"error", message}}); }

nlohmann::json events_json(const std::vector<Event>& events) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : events) out.push_back(e.to_json());
  return out;
}

// What the server thread, the observer (sim thread) and the API share.
class Session {
 public:
  Session(const scenario::Scenario& scenario, const WebSessionOptions& options)
      : log_(options.out / "events.jsonl"),
        experiment_(options.out / "experiment.yaml", scenario.condition,
                    std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count(),
                    log_),
        scene_(scene_json(*runner::SharedModels::shipped().catalogue, scenario).dump()),
        signals_(options.signals) {
    for (const auto& item : runner::SharedModels::shipped().catalogue->items()) {
      item_names_.push_back(item.name);
      std::vector<uchar> png;
      cv::imencode(".png", sim::item_picture(item, kItemPicturePx), png);
      item_pictures_["/api/item/" + item.name + ".png"] = std::string(png.begin(), png.end());
    }
    if (scenario.condition == scenario::Condition::ChildRobot) {
      robot_ = std::make_unique<WizardSource>(scenario, log_, options.mode, options.sparc_timeout_s);
    }
    // The session's bag (`<out>/recording/`), paused until the page starts it unless told to record.
    recorder_ = std::make_unique<RecorderSwitch>(std::make_unique<recording::BagRecorder>(options.out, scenario.recording),
                                                 "recording", options.record || scenario.record, log_);
    for (const auto& c : scenario.cameras) camera_names_.push_back(c.name);
  }

  /// The signals the page sends, for the episode.
  WebSignals& signals() { return signals_; }
  /// The bag recorder's switch.
  RecorderSwitch& recorder() { return *recorder_; }
  /// Switches the scenario's camera rig with `cameras` (the live episode's switch; it must outlive the session's API).
  void set_cameras(runner::ObserverSwitch& cameras) { cameras_ = &cameras; }
  /// Logs a switch of the cameras at episode time `t` (`cameras`/`paused|resumed`).
  void cameras_switched(double t, bool on) { log_.add({t, "cameras", on ? "resumed" : "paused", nullptr}); }

  /// Every component's state: the game, the robot side, the recorder, the cameras (sim thread).
  nlohmann::json components(const std::string& stage) const {
    nlohmann::json out{{"game", {{"state", stage == "ended" ? "ended" : "running"}, {"stage", stage}}},
                       {"robot", nullptr},
                       {"recorder", recorder_->status()},
                       {"cameras", {{"state", cameras_state()}, {"names", camera_names_}}}};
    if (robot_) {
      const auto r = robot_->state();
      out["robot"] = {{"state", r["paused"].get<bool>() ? "paused" : "running"}, {"mode", r["mode"]}};
    }
    return out;
  }

  /// "none" (the scenario lists no cameras), "running" or "paused" (any thread).
  std::string cameras_state() const {
    const auto* cameras = cameras_.load();
    return cameras == nullptr ? "none" : cameras->on() ? "running" : "paused";
  }

  WizardSource* robot() { return robot_.get(); }
  SessionLog& log() { return log_; }
  ExperimentManager& experiment() { return experiment_; }
  bool finalised() const { return finalised_; }
  /// The camera the page asked for since the last call ("off" to stop; nullopt: no change).
  std::optional<std::string> take_camera_request() {
    std::lock_guard lock(mutex_);
    auto out = std::move(camera_request_);
    camera_request_.reset();
    return out;
  }

  /// Keeps the latest 3-D camera image (JPEG) for `GET /api/camera.jpg`; returns its version.
  std::uint64_t set_camera(std::string jpeg) {
    std::lock_guard lock(mutex_);
    camera_ = std::move(jpeg);
    return ++camera_version_;
  }

  /// Takes the screenshot requests made since the last call (sim thread).
  int take_screenshot_requests() { return screenshots_requested_.exchange(0); }

  // The full state a new client starts from.
  std::string greeting() const {
    std::lock_guard lock(mutex_);
    return latest_full_.empty() ? std::string(kStartingFrame) : latest_full_;
  }

  void publish(nlohmann::json frame, const std::string& stage, double t, double freeplay_t) {
    auto full = frame;
    full["events"] = nlohmann::json::array();
    std::lock_guard lock(mutex_);
    if (!frame.contains("zones")) full["zones"] = zones_;
    latest_full_ = full.dump();
    stage_ = stage;
    t_ = t;
    freeplay_t_ = freeplay_t;
  }

  // Keeps the new background (JPEG) and zones for the API.
  void set_background(const sim::Sandtray& tray, nlohmann::json zones) {
    std::vector<uchar> jpeg;
    cv::imencode(".jpg", tray.background(), jpeg, {cv::IMWRITE_JPEG_QUALITY, kBackgroundJpegQuality});
    std::lock_guard lock(mutex_);
    background_ = std::string(jpeg.begin(), jpeg.end());
    zones_ = std::move(zones);
  }

  HttpReply api(const HttpRequest& r) {
    if (r.path == "/api/command") {
      if (r.method != "POST") return error_reply(405, "/api/command takes POST with a JSON body (docs/web.md)");
      try {
        return command(parse_command(r.body, item_names_));
      } catch (const CommandError& e) {
        return error_reply(e.status(), e.what());
      }
    }
    if (r.method != "GET") return error_reply(405, fmt::format("{} takes GET", r.path));
    if (r.path == "/api/scene") return {200, "application/json", scene_};
    if (r.path == "/api/state") return {200, "application/json", greeting()};
    if (r.path == "/api/events") return json_reply(200, events_json(log_.all()));
    if (const auto it = item_pictures_.find(r.path); it != item_pictures_.end()) return {200, "image/png", it->second};
    if (r.path == "/api/camera.jpg") {
      std::lock_guard lock(mutex_);
      if (camera_.empty()) return error_reply(404, "no camera image yet (send {\"type\":\"camera\",\"name\":…})");
      return {200, "image/jpeg", camera_};
    }
    if (r.path == "/api/background.jpg") {
      std::lock_guard lock(mutex_);
      if (background_.empty()) return error_reply(404, "no background published yet");
      return {200, "image/jpeg", background_};
    }
    return error_reply(404, fmt::format("no such endpoint: {} (allowed: /api/scene, /api/state, /api/events, "
                                        "/api/background.jpg, /api/item/<item>.png, /api/camera.jpg, /api/command)", r.path));
  }

 private:
  HttpReply command(const Command& c) {
    std::string stage;
    double t = 0.0;
    double freeplay_t = 0.0;
    {
      std::lock_guard lock(mutex_);
      stage = stage_;
      t = t_;
      freeplay_t = freeplay_t_;
    }
    switch (c.target) {
      case CommandTarget::Experiment:
        experiment_.apply(c, freeplay_t, t);
        if (c.type == "finalise") finalised_ = true;
        if (c.type == "marker" && c.args["kind"] == "screenshot") ++screenshots_requested_;
        return json_reply(200, {{"ok", true}, {"type", c.type}, {"experiment", experiment_.state()}});
      case CommandTarget::Protocol: {  // to the served episode: a stage signal moves its protocol on
        const auto name = c.args["name"].get<std::string>();
        const auto topic = "sandtray/signals/" + name;
        log_.add({t, "experimenter", "signal", {{"name", name}, {"topic", topic}}});
        signals_.push(*sim::signal_from_name(name));
        return json_reply(202, {{"ok", true}, {"type", c.type}, {"topic", topic}});
      }
      case CommandTarget::Component: return component(c, t);
      case CommandTarget::View: {
        std::lock_guard lock(mutex_);
        camera_request_ = c.args["name"].get<std::string>();
        return json_reply(202, {{"ok", true}, {"type", c.type}});
      }
      case CommandTarget::Robot: break;
    }
    if (!robot_) return error_reply(409, fmt::format("'{}': a child-child session has no robot", c.type));
    const bool setting = c.type == "mode" || c.type == "sparc_timeout";
    if (!setting && stage != "freeplay") {
      return error_reply(409, fmt::format("'{}': the robot acts in free play only (the stage is '{}'; the game hides "
                                          "the sandbox and ignores /poses outside it)", c.type, stage));
    }
    robot_->push(c);
    return json_reply(202, {{"ok", true}, {"type", c.type}});
  }

  // Starts or stops one component (`component` command); logged as `experimenter`/`component`.
  HttpReply component(const Command& c, double t) {
    const auto name = c.args["name"].get<std::string>();
    const bool start = c.args["action"] == "start";
    if (name == "robot" && !robot_) return error_reply(409, "'component': a child-child session has no robot side");
    if (name == "cameras" && cameras_ == nullptr) {
      return error_reply(409, "'component': the scenario lists no cameras (cameras: in the scenario, docs/scenarios.md)");
    }
    log_.add({t, "experimenter", "component", c.args});
    if (name == "robot") robot_->push(c);
    if (name == "recorder") recorder_->request(start);
    if (name == "cameras") cameras_.load()->request(start);
    return json_reply(202, {{"ok", true}, {"type", c.type}});
  }

  SessionLog log_;
  ExperimentManager experiment_;
  std::string scene_;
  WebSignals signals_;
  std::unique_ptr<RecorderSwitch> recorder_;
  std::atomic<runner::ObserverSwitch*> cameras_{nullptr};
  std::vector<std::string> camera_names_;
  std::vector<std::string> item_names_;
  std::map<std::string, std::string> item_pictures_;  // API path → PNG
  std::unique_ptr<WizardSource> robot_;
  std::atomic<bool> finalised_{false};
  std::atomic<int> screenshots_requested_{0};
  mutable std::mutex mutex_;
  std::string latest_full_;
  std::string background_;
  std::optional<std::string> camera_request_;
  std::string camera_;
  std::uint64_t camera_version_ = 0;
  nlohmann::json zones_ = nlohmann::json::array();
  std::string stage_ = "starting";
  double t_ = 0.0;
  double freeplay_t_ = -1e9;
};

/// The 3-D camera view the page asked for: each rendered frame becomes the session's JPEG.
class CameraSink final : public runner::FrameSink {
 public:
  explicit CameraSink(Session& session) : session_(session) {}
  void write(const stage::FramePack& frame) override {
    cv::Mat bgr;
    cv::cvtColor(frame.rgb, bgr, cv::COLOR_RGB2BGR);
    std::vector<uchar> jpeg;
    cv::imencode(".jpg", bgr, jpeg, {cv::IMWRITE_JPEG_QUALITY, kBackgroundJpegQuality});
    version_ = session_.set_camera(std::string(jpeg.begin(), jpeg.end()));
    stamp_ = frame.stamp;
  }
  /// The latest image's version and stamp.
  std::pair<std::uint64_t, double> latest() const { return {version_, stamp_}; }

 private:
  Session& session_;
  std::uint64_t version_ = 0;
  double stamp_ = 0.0;
};

/// The scenario's cameras on their Foxglove channels: every rendered colour frame as a JPEG CompressedImage in the
/// camera's optical frame, while a Foxglove client is connected (the server's per-client queue cap applies).
class FoxgloveCameras final : public runner::FrameSink {
 public:
  FoxgloveCameras(WebServer& server, const scenario::Scenario& scenario) : server_(server), quality_(scenario.recording.jpeg_quality) {
    for (std::size_t i = 0; i < scenario.cameras.size(); ++i) {
      channels_[scenario.cameras[i].name] = {kFoxgloveFirstCamera + static_cast<int>(i),
                                             recording::camera_topics(scenario.cameras[i].name).rgb_frame};
    }
  }
  void write(const stage::FramePack& frame) override {
    const auto it = channels_.find(frame.camera);
    if (frame.rgb.empty() || it == channels_.end() || server_.foxglove_clients() == 0) return;
    const auto stamp_ns = static_cast<std::uint64_t>(unix_ms() * 1e6);
    server_.publish_foxglove({foxglove_camera(it->second.first, it->second.second,
                                              recording::encode_jpeg(frame.rgb, quality_), stamp_ns)});
  }

 private:
  WebServer& server_;
  int quality_;
  std::map<std::string, std::pair<int, std::string>> channels_;  // camera → (channel id, optical frame)
};

/// Turns every tick into a state frame for the page (the live episode paces the ticks).
class WebObserver final : public runner::EpisodeObserver {
 public:
  WebObserver(Session& session, WebServer& server, const runner::EpisodeInfo& info, std::filesystem::path out,
              std::size_t& ticks)
      : session_(session), server_(server), info_(info), out_(std::move(out)), ticks_(ticks), camera_sink_(session) {}

  void observe(const runner::EpisodeSnapshot& s) override {
    const double tick_ms = unix_ms();
    for (const auto& e : s.new_events) session_.log().add(e);
    if (auto* robot = session_.robot()) robot->clock(s.tray->time());
    if (s.stage == "freeplay" && !freeplay_seen_) {
      freeplay_seen_ = true;
      session_.experiment().freeplay_started(static_cast<std::uint64_t>(tick_ms * 1e6));
    }
    auto frame = tick_json(s);
    if (s.tray->background_version() != background_version_) {
      background_version_ = s.tray->background_version();
      auto zones = zones_json(*s.tray);
      frame["zones"] = zones;
      session_.set_background(*s.tray, std::move(zones));
    }
    if (!foxglove_topics_) {  // the session's time base: sandtray time 0 is this tick's wall-clock time minus t
      const auto origin_ns = static_cast<std::uint64_t>(tick_ms * 1e6) - static_cast<std::uint64_t>(std::llround(s.t * 1e9));
      foxglove_topics_ = std::make_unique<FoxgloveTopics>(info_.seed, origin_ns, info_.scenario->robot.arm_reach_m);
    }
    std::vector<FoxgloveMessage> foxglove;
    for (auto& m : foxglove_topics_->tick(s)) {  // the bag's and the live graph's messages (recording::TickTopics)
      if (m.latched) server_.latch_foxglove(m);
      if (server_.foxglove_clients() > 0) foxglove.push_back(std::move(m));
    }
    if (!foxglove.empty()) server_.publish_foxglove(std::move(foxglove));
    camera(s, frame);
    send(std::move(frame), std::string(s.stage), s.t, s.freeplay_t, tick_ms);
    // After the tick's frame went out, so that the screen render does not delay the page.
    if (session_.take_screenshot_requests() > 0) screenshot(*s.tray, s.t);
  }

  // A frame without a tick (after the episode): the experiment and the events still reach the page.
  void idle_frame(double t) {
    send({{"type", "state"}, {"stage", "ended"}, {"t", t}}, "ended", t, -1.0, unix_ms());
  }

 private:
  void send(nlohmann::json frame, const std::string& stage, double t, double freeplay_t, double tick_ms) {
    frame["seq"] = ++seq_;
    frame["tick_unix_ms"] = tick_ms;
    frame["robot_control"] = session_.robot() != nullptr ? session_.robot()->state() : nlohmann::json();
    frame["experiment"] = session_.experiment().state();
    frame["components"] = session_.components(stage);
    nlohmann::json events = nlohmann::json::array();
    for (const auto& e : session_.log().take_new()) events.push_back(e.to_json());
    frame["events"] = std::move(events);
    auto text = std::make_shared<const std::string>(frame.dump());
    session_.publish(std::move(frame), stage, t, freeplay_t);
    server_.broadcast(std::move(text));
    ++ticks_;
  }

  // The screenshot marker, as the supervisor's `sandtray/screenshot`: the game's screen as a PNG in the session
  // folder, named as the PInSoRo sessions' screenshots (freeplay-<n>-<date>_<time>.png).
  void screenshot(const sim::Sandtray& tray, double t) {
    const auto name = fmt::format("freeplay-{}-{:%Y-%m-%d_%H-%M-%S}.png", ++screenshots_, fmt::gmtime(std::time(nullptr)));
    // The PNG is encoded and written beside the simulation; a pending write is waited for when the session ends.
    pending_writes_.push_back(std::async(std::launch::async, [path = out_ / name, screen = tray.render_screen()] {
      std::vector<std::uint8_t> png;
      cv::imencode(".png", screen, png);
      auto partial = path;
      partial += ".part";
      std::ofstream(partial, std::ios::binary).write(reinterpret_cast<const char*>(png.data()),
                                                     static_cast<std::streamsize>(png.size()));
      std::filesystem::rename(partial, path);  // never seen half-written
    }));
    session_.log().add({t, "experiment", "screenshot_saved", {{"file", name}}});
  }

  // The 3-D view on request: one stage camera at 1 Hz, 480 × 270, rendered on this thread while the page wants it.
  void camera(const runner::EpisodeSnapshot& s, nlohmann::json& frame) {
    if (auto request = session_.take_camera_request()) {
      rig_.reset();
      camera_name_.clear();
      if (*request != "off") {
        camera_scenario_ = *info_.scenario;
        camera_scenario_.cameras = {{*request, kCameraRateHz, kCameraWidthPx, kCameraHeightPx, false, false}};
        try {
          rig_ = std::make_unique<runner::CameraRig>(camera_scenario_, runner::renderer_options(camera_scenario_.rendering),
                                                     std::vector<runner::FrameSink*>{&camera_sink_});
          rig_->begin(info_);
          camera_name_ = *request;
        } catch (const std::exception& e) {
          session_.log().add({s.t, "web", "camera_failed", {{"camera", *request}, {"error", e.what()}}});
        }
      }
      session_.log().add({s.t, "web", "camera", {{"camera", *request}}});
    }
    if (rig_) {
      try {
        rig_->observe(s);
      } catch (const std::exception& e) {
        session_.log().add({s.t, "web", "camera_failed", {{"camera", camera_name_}, {"error", e.what()}}});
        rig_.reset();
        camera_name_.clear();
      }
    }
    const auto [version, stamp] = camera_sink_.latest();
    frame["camera"] = camera_name_.empty() ? nlohmann::json() : nlohmann::json{{"name", camera_name_}, {"version", version}, {"stamp", stamp}};
  }

  Session& session_;
  WebServer& server_;
  runner::EpisodeInfo info_;
  std::filesystem::path out_;
  std::size_t& ticks_;
  int screenshots_ = 0;
  std::vector<std::future<void>> pending_writes_;  // screenshots being written (their futures wait when destroyed)
  CameraSink camera_sink_;
  scenario::Scenario camera_scenario_;
  std::unique_ptr<runner::CameraRig> rig_;
  std::unique_ptr<FoxgloveTopics> foxglove_topics_;  // made at the first tick
  std::string camera_name_;
  std::uint64_t background_version_ = ~std::uint64_t{0};
  bool freeplay_seen_ = false;
  std::uint64_t seq_ = 0;
};

}  // namespace

WebSessionReport serve_web(const scenario::Scenario& scenario, std::uint64_t seed, const WebSessionOptions& options,
                           const std::atomic<bool>& stop) {
  // The server binds first, so a bad address or a port in use leaves no session folder behind; it is declared after
  // the session and the live episode (whose camera switch the API turns) so that it stops (joining its thread)
  // before they go.
  std::optional<Session> session;
  runner::LiveEpisode live(options.rate, stop);
  std::atomic<Session*> ready{nullptr};
  auto server_options = options.server;
  std::vector<std::string> cameras;
  for (const auto& c : scenario.cameras) cameras.push_back(c.name);
  server_options.foxglove = foxglove_channels(cameras, scenario.condition == scenario::Condition::ChildRobot);
  WebServer server(
      server_options,
      [&ready](const HttpRequest& r) {
        auto* s = ready.load();
        return s != nullptr ? s->api(r) : error_reply(503, "the session is starting");
      },
      [&ready] {
        auto* s = ready.load();
        return s != nullptr ? s->greeting() : std::string(kStartingFrame);
      });
  std::filesystem::create_directories(options.out);
  ready = &session.emplace(scenario, options);
  if (options.on_listening) options.on_listening(server.url());
  if (options.on_commands) {
    options.on_commands([&session](const std::string& body) { return session->api({"POST", "/api/command", {}, body}); });
  }
  struct Detach {  // the other sources lose the session before it goes, however serve_web leaves
    const WebSessionOptions& options;
    ~Detach() {
      if (options.on_commands) options.on_commands({});
    }
  } detach{options};
  WebSessionReport report;
  const runner::EpisodeInputs inputs{.scenario = scenario, .seed = seed, .id = "web", .decisions = session->robot(),
                                     .signals = &session->signals()};
  WebObserver observer(*session, server, inputs.info(), options.out, report.ticks);
  // The page first (it adds the tick's events to the session log), then the bag, then the other fronts.
  live.attach(observer);
  live.attach(session->recorder());
  if (options.also_observe != nullptr) live.attach(*options.also_observe);
  FoxgloveCameras foxglove_cameras(server, scenario);
  std::unique_ptr<runner::CameraRig> rig;
  if (!scenario.cameras.empty()) {  // the scenario's cameras, at their rates: into the bag and to Foxglove
    std::vector<runner::FrameSink*> sinks{&session->recorder(), &foxglove_cameras};
    if (options.also_frames != nullptr) sinks.push_back(options.also_frames);
    rig = std::make_unique<runner::CameraRig>(scenario, runner::renderer_options(scenario.rendering), std::move(sinks));
    session->set_cameras(live.attach(*rig, true, [&session](double t, bool on) { session->cameras_switched(t, on); }));
  }
  report.result = live.run(inputs);
  if (!report.result.aborted) {
    std::ofstream(options.out / "episode.json") << report.result.record.dump(2) << '\n';
    while (options.linger && !session->finalised() && !stop.load()) {
      observer.idle_frame(report.result.simulated_s);
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    observer.idle_frame(report.result.simulated_s);
  }
  report.server = server.stats();
  report.timing = live.timing();
  return report;
}

}  // namespace freeplay::web
