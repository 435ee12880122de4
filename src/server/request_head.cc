#include "server/request_head.h"

#include <algorithm>
#include <cctype>

namespace isegman::server {
namespace {

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\r')) --e;
  return s.substr(b, e - b);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

}  // namespace

HeadCheck check_request_head(const std::string& head, size_t max_body_bytes) {
  HeadCheck r;
  const size_t line_end = head.find("\r\n");
  if (line_end == std::string::npos) return {400, "malformed request line", false};
  const std::string method = head.substr(0, head.find(' '));
  bool has_length = false, chunked = false;
  std::string length_text;
  size_t pos = line_end + 2;
  while (pos < head.size()) {
    const size_t end = head.find("\r\n", pos);
    if (end == std::string::npos || end == pos) break;
    const std::string line = head.substr(pos, end - pos);
    pos = end + 2;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;  // cpp-httplib answers malformed lines itself
    const std::string name = lower(trim(line.substr(0, colon))), value = trim(line.substr(colon + 1));
    if (name == "content-length") {
      if (has_length && value != length_text)
        return {400, "conflicting Content-Length headers ('" + length_text.substr(0, 24) + "', '" +
                         value.substr(0, 24) + "')", false};
      has_length = true;
      length_text = value;
    } else if (name == "transfer-encoding") {
      chunked = true;
    }
  }
  if (chunked)
    return {411, "Transfer-Encoding is not accepted; send the body with a Content-Length (at most " +
                     std::to_string(max_body_bytes) + " bytes)", false};
  if (has_length) {
    if (length_text.empty() || !std::all_of(length_text.begin(), length_text.end(), ::isdigit))
      return {400, "Content-Length '" + length_text.substr(0, 24) + "' is not a non-negative whole number", false};
    const std::string digits = length_text.substr(std::min(length_text.find_first_not_of('0'), length_text.size()));
    if (digits.size() > 18 || std::stoull(digits.empty() ? "0" : digits) > max_body_bytes)
      return {413, "request body of " + length_text.substr(0, 24) + " bytes is larger than the limit of " +
                       std::to_string(max_body_bytes) + " bytes", false};
    return r;
  }
  r.add_zero_length = method == "POST" || method == "PUT" || method == "PATCH" || method == "DELETE";
  return r;
}

}  // namespace isegman::server
