#include "server/serve.h"

#include <pthread.h>
#include <signal.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "core/error.h"
#include "server/http_server.h"

namespace isegman::server {

int serve_scene(const SceneBundle& bundle, const ServeOptions& options) {
  if (bundle.cameras.empty()) throw Error(bundle.ply_path, "the web app needs cameras (give --cameras FILE)");
  // Block the stop signals in every thread started from here on; this thread waits for them.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  sigset_t previous;
  pthread_sigmask(SIG_BLOCK, &stop_signals, &previous);

  int code = 0;
  {
    AppState app(bundle, options.app);
    HttpLimits limits;
    limits.max_upload_bytes = size_t(options.app.max_upload_bytes);
    HttpServer http(app, limits);
    const int port = http.start(options.host, options.port);
    std::printf("isegman serve: %zu Gaussians, %zu cameras; exports go to %s\n", bundle.gaussians.size(),
                bundle.cameras.size(), options.app.out_dir.c_str());
    std::printf("listening on http://%s:%d/  (Ctrl-C stops)\n", options.host.c_str(), port);
    if (options.host != "127.0.0.1" && options.host != "localhost" && options.host != "::1")
      std::printf("warning: --host %s is reachable from other machines: anyone who can connect can view the scene, "
                  "edit it and export under %s (docs/security.md)\n",
                  options.host.c_str(), options.app.out_dir.c_str());
    std::fflush(stdout);
    app.start();
    timespec wait{};
    const bool limited = options.max_seconds > 0;
    wait.tv_sec = limited ? time_t(options.max_seconds) : 3600;
    wait.tv_nsec = limited ? long((options.max_seconds - std::floor(options.max_seconds)) * 1e9) : 0;
    for (;;) {
      const int sig = sigtimedwait(&stop_signals, nullptr, &wait);
      if (sig == SIGINT || sig == SIGTERM) {
        std::printf("isegman serve: stopping (signal %d)\n", sig);
        break;
      }
      if (sig < 0 && errno == EAGAIN && limited) {
        std::printf("isegman serve: stopping after %.0f s (--max-seconds)\n", options.max_seconds);
        break;
      }
    }
    std::fflush(stdout);
    http.stop();
    app.stop();
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return code;
}

}  // namespace isegman::server
