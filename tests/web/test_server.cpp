#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>

#include "freeplay/core/error.hpp"
#include "freeplay/web/server.hpp"
#include "http_client.hpp"

using namespace freeplay::web;

namespace {

// One HTTP exchange with 127.0.0.1:`port`: the status code and the body.
std::pair<int, std::string> http(int port, const std::string& request) { return test_http::send_raw(port, request); }

std::string get(const std::string& target, const std::string& headers = "") {
  return "GET " + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n" + headers + "\r\n";
}

std::string post(const std::string& target, const std::string& body) {
  return "POST " + target + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\nContent-Type: application/json\r\n"
         "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

// A WebSocket client that completes the handshake on /ws and then never reads (a stalled page).
int stalled_client(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  const int small = 4096;
  setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) return -1;
  const std::string handshake =
      "GET /ws HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";
  (void)!write(fd, handshake.data(), handshake.size());
  std::string response;
  char c = 0;
  while (response.find("\r\n\r\n") == std::string::npos && read(fd, &c, 1) == 1) response += c;
  return response.find(" 101 ") != std::string::npos ? fd : -1;
}

WebServer::ApiHandler echo() {
  return [](const HttpRequest& r) { return HttpReply{200, "application/json", r.method + " " + r.path + " " + r.body}; };
}

}  // namespace

TEST(WebServer, ServesThePageAndTheApiOnOnePort) {
  ServerOptions options;
  options.port = 0;
  WebServer server(options, echo(), [] { return std::string("{}"); });
  ASSERT_GT(server.port(), 0);
  const auto [page_status, page] = http(server.port(), get("/"));
  EXPECT_EQ(page_status, 200);
  EXPECT_NE(page.find("<canvas id=\"tray\""), std::string::npos);
  EXPECT_EQ(http(server.port(), get("/app.js")).first, 200);
  EXPECT_EQ(http(server.port(), get("/nothing-here")).first, 404);
  EXPECT_EQ(http(server.port(), post("/api/command", R"({"type":"stop"})")).second, R"(POST /api/command {"type":"stop"})");
  EXPECT_EQ(http(server.port(), post("/index.html", "x")).first, 405);
}

TEST(WebServer, ATokenIsRequiredOfEveryRequestOnceSet) {
  ServerOptions options;
  options.port = 0;
  options.token = "0123456789abcdef-secret";
  WebServer server(options, echo(), [] { return std::string("{}"); });
  auto [status, body] = http(server.port(), get("/"));
  EXPECT_EQ(status, 401);
  EXPECT_NE(body.find("access token"), std::string::npos);
  EXPECT_EQ(http(server.port(), get("/?token=wrong-token-wrong-token")).first, 401);
  EXPECT_EQ(http(server.port(), get("/api/state?token=0123456789abcdef-secre")).first, 401);
  EXPECT_EQ(http(server.port(), get("/?token=0123456789abcdef-secret")).first, 200);
  EXPECT_EQ(http(server.port(), get("/api/state", "Authorization: Bearer 0123456789abcdef-secret\r\n")).first, 200);
  EXPECT_EQ(http(server.port(), get("/app.js", "Cookie: a=b; freeplay_token=0123456789abcdef-secret\r\n")).first, 200);
  EXPECT_EQ(http(server.port(), get("/app.js", "Cookie: freeplay_token=0123456789abcdef-secreT\r\n")).first, 401);
  EXPECT_EQ(http(server.port(), post("/api/command", "{}")).first, 401);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/?token=0123456789abcdef-secret");
  EXPECT_GE(server.stats().refused, 4u);
}

TEST(WebServer, BindingBeyondLoopbackNeedsAToken) {
  ServerOptions options;
  options.port = 0;
  options.address = "0.0.0.0";
  EXPECT_THROW(WebServer(options, echo(), [] { return std::string("{}"); }), freeplay::InputError);
  EXPECT_TRUE(is_loopback("127.0.0.1"));
  EXPECT_TRUE(is_loopback("::1"));
  EXPECT_FALSE(is_loopback("0.0.0.0"));
  EXPECT_FALSE(is_loopback("192.168.2.105"));
}

TEST(WebServer, OversizedBodiesAreRefused) {
  ServerOptions options;
  options.port = 0;
  options.max_body_bytes = 1024;
  WebServer server(options, echo(), [] { return std::string("{}"); });
  const auto status = http(server.port(), post("/api/command", std::string(4096, 'x'))).first;
  EXPECT_GE(status, 400);
  EXPECT_LT(status, 500);
}

TEST(WebServer, AStalledClientSkipsFramesInsteadOfGrowingTheQueue) {
  ServerOptions options;
  options.port = 0;
  options.max_client_queue_bytes = 64 * 1024;
  WebServer server(options, echo(), [] { return std::string("{}"); });
  const int fd = stalled_client(server.port());
  ASSERT_GE(fd, 0);
  for (int i = 0; i < 200 && server.clients() == 0; ++i) usleep(10000);
  ASSERT_EQ(server.clients(), 1u);
  const auto frame = std::make_shared<const std::string>(std::string(100 * 1024, 'x'));
  constexpr int kFrames = 300;  // 30 MB offered: far more than the socket buffers and the cap hold
  for (int i = 0; i < kFrames; ++i) {
    server.broadcast(frame);
    usleep(1000);
  }
  ServerStats stats;
  for (int i = 0; i < 200; ++i) {  // the I/O thread hands out the posted frames
    stats = server.stats();
    if (stats.frames_sent + stats.frames_dropped == kFrames) break;
    usleep(10000);
  }
  EXPECT_EQ(stats.frames_sent + stats.frames_dropped, static_cast<std::uint64_t>(kFrames));
  EXPECT_GT(stats.frames_dropped, kFrames / 2u);
  close(fd);
}
