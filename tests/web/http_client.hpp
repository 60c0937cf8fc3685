#pragma once
// A minimal blocking HTTP/1.1 client for the web tests: one request per connection to 127.0.0.1.

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>
#include <utility>

namespace freeplay::web::test_http {

/// Sends the raw HTTP `text` to 127.0.0.1:`port` on one connection: the status code and the body ({-1, ""} when
/// unreachable or the answer is not HTTP).
inline std::pair<int, std::string> send_raw(int port, const std::string& text) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    close(fd);
    return {-1, ""};
  }
  (void)!write(fd, text.data(), text.size());
  std::string response;
  char buffer[4096];
  for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;) response.append(buffer, static_cast<std::size_t>(n));
  close(fd);
  if (response.size() < 12) return {-1, ""};
  const auto at = response.find("\r\n\r\n");
  return {std::stoi(response.substr(9, 3)), at == std::string::npos ? "" : response.substr(at + 4)};
}

/// Sends `method path` with `body` to 127.0.0.1:`port`: the status code and the body ({-1, ""} when unreachable).
inline std::pair<int, std::string> request(int port, const std::string& method, const std::string& path,
                                           const std::string& body = "") {
  return send_raw(port, fmt::format("{} {} HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Length: {}\r\n\r\n{}",
                                    method, path, body.size(), body));
}

/// POSTs `body` to /api/command.
inline std::pair<int, std::string> post(int port, const std::string& body) {
  return request(port, "POST", "/api/command", body);
}

}  // namespace freeplay::web::test_http
