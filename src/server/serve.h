// `isegman serve` and `isegman demo --serve`: open a scene in the web app and serve it
// until interrupted (Ctrl-C / SIGTERM) or until `max_seconds` have passed.
#pragma once

#include <string>

#include "core/scene.h"
#include "server/app_state.h"

namespace isegman::server {

struct ServeOptions {
  std::string host = "127.0.0.1";  // loopback unless asked otherwise
  int port = 8080;                 // 0 = an ephemeral port (printed)
  double max_seconds = 0;          // > 0: stop by itself after this long
  AppOptions app;                  // output folder, SAM, embedding cache, segmentation settings
};

// Serves `bundle` (it needs cameras) and blocks; prints "listening on http://HOST:PORT/"
// on stdout once ready. Returns the exit code (0 after a clean stop).
int serve_scene(const SceneBundle& bundle, const ServeOptions& options);

}  // namespace isegman::server
