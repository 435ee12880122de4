#include "server/web_assets.h"

namespace isegman::server {

const WebAsset* find_web_asset(const std::string& path) {
  for (const WebAsset& a : web_assets())
    if (path == a.path) return &a;
  return nullptr;
}

std::string mime_type_for(const std::string& path) {
  auto ends = [&](const std::string& s) { return path.size() >= s.size() && path.compare(path.size() - s.size(), s.size(), s) == 0; };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js") || ends(".mjs")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".svg")) return "image/svg+xml";
  if (ends(".png")) return "image/png";
  if (ends(".json")) return "application/json";
  return "application/octet-stream";
}

}  // namespace isegman::server
