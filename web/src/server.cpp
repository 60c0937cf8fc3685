#include "freeplay/web/server.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/web/assets.hpp"

namespace freeplay::web {

namespace {

using Endpoint = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

constexpr const char* kTokenCookie = "freeplay_token";
constexpr const char* kFoxgloveProtocol = "foxglove.websocket.v1";

// A Foxglove client: its subscriptions (subscription id → channel id).
struct FoxgloveClient {
  std::map<std::uint32_t, int> subscriptions;
};

std::string decode(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
               std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += static_cast<char>(std::stoi(std::string(s.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// Splits a request target into its path and decoded query parameters.
std::pair<std::string, std::map<std::string, std::string>> split_target(const std::string& target) {
  const auto q = target.find('?');
  std::map<std::string, std::string> query;
  if (q != std::string::npos) {
    std::string_view rest(target);
    rest.remove_prefix(q + 1);
    while (!rest.empty()) {
      const auto amp = rest.find('&');
      const auto pair = rest.substr(0, amp);
      const auto eq = pair.find('=');
      query[decode(pair.substr(0, eq))] = eq == std::string_view::npos ? "" : decode(pair.substr(eq + 1));
      if (amp == std::string_view::npos) break;
      rest.remove_prefix(amp + 1);
    }
  }
  return {decode(target.substr(0, q)), query};
}

std::string error_body(const std::string& message) { return nlohmann::json{{"error", message}}.dump(); }

// Constant-time comparison of the presented and the expected token.
bool same_token(const std::string& a, const std::string& b) {
  if (a.size() != b.size() || b.empty()) return false;
  unsigned diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned>(a[i] ^ b[i]);
  return diff == 0;
}

}  // namespace

bool is_loopback(const std::string& address) {
  if (address == "localhost" || address == "::1") return true;
  websocketpp::lib::asio::error_code ec;
  const auto parsed = websocketpp::lib::asio::ip::address::from_string(address, ec);
  return !ec && parsed.is_loopback();
}

struct WebServer::Impl {
  ServerOptions options;
  ApiHandler api;
  Greeting greeting;
  Endpoint endpoint;
  std::thread thread;
  std::set<Handle, std::owner_less<Handle>> clients;  // I/O thread only
  std::atomic<std::size_t> client_count{0};
  std::map<Handle, FoxgloveClient, std::owner_less<Handle>> foxglove;  // I/O thread only
  std::map<int, FoxgloveMessage> latched;                              // I/O thread only
  std::atomic<std::size_t> foxglove_count{0};
  int port = 0;
  mutable std::mutex stats_mutex;
  ServerStats stats;

  // The token presented with a request: query `token`, `Authorization: Bearer …`, or the cookie the page got.
  template <typename Request>
  bool authorised(const std::map<std::string, std::string>& query, const Request& request) const {
    if (options.token.empty()) return true;
    if (const auto it = query.find("token"); it != query.end() && same_token(it->second, options.token)) return true;
    const std::string bearer = "Bearer ";
    const auto authorization = request.get_header("Authorization");
    if (authorization.rfind(bearer, 0) == 0 && same_token(authorization.substr(bearer.size()), options.token)) return true;
    const auto cookies = request.get_header("Cookie");
    const std::string name = std::string(kTokenCookie) + "=";
    for (auto at = cookies.find(name); at != std::string::npos; at = cookies.find(name, at + 1)) {
      if (at != 0 && cookies[at - 1] != ' ' && cookies[at - 1] != ';') continue;
      const auto start = at + name.size();
      if (same_token(cookies.substr(start, cookies.find(';', start) - start), options.token)) return true;
    }
    return false;
  }

  void count(int status) {
    std::lock_guard lock(stats_mutex);
    ++stats.requests;
    if (status >= 400 && status < 500) ++stats.refused;
  }

  void on_http(Handle hdl) {
    auto con = endpoint.get_con_from_hdl(hdl);
    const auto& request = con->get_request();
    auto [path, query] = split_target(request.get_uri());
    HttpReply reply;
    if (!authorised(query, request)) {
      reply = {401, "application/json", error_body("missing or wrong access token (pass ?token=… or "
                                                   "'Authorization: Bearer …'; see docs/web.md)")};
    } else if (path.rfind("/api/", 0) == 0) {
      HttpRequest r{request.get_method(), path, query, con->get_request_body()};
      try {
        reply = api(r);
      } catch (const std::exception& e) {
        reply = {500, "application/json", error_body(e.what())};
      }
    } else if (request.get_method() != "GET") {
      reply = {405, "application/json", error_body(fmt::format("{} {}: only GET serves the page", request.get_method(), path))};
    } else if (const auto asset = find_asset(path)) {
      reply = {200, std::string(asset->content_type), std::string(asset->body)};
    } else {
      reply = {404, "application/json", error_body(fmt::format("no such page: {}", path))};
    }
    count(reply.status);
    con->set_status(static_cast<websocketpp::http::status_code::value>(reply.status));
    con->replace_header("Content-Type", reply.content_type);
    con->replace_header("Cache-Control", "no-store");
    if (!options.token.empty() && query.count("token") != 0 && reply.status < 400) {
      // The page's own requests (scripts, styles, the WebSocket) then carry the token without repeating it.
      con->replace_header("Set-Cookie", fmt::format("{}={}; Path=/; HttpOnly; SameSite=Strict", kTokenCookie, options.token));
    }
    con->set_body(std::move(reply.body));
  }

  bool on_validate(Handle hdl) {
    auto con = endpoint.get_con_from_hdl(hdl);
    auto [path, query] = split_target(con->get_request().get_uri());
    const auto& protocols = con->get_requested_subprotocols();
    const bool foxglove_client = std::find(protocols.begin(), protocols.end(), kFoxgloveProtocol) != protocols.end();
    if (foxglove_client) con->select_subprotocol(kFoxgloveProtocol);
    if (path != "/ws" && !foxglove_client) {
      con->set_status(websocketpp::http::status_code::not_found);
      con->set_body(error_body("the state stream is at /ws"));
      count(404);
      return false;
    }
    if (!authorised(query, con->get_request())) {
      con->set_status(websocketpp::http::status_code::unauthorized);
      con->set_body(error_body("missing or wrong access token"));
      count(401);
      return false;
    }
    return true;
  }

  void send(Handle hdl, const std::string& frame, websocketpp::frame::opcode::value opcode = websocketpp::frame::opcode::text) {
    websocketpp::lib::error_code ec;
    endpoint.send(hdl, frame, opcode, ec);
  }

  void on_open(Handle hdl) {
    auto con = endpoint.get_con_from_hdl(hdl);
    if (con->get_subprotocol() != kFoxgloveProtocol) {
      clients.insert(hdl);
      client_count = clients.size();
      send(hdl, greeting());
      return;
    }
    foxglove[hdl] = {};
    foxglove_count = foxglove.size();
    send(hdl, nlohmann::json{{"op", "serverInfo"}, {"name", "freeplay serve --web"}, {"capabilities", nlohmann::json::array()},
                             {"supportedEncodings", nlohmann::json::array()}, {"metadata", nlohmann::json::object()}}
                  .dump());
    nlohmann::json channels = nlohmann::json::array();
    for (const auto& c : options.foxglove.empty() ? foxglove_channels() : options.foxglove) {
      channels.push_back({{"id", c.id}, {"topic", c.topic}, {"encoding", "ros1"}, {"schemaName", c.schema_name},
                          {"schema", c.schema}, {"schemaEncoding", "ros1msg"}});
    }
    send(hdl, nlohmann::json{{"op", "advertise"}, {"channels", channels}}.dump());
  }

  void on_close(Handle hdl) {
    clients.erase(hdl);
    client_count = clients.size();
    foxglove.erase(hdl);
    foxglove_count = foxglove.size();
  }

  // Foxglove client operations: subscribe / unsubscribe (anything else is ignored, as the protocol allows).
  void on_message(Handle hdl, const Endpoint::message_ptr& message) {
    const auto it = foxglove.find(hdl);
    if (it == foxglove.end()) return;  // pages only listen
    const auto request = nlohmann::json::parse(message->get_payload(), nullptr, false);
    if (!request.is_object()) return;
    const auto op = request.value("op", "");
    if (op == "subscribe" && request.contains("subscriptions") && request["subscriptions"].is_array()) {
      for (const auto& sub : request["subscriptions"]) {
        if (!sub.is_object() || !sub.contains("id") || !sub.contains("channelId")) continue;
        const auto id = sub["id"].get<std::uint32_t>();
        const auto channel = sub["channelId"].get<int>();
        it->second.subscriptions[id] = channel;
        if (const auto l = latched.find(channel); l != latched.end()) {
          send(hdl, foxglove_frame(id, l->second), websocketpp::frame::opcode::binary);
        }
      }
    } else if (op == "unsubscribe" && request.contains("subscriptionIds") && request["subscriptionIds"].is_array()) {
      for (const auto& id : request["subscriptionIds"]) {
        if (id.is_number_unsigned()) it->second.subscriptions.erase(id.get<std::uint32_t>());
      }
    }
  }

  void fan_out_foxglove(const std::vector<FoxgloveMessage>& messages) {
    std::uint64_t sent = 0;
    std::uint64_t dropped = 0;
    for (const auto& [hdl, client] : foxglove) {
      websocketpp::lib::error_code ec;
      auto con = endpoint.get_con_from_hdl(hdl, ec);
      if (ec) continue;
      for (const auto& [id, channel] : client.subscriptions) {
        for (const auto& m : messages) {
          if (m.channel != channel) continue;
          if (con->get_buffered_amount() > options.max_client_queue_bytes) {
            ++dropped;
          } else {
            con->send(foxglove_frame(id, m), websocketpp::frame::opcode::binary);
            ++sent;
          }
        }
      }
    }
    std::lock_guard lock(stats_mutex);
    stats.frames_sent += sent;
    stats.frames_dropped += dropped;
  }

  void fan_out(const std::shared_ptr<const std::string>& frame) {
    std::uint64_t sent = 0;
    std::uint64_t dropped = 0;
    for (const auto& hdl : clients) {
      websocketpp::lib::error_code ec;
      auto con = endpoint.get_con_from_hdl(hdl, ec);
      if (ec) continue;
      if (con->get_buffered_amount() > options.max_client_queue_bytes) {
        ++dropped;
        continue;
      }
      con->send(*frame, websocketpp::frame::opcode::text);
      ++sent;
    }
    std::lock_guard lock(stats_mutex);
    stats.frames_sent += sent;
    stats.frames_dropped += dropped;
  }
};

WebServer::WebServer(const ServerOptions& options, ApiHandler api, Greeting greeting)
    : impl_(std::make_unique<Impl>()) {
  websocketpp::lib::asio::error_code ec;
  const auto address = websocketpp::lib::asio::ip::address::from_string(
      options.address == "localhost" ? "127.0.0.1" : options.address, ec);
  if (ec) throw InputError(fmt::format("--web: '{}' is not an IP address", options.address), "--web", "[ADDR:]PORT, e.g. 127.0.0.1:8080");
  if (!is_loopback(options.address) && options.token.empty()) {
    throw InputError(fmt::format("--web {}: serving beyond loopback needs an access token", options.address),
                     "--web-token", "a token of 16 or more characters, or a loopback address (127.0.0.1)");
  }
  auto& s = *impl_;
  s.options = options;
  s.api = std::move(api);
  s.greeting = std::move(greeting);
  s.endpoint.clear_access_channels(websocketpp::log::alevel::all);
  s.endpoint.clear_error_channels(websocketpp::log::elevel::all);
  s.endpoint.init_asio();
  s.endpoint.set_reuse_addr(true);
  s.endpoint.set_max_http_body_size(options.max_body_bytes);
  s.endpoint.set_http_handler([&s](Handle hdl) { s.on_http(hdl); });
  s.endpoint.set_validate_handler([&s](Handle hdl) { return s.on_validate(hdl); });
  s.endpoint.set_open_handler([&s](Handle hdl) { s.on_open(hdl); });
  s.endpoint.set_close_handler([&s](Handle hdl) { s.on_close(hdl); });
  s.endpoint.set_fail_handler([&s](Handle hdl) { s.on_close(hdl); });
  s.endpoint.set_message_handler([&s](Handle hdl, Endpoint::message_ptr message) { s.on_message(hdl, message); });
  websocketpp::lib::error_code listen_error;
  s.endpoint.listen(websocketpp::lib::asio::ip::tcp::endpoint(address, static_cast<unsigned short>(options.port)),
                    listen_error);
  if (listen_error) {
    throw InputError(fmt::format("--web: cannot listen on {}:{}: {}", options.address, options.port,
                                 listen_error.message()),
                     "--web", "a free port");
  }
  s.port = s.endpoint.get_local_endpoint(ec).port();
  s.endpoint.start_accept();
  s.thread = std::thread([&s] { s.endpoint.run(); });
}

WebServer::~WebServer() {
  auto& s = *impl_;
  websocketpp::lib::asio::post(s.endpoint.get_io_service(), [&s] {
    websocketpp::lib::error_code ec;
    s.endpoint.stop_listening(ec);
    for (const auto& hdl : s.clients) s.endpoint.close(hdl, websocketpp::close::status::going_away, "session ended", ec);
    for (const auto& [hdl, client] : s.foxglove) {
      s.endpoint.close(hdl, websocketpp::close::status::going_away, "session ended", ec);
    }
  });
  // Give clients a moment to see the close frame, then stop the loop.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  s.endpoint.stop();
  if (s.thread.joinable()) s.thread.join();
}

void WebServer::broadcast(std::shared_ptr<const std::string> frame) {
  auto& s = *impl_;
  if (s.client_count == 0) return;
  websocketpp::lib::asio::post(s.endpoint.get_io_service(), [&s, frame = std::move(frame)] { s.fan_out(frame); });
}

void WebServer::publish_foxglove(std::vector<FoxgloveMessage> messages) {
  auto& s = *impl_;
  if (s.foxglove_count == 0) return;
  websocketpp::lib::asio::post(s.endpoint.get_io_service(),
                               [&s, messages = std::move(messages)] { s.fan_out_foxglove(messages); });
}

void WebServer::latch_foxglove(FoxgloveMessage message) {
  auto& s = *impl_;
  websocketpp::lib::asio::post(s.endpoint.get_io_service(),
                               [&s, message = std::move(message)] { s.latched[message.channel] = message; });
}

std::size_t WebServer::foxglove_clients() const { return impl_->foxglove_count; }

int WebServer::port() const { return impl_->port; }

std::string WebServer::url() const {
  const auto& o = impl_->options;
  const auto host = o.address.find(':') != std::string::npos ? "[" + o.address + "]" : o.address;
  return fmt::format("http://{}:{}/{}", host, impl_->port, o.token.empty() ? "" : "?token=" + o.token);
}

ServerStats WebServer::stats() const {
  std::lock_guard lock(impl_->stats_mutex);
  return impl_->stats;
}

std::size_t WebServer::clients() const { return impl_->client_count; }

}  // namespace freeplay::web
