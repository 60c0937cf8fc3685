#include "freeplay/recording/bag_description.hpp"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <tuple>
#include <vector>

#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/recording/ros_messages.hpp"

namespace freeplay::recording {

namespace {

/// python3-rosbag's _median: the middle value, or the mean of the two middle values.
double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2.0;
}

}  // namespace

std::string describe_bag_yaml(const std::filesystem::path& bag_path, const std::string& path_field,
                              const std::string& compression) {
  Bag bag;
  open_session_bag(bag_path, bag);
  rosbag::View view(bag.get());
  struct Topic {
    std::string type;
    std::set<std::uint32_t> connections;
    std::vector<double> times;
  };
  std::map<std::string, Topic> topics;
  std::set<std::tuple<std::string, std::string>> types;  // (datatype, md5), listed once per datatype
  std::set<std::string> seen_types;
  for (const auto* c : view.getConnections()) {
    auto& topic = topics[c->topic];
    if (topic.type.empty()) topic.type = c->datatype;
    topic.connections.insert(c->id);
    if (seen_types.insert(c->datatype).second) types.emplace(c->datatype, c->md5sum);
  }
  std::uint64_t messages = 0;
  for (const auto& m : view) {
    topics[m.getTopic()].times.push_back(m.getTime().toSec());
    ++messages;
  }
  const double start = view.size() > 0 ? view.getBeginTime().toSec() : 0.0;
  const double end = view.size() > 0 ? view.getEndTime().toSec() : 0.0;
  std::string out = fmt::format("path: {}\nversion: 2.0\n", path_field);
  out += fmt::format("duration: {:.6f}\nstart: {:.6f}\nend: {:.6f}\n", end - start, start, end);
  out += fmt::format("size: {}\nmessages: {}\nindexed: True\n", std::filesystem::file_size(bag_path), messages);
  out += fmt::format("compression: {}\n", compression);
  out += "types:\n";
  for (const auto& [type, md5] : types) out += fmt::format("    - type: {}\n      md5: {}\n", type, md5);
  out += "topics:\n";
  for (auto& [name, topic] : topics) {
    out += fmt::format("    - topic: {}\n      type: {}\n      messages: {}\n", name, topic.type, topic.times.size());
    if (topic.connections.size() > 1) out += fmt::format("      connections: {}\n", topic.connections.size());
    if (topic.times.size() > 1) {
      std::sort(topic.times.begin(), topic.times.end());
      std::vector<double> periods;
      for (std::size_t i = 1; i < topic.times.size(); ++i) periods.push_back(topic.times[i] - topic.times[i - 1]);
      const double period = median(std::move(periods));
      if (period > 0.0) out += fmt::format("      frequency: {:.4f}\n", 1.0 / period);
    }
  }
  return out + "\n";  // `rosbag info --yaml > file` ends with print()'s extra line
}

std::string md5_hex(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("cannot read '{}' for its checksum", file.string()), "file");
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  EVP_DigestInit_ex(ctx.get(), EVP_md5(), nullptr);
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    EVP_DigestUpdate(ctx.get(), buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(ctx.get(), digest, &length);
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

std::filesystem::path write_md5_file(const std::filesystem::path& file) {
  auto md5 = file;
  md5 += ".md5";
  write_file_atomically(md5, fmt::format("{}  {}\n", md5_hex(file), file.filename().string()));
  return md5;
}

}  // namespace freeplay::recording
