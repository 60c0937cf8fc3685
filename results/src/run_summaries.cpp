// The summaries a run folder gets (summary.csv, summary.md); apart from summary.cpp, which the bag reader's fuzz
// target compiles without the run folder.
#include "freeplay/results/run_folder.hpp"
#include "freeplay/results/summary.hpp"

namespace freeplay::results {

std::string write_summaries(const std::filesystem::path& dir, const std::vector<std::string>& variant_order,
                            const std::string& title, int threads) {
  RunFolder folder(dir);
  RunSummarizer summarizer(variant_order);
  folder.for_each_record([&](const nlohmann::json& record) { summarizer.add(record); });
  const auto summaries = summarizer.finish(threads);
  const auto markdown = summary_markdown(summaries, title);
  folder.write("summary.csv", summary_csv(summaries));
  folder.write("summary.md", markdown);
  return markdown;
}

}  // namespace freeplay::results
