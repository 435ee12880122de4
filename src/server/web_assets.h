// The page (web/*.html, *.js, *.css) compiled into the binary at build time
// (embed_assets.cmake), so `isegman serve` needs nothing from the source tree.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace isegman::server {

struct WebAsset {
  const char* path;  // "/index.html", "/js/app.js", ...
  const char* data;
  size_t size;
};

const std::vector<WebAsset>& web_assets();
const WebAsset* find_web_asset(const std::string& path);
// Content type by extension (text types carry charset=utf-8).
std::string mime_type_for(const std::string& path);

}  // namespace isegman::server
