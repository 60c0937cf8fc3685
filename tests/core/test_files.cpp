#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/event_log.hpp"

using namespace freeplay;

TEST(AtomicFile, WritesWholeFileAndLeavesNoTemporary) {
  const auto dir = std::filesystem::temp_directory_path() / "freeplay_test_atomic";
  std::filesystem::remove_all(dir);
  write_file_atomically(dir / "out.txt", "hello\n");
  EXPECT_EQ(read_file(dir / "out.txt"), "hello\n");
  write_file_atomically(dir / "out.txt", "again\n");
  EXPECT_EQ(read_file(dir / "out.txt"), "again\n");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1);
  std::filesystem::remove_all(dir);
}

TEST(InputError, NamesFileLineColumnKeyAndAllowed) {
  const InputError e("unknown colour 'pink'", "brush", "yellow, blue", {"scene.yaml", 3, 7});
  EXPECT_STREQ(e.what(), "scene.yaml:3:7: 'brush': unknown colour 'pink' (allowed: yellow, blue)");
}

TEST(EventLog, HashChangesWithContent) {
  EventLog a;
  EventLog b;
  a.emit({1.0, "sandtray", "releasing_zebra", nullptr});
  b.emit({1.0, "sandtray", "releasing_zebra", nullptr});
  EXPECT_EQ(a.hash(), b.hash());
  b.emit({1.1, "sandtray", "x", {{"k", 1}}});
  EXPECT_NE(a.hash(), b.hash());
  EXPECT_EQ(b.to_jsonl().find("\"type\":\"x\"") != std::string::npos, true);
}

TEST(EventLog, IncrementalTextAndHashEqualTheEventsSerialisedAgain) {
  EventLog log;
  log.emit({0.5, "child.purple", "stroke_finished", {{"colour", "blue"}, {"points", {1, 2.5, -3e-7}}}});
  log.append({{1.25, "sandtray", "releasing_zebra", nullptr}, {2.0, "robot", "say", {{"text", "h\u00e9 \"x\"\n"}}}});
  // Sources and types that need escaping, times that are not plain numbers, data that is not an object.
  log.append({{std::nan(""), "child.\"odd\"\\", "t\u00e9\x01\x7f", {{"a", nlohmann::json::object()}}},
              {1e300, "", "x y", "plain text"},
              {-0.0, "robot", "say", {1, 2}},
              {std::numeric_limits<double>::infinity(), "robot", "say", 3}});
  std::string rebuilt;
  for (const auto& e : log.events()) rebuilt += e.to_json().dump() + '\n';
  EXPECT_EQ(log.to_jsonl(), rebuilt);
  EXPECT_EQ(log.hash(), fnv1a64(rebuilt));
  EXPECT_EQ(log.events()[0].data().at("colour"), "blue");  // the data survives its serialisation
  EXPECT_EQ(EventLog{}.hash(), fnv1a64(""));
}
