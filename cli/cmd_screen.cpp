// `freeplay screen`: renders the free-play screen of a fresh sandtray, or of a scenario's episode at a moment, to a
// PNG (optionally with its zones).

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string_view>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "command_registry.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/sim/background.hpp"
#include "freeplay/sim/item_catalogue.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen_renderer.hpp"
#include "freeplay/sim/zones.hpp"
#include "scenario_moment.hpp"

namespace freeplay::cli {
namespace {

struct ScreenOptions {
  std::string out;
  bool zones = false;
  bool shuffle = false;
  int width = sim::kScreenWidthPx;
  std::optional<std::uint64_t> seed;
  MomentOptions moment;
};

constexpr int kMinWidthPx = 16;
constexpr int kMaxWidthPx = 16384;
constexpr double kSettleTimeS = 0.5;  // long enough for the background to be published and segmented

void check_output_path(const std::filesystem::path& out) {
  if (out.extension() != ".png" && out.extension() != ".PNG") {
    throw InputError("the output file '" + out.string() + "' is not a .png file", "--out", "a path ending in .png");
  }
  const std::filesystem::path folder = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    throw InputError("the folder '" + folder.string() + "' does not exist", "--out", "a path in an existing folder");
  }
}

void run_screen(const ScreenOptions& options) {
  if (options.width < kMinWidthPx || options.width > kMaxWidthPx) {
    throw InputError(fmt::format("width {} px is out of range", options.width), "--width",
                     fmt::format("{}…{}", kMinWidthPx, kMaxWidthPx));
  }
  const std::filesystem::path out(options.out);
  check_output_path(out);

  cv::Mat screen;
  sim::ZoneMap zones;
  std::string what;
  if (!options.moment.scenario.empty()) {
    if (options.shuffle) throw InputError("--shuffle acts on a fresh tray", "--shuffle", "leave it out with --scenario");
    what = capture_moment(options.moment, options.seed, [&](const scenario::Scenario&, const runner::EpisodeSnapshot& s) {
      screen = s.tray->render_screen(options.width);
      zones = s.tray->zones();
    });
  } else {
    if (options.moment.time || !options.moment.overrides.empty()) {
      throw InputError("--time and --set need a scenario", options.moment.time ? "--time" : "--set", "--scenario FILE");
    }
    auto catalogue = std::make_shared<const sim::ItemCatalogue>(sim::ItemCatalogue::load_default());
    const SeedSequence seeds(options.seed.value_or(1));
    sim::Sandtray sandtray(catalogue, sim::SandtrayConfig{}, seeds.stream("sandtray"));
    sandtray.signal(sim::Signal::StartFreeplay);
    if (options.shuffle) sandtray.signal(sim::Signal::ShuffleItems);
    sandtray.step(kSettleTimeS);
    screen = sandtray.render_screen(options.width);
    zones = sandtray.zones();
    what = fmt::format("free-play map, seed {}{}", options.seed.value_or(1),
                       options.shuffle ? ", items shuffled" : ", items in the stash");
  }
  if (options.zones) sim::draw_zones(screen, zones, true);

  std::vector<unsigned char> png;
  if (!cv::imencode(".png", screen, png)) throw std::runtime_error("PNG encoding failed");
  write_file_atomically(out, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));

  std::string counts;
  for (const auto colour : sim::kZoneColours) {
    counts += fmt::format("{}{} {}", counts.empty() ? "" : ", ", zones.count(colour), colour);
  }
  std::cout << fmt::format("wrote {} ({}×{} px, {}{})\nzones: {}\n", out.string(), screen.cols, screen.rows, what,
                           options.zones ? ", zones outlined" : "", counts);
}

const RegisterCommand kScreenCommand(50, [](CLI::App& program) {
  auto options = std::make_shared<ScreenOptions>();
  auto* command = program.add_subcommand("screen", "Render the free-play screen of a fresh sandtray (or of a scenario's episode at --time) to a PNG");
  command->add_option("--out", options->out, "Output PNG file (written atomically)")->required();
  command->add_flag("--zones", options->zones, "Outline and label the colour zones the robot sees");
  command->add_option("--width", options->width, "Image width in pixels (height follows 0.6 × 0.335 m)")
      ->capture_default_str();
  command->add_option("--seed", options->seed,
                      "Seed of the sandtray (initial item poses in the stash; default 1); with --scenario: the "
                      "episode's seed (default: the scenario's episode 0)");
  command->add_flag("--shuffle", options->shuffle, "Spread the items over the map (the game's shuffle_items)");
  add_moment_options(*command, options->moment);
  command->callback([options] { run_screen(*options); });
});

}  // namespace
}  // namespace freeplay::cli
