#include "server/http_server.h"

#include <httplib.h>

#include "core/error.h"
#include "server/api.h"

namespace isegman::server {

struct HttpServer::Impl {
  httplib::Server server;
};

HttpServer::HttpServer(AppState& app) : impl_(std::make_unique<Impl>()) {
  httplib::Server& s = impl_->server;
  s.set_payload_max_length(size_t(1) << 20);
  s.set_read_timeout(10, 0);
  s.set_write_timeout(30, 0);
  s.set_keep_alive_max_count(100);
  s.set_keep_alive_timeout(5);
  register_routes(s, app);
}

HttpServer::~HttpServer() { stop(); }

int HttpServer::start(const std::string& host, int port) {
  if (port < 0 || port > 65535) throw Error("--port must be in [0, 65535]");
  httplib::Server& s = impl_->server;
  const int bound = port == 0 ? s.bind_to_any_port(host) : (s.bind_to_port(host, port) ? port : -1);
  if (bound <= 0) throw Error(host + ":" + std::to_string(port), "cannot listen there (address in use or not local?)");
  port_ = bound;
  thread_ = std::thread([this] { impl_->server.listen_after_bind(); });
  return bound;
}

void HttpServer::stop() {
  if (impl_) impl_->server.stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace isegman::server
