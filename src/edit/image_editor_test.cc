#include "edit/image_editor.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cmath>
#include <functional>
#include <string>
#include <thread>

#include "core/error.h"
#include "io/image_io.h"

namespace isegman::edit {
namespace {

Image gradient_image(int w, int h) {
  Image im(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      im.at(x, y, 0) = float(x) / w;
      im.at(x, y, 1) = float(y) / h;
      im.at(x, y, 2) = 0.5f;
    }
  return im;
}

Image half_mask(int w, int h) {
  Image m(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = w / 2; x < w; ++x) m.at(x, y) = 1.f;
  return m;
}

std::string message_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ImageEditor, BuiltinRecolorChangesOnlyTheMaskedRegionDeterministically) {
  const Image in = gradient_image(32, 24), mask = half_mask(32, 24);
  auto ed = make_builtin_editor("builtin:recolor");
  EXPECT_NE(ed->describe().find("not InstructPix2Pix"), std::string::npos);
  EditRequest r{&in, &mask, "Turn the vase into gold", "v0"};
  const Image a = ed->edit(r), b = ed->edit(r);
  EXPECT_EQ(a.data, b.data);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) {
        if (x < 16) {
          ASSERT_EQ(a.at(x, y, c), in.at(x, y, c));
        }
      }
  // Gold: red > green > blue inside the mask.
  EXPECT_GT(a.at(20, 12, 0), a.at(20, 12, 1));
  EXPECT_GT(a.at(20, 12, 1), a.at(20, 12, 2));
  float rgb[3];
  std::string word;
  ASSERT_TRUE(instruction_color("make the red car blue", rgb, &word));
  EXPECT_EQ(word, "blue");
  EXPECT_FALSE(instruction_color("make it reddish", rgb));
  EXPECT_NE(message_of([&] { EditRequest q{&in, &mask, "make it shiny", "v0"}; ed->edit(q); }).find("names no colour"),
            std::string::npos);
  EXPECT_THROW(make_builtin_editor("builtin:sepia"), Error);
  EXPECT_THROW(make_builtin_editor("builtin:recolor=1,2,0"), Error);
  auto grey = make_builtin_editor("builtin:grayscale");
  const Image g = grey->edit(r);
  EXPECT_FLOAT_EQ(g.at(20, 12, 0), g.at(20, 12, 2));
}

TEST(ImageEditor, CommandTemplateRunsTheProgramWithQuotedArguments) {
  const Image in = gradient_image(16, 12);
  // A command that copies its input and proves the instruction arrived intact.
  auto ed = make_command_editor("test \"$(printf %s {instruction})\" = \"it's a 'test' \\$HOME\" && cp {in} {out}", 10);
  EditRequest r{&in, nullptr, "it's a 'test' $HOME", "view 1"};
  const Image out = ed->edit(r);
  ASSERT_EQ(out.width, 16);
  for (size_t i = 0; i < out.data.size(); ++i) ASSERT_NEAR(out.data[i], in.data[i], 1.0 / 255);
}

TEST(ImageEditor, CommandFailuresAndTimeoutsAreClearErrors) {
  const Image in = gradient_image(8, 8);
  EditRequest r{&in, nullptr, "x", "cam7"};
  const std::string failed =
      message_of([&] { make_command_editor("echo broken model >&2; exit 3; {in} {out}", 10)->edit(r); });
  EXPECT_NE(failed.find("exited with status 3"), std::string::npos) << failed;
  EXPECT_NE(failed.find("broken model"), std::string::npos) << failed;
  EXPECT_NE(failed.find("cam7"), std::string::npos) << failed;
  const std::string nothing = message_of([&] { make_command_editor("true {in} {out}", 10)->edit(r); });
  EXPECT_NE(nothing.find("wrote no image"), std::string::npos) << nothing;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string slow = message_of([&] { make_command_editor("sleep 20; cp {in} {out}", 0.3)->edit(r); });
  EXPECT_NE(slow.find("timed out"), std::string::npos) << slow;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  EXPECT_THROW(make_command_editor("prog {in}", 10), Error);  // no {out}
}

// A one-shot HTTP server on 127.0.0.1 (ephemeral port) answering with `respond`.
class TestServer {
 public:
  explicit TestServer(std::function<std::string(const std::string& body)> respond) : respond_(std::move(respond)) {
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    if (bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || listen(fd_, 4) != 0) std::abort();
    socklen_t len = sizeof a;
    getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { serve(); });
  }
  ~TestServer() {
    shutdown(fd_, SHUT_RDWR);
    close(fd_);
    thread_.join();
  }
  std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/edit"; }
  std::string request_line;

 private:
  void serve() {
    const int c = accept(fd_, nullptr, nullptr);
    if (c < 0) return;
    std::string req;
    char buf[65536];
    size_t need = std::string::npos;
    while (need == std::string::npos || req.size() < need) {
      const ssize_t n = recv(c, buf, sizeof buf, 0);
      if (n <= 0) break;
      req.append(buf, size_t(n));
      const size_t end = req.find("\r\n\r\n");
      if (end != std::string::npos && need == std::string::npos) {
        const size_t k = req.find("Content-Length: ");
        need = end + 4 + std::stoul(req.substr(k + 16));
      }
    }
    request_line = req.substr(0, req.find("\r\n"));
    const std::string body = req.substr(req.find("\r\n\r\n") + 4);
    const std::string response = respond_(body);
    if (!response.empty()) send(c, response.data(), response.size(), MSG_NOSIGNAL);
    else std::this_thread::sleep_for(std::chrono::milliseconds(800));  // never answer in time
    close(c);
  }
  std::function<std::string(const std::string&)> respond_;
  int fd_ = -1;
  int port_ = 0;
  std::thread thread_;
};

