#include "server/http_server.h"

#include <httplib.h>
#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "server/api.h"
#include "server/origin_policy.h"
#include "server/request_head.h"

namespace isegman::server {
namespace {

using Clock = std::chrono::steady_clock;

int ms_left(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left <= 0 ? 0 : int(std::min<long long>(left, 1 << 30));
}

bool wait_for(int fd, short events, int timeout_ms) {
  pollfd p{fd, events, 0};
  for (;;) {
    const int r = ::poll(&p, 1, timeout_ms);
    if (r < 0 && errno == EINTR) continue;
    return r > 0;
  }
}

bool send_all(int fd, const char* data, size_t size, int timeout_ms) {
  while (size > 0) {
    if (!wait_for(fd, POLLOUT, timeout_ms)) return false;
    const ssize_t n = ::send(fd, data, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= size_t(n);
  }
  return true;
}

const char* reason(int status) {
  switch (status) {
    case 400: return "Bad Request";
    case 408: return "Request Timeout";
    case 411: return "Length Required";
    case 413: return "Payload Too Large";
    case 431: return "Request Header Fields Too Large";
    default: return "Error";
  }
}

// The header block and body of one request: first the bytes read while checking the
// headers, then the socket, every read bounded by the request's deadline.
class RequestStream : public httplib::Stream {
 public:
  RequestStream(int fd, std::string head, Clock::time_point deadline, int write_timeout_ms)
      : fd_(fd), head_(std::move(head)), deadline_(deadline), write_timeout_ms_(write_timeout_ms) {}

  bool is_readable() const override { return pos_ < head_.size() || wait_for(fd_, POLLIN, ms_left(deadline_)); }
  bool is_writable() const override { return wait_for(fd_, POLLOUT, write_timeout_ms_); }
  ssize_t read(char* ptr, size_t size) override {
    if (pos_ < head_.size()) {
      const size_t n = std::min(size, head_.size() - pos_);
      std::memcpy(ptr, head_.data() + pos_, n);
      pos_ += n;
      return ssize_t(n);
    }
    if (!wait_for(fd_, POLLIN, ms_left(deadline_))) return -1;
    for (;;) {
      const ssize_t n = ::recv(fd_, ptr, size, 0);
      if (n < 0 && errno == EINTR) continue;
      return n;
    }
  }
  ssize_t write(const char* ptr, size_t size) override {
    if (!is_writable()) return -1;
    for (;;) {
      const ssize_t n = ::send(fd_, ptr, size, MSG_NOSIGNAL);
      if (n < 0 && errno == EINTR) continue;
      return n;
    }
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override { address(false, ip, port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { address(true, ip, port); }
  socket_t socket() const override { return fd_; }

 private:
  void address(bool local, std::string& ip, int& port) const {
    sockaddr_storage a{};
    socklen_t len = sizeof a;
    const int r = local ? ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len)
                        : ::getpeername(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    char buf[INET6_ADDRSTRLEN] = "";
    port = 0;
    if (r == 0 && a.ss_family == AF_INET) {
      const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
      ::inet_ntop(AF_INET, &v4->sin_addr, buf, sizeof buf);
      port = ntohs(v4->sin_port);
    } else if (r == 0 && a.ss_family == AF_INET6) {
      const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
      ::inet_ntop(AF_INET6, &v6->sin6_addr, buf, sizeof buf);
      port = ntohs(v6->sin6_port);
    }
    ip = buf;
  }

  int fd_;
  std::string head_;
  size_t pos_ = 0;
  Clock::time_point deadline_;
  int write_timeout_ms_;
};

}  // namespace

// cpp-httplib with its per-connection loop replaced: one request per connection, read
// under a total deadline, its head checked before any body is read.
class GuardedServer : public httplib::Server {
 public:
  explicit GuardedServer(const HttpLimits& limits) : limits_(limits) {}

 private:
  void answer(int fd, int status, const std::string& message) {
    const std::string body = nlohmann::json{{"error", message}, {"status", status}}.dump();
    const std::string text = "HTTP/1.1 " + std::to_string(status) + " " + reason(status) +
                             "\r\nContent-Type: application/json\r\nCache-Control: no-store\r\nContent-Length: " +
                             std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body;
    send_all(fd, text.data(), text.size(), 2000);
    // Let the client read the answer before the close (unread input would reset it).
    ::shutdown(fd, SHUT_WR);
    char sink[4096];
    const auto until = Clock::now() + std::chrono::milliseconds(200);
    while (wait_for(fd, POLLIN, ms_left(until)) && ::recv(fd, sink, sizeof sink, 0) > 0) {
    }
  }

  bool process_and_close_socket(socket_t fd) override {
    const auto start = Clock::now();
    auto deadline = start + std::chrono::milliseconds(long(limits_.request_seconds * 1000));
    std::string head;
    size_t header_end = std::string::npos;
    char buf[4096];
    while (header_end == std::string::npos) {
      if (head.size() > limits_.max_header_bytes) {
        answer(fd, 431, "request headers larger than " + std::to_string(limits_.max_header_bytes) + " bytes");
        break;
      }
      if (!wait_for(fd, POLLIN, ms_left(deadline))) {
        if (!head.empty())
          answer(fd, 408, "the request was not received within " + std::to_string(int(limits_.request_seconds)) + " s");
        break;
      }
      const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      head.append(buf, size_t(n));
      header_end = head.find("\r\n\r\n");
    }
    if (header_end != std::string::npos) {
      const bool upload = is_upload(head);
      if (upload) deadline = start + std::chrono::milliseconds(long(limits_.upload_seconds * 1000));
      const HeadCheck check = check_request_head(head.substr(0, header_end + 4),
                                                 upload ? limits_.max_upload_bytes : limits_.max_body_bytes);
      if (check.status != 0) {
        answer(fd, check.status, check.message);
      } else {
        if (check.add_zero_length) head.insert(head.find("\r\n") + 2, "Content-Length: 0\r\n");
        RequestStream stream(fd, std::move(head), deadline, int(write_timeout_sec_ * 1000 + write_timeout_usec_ / 1000));
        bool closed = false;
        process_request(stream, true, closed, nullptr);
      }
    }
    ::shutdown(fd, SHUT_RDWR);
    ::close(fd);
    return true;
  }

  // "POST /api/upload?..." or "POST /api/upload HTTP/1.1": the one route with a large body.
  static bool is_upload(const std::string& head) {
    const std::string prefix = "POST /api/upload";
    if (head.compare(0, prefix.size(), prefix) != 0 || head.size() <= prefix.size()) return false;
    const char next = head[prefix.size()];
    return next == '?' || next == ' ';
  }

  HttpLimits limits_;
};

struct HttpServer::Impl {
  explicit Impl(const HttpLimits& limits) : server(limits) {}
  GuardedServer server;
  OriginPolicy policy;
};

HttpServer::HttpServer(AppState& app, const HttpLimits& limits) : impl_(std::make_unique<Impl>(limits)) {
  GuardedServer& s = impl_->server;
  // Each request's own limit is checked from its head (process_and_close_socket).
  s.set_payload_max_length(std::max(limits.max_body_bytes, limits.max_upload_bytes));
  s.set_read_timeout(10, 0);
  s.set_write_timeout(30, 0);
  const int workers = std::max(1, limits.workers);
  s.new_task_queue = [workers] { return new httplib::ThreadPool(size_t(workers)); };
  OriginPolicy* policy = &impl_->policy;
  s.set_pre_routing_handler([policy](const httplib::Request& req, httplib::Response& res) {
    const std::string why = check_request_origin(*policy, req.method, req.get_header_value("Host"),
                                                 req.get_header_value("Origin"),
                                                 req.get_header_value("Sec-Fetch-Site"));
    if (why.empty()) return httplib::Server::HandlerResponse::Unhandled;
    res.status = 403;
    res.set_header("Cache-Control", "no-store");
    res.set_content(nlohmann::json{{"error", why}, {"status", 403}}.dump(), "application/json");
    return httplib::Server::HandlerResponse::Handled;
  });
  register_routes(s, app);
}

HttpServer::~HttpServer() { stop(); }

int HttpServer::start(const std::string& host, int port) {
  if (port < 0 || port > 65535) throw Error("--port must be in [0, 65535]");
  httplib::Server& s = impl_->server;
  const int bound = port == 0 ? s.bind_to_any_port(host) : (s.bind_to_port(host, port) ? port : -1);
  if (bound <= 0) throw Error(host + ":" + std::to_string(port), "cannot listen there (address in use or not local?)");
  port_ = bound;
  impl_->policy = OriginPolicy{host, bound};
  thread_ = std::thread([this] { impl_->server.listen_after_bind(); });
  return bound;
}

void HttpServer::stop() {
  if (impl_) impl_->server.stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace isegman::server
