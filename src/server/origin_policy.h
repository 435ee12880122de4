// Which requests the local server answers (cross-site request forgery and DNS rebinding).
// A page on another site can make the browser send requests to 127.0.0.1; what tells
// them apart is the Host header (a rebinding attack names the attacker's domain there)
// and, on state-changing requests, Origin / Sec-Fetch-Site (set by the browser, not the
// page). Clients without a browser (curl, scripts) send neither Origin nor
// Sec-Fetch-Site and are let through when their Host is right.
#pragma once

#include <string>

namespace isegman::server {

struct OriginPolicy {
  std::string bound_host;  // the --host the server listens on
  int port = 0;            // the port it listens on
};

// "" when the request may be served, else why not (answered with 403).
std::string check_request_origin(const OriginPolicy& policy, const std::string& method, const std::string& host,
                                 const std::string& origin, const std::string& sec_fetch_site);

// True for "localhost", IPv4 literals and bracketed IPv6 literals: names no DNS answer
// can redirect.
bool is_literal_host(const std::string& hostname);

}  // namespace isegman::server