std::string http_response(int status, const std::string& type, const std::string& body) {
  return "HTTP/1.1 " + std::to_string(status) + " X\r\nContent-Type: " + type +
         "\r\nContent-Length: " + std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body;
}

TEST(ImageEditor, HttpEndpointJsonAndRawImageResponses) {
  const Image in = gradient_image(20, 10), mask = half_mask(20, 10);
  EditRequest r{&in, &mask, "turn it into gold", "cam0"};
  {
    // JSON in, JSON out: the server inverts the image it received.
    TestServer server([](const std::string& body) {
      const auto j = nlohmann::json::parse(body);
      if (j.at("instruction") != "turn it into gold" || !j.contains("mask") || j.at("width") != 20)
        return http_response(400, "text/plain", "bad request");
      const auto bytes = base64_decode(j.at("image").get<std::string>(), "test");
      Image im = decode_image(bytes.data(), bytes.size(), "test", 3);
      for (float& v : im.data) v = 1.f - v;
      const auto png = encode_png(im);
      return http_response(200, "application/json",
                           nlohmann::json{{"image", "data:image/png;base64," + base64_encode(png.data(), png.size())}}.dump());
    });
    const Image out = make_http_editor(server.url(), 10)->edit(r);
    EXPECT_EQ(server.request_line, "POST /edit HTTP/1.1");
    ASSERT_EQ(out.width, 20);
    EXPECT_NEAR(out.at(5, 5, 0), 1.f - in.at(5, 5, 0), 1.0 / 255);
  }
  {
    // Raw PNG body at another size: resized back to the view.
    TestServer server([](const std::string&) {
      const auto png = encode_png(Image(40, 20, 3, 0.25f));
      return http_response(200, "image/png", std::string(png.begin(), png.end()));
    });
    const Image out = make_http_editor(server.url(), 10)->edit(r);
    EXPECT_EQ(out.width, 20);
    EXPECT_EQ(out.height, 10);
    EXPECT_NEAR(out.at(3, 3, 1), 0.25f, 1.0 / 255);
  }
}

TEST(ImageEditor, HttpErrorsAndTimeoutsAreClearErrors) {
  const Image in = gradient_image(8, 8);
  EditRequest r{&in, nullptr, "x", "cam3"};
  {
    TestServer server([](const std::string&) { return http_response(500, "text/plain", "CUDA out of memory"); });
    const std::string m = message_of([&] { make_http_editor(server.url(), 10)->edit(r); });
    EXPECT_NE(m.find("HTTP status 500"), std::string::npos) << m;
    EXPECT_NE(m.find("CUDA out of memory"), std::string::npos) << m;
  }
  {
    TestServer server([](const std::string&) { return std::string(); });
    const std::string m = message_of([&] { make_http_editor(server.url(), 0.4)->edit(r); });
    EXPECT_NE(m.find("timed out"), std::string::npos) << m;
  }
  EXPECT_THROW(make_http_editor("https://example.com/edit", 10), Error);
  EXPECT_THROW(make_http_editor("ftp://x", 10), Error);
  // Nothing listens on this port (bound, then closed without listening).
  int port;
  {
    const int s = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    socklen_t len = sizeof a;
    getsockname(s, reinterpret_cast<sockaddr*>(&a), &len);
    port = ntohs(a.sin_port);
    close(s);
  }
  const std::string refused =
      message_of([&] { make_http_editor("http://127.0.0.1:" + std::to_string(port) + "/", 5)->edit(r); });
  EXPECT_NE(refused.find("cannot connect"), std::string::npos) << refused;
}

TEST(ImageEditor, Base64RoundTrip) {
  const std::string s = "any carnal pleasure.";
  for (size_t n = 0; n <= s.size(); ++n) {
    const std::string enc = base64_encode(reinterpret_cast<const uint8_t*>(s.data()), n);
    const auto dec = base64_decode(enc, "t");
    EXPECT_EQ(std::string(dec.begin(), dec.end()), s.substr(0, n));
  }
  EXPECT_EQ(base64_encode(reinterpret_cast<const uint8_t*>("Man"), 3), "TWFu");
  EXPECT_THROW(base64_decode("TW*u", "t"), Error);
}

}  // namespace
}  // namespace isegman::edit
