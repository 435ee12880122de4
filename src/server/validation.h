// Strict parsing of request inputs: query parameters (text) and JSON bodies. Every
// function names the field in its error and throws HttpError(400): numbers must be finite
// and inside the given range, integers must be whole, strings bounded in length.
#pragma once

#include <initializer_list>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/math.h"
#include "edit/colorize.h"

namespace isegman::server {

using nlohmann::json;

// Query-string values.
double parse_number(const std::string& text, const std::string& field, double lo, double hi);
int parse_integer(const std::string& text, const std::string& field, int lo, int hi);
bool parse_flag(const std::string& text, const std::string& field);  // 0/1/true/false
// "x,y,z" with every component finite and |c| <= limit.
Vec3 parse_vec3(const std::string& text, const std::string& field, double limit);
// "#RRGGBB" / "RRGGBB" / "#RGB" or "r,g,b" in [0, 1] (edit::parse_color), as a 400.
edit::Rgb parse_rgb(const std::string& text, const std::string& field);

// A JSON object body (at most `max_bytes`); anything else is a 400.
json parse_body(const std::string& body, size_t max_bytes = 1 << 16);

// Refuses members other than `allowed` (a misspelt key would otherwise be ignored).
void json_only_keys(const json& j, std::initializer_list<const char*> allowed);

// Members of a JSON object. Without a fallback the member is required.
double json_number(const json& j, const std::string& key, double lo, double hi,
                   std::optional<double> fallback = std::nullopt);
int json_integer(const json& j, const std::string& key, int lo, int hi, std::optional<int> fallback = std::nullopt);
bool json_bool(const json& j, const std::string& key, std::optional<bool> fallback = std::nullopt);
std::string json_string(const json& j, const std::string& key, size_t max_length,
                        std::optional<std::string> fallback = std::nullopt);
// [x, y, z] numbers with |c| <= limit.
Vec3 json_vec3(const json& j, const std::string& key, double limit, std::optional<Vec3> fallback = std::nullopt);

}  // namespace isegman::server
