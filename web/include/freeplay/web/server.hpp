#pragma once
// The web server of `freeplay serve --web`: HTTP (the page's assets, the JSON API) and a WebSocket state stream on
// one port (websocketpp over Boost.Asio, one I/O thread). Loopback by default; with a token every request and
// every WebSocket must carry it (`?token=` or `Authorization: Bearer`). Each client's send queue is capped: while a
// client is behind, state frames are dropped for it, so a slow page never grows the server's memory. A WebSocket
// that asks for the `foxglove.websocket.v1` subprotocol (any path) speaks the Foxglove protocol instead.

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "freeplay/web/foxglove.hpp"

namespace freeplay::web {

/// One HTTP request as the API handler sees it (already past the token check).
struct HttpRequest {
  std::string method;  ///< "GET" | "POST" | …
  std::string path;    ///< without the query, e.g. "/api/command"
  std::map<std::string, std::string> query;  ///< decoded query parameters
  std::string body;    ///< request body (POST)
};

/// An HTTP answer.
struct HttpReply {
  int status = 200;                                ///< HTTP status
  std::string content_type = "application/json";  ///< Content-Type
  std::string body;                                ///< body bytes
};

/// Where and how to listen.
struct ServerOptions {
  std::string address = "127.0.0.1";  ///< bind address (loopback unless told otherwise)
  int port = 8080;                    ///< TCP port (0: any free port)
  std::string token;                  ///< required of every request when not empty
  std::size_t max_client_queue_bytes = 512 * 1024;  ///< a client with more unsent bytes skips state frames
  std::size_t max_body_bytes = 64 * 1024;          ///< larger request bodies get 413
  std::vector<FoxgloveChannel> foxglove;           ///< the channels Foxglove clients are offered (empty: the game's)
};

/// Counters of the server (for tests and the report).
struct ServerStats {
  std::uint64_t frames_sent = 0;     ///< state frames handed to clients
  std::uint64_t frames_dropped = 0;  ///< state frames skipped for clients that were behind
  std::uint64_t requests = 0;        ///< HTTP requests answered
  std::uint64_t refused = 0;         ///< requests answered 4xx
};

/// HTTP + WebSocket server on its own thread.
class WebServer {
 public:
  /// Answers `/api/…` requests (any other GET path serves the embedded page).
  using ApiHandler = std::function<HttpReply(const HttpRequest&)>;
  /// The frame a WebSocket client gets on connecting (the full state).
  using Greeting = std::function<std::string()>;

  /// Binds and starts serving; throws InputError (address in use, bad address, exposed without a token).
  WebServer(const ServerOptions& options, ApiHandler api, Greeting greeting);
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  /// Sends a state frame to every WebSocket client that is not behind (any thread).
  void broadcast(std::shared_ptr<const std::string> frame);
  /// The port actually bound.
  int port() const;
  /// The page's URL (with the token).
  std::string url() const;
  /// Counters so far.
  ServerStats stats() const;
  /// Number of connected WebSocket clients (pages and scripts).
  std::size_t clients() const;

  /// Sends each message to the Foxglove clients subscribed to its channel (any thread; same queue cap).
  void publish_foxglove(std::vector<FoxgloveMessage> messages);
  /// Keeps `message` as its channel's latest: a new subscriber gets it at once (zones, footprints, background).
  void latch_foxglove(FoxgloveMessage message);
  /// Number of connected Foxglove clients (`foxglove.websocket.v1`).
  std::size_t foxglove_clients() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// True when `address` is a loopback address (127.0.0.0/8, ::1, "localhost").
bool is_loopback(const std::string& address);

}  // namespace freeplay::web
