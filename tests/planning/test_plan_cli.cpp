// `freeplay plan` end to end: metrics, JSON, execution, picture, exit statuses 0 / 1 (no path) / 2 (bad input).

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace {

struct CliRun {
  int status = -1;
  std::string output;  // stdout and stderr together
};

CliRun freeplay(const std::string& arguments) {
  CliRun run;
  const std::string command = std::string(FREEPLAY_CLI) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return run;
}

nlohmann::json json_of(const CliRun& run) {
  const auto start = run.output.find('{');
  return nlohmann::json::parse(run.output.substr(start == std::string::npos ? 0 : start));
}

TEST(PlanCli, PrintsTheMetricsOfAPath) {
  const CliRun run = freeplay("plan --item hippo --to 0.30,-0.25 --layout 1");
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* row : {"path found", "planning time", "path length", "min clearance", "finger poses",
                          "expected execution"}) {
    EXPECT_NE(run.output.find(row), std::string::npos) << row << "\n" << run.output;
  }
}

TEST(PlanCli, JsonAndExecutionInThePhysics) {
  const CliRun run = freeplay("plan --item hippo --to 0.30,-0.25 --planner rrtconnect --items 6 --execute --json");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto report = json_of(run);
  EXPECT_TRUE(report["ok"].get<bool>());
  EXPECT_EQ(report["reason"], "none");
  EXPECT_EQ(report["items_on_map"], 6);
  EXPECT_GT(report["poses"].get<int>(), 10);
  EXPECT_GT(report["path_length_m"].get<double>(), 0.1);
  ASSERT_TRUE(report.contains("executed"));
  EXPECT_EQ(report["executed"]["status"], "succeeded");
  EXPECT_LT(report["executed"]["placement_error_m"].get<double>(), 0.01);
  EXPECT_NEAR(report["executed"]["release_s"].get<double>(), report["expected_execution_s"].get<double>() + 1.0,
              0.11);
}

TEST(PlanCli, SameLayoutSeedSameResult) {
  const auto a = json_of(freeplay("plan --item lion --to 0.25,-0.20 --layout 4 --json"));
  const auto b = json_of(freeplay("plan --item lion --to 0.25,-0.20 --layout 4 --json"));
  EXPECT_EQ(a["start"], b["start"]);
  EXPECT_EQ(a["poses"], b["poses"]);
  EXPECT_EQ(a["path_length_m"], b["path_length_m"]);
  const auto c = json_of(freeplay("plan --item lion --to 0.25,-0.20 --layout 5 --json"));
  EXPECT_NE(a["start"], c["start"]);
}

TEST(PlanCli, WritesThePicture) {
  const auto path = std::filesystem::temp_directory_path() / "freeplay_test_plan_cli.png";
  std::filesystem::remove(path);
  const CliRun run = freeplay("plan --item zebra --to-px 900,500 --width 480 --out " + path.string());
  ASSERT_EQ(run.status, 0) << run.output;
  ASSERT_TRUE(std::filesystem::exists(path));
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> magic{};
  in.read(magic.data(), magic.size());
  EXPECT_EQ(std::string(magic.data() + 1, 3), "PNG");
  std::filesystem::remove(path);
}

TEST(PlanCli, NoPathExitsWith1AndTheReason) {
  const CliRun run = freeplay("plan --item hippo --to 0.70,-0.10");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("goal_off_screen"), std::string::npos) << run.output;
}

TEST(PlanCli, BadInputExitsWith2AndTheAllowedValues) {
  const CliRun unknown = freeplay("plan --item unicorn --to 0.3,-0.1");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.output.find("zebra, elephant"), std::string::npos) << unknown.output;
  const CliRun nan = freeplay("plan --item hippo --to nan,-0.1");
  EXPECT_EQ(nan.status, 2);
  EXPECT_NE(nan.output.find("--to"), std::string::npos) << nan.output;
  const CliRun planner = freeplay("plan --item hippo --to 0.3,-0.1 --planner dijkstra");
  EXPECT_EQ(planner.status, 2);
  EXPECT_NE(planner.output.find("rrtconnect"), std::string::npos) << planner.output;
  EXPECT_EQ(freeplay("plan --item hippo").status, 2);                                  // no target
  EXPECT_EQ(freeplay("plan --item hippo --to 0.3,-0.1 --to-px 5,5").status, 2);        // two targets
  EXPECT_EQ(freeplay("plan --item hippo --to 0.3,-0.1 --items 11").status, 2);
  EXPECT_EQ(freeplay("plan --item hippo --to 0.3,-0.1 --out plan.jpg").status, 2);
}

}  // namespace
