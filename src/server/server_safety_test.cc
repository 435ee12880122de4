// Issue 11 (untrusted names, paths and origins), server side: each attack reproduced
// against a real server on an ephemeral loopback port, then shown refused or handled.
#include <arpa/inet.h>
#include <httplib.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/demo_scene.h"
#include "io/atomic_file.h"
#include "io/ply.h"
#include "server/app_state.h"
#include "server/http_server.h"
#include "server/origin_policy.h"
#include "server/request_head.h"
#include "core/test_dirs.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace isegman::server {
namespace {

std::string temp_dir(const std::string& name) { return testing::fresh_temp_dir("isegman-safety-", name); }

DemoScene tiny_demo() {
  DemoSceneOptions o;
  o.cameras = 4;
  o.width = 96;
  o.height = 64;
  o.density = 0.2f;
  o.sh_degree = 0;
  return make_demo_scene(o);
}

struct Server {
  std::unique_ptr<AppState> app;
  std::unique_ptr<HttpServer> http;
  int port = 0;
  Server(const SceneBundle& b, const std::string& out, HttpLimits limits = {}) {
    AppOptions o;
    o.segmentation = false;
    o.out_dir = out;
    o.threads = 2;
    app = std::make_unique<AppState>(b, o);
    http = std::make_unique<HttpServer>(*app, limits);
    port = http->start("127.0.0.1", 0);
    app->start();
  }
  ~Server() {
    http->stop();
    app->stop();
  }
  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", port);
    c->set_connection_timeout(5);
    c->set_read_timeout(30);
    return c;
  }
};

// A raw TCP connection, for requests no well-behaved client would send.
struct Raw {
  int fd = -1;
  explicit Raw(int port) {
    fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(uint16_t(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  }
  ~Raw() { ::close(fd); }
  void send(const std::string& s) { (void)!::send(fd, s.data(), s.size(), MSG_NOSIGNAL); }
  // Everything the server sends within `seconds` (until it closes).
  std::string read_all(double seconds) {
    std::string out;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(long(seconds * 1000));
    char buf[4096];
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now());
      if (left.count() <= 0) break;
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, int(left.count())) <= 0) break;
      const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
      if (n <= 0) break;
      out.append(buf, size_t(n));
    }
    return out;
  }
};

int status_of(const std::string& response) {
  if (response.compare(0, 9, "HTTP/1.1 ") != 0) return 0;
  return std::atoi(response.c_str() + 9);
}

