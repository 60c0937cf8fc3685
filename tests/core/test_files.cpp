#include <gtest/gtest.h>

#include <filesystem>

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
