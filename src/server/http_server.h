// The app's HTTP server: cpp-httplib listening on one address (loopback by default) in a
// thread of its own, serving the API of api.h. stop() (or destruction) shuts it down.
//
// Each connection carries one request, read under a total deadline (a client that
// trickles its headers is cut off, not waited for per byte), with the header block and
// body bounded and checked before the body is read (request_head.h). Requests whose
// Host/Origin is not this server are refused (origin_policy.h).
#pragma once

#include <memory>
#include <string>
#include <thread>

namespace isegman::server {

class AppState;

struct HttpLimits {
  double request_seconds = 10;     // to receive a whole request (headers + body)
  size_t max_header_bytes = 16384;
  size_t max_body_bytes = 1 << 20;
  // POST /api/upload (a scene to combine) alone takes a larger body, in a longer time.
  size_t max_upload_bytes = size_t(256) << 20;
  double upload_seconds = 300;
  int workers = 32;                // connections served at once
};

class HttpServer {
 public:
  explicit HttpServer(AppState& app, const HttpLimits& limits = {});
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds host:port (port 0 = an ephemeral port) and starts serving; returns the port.
  // Throws Error when the address cannot be bound.
  int start(const std::string& host, int port);
  void stop();
  int port() const { return port_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::thread thread_;
  int port_ = 0;
};

}  // namespace isegman::server
