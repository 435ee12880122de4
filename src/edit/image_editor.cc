#include "edit/image_editor.h"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/image_io.h"

namespace fs = std::filesystem;

namespace isegman::edit {
namespace {

using Clock = std::chrono::steady_clock;

Image fit_to(const Image& edited, const Image& input) {
  if (edited.width == input.width && edited.height == input.height) return edited;
  return resize_image(edited, input.width, input.height);
}

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

float luminance(float r, float g, float b) { return 0.299f * r + 0.587f * g + 0.114f * b; }

// ---------------------------------------------------------------------------------------
// builtin

struct NamedColor {
  const char* word;
  float rgb[3];
};
const NamedColor kColors[] = {
    {"gold", {1.00f, 0.78f, 0.25f}},   {"golden", {1.00f, 0.78f, 0.25f}}, {"silver", {0.80f, 0.82f, 0.86f}},
    {"bronze", {0.80f, 0.50f, 0.20f}}, {"copper", {0.85f, 0.45f, 0.30f}}, {"red", {0.90f, 0.10f, 0.10f}},
    {"green", {0.15f, 0.80f, 0.20f}},  {"blue", {0.15f, 0.30f, 0.95f}},   {"yellow", {0.95f, 0.90f, 0.15f}},
    {"orange", {1.00f, 0.55f, 0.10f}}, {"purple", {0.55f, 0.20f, 0.80f}}, {"pink", {1.00f, 0.50f, 0.75f}},
    {"white", {0.95f, 0.95f, 0.95f}},  {"black", {0.08f, 0.08f, 0.08f}},
};

class BuiltinEditor : public ImageEditor {
 public:
  BuiltinEditor(std::string spec, bool grayscale, bool fixed, const float rgb[3])
      : spec_(std::move(spec)), grayscale_(grayscale), fixed_(fixed) {
    for (int c = 0; c < 3; ++c) rgb_[c] = rgb ? rgb[c] : 0.f;
  }
  std::string describe() const override { return spec_ + " (built-in deterministic editor, not InstructPix2Pix)"; }
  Image edit(const EditRequest& r) override {
    const Image& in = *r.image;
    if (in.channels != 3) throw Error(spec_, "expects a 3-channel image");
    float target[3] = {rgb_[0], rgb_[1], rgb_[2]};
    if (!grayscale_ && !fixed_ && !instruction_color(r.instruction, target)) {
      std::string names;
      for (const auto& c : kColors) names += std::string(names.empty() ? "" : ", ") + c.word;
      throw Error(spec_, "the instruction '" + r.instruction + "' names no colour it knows (" + names +
                             "); use builtin:recolor=r,g,b for another colour");
    }
    if (r.mask && (r.mask->width != in.width || r.mask->height != in.height))
      throw Error(spec_, "mask size differs from the image size");
    Image out = in;
    for (int y = 0; y < in.height; ++y)
      for (int x = 0; x < in.width; ++x) {
        const float m = r.mask ? std::min(1.f, std::max(0.f, r.mask->at(x, y))) : 1.f;
        if (m <= 0.f) continue;
        const float lum = luminance(in.at(x, y, 0), in.at(x, y, 1), in.at(x, y, 2));
        for (int c = 0; c < 3; ++c) {
          const float v = grayscale_ ? lum : std::min(1.f, std::max(0.f, target[c] * (0.35f + 0.9f * lum)));
          out.at(x, y, c) = in.at(x, y, c) + m * (v - in.at(x, y, c));
        }
      }
    return out;
  }

