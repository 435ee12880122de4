#include "server/validation.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "server/http_error.h"

namespace isegman::server {
namespace {

std::string range_text(double lo, double hi) {
  std::ostringstream s;
  s << "[" << lo << ", " << hi << "]";
  return s.str();
}

double checked(double v, const std::string& field, double lo, double hi) {
  if (!std::isfinite(v)) bad_request(field + ": must be a finite number");
  if (v < lo || v > hi) {
    std::ostringstream s;
    s << field << ": " << v << " is outside " << range_text(lo, hi);
    bad_request(s.str());
  }
  return v;
}

}  // namespace

double parse_number(const std::string& text, const std::string& field, double lo, double hi) {
  if (text.empty() || text.size() > 64) bad_request(field + ": expected a number");
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (end != begin + text.size() || errno == ERANGE || std::isspace(static_cast<unsigned char>(text[0])))
    bad_request(field + ": '" + text + "' is not a number");
  return checked(v, field, lo, hi);
}

int parse_integer(const std::string& text, const std::string& field, int lo, int hi) {
  const double v = parse_number(text, field, lo, hi);
  if (v != std::floor(v)) bad_request(field + ": '" + text + "' is not a whole number");
  return int(v);
}

bool parse_flag(const std::string& text, const std::string& field) {
  if (text == "1" || text == "true") return true;
  if (text == "0" || text == "false") return false;
  bad_request(field + ": expected 0, 1, true or false, got '" + text.substr(0, 32) + "'");
}

Vec3 parse_vec3(const std::string& text, const std::string& field, double limit) {
  std::vector<std::string> parts;
  std::string item;
  std::stringstream ss(text);
  while (std::getline(ss, item, ',')) parts.push_back(item);
  if (parts.size() != 3 || text.empty() || text.back() == ',') bad_request(field + ": expected x,y,z");
  return {parse_number(parts[0], field + ".x", -limit, limit), parse_number(parts[1], field + ".y", -limit, limit),
          parse_number(parts[2], field + ".z", -limit, limit)};
}

edit::Rgb parse_rgb(const std::string& text, const std::string& field) {
  if (text.size() > 64) bad_request(field + ": colour text too long");
  try {
    return edit::parse_color(text);
  } catch (const std::exception& e) {
    bad_request(field + ": " + e.what());
  }
}

json parse_body(const std::string& body, size_t max_bytes) {
  if (body.size() > max_bytes) throw HttpError(413, "request body larger than " + std::to_string(max_bytes) + " bytes");
  if (body.empty()) bad_request("the request body is empty; this endpoint expects a JSON object");
  json j = json::parse(body, nullptr, false);
  if (j.is_discarded()) bad_request("the request body is not valid JSON");
  if (!j.is_object()) bad_request("the request body must be a JSON object");
  return j;
}

void json_only_keys(const json& j, std::initializer_list<const char*> allowed) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (ok) continue;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    bad_request("unknown field '" + it.key().substr(0, 40) + "' (expected: " + list + ")");
  }
}

double json_number(const json& j, const std::string& key, double lo, double hi, std::optional<double> fallback) {
  auto it = j.find(key);
  if (it == j.end() || it->is_null()) {
    if (fallback) return *fallback;
    bad_request("missing field '" + key + "'");
  }
  if (!it->is_number()) bad_request(key + ": expected a number");
  return checked(it->get<double>(), key, lo, hi);
}

int json_integer(const json& j, const std::string& key, int lo, int hi, std::optional<int> fallback) {
  auto it = j.find(key);
  if (it == j.end() || it->is_null()) {
    if (fallback) return *fallback;
    bad_request("missing field '" + key + "'");
  }
  if (!it->is_number()) bad_request(key + ": expected a whole number");
  const double v = checked(it->get<double>(), key, lo, hi);
  if (v != std::floor(v)) bad_request(key + ": expected a whole number");
  return int(v);
}

bool json_bool(const json& j, const std::string& key, std::optional<bool> fallback) {
  auto it = j.find(key);
  if (it == j.end() || it->is_null()) {
    if (fallback) return *fallback;
    bad_request("missing field '" + key + "'");
  }
  if (!it->is_boolean()) bad_request(key + ": expected true or false");
  return it->get<bool>();
}

std::string json_string(const json& j, const std::string& key, size_t max_length, std::optional<std::string> fallback) {
  auto it = j.find(key);
  if (it == j.end() || it->is_null()) {
    if (fallback) return *fallback;
    bad_request("missing field '" + key + "'");
  }
  if (!it->is_string()) bad_request(key + ": expected a string");
  std::string s = it->get<std::string>();
  if (s.size() > max_length) bad_request(key + ": longer than " + std::to_string(max_length) + " characters");
  if (s.find('\0') != std::string::npos) bad_request(key + ": contains a NUL character");
  return s;
}

Vec3 json_vec3(const json& j, const std::string& key, double limit, std::optional<Vec3> fallback) {
  auto it = j.find(key);
  if (it == j.end() || it->is_null()) {
    if (fallback) return *fallback;
    bad_request("missing field '" + key + "'");
  }
  if (!it->is_array() || it->size() != 3) bad_request(key + ": expected [x, y, z]");
  double c[3];
  for (int k = 0; k < 3; ++k) {
    if (!(*it)[k].is_number()) bad_request(key + ": expected [x, y, z] numbers");
    c[k] = checked((*it)[k].get<double>(), key, -limit, limit);
  }
  return {c[0], c[1], c[2]};
}

}  // namespace isegman::server
