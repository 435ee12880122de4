// The app's HTTP server: cpp-httplib listening on one address (loopback by default) in a
// thread of its own, serving the API of api.h. stop() (or destruction) shuts it down.
#pragma once

#include <memory>
#include <string>
#include <thread>

namespace isegman::server {

class AppState;

class HttpServer {
 public:
  explicit HttpServer(AppState& app);
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
