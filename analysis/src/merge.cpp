#include "freeplay/analysis/merge.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <functional>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/results/run_folder.hpp"
#include "freeplay/results/summary.hpp"

namespace freeplay::analysis {

using results::ExpectedRun;
using results::kRunManifestFile;

namespace {

namespace fs = std::filesystem;

/// Files of the run folder itself (the merge rewrites them); everything else is a per-episode file to copy.
const std::set<std::string> kRunLevelFiles = {"episodes.jsonl", "summary.csv", "summary.md", kRunManifestFile};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Up to `limit` items, then "… and N more".
std::string listing(const std::vector<std::string>& items, std::size_t limit = 10) {
  std::vector<std::string> shown(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(std::min(limit, items.size())));
  auto text = fmt::format("{}", fmt::join(shown, ", "));
  if (items.size() > limit) text += fmt::format(" … and {} more", items.size() - limit);
  return text;
}

struct Input {
  fs::path dir;
  std::optional<nlohmann::json> manifest;
};

/// Up to 10 examples of a kind of problem and how many there were (memory does not grow with bad input).
struct Examples {
  std::vector<std::string> shown;
  std::size_t count = 0;
  void add(std::string item) {
    if (shown.size() < 10) shown.push_back(std::move(item));
    ++count;
  }
  std::string text() const {
    auto out = fmt::format("{}", fmt::join(shown, ", "));
    if (count > shown.size()) out += fmt::format(" … and {} more", count - shown.size());
    return out;
  }
};

bool same_bytes(const fs::path& a, const fs::path& b) {
  if (fs::file_size(a) != fs::file_size(b)) return false;
  std::ifstream x(a, std::ios::binary);
  std::ifstream y(b, std::ios::binary);
  std::array<char, 65536> bx{};
  std::array<char, 65536> by{};
  while (x && y) {
    x.read(bx.data(), bx.size());
    y.read(by.data(), by.size());
    if (x.gcount() != y.gcount() || !std::equal(bx.begin(), bx.begin() + x.gcount(), by.begin())) return false;
  }
  return true;
}

ExpectedRun expected_from_manifest(const nlohmann::json& manifest, const fs::path& file) {
  ExpectedRun expected;
  expected.title = manifest.value("title", manifest.value("suite", std::string{}));
  const auto variants = manifest.find("variants");
  if (variants == manifest.end() || !variants->is_array()) {
    throw InputError("run.json lists no variants", "variants", "[{\"id\": …, \"episodes\": …}, …]",
                     {file.string(), 0, 0});
  }
  for (const auto& v : *variants) {
    if (!v.is_object() || !v.contains("id") || !v["id"].is_string() || !v.contains("episodes") ||
        !v["episodes"].is_number_integer()) {
      throw InputError(fmt::format("bad variant entry {}", v.dump()), "variants", "{\"id\": STRING, \"episodes\": N}",
                       {file.string(), 0, 0});
    }
    expected.variants.push_back({v["id"].get<std::string>(), v["episodes"].get<int>(), std::nullopt});
  }
  return expected;
}

std::optional<std::pair<int, int>> shard_of(const nlohmann::json& manifest) {
  const auto shard = manifest.find("shard");
  if (shard == manifest.end() || !shard->is_array() || shard->size() != 2) return std::nullopt;
  if (!(*shard)[0].is_number_integer() || !(*shard)[1].is_number_integer()) return std::nullopt;
  return std::make_pair((*shard)[0].get<int>(), (*shard)[1].get<int>());
}

}  // namespace

MergeReport merge_runs(const std::vector<fs::path>& inputs, const fs::path& out,
                       const std::optional<ExpectedRun>& expected_override) {
  if (inputs.empty()) throw InputError("no run folder to merge", "DIR", "one or more shard run folders");
  // Read every input first: nothing is written until everything checks out.
  std::vector<Input> runs;
  for (const auto& dir : inputs) {
    if (!fs::is_regular_file(dir / "episodes.jsonl")) {
      throw InputError(fmt::format("'{}' is not a run folder (it has no episodes.jsonl)", dir.string()), "DIR",
                       "folders written by `freeplay suite --shard I/N`");
    }
    Input input;
    input.dir = dir;
    if (fs::is_regular_file(dir / kRunManifestFile)) {
      try {
        input.manifest = nlohmann::json::parse(read_text(dir / kRunManifestFile));
      } catch (const nlohmann::json::exception& e) {
        throw InputError(fmt::format("run.json is not valid JSON: {}", e.what()), kRunManifestFile, {},
                         {(dir / kRunManifestFile).string(), 0, 0});
      }
    }
    runs.push_back(std::move(input));
  }
  std::error_code ec;
  if (fs::exists(out) && !(fs::is_directory(out) && fs::is_empty(out))) {
    throw InputError(fmt::format("'{}' already exists and is not empty", out.string()), "--out",
                     "a new folder (merge never overwrites)");
  }
  for (const auto& r : runs) {
    if (fs::exists(out) && fs::equivalent(r.dir, out, ec)) {
      throw InputError("the output folder is one of the inputs", "--out", "a new folder");
    }
  }

  ValidationErrors problems;
  auto problem = [&problems](std::string text, std::string key, std::string allowed = {}) {
    problems.add(InputError(std::move(text), std::move(key), std::move(allowed)));
  };

  // The manifests: all or none, same suite and overrides, distinct shards of one split.
  const auto with_manifest = std::count_if(runs.begin(), runs.end(), [](const Input& r) { return r.manifest.has_value(); });
  if (with_manifest != 0 && with_manifest != static_cast<std::ptrdiff_t>(runs.size())) {
    std::vector<std::string> lacking;
    for (const auto& r : runs) {
      if (!r.manifest) lacking.push_back(r.dir.string());
    }
    problem(fmt::format("some run folders have no run.json: {}", listing(lacking)), "DIR",
            "shard folders of one `freeplay suite` invocation");
  }
  std::map<int, std::string> shard_dirs;
  std::optional<int> shard_count;
  bool zero_based = false;
  if (with_manifest == static_cast<std::ptrdiff_t>(runs.size())) {
    const auto& first = *runs.front().manifest;
    for (const auto& r : runs) {
      for (const char* key : {"suite", "overrides", "variants"}) {
        const auto a = first.value(key, nlohmann::json());
        const auto b = r.manifest->value(key, nlohmann::json());
        if (a != b) {
          problem(fmt::format("'{}' and '{}' ran different {}: {} vs {}", runs.front().dir.string(), r.dir.string(),
                              key, a.dump(), b.dump()),
                  fmt::format("run.json {}", key), "shards of the same suite with the same --set overrides");
        }
      }
      const auto shard = shard_of(*r.manifest);
      if (!shard) continue;
      zero_based = zero_based || shard->first == 0;
      if (shard_count && *shard_count != shard->second) {
        problem(fmt::format("'{}' is a shard of {} parts, another input of {}", r.dir.string(), shard->second,
                            *shard_count),
                "run.json shard", "shards of one split (the same N in --shard I/N)");
      }
      shard_count = shard->second;
      const auto [it, inserted] = shard_dirs.emplace(shard->first, r.dir.string());
      if (!inserted) {
        problem(fmt::format("shard {}/{} is given twice: '{}' and '{}'", shard->first, shard->second, it->second,
                            r.dir.string()),
                "DIR", "each shard once");
      }
    }
  }
  problems.throw_if_any();

  ExpectedRun expected;
  if (expected_override) {
    expected = *expected_override;
    if (with_manifest > 0) {
      const auto from_manifest = expected_from_manifest(*runs.front().manifest, runs.front().dir / kRunManifestFile);
      std::vector<std::pair<std::string, int>> a;
      std::vector<std::pair<std::string, int>> b;
      for (const auto& v : expected.variants) a.emplace_back(v.id, v.episodes);
      for (const auto& v : from_manifest.variants) b.emplace_back(v.id, v.episodes);
      if (a != b) {
        throw InputError("the run folders were made from a different suite than --suite (other variants or episode "
                         "counts)",
                         "--suite", "the suite file (and --set overrides) the shards ran");
      }
    }
  } else if (with_manifest > 0) {
    expected = expected_from_manifest(*runs.front().manifest, runs.front().dir / kRunManifestFile);
  } else {
    throw InputError(fmt::format("cannot tell which episodes to expect: '{}' has no run.json",
                                 runs.front().dir.string()),
                     "--suite", "the suite file the shards ran (with the same --set overrides)");
  }

  // Every record, streamed from disk: known variant and index, once, one configuration per variant. Memory: the
  // input that holds each expected episode (2 bytes per episode), never the records.
  std::map<std::string, std::size_t> variant_rank;
  for (std::size_t i = 0; i < expected.variants.size(); ++i) variant_rank[expected.variants[i].id] = i;
  std::vector<std::vector<std::uint16_t>> seen_in(expected.variants.size());  // input + 1, 0 = not seen
  for (std::size_t i = 0; i < expected.variants.size(); ++i) {
    seen_in[i].assign(static_cast<std::size_t>(std::max(0, expected.variants[i].episodes)), 0);
  }
  if (runs.size() >= 0xFFFF) throw InputError("too many run folders to merge at once", "DIR", "fewer than 65 535");
  std::map<std::string, std::pair<std::uint64_t, std::string>> hash_of_variant;
  std::set<std::string> versions;
  Examples duplicates;
  Examples unknown;
  Examples mismatched;
  int episodes = 0;
  for (std::size_t input = 0; input < runs.size(); ++input) {
    const auto& r = runs[input];
    results::RunFolder(r.dir).for_each_record([&](const nlohmann::json& record) {
      const auto variant = record.value("variant", std::string{});
      const int index = record.value("episode", -1);
      const auto name = fmt::format("{} #{}", variant, index);
      const auto rank = variant_rank.find(variant);
      if (rank == variant_rank.end() || index < 0 || index >= expected.variants[rank->second].episodes) {
        unknown.add(fmt::format("{} (in '{}')", name, r.dir.string()));
        return;
      }
      auto& seen = seen_in[rank->second][static_cast<std::size_t>(index)];
      if (seen != 0) {
        duplicates.add(fmt::format("{} (in '{}' and '{}')", name, runs[seen - 1U].dir.string(), r.dir.string()));
        return;
      }
      seen = static_cast<std::uint16_t>(input + 1);
      ++episodes;
      const auto hash = record.value("config_hash", std::uint64_t{0});
      const auto& wanted = expected.variants[rank->second].config_hash;
      if (wanted && *wanted != hash) {
        mismatched.add(fmt::format("{} in '{}' ran configuration {:016x}, the suite's is {:016x}", name,
                                   r.dir.string(), hash, *wanted));
      }
      const auto [h, first_of_variant] = hash_of_variant.emplace(variant, std::make_pair(hash, r.dir.string()));
      if (!first_of_variant && h->second.first != hash) {
        mismatched.add(fmt::format("variant '{}' ran two configurations: {:016x} in '{}' and {:016x} in '{}'",
                                   variant, h->second.first, h->second.second, hash, r.dir.string()));
      }
      versions.insert(record.value("program_version", std::string{}));
    });
  }
  if (mismatched.count > 0) {
    problem(fmt::format("{} configuration mismatch(es): {}", mismatched.count, mismatched.text()), "config_hash",
            "shards run with the same suite, overrides and program");
  }
  if (duplicates.count > 0) {
    problem(fmt::format("{} episode(s) appear twice: {}", duplicates.count, duplicates.text()), "DIR",
            "disjoint shards (each --shard I/N once)");
  }
  if (unknown.count > 0) {
    problem(fmt::format("{} episode(s) are not part of the suite: {}", unknown.count, unknown.text()), "DIR",
            "shards of this suite");
  }
  Examples missing;
  for (std::size_t v = 0; v < expected.variants.size(); ++v) {
    for (std::size_t i = 0; i < seen_in[v].size(); ++i) {
      if (seen_in[v][i] == 0) missing.add(fmt::format("{} #{}", expected.variants[v].id, i));
    }
  }
  if (missing.count > 0) {
    problem(fmt::format("{} episode(s) are missing: {}", missing.count, missing.text()), "DIR",
            "every shard, each finished (resume an unfinished shard with the same command)");
  }
  problems.throw_if_any();

  // Write into a sibling folder, then move it into place: a failed merge leaves no half-written output.
  MergeReport report;
  report.out = out;
  report.inputs = static_cast<int>(runs.size());
  report.episodes = episodes;
  if (versions.size() > 1) {
    report.warnings.push_back(fmt::format("the shards ran different program versions: {}",
                                          fmt::join(versions, ", ")));
  }
  const auto staging = out.parent_path() / fmt::format(".{}.merging-{}", out.filename().string(), ::getpid());
  fs::remove_all(staging);
  fs::create_directories(staging);
  try {
    // Per-episode files: copied once, streamed (the staging folder is the index of what was copied); the same path
    // in two inputs must hold the same bytes.
    Examples differing;
    for (const auto& r : runs) {
      for (auto it = fs::recursive_directory_iterator(r.dir); it != fs::recursive_directory_iterator(); ++it) {
        if (!it->is_regular_file()) continue;
        const auto relative = fs::relative(it->path(), r.dir);
        if (relative.parent_path().empty() && kRunLevelFiles.count(relative.string())) continue;
        const auto target = staging / relative;
        if (fs::exists(target)) {
          if (!same_bytes(target, it->path())) {
            differing.add(fmt::format("'{}' (in '{}')", relative.string(), it->path().string()));
          }
          continue;
        }
        fs::create_directories(target.parent_path());
        fs::copy_file(it->path(), target);
        ++report.files;
      }
    }
    if (differing.count > 0) {
      problem(fmt::format("{} per-episode file(s) differ between inputs: {}", differing.count, differing.text()),
              "DIR", "disjoint shards");
      problems.throw_if_any();
    }
    write_file_atomically(staging / "episodes.jsonl", [&](const std::function<void(std::string_view)>& write) {
      for (const auto& r : runs) {
        results::RunFolder(r.dir).for_each_record([&](const nlohmann::json& record) { write(record.dump() + "\n"); });
      }
    });
    std::vector<std::string> order;
    for (const auto& v : expected.variants) order.push_back(v.id);
    results::RunFolder(staging).finalize(order);  // the same order and bytes as a single-machine run
    if (with_manifest > 0) {
      auto manifest = *runs.front().manifest;
      if (manifest.contains("shard")) manifest["shard"] = {zero_based ? 0 : 1, 1};
      nlohmann::json sources = nlohmann::json::array();
      for (const auto& r : runs) sources.push_back(r.dir.string());
      manifest["merged_from"] = sources;
      write_file_atomically(staging / kRunManifestFile, manifest.dump(2) + "\n");
    }
    results::write_summaries(staging, order, expected.title);
    if (fs::exists(out)) fs::remove(out);  // empty (checked above)
    fs::rename(staging, out);
  } catch (...) {
    fs::remove_all(staging, ec);
    throw;
  }
  return report;
}

}  // namespace freeplay::analysis