 private:
  std::string spec_;
  bool grayscale_, fixed_;
  float rgb_[3];
};

// ---------------------------------------------------------------------------------------
// command

class TempDir {
 public:
  TempDir() {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/isegman-editor-XXXXXX";
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) throw Error(pattern, std::string("cannot create a temporary folder: ") + std::strerror(errno));
    path_ = buf.data();
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string tail_of_file(const std::string& path, size_t n) {
  std::ifstream f(path, std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (s.size() > n) s = "..." + s.substr(s.size() - n);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s;
}

class CommandEditor : public ImageEditor {
 public:
  CommandEditor(std::string tmpl, double timeout) : tmpl_(std::move(tmpl)), timeout_(timeout) {
    if (tmpl_.find("{in}") == std::string::npos || tmpl_.find("{out}") == std::string::npos)
      throw Error("--editor-cmd", "the command template must contain {in} and {out} (got '" + tmpl_ + "')");
    if (!(timeout_ > 0)) throw Error("--editor-timeout", "must be positive");
  }
  std::string describe() const override { return "command '" + tmpl_ + "'"; }

  Image edit(const EditRequest& r) override {
    TempDir dir;
    const std::string in = dir.path() + "/in.png", out = dir.path() + "/out.png", mask = dir.path() + "/mask.png",
                      log = dir.path() + "/stderr.txt";
    write_png(in, *r.image);
    if (r.mask) write_png(mask, *r.mask);
    std::string cmd;
    for (size_t i = 0; i < tmpl_.size();) {
      auto sub = [&](const char* key, const std::string& value) {
        const size_t n = std::strlen(key);
        if (tmpl_.compare(i, n, key) != 0) return false;
        cmd += shell_quote(value);
        i += n;
        return true;
      };
      if (sub("{in}", in) || sub("{out}", out) || sub("{instruction}", r.instruction) ||
          sub("{mask}", r.mask ? mask : std::string()) || sub("{view}", r.view))
        continue;
      cmd += tmpl_[i++];
    }
    const std::string who = "editor command '" + tmpl_ + "' (view " + r.view + ")";
    const pid_t pid = fork();
    if (pid < 0) throw Error(who, std::string("cannot start: ") + std::strerror(errno));
    if (pid == 0) {
      setpgid(0, 0);
      const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      if (fd >= 0) {
        dup2(fd, 2);
        dup2(fd, 1);
        close(fd);
      }
      const int devnull = open("/dev/null", O_RDONLY);
      if (devnull >= 0) dup2(devnull, 0);
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    setpgid(pid, pid);
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_));
    int status = 0;
    for (;;) {
      const pid_t w = waitpid(pid, &status, WNOHANG);
      if (w == pid) break;
      if (w < 0 && errno != EINTR) throw Error(who, std::string("waitpid failed: ") + std::strerror(errno));
      if (Clock::now() > deadline) {
        kill(-pid, SIGKILL);
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
        throw Error(who, "timed out after " + seconds_text(timeout_) + " s (raise --editor-timeout)");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (WIFSIGNALED(status)) throw Error(who, "killed by signal " + std::to_string(WTERMSIG(status)) + details(log));
    if (WEXITSTATUS(status) != 0)
      throw Error(who, "exited with status " + std::to_string(WEXITSTATUS(status)) + details(log));
    if (!fs::exists(out)) throw Error(who, "exited successfully but wrote no image to {out}" + details(log));
    Image edited;
    try {
      edited = read_image(out, 3);
    } catch (const Error& e) {
      throw Error(who, std::string("wrote an unreadable image: ") + e.what());
    }
    return fit_to(edited, *r.image);
  }

 private:
  static std::string details(const std::string& log) {
    const std::string t = tail_of_file(log, 600);
    return t.empty() ? std::string() : "; its output ends with: " + t;
  }
  std::string tmpl_;
  double timeout_;
};

// ---------------------------------------------------------------------------------------
// http

struct Url {
  std::string host, port = "80", path = "/";
};

Url parse_url(const std::string& url) {
  const std::string scheme = "http://";
  if (url.compare(0, 8, "https://") == 0)
    throw Error("--editor-url", "https is not supported by the built-in HTTP client; use http:// (e.g. through an "
                                "ssh tunnel) for '" + url + "'");
  if (url.compare(0, scheme.size(), scheme) != 0) throw Error("--editor-url", "expected http://host[:port]/path, got '" + url + "'");
  Url u;
  std::string rest = url.substr(scheme.size());
  const size_t slash = rest.find('/');
  std::string hostport = rest.substr(0, slash);
  if (slash != std::string::npos) u.path = rest.substr(slash);
  if (!hostport.empty() && hostport[0] == '[') {  // [IPv6]:port
    const size_t close = hostport.find(']');
    if (close == std::string::npos) throw Error("--editor-url", "bad IPv6 host in '" + url + "'");
    u.host = hostport.substr(1, close - 1);
    if (close + 1 < hostport.size() && hostport[close + 1] == ':') u.port = hostport.substr(close + 2);
  } else {
    const size_t colon = hostport.rfind(':');
    u.host = hostport.substr(0, colon);
    if (colon != std::string::npos) u.port = hostport.substr(colon + 1);
  }
  if (u.host.empty()) throw Error("--editor-url", "no host in '" + url + "'");
  if (u.port.empty() || u.port.find_first_not_of("0123456789") != std::string::npos)
    throw Error("--editor-url", "bad port in '" + url + "'");
  return u;
}

class Socket {
 public:
  explicit Socket(int fd) : fd_(fd) {}
  ~Socket() {
    if (fd_ >= 0) close(fd_);
  }
  int fd() const { return fd_; }

 private:
  int fd_;
};

int remaining_ms(Clock::time_point deadline) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return ms > 0 ? int(std::min<long long>(ms, 1 << 30)) : 0;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

class HttpEditor : public ImageEditor {
 public:
  HttpEditor(std::string url, double timeout) : url_(std::move(url)), u_(parse_url(url_)), timeout_(timeout) {
    if (!(timeout_ > 0)) throw Error("--editor-timeout", "must be positive");
  }
  std::string describe() const override { return "HTTP endpoint " + url_; }

  Image edit(const EditRequest& r) override {
    const std::string who = "image editor at " + url_ + " (view " + r.view + ")";
    nlohmann::json req;
    req["instruction"] = r.instruction;
    req["view"] = r.view;
    req["width"] = r.image->width;
    req["height"] = r.image->height;
    const std::vector<uint8_t> png = encode_png(*r.image);
    req["image"] = base64_encode(png.data(), png.size());
    if (r.mask) {
      const std::vector<uint8_t> m = encode_png(*r.mask);
      req["mask"] = base64_encode(m.data(), m.size());
    }
    const std::string body = req.dump();
    std::string head = "POST " + u_.path + " HTTP/1.1\r\nHost: " + u_.host + (u_.port == "80" ? "" : ":" + u_.port) +
                       "\r\nContent-Type: application/json\r\nAccept: image/png, image/jpeg, application/json\r\n"
                       "User-Agent: isegman\r\nConnection: close\r\nContent-Length: " +
                       std::to_string(body.size()) + "\r\n\r\n";
    const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_));
    const std::string response = exchange(head + body, deadline, who);

    const size_t header_end = response.find("\r\n\r\n");
    if (header_end == std::string::npos) throw Error(who, "malformed HTTP response (no header end)");
    const std::string headers = response.substr(0, header_end);
    std::string payload = response.substr(header_end + 4);
    int status = 0;
    if (std::sscanf(headers.c_str(), "HTTP/%*d.%*d %d", &status) != 1) throw Error(who, "malformed HTTP status line");
    std::string content_type;
    bool chunked = false;
    long long content_length = -1;
    size_t pos = headers.find("\r\n");
    while (pos != std::string::npos) {
      const size_t next = headers.find("\r\n", pos + 2);
      const std::string line = headers.substr(pos + 2, next == std::string::npos ? std::string::npos : next - pos - 2);
      const size_t colon = line.find(':');
      if (colon != std::string::npos) {
        const std::string key = lower(line.substr(0, colon));
        std::string value = line.substr(colon + 1);
        value.erase(0, value.find_first_not_of(" \t"));
        if (key == "content-type") content_type = lower(value);
        if (key == "transfer-encoding" && lower(value).find("chunked") != std::string::npos) chunked = true;
        if (key == "content-length") content_length = std::atoll(value.c_str());
      }
      pos = next;
    }
    if (chunked) payload = dechunk(payload, who);
    else if (content_length >= 0) {
      if (payload.size() < size_t(content_length))
        throw Error(who, "response body truncated (" + std::to_string(payload.size()) + " of " +
                             std::to_string(content_length) + " bytes)");
      payload.resize(size_t(content_length));
    }
    if (status != 200) {
      std::string excerpt = payload.substr(0, 300);
      for (char& c : excerpt)
        if (!std::isprint(static_cast<unsigned char>(c))) c = ' ';
      throw Error(who, "HTTP status " + std::to_string(status) + (excerpt.empty() ? "" : ": " + excerpt));
    }
    std::vector<uint8_t> image_bytes;
    if (content_type.find("json") != std::string::npos) {
      nlohmann::json j;
      try {
        j = nlohmann::json::parse(payload);
      } catch (const std::exception& e) {
        throw Error(who, std::string("response is not valid JSON: ") + e.what());
      }
      if (j.contains("error")) throw Error(who, "the editor reported: " + j["error"].dump());
      if (!j.contains("image") || !j["image"].is_string()) throw Error(who, "JSON response has no \"image\" string");
      std::string b64 = j["image"].get<std::string>();
      const size_t comma = b64.find(',');
      if (b64.compare(0, 5, "data:") == 0 && comma != std::string::npos) b64 = b64.substr(comma + 1);
      image_bytes = base64_decode(b64, who);
    } else {
      image_bytes.assign(payload.begin(), payload.end());
    }
    Image edited;
    try {
      edited = decode_image(image_bytes.data(), image_bytes.size(), who, 3);
    } catch (const Error& e) {
      throw Error(who, std::string("returned an unreadable image: ") + e.what());
    }
    return fit_to(edited, *r.image);
  }

 private:
  std::string exchange(const std::string& request, Clock::time_point deadline, const std::string& who) const {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* res = nullptr;
    const int rc = getaddrinfo(u_.host.c_str(), u_.port.c_str(), &hints, &res);
    if (rc != 0) throw Error(who, std::string("cannot resolve host: ") + gai_strerror(rc));
    std::string last_error = "no address";
    int fd = -1;
    for (addrinfo* a = res; a && fd < 0; a = a->ai_next) {
      int s = socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
      if (s < 0) continue;
      fcntl(s, F_SETFL, fcntl(s, F_GETFL) | O_NONBLOCK);
      if (connect(s, a->ai_addr, a->ai_addrlen) != 0 && errno != EINPROGRESS) {
        last_error = std::strerror(errno);
        close(s);
        continue;
      }
      pollfd p{s, POLLOUT, 0};
      const int pr = poll(&p, 1, remaining_ms(deadline));
      int err = 0;
      socklen_t len = sizeof err;
      if (pr <= 0) {
        close(s);
        freeaddrinfo(res);
        throw Error(who, "timed out connecting after " + seconds_text(timeout_) + " s");
      }
      getsockopt(s, SOL_SOCKET, SO_ERROR, &err, &len);
      if (err != 0) {
        last_error = std::strerror(err);
        close(s);
        continue;
      }
      fd = s;
    }
    freeaddrinfo(res);
    if (fd < 0) throw Error(who, "cannot connect: " + last_error);
    Socket sock(fd);
    size_t sent = 0;
    while (sent < request.size()) {
      pollfd p{fd, POLLOUT, 0};
      if (poll(&p, 1, remaining_ms(deadline)) <= 0)
        throw Error(who, "timed out sending the request after " + seconds_text(timeout_) + " s");
      const ssize_t n = send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
      if (n < 0) {
        if (errno == EAGAIN || errno == EINTR) continue;
        throw Error(who, std::string("send failed: ") + std::strerror(errno));
      }
      sent += size_t(n);
    }
    std::string response;
    char buf[65536];
    for (;;) {
      pollfd p{fd, POLLIN, 0};
      const int pr = poll(&p, 1, remaining_ms(deadline));
      if (pr == 0 || (pr < 0 && errno != EINTR) || remaining_ms(deadline) == 0)
        throw Error(who, "timed out waiting for the edited image after " + seconds_text(timeout_) +
                             " s (raise --editor-timeout)");
      if (pr < 0) continue;
      const ssize_t n = recv(fd, buf, sizeof buf, 0);
      if (n < 0) {
        if (errno == EAGAIN || errno == EINTR) continue;
        throw Error(who, std::string("receive failed: ") + std::strerror(errno));
      }
      if (n == 0) break;
      response.append(buf, size_t(n));
      if (response.size() > (size_t(1) << 30)) throw Error(who, "response larger than 1 GiB");
      if (complete(response)) break;
    }
    if (response.empty()) throw Error(who, "the server closed the connection without answering");
    return response;
  }

  // True when a Content-Length response has all its bytes (Connection: close covers the rest).
  static bool complete(const std::string& r) {
    const size_t end = r.find("\r\n\r\n");
    if (end == std::string::npos) return false;
    const std::string h = lower(r.substr(0, end));
    const size_t k = h.find("\r\ncontent-length:");
    if (k == std::string::npos) return false;
    return r.size() - end - 4 >= size_t(std::atoll(h.c_str() + k + 17));
  }

  static std::string dechunk(const std::string& in, const std::string& who) {
    std::string out;
    size_t p = 0;
    for (;;) {
      const size_t eol = in.find("\r\n", p);
      if (eol == std::string::npos) throw Error(who, "malformed chunked response");
      const unsigned long n = std::strtoul(in.substr(p, eol - p).c_str(), nullptr, 16);
      p = eol + 2;
      if (n == 0) break;
      if (p + n > in.size()) throw Error(who, "truncated chunked response");
      out.append(in, p, n);
      p += n + 2;
    }
    return out;
  }

  std::string url_;
  Url u_;
  double timeout_;
};

}  // namespace

bool instruction_color(const std::string& instruction, float rgb[3], std::string* word) {
  // The last colour word wins ("turn the red vase into gold" -> gold).
  const std::string text = lower(instruction);
  size_t best_pos = std::string::npos;
  const NamedColor* best = nullptr;
  for (const auto& c : kColors) {
    const std::string w = c.word;
    for (size_t p = text.find(w); p != std::string::npos; p = text.find(w, p + 1)) {
      const bool start = p == 0 || !std::isalpha(static_cast<unsigned char>(text[p - 1]));
      const bool end = p + w.size() == text.size() || !std::isalpha(static_cast<unsigned char>(text[p + w.size()]));
      if (start && end && (best_pos == std::string::npos || p > best_pos)) {
        best_pos = p;
        best = &c;
      }
    }
  }
  if (!best) return false;
  for (int k = 0; k < 3; ++k) rgb[k] = best->rgb[k];
  if (word) *word = best->word;
  return true;
}

std::unique_ptr<ImageEditor> make_builtin_editor(const std::string& spec) {
  const std::string prefix = "builtin:";
  const std::string name = spec.compare(0, prefix.size(), prefix) == 0 ? spec.substr(prefix.size()) : spec;
  if (name == "recolor" || name == "recolour") return std::make_unique<BuiltinEditor>(prefix + name, false, false, nullptr);
  if (name == "grayscale" || name == "greyscale")
    return std::make_unique<BuiltinEditor>(prefix + name, true, false, nullptr);
  if (name.compare(0, 8, "recolor=") == 0 || name.compare(0, 9, "recolour=") == 0) {
    const std::string values = name.substr(name.find('=') + 1);
    float rgb[3];
    char extra;
    if (std::sscanf(values.c_str(), "%f,%f,%f%c", &rgb[0], &rgb[1], &rgb[2], &extra) != 3)
      throw Error("--editor", "expected builtin:recolor=r,g,b with values in [0, 1], got '" + spec + "'");
    for (float v : rgb)
      if (!(v >= 0.f && v <= 1.f)) throw Error("--editor", "colour values must be in [0, 1] in '" + spec + "'");
    return std::make_unique<BuiltinEditor>(prefix + name, false, true, rgb);
  }
  throw Error("--editor", "unknown editor '" + spec +
                              "' (built-in editors: builtin:recolor, builtin:recolor=r,g,b, builtin:grayscale)");
}

std::unique_ptr<ImageEditor> make_command_editor(const std::string& command_template, double timeout_s) {
  return std::make_unique<CommandEditor>(command_template, timeout_s);
}

std::unique_ptr<ImageEditor> make_http_editor(const std::string& url, double timeout_s) {
  return std::make_unique<HttpEditor>(url, timeout_s);
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

std::string base64_encode(const uint8_t* data, size_t size) {
  static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  for (size_t i = 0; i < size; i += 3) {
    const uint32_t v = uint32_t(data[i]) << 16 | (i + 1 < size ? uint32_t(data[i + 1]) << 8 : 0) |
                       (i + 2 < size ? uint32_t(data[i + 2]) : 0);
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += i + 1 < size ? kTable[(v >> 6) & 63] : '=';
    out += i + 2 < size ? kTable[v & 63] : '=';
  }
  return out;
}

std::vector<uint8_t> base64_decode(const std::string& text, const std::string& source) {
  std::vector<uint8_t> out;
  uint32_t acc = 0;
  int bits = 0;
  for (char c : text) {
    int v;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '+' || c == '-') v = 62;
    else if (c == '/' || c == '_') v = 63;
    else if (c == '=' || std::isspace(static_cast<unsigned char>(c))) continue;
    else throw Error(source, std::string("invalid base64 character '") + c + "'");
    acc = (acc << 6) | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(uint8_t((acc >> bits) & 0xff));
    }
  }
  return out;
}

}  // namespace isegman::edit
