#include "freeplay/core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace freeplay {

void write_file_atomically(const std::filesystem::path& path, std::string_view contents) {
  write_file_atomically(path, [&](const std::function<void(std::string_view)>& write) { write(contents); });
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::function<void(std::string_view)>&)>& produce) {
  const auto parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::filesystem::create_directories(parent);
  std::string tmp_name = fmt::format(".{}.tmp-XXXXXX", path.filename().string());
  std::string tmp = (parent / tmp_name).string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) {
    throw std::runtime_error(fmt::format("cannot create a temporary file beside {}: {}", path.string(),
                                         std::strerror(errno)));
  }
  const auto write = [&](std::string_view contents) {
    std::size_t written = 0;
    while (written < contents.size()) {
      const auto n = ::write(fd, contents.data() + written, contents.size() - written);
      if (n < 0) throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), std::strerror(errno)));
      written += static_cast<std::size_t>(n);
    }
  };
  try {
    produce(write);
  } catch (...) {  // nothing half-written stays behind
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error(fmt::format("cannot flush {}: {}", path.string(), std::strerror(err)));
  }
  ::chmod(tmp.c_str(), 0644);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error(fmt::format("cannot move {} into place: {}", path.string(), std::strerror(err)));
  }
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot open {}", path.string()));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace freeplay
