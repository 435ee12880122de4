#include "server/origin_policy.h"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>

namespace isegman::server {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// Splits "name:port" / "[v6]:port"; port -1 when absent, -2 when malformed.
void split_host(const std::string& host, std::string& name, int& port) {
  port = -1;
  size_t colon = std::string::npos;
  if (!host.empty() && host[0] == '[') {
    const size_t close = host.find(']');
    if (close == std::string::npos) {
      name = host;
      port = -2;
      return;
    }
    name = host.substr(0, close + 1);
    if (close + 1 < host.size()) {
      if (host[close + 1] != ':') port = -2;
      colon = close + 1;
    }
  } else {
    colon = host.rfind(':');
    name = host.substr(0, colon);
  }
  if (colon != std::string::npos && port != -2) {
    const std::string p = host.substr(colon + 1);
    if (p.empty() || p.size() > 5 || !std::all_of(p.begin(), p.end(), ::isdigit)) port = -2;
    else port = std::stoi(p);
  }
}

bool safe_method(const std::string& m) { return m == "GET" || m == "HEAD" || m == "OPTIONS"; }

}  // namespace

bool is_literal_host(const std::string& hostname) {
  const std::string h = lower(hostname);
  if (h == "localhost") return true;
  unsigned char buf[16];
  if (h.size() > 2 && h.front() == '[' && h.back() == ']')
    return inet_pton(AF_INET6, h.substr(1, h.size() - 2).c_str(), buf) == 1;
  return inet_pton(AF_INET, h.c_str(), buf) == 1;
}

std::string check_request_origin(const OriginPolicy& policy, const std::string& method, const std::string& host,
                                 const std::string& origin, const std::string& sec_fetch_site) {
  if (host.empty()) return "the Host header is missing";
  std::string name;
  int port;
  split_host(lower(host), name, port);
  if (port == -2) return "the Host header '" + host.substr(0, 80) + "' is malformed";
  if ((port == -1 ? 80 : port) != policy.port)
    return "the Host header '" + host.substr(0, 80) + "' names another port than this server's (" +
           std::to_string(policy.port) + ")";
  // A DNS name could be rebound to this machine by someone else's DNS server: only names
  // that cannot (IP literals, localhost) or the --host given at launch are served.
  if (!is_literal_host(name) && name != lower(policy.bound_host))
    return "the Host header '" + host.substr(0, 80) +
           "' is not this server's address (use http://127.0.0.1:" + std::to_string(policy.port) + "/)";
  if (safe_method(method)) return "";
  if (!origin.empty()) {
    if (lower(origin) != "http://" + lower(host))
      return "cross-site request refused: Origin '" + origin.substr(0, 80) + "' is not this server (http://" +
             host.substr(0, 80) + ")";
    return "";
  }
  const std::string site = lower(sec_fetch_site);
  if (!site.empty() && site != "same-origin" && site != "none")
    return "cross-site request refused (Sec-Fetch-Site: " + sec_fetch_site.substr(0, 40) + ")";
  return "";
}

}  // namespace isegman::server