// Item 7: a page on another site (Origin), or a DNS-rebinding name (Host), is refused.
TEST(ServerSafety, RefusesCrossSiteAndRebindingRequests) {
  DemoScene d = tiny_demo();
  Server s(d.bundle, temp_dir("origin"));
  auto c = s.client();
  const std::string self = "127.0.0.1:" + std::to_string(s.port);
  // The attack: a text/plain POST from evil.example.
  auto r = c->Post("/api/edit/remove", {{"Origin", "http://evil.example"}}, "{}", "text/plain");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403) << r->body;
  EXPECT_NE(r->body.find("cross-site"), std::string::npos) << r->body;
  r = c->Post("/api/export", {{"Sec-Fetch-Site", "cross-site"}}, R"({"path": "x.ply"})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  r = c->Post("/api/edit/undo", {{"Origin", "null"}}, "", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  // DNS rebinding: the attacker's name in Host, even for reads.
  r = c->Get("/api/scene", {{"Host", "evil.example:" + std::to_string(s.port)}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403) << r->body;
  r = c->Get("/api/scene", {{"Host", "127.0.0.1:1"}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  // The server's own page and plain clients still work.
  r = c->Post("/api/select/all", {{"Origin", "http://" + self}}, "", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  r = c->Get("/api/scene", {{"Host", "localhost:" + std::to_string(s.port)}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(c->Get("/api/status")->status, 200);
}

TEST(OriginPolicy, Rules) {
  const OriginPolicy p{"127.0.0.1", 8080};
  EXPECT_EQ(check_request_origin(p, "GET", "127.0.0.1:8080", "", ""), "");
  EXPECT_EQ(check_request_origin(p, "POST", "[::1]:8080", "http://[::1]:8080", "same-origin"), "");
  EXPECT_NE(check_request_origin(p, "GET", "", "", ""), "");
  EXPECT_NE(check_request_origin(p, "GET", "attacker.test:8080", "", ""), "");
  EXPECT_NE(check_request_origin(p, "POST", "127.0.0.1:8080", "http://127.0.0.1:9999", ""), "");
  EXPECT_NE(check_request_origin(p, "POST", "127.0.0.1:8080", "", "cross-site"), "");
  EXPECT_NE(check_request_origin(p, "GET", "127.0.0.1:80x", "", ""), "");
  EXPECT_EQ(check_request_origin({"myhost.lan", 8080}, "GET", "MyHost.lan:8080", "", ""), "");
  EXPECT_TRUE(is_literal_host("192.168.1.5"));
  EXPECT_FALSE(is_literal_host("192.168.1.5.nip.io"));
}

// Item 8: clients that trickle their headers are cut off at the request deadline and
// never stall the others; bad Content-Length values are answered at once.
TEST(ServerSafety, SlowClientsDoNotStallOthers) {
  DemoScene d = tiny_demo();
  HttpLimits limits;
  limits.request_seconds = 1.5;
  limits.workers = 4;
  Server s(d.bundle, temp_dir("slow"), limits);
  std::vector<std::unique_ptr<Raw>> slow;
  for (int i = 0; i < 8; ++i) {  // twice the worker count
    slow.push_back(std::make_unique<Raw>(s.port));
    slow.back()->send("GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\n");
  }
  std::atomic<bool> stop{false};
  std::thread trickle([&] {
    while (!stop) {
      for (auto& r : slow) r->send("X-Slow: 1\r\n");
      std::this_thread::sleep_for(std::chrono::milliseconds(400));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto t0 = std::chrono::steady_clock::now();
  auto c = s.client();
  auto r = c->Get("/api/status");
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stop = true;
  trickle.join();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_LT(waited, 4.0);  // at most about two request deadlines, never the trickle's pace
  // The slow ones got a 408 (or were closed), not service.
  const std::string answer = slow[0]->read_all(3);
  EXPECT_TRUE(answer.empty() || status_of(answer) == 408) << answer;
}

TEST(ServerSafety, BadContentLengthIsAnsweredAtOnce) {
  DemoScene d = tiny_demo();
  Server s(d.bundle, temp_dir("length"));
  const std::string host = "Host: 127.0.0.1:" + std::to_string(s.port) + "\r\n";
  for (const auto& [length, expect] : std::vector<std::pair<std::string, int>>{
           {"-5", 400}, {"abc", 400}, {"99999999999999999999999", 413}, {"2000000", 413}}) {
    Raw raw(s.port);
    const auto t0 = std::chrono::steady_clock::now();
    raw.send("POST /api/click HTTP/1.1\r\n" + host + "Content-Length: " + length + "\r\n\r\n");
    const std::string answer = raw.read_all(5);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(status_of(answer), expect) << length << ": " << answer;
    EXPECT_NE(answer.find("Content-Length"), std::string::npos);
    EXPECT_LT(took, 2.0) << length;
  }
  // Header block beyond the limit: 431.
  Raw big(s.port);
  big.send("GET /api/status HTTP/1.1\r\n" + host + "X-Big: " + std::string(40000, 'a') + "\r\n\r\n");
  EXPECT_EQ(status_of(big.read_all(5)), 431);
}

TEST(RequestHead, Checks) {
  EXPECT_EQ(check_request_head("POST / HTTP/1.1\r\nContent-Length: 10\r\n\r\n", 100).status, 0);
  EXPECT_EQ(check_request_head("POST / HTTP/1.1\r\nContent-Length: 1000\r\n\r\n", 100).status, 413);
  EXPECT_EQ(check_request_head("POST / HTTP/1.1\r\ncontent-length: +1\r\n\r\n", 100).status, 400);
  EXPECT_EQ(check_request_head("POST / HTTP/1.1\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\n", 100).status, 400);
  EXPECT_EQ(check_request_head("POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n", 100).status, 411);
  EXPECT_TRUE(check_request_head("POST / HTTP/1.1\r\nHost: x\r\n\r\n", 100).add_zero_length);
  EXPECT_FALSE(check_request_head("GET / HTTP/1.1\r\nHost: x\r\n\r\n", 100).add_zero_length);
}

// Item 10: a known path with the wrong method is a 405 with Allow; undo/redo take an
// empty body (even without Content-Length); a body that is needed and missing is named.
TEST(ServerSafety, WrongMethodsAndEmptyBodies) {
  DemoScene d = tiny_demo();
  Server s(d.bundle, temp_dir("methods"));
  auto c = s.client();
  auto r = c->Delete("/api/scene");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 405) << r->body;
  EXPECT_EQ(r->get_header_value("Allow"), "GET, HEAD");
  r = c->Get("/api/edit/undo");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 405);
  EXPECT_EQ(r->get_header_value("Allow"), "POST");
  r = c->Put("/api/export", "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 405);
  EXPECT_EQ(r->get_header_value("Allow"), "GET, HEAD, POST");
  EXPECT_EQ(c->Delete("/no/such/thing")->status, 404);

  for (const char* path : {"/api/undo", "/api/redo", "/api/edit/undo", "/api/edit/redo", "/api/click/undo"}) {
    Raw raw(s.port);  // like `curl -X POST`: no body, no Content-Length
    raw.send(std::string("POST ") + path + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(s.port) + "\r\n\r\n");
    const std::string answer = raw.read_all(5);
    const int st = status_of(answer);
    EXPECT_TRUE(st == 200 || st == 202 || st == 409) << path << ": " << answer;
    EXPECT_EQ(answer.find("request failed"), std::string::npos) << answer;
  }
  r = c->Post("/api/export", "", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("body is empty"), std::string::npos) << r->body;
}

// Item 12 (server part): unknown keys in /api/settings are named, not ignored.
TEST(ServerSafety, UnknownSettingsKeysAreRefused) {
  DemoScene d = tiny_demo();
  Server s(d.bundle, temp_dir("settings"));
  auto r = s.client()->Post("/api/settings", R"({"tau": 0.5, "taux": 0.9})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("taux"), std::string::npos) << r->body;
}

// Items 4-6: exports. A symlink planted where the old temporary name was is not
// followed; 100 parallel exports to one name all succeed and a reader only ever sees a
// complete file; a folder behind a symlink leading out is refused before it is made.
TEST(ServerSafety, ExportsAreExclusiveCompleteAndCheckedBeforeCreating) {
  DemoScene d = tiny_demo();
  const std::string dir = temp_dir("export");
  const std::string out = dir + "/out";
  Server s(d.bundle, out);
  auto c = s.client();
  fs::create_directories(out);
  const std::string victim = dir + "/victim.txt";
  { std::ofstream(victim) << "precious"; }
  fs::create_symlink(victim, out + "/e.ply.tmp-" + std::to_string(::getpid()));
  auto r = c->Post("/api/export", R"({"path": "e.ply"})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  std::string text;
  std::getline(std::ifstream(victim), text);
  EXPECT_EQ(text, "precious");

  const size_t expected = fs::file_size(out + "/e.ply");
  std::atomic<bool> done{false};
  std::atomic<int> partial{0}, reads{0};
  std::thread reader([&] {
    while (!done) {
      std::error_code ec;
      const auto n = fs::file_size(out + "/same.ply", ec);
      if (!ec) {
        ++reads;
        if (n != expected) ++partial;
      }
    }
  });
  std::vector<std::thread> writers;
  std::atomic<int> failures{0};
  for (int t = 0; t < 10; ++t)
    writers.emplace_back([&] {
      auto cl = s.client();
      for (int k = 0; k < 10; ++k) {
        auto w = cl->Post("/api/export", R"({"path": "same.ply"})", "application/json");
        if (!w || w->status != 200) ++failures;
      }
    });
  for (auto& w : writers) w.join();
  done = true;
  reader.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_EQ(partial.load(), 0) << "of " << reads.load() << " reads";
  const std::vector<uint8_t> bytes = read_file_bytes(out + "/same.ply");
  EXPECT_EQ(parse_ply(bytes.data(), bytes.size(), "same.ply").size(), d.bundle.gaussians.size());
  for (const auto& e : fs::directory_iterator(out)) {  // no temporaries left (the planted link aside)
    const std::string name = e.path().filename().string();
    EXPECT_FALSE(name[0] == '.' && name.find(".tmp-") != std::string::npos) << e.path();
  }

  fs::create_directories(dir + "/outside");
  fs::create_directory_symlink(dir + "/outside", out + "/linkdir");
  r = c->Post("/api/export", R"({"path": "linkdir/newdir/x.ply"})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_FALSE(fs::exists(dir + "/outside/newdir"));
}

}  // namespace
}  // namespace isegman::server
