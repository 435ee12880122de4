#include "server/api.h"

#include <httplib.h>

#include <memory>
#include <new>
#include <regex>
#include <vector>

#include "core/error.h"
#include "server/api_json.h"
#include "server/app_error.h"
#include "server/app_state.h"
#include "server/http_error.h"
#include "server/validation.h"
#include "server/web_assets.h"

using nlohmann::json;

namespace isegman::server {

namespace {

void send_json(httplib::Response& res, const json& j, int status = 200) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(j.dump(), "application/json");
}

void send_error(httplib::Response& res, int status, const std::string& message) {
  send_json(res, {{"error", message}, {"status", status}}, status);
}

// The status code of an app error: the one place that knows both.
int status_for(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kInvalid: return 400;
    case ErrorKind::kNotFound: return 404;
    case ErrorKind::kConflict: return 409;
    case ErrorKind::kUnavailable: return 409;
    case ErrorKind::kBusy: return 503;
  }
  return 500;
}

// Runs a handler, turning every exception into an error response: the server never
// dies on a request.
template <typename Fn>
httplib::Server::Handler guarded(Fn fn) {
  return [fn](const httplib::Request& req, httplib::Response& res) {
    try {
      fn(req, res);
    } catch (const HttpError& e) {
      send_error(res, e.status(), e.what());
    } catch (const AppError& e) {
      send_error(res, status_for(e.kind()), e.what());
    } catch (const Error& e) {
      send_error(res, 400, e.what());
    } catch (const json::exception& e) {
      send_error(res, 400, std::string("bad JSON: ") + e.what());
    } catch (const std::bad_alloc&) {
      send_error(res, 503, "out of memory for this request");
    } catch (const std::exception& e) {
      send_error(res, 500, std::string("internal error: ") + e.what());
    } catch (...) {
      send_error(res, 500, "internal error");
    }
  };
}

std::string param(const httplib::Request& req, const std::string& name) {
  if (req.get_param_value_count(name) > 1) bad_request(name + ": given more than once");
  return req.get_param_value(name);
}

void check_params(const httplib::Request& req, std::initializer_list<const char*> allowed) {
  for (const auto& [name, value] : req.params) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || name == a;
    if (!ok) bad_request("unknown parameter '" + name.substr(0, 40) + "'");
  }
}

RenderRequest parse_render(const httplib::Request& req) {
  check_params(req, {"view", "eye", "target", "up", "fov", "width", "height", "size", "highlight", "tint", "format", "bg", "t"});
  RenderRequest r;
  const bool has_view = req.has_param("view"), has_eye = req.has_param("eye");
  if (has_view == has_eye) bad_request("give either view=K or a free camera (eye, target, up, fov, width, height)");
  if (has_view) {
    r.camera_index = parse_integer(param(req, "view"), "view", 0, 1 << 20);
  } else {
    FreeCameraSpec s;
    s.eye = parse_vec3(param(req, "eye"), "eye", 1e7);
    if (!req.has_param("target")) bad_request("missing parameter 'target'");
    s.target = parse_vec3(param(req, "target"), "target", 1e7);
    if (req.has_param("up")) s.up = parse_vec3(param(req, "up"), "up", 1e7);
    if (req.has_param("fov")) s.fov_x_deg = parse_number(param(req, "fov"), "fov", 5, 150);
    if (req.has_param("width")) s.width = parse_integer(param(req, "width"), "width", 16, 4096);
    if (req.has_param("height")) s.height = parse_integer(param(req, "height"), "height", 16, 4096);
    r.free = s;
  }
  if (req.has_param("size")) {
    const std::string s = param(req, "size");
    r.max_side = s == "full" ? 0 : parse_integer(s, "size", 32, 4096);
  } else {
    r.max_side = r.free ? 0 : 640;
  }
  if (req.has_param("highlight")) r.highlight = parse_flag(param(req, "highlight"), "highlight");
  if (req.has_param("tint")) r.tint = float(parse_number(param(req, "tint"), "tint", 0, 1));
  if (req.has_param("format")) {
    const std::string f = param(req, "format");
    if (f != "jpeg" && f != "png") bad_request("format: expected jpeg or png");
    r.png = f == "png";
  }
  if (req.has_param("bg")) r.background = parse_rgb(param(req, "bg"), "bg");
  return r;
}

// The route table, kept for answering a known path with the wrong method: 405 + Allow.
struct Routes {
  httplib::Server& server;
  std::vector<std::pair<std::string, std::regex>> list;  // method, pattern

  void get(const std::string& pattern, httplib::Server::Handler h) {
    list.emplace_back("GET", std::regex(pattern));
    server.Get(pattern, std::move(h));
  }
  void post(const std::string& pattern, httplib::Server::Handler h) {
    list.emplace_back("POST", std::regex(pattern));
    server.Post(pattern, std::move(h));
  }
  // "GET, HEAD" / "POST" for a path some route matches; "" for none.
  std::string allowed(const std::string& path) const {
    bool get = false, post = false;
    for (const auto& [method, re] : list)
      if (std::regex_match(path, re)) (method == "GET" ? get : post) = true;
    std::string a = get ? "GET, HEAD" : "";
    if (post) a += std::string(a.empty() ? "" : ", ") + "POST";
    return a;
  }
};

void serve_asset(const std::string& path, httplib::Response& res) {
  const WebAsset* a = find_web_asset(path);
  if (!a) throw HttpError(404, "no such page: " + path.substr(0, 100));
  res.set_header("Cache-Control", "no-cache");
  res.set_content(a->data, a->size, mime_type_for(path).c_str());
}

}  // namespace

void register_routes(httplib::Server& server, AppState& app) {
  auto routes = std::make_shared<Routes>(Routes{server, {}});
  routes->get("/", guarded([](const httplib::Request&, httplib::Response& res) { serve_asset("/index.html", res); }));
  for (const WebAsset& a : web_assets()) {
    const std::string path = a.path;
    routes->get(path, guarded([path](const httplib::Request&, httplib::Response& res) { serve_asset(path, res); }));
  }

  routes->get("/api/scene", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, to_json(app.scene_info()));
  }));
  routes->get("/api/status", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, to_json(app.status()));
  }));
  routes->get("/api/render", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const RenderRequest r = parse_render(req);
    const std::vector<uint8_t> bytes = app.render(r);
    res.set_header("Cache-Control", "no-store");
    res.set_content(reinterpret_cast<const char*>(bytes.data()), bytes.size(), r.png ? "image/png" : "image/jpeg");
  }));
  routes->get("/api/thumb", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    check_params(req, {"index", "v"});
    if (!req.has_param("index")) bad_request("missing parameter 'index'");
    const std::vector<uint8_t> bytes = app.thumbnail(parse_integer(param(req, "index"), "index", 0, 1 << 20));
    res.set_header("Cache-Control", "no-store");
    res.set_content(reinterpret_cast<const char*>(bytes.data()), bytes.size(), "image/jpeg");
  }));
  // The page's WebGL renderer: the scene and the selection as binary records (scene_binary.h).
  routes->get("/api/splats", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    check_params(req, {"v"});
    const std::vector<uint8_t> bytes = app.splats();
    res.set_header("Cache-Control", "no-store");
    res.set_content(reinterpret_cast<const char*>(bytes.data()), bytes.size(), "application/octet-stream");
  }));
  routes->get("/api/selection/mask", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    check_params(req, {"v"});
    const std::vector<uint8_t> bytes = app.selection_mask();
    res.set_header("Cache-Control", "no-store");
    res.set_content(reinterpret_cast<const char*>(bytes.data()), bytes.size(), "application/octet-stream");
  }));
  // Pick-to-focus: the surface point under x, y (pixels of the view's full-size image).
  routes->get("/api/pick", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    if (!req.has_param("x") || !req.has_param("y")) bad_request("missing parameter 'x' or 'y'");
    const double x = parse_number(param(req, "x"), "x", 0, 1e6), y = parse_number(param(req, "y"), "y", 0, 1e6);
    httplib::Request view = req;
    view.params.erase("x");
    view.params.erase("y");
    const PickResult p = app.pick(parse_render(view), x, y);
    json j = {{"hit", p.hit}};
    if (p.hit) j.update({{"point", {p.point.x, p.point.y, p.point.z}}, {"depth", p.depth}});
    send_json(res, j);
  }));
  routes->post(R"(/api/display/(hide|isolate|show))", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const std::string op = req.matches[1].str();
    const DisplayResult r = app.display(op == "hide" ? DisplayOp::kHide : op == "isolate" ? DisplayOp::kIsolate : DisplayOp::kShowAll);
    send_json(res, {{"label", r.label}, {"hidden", r.hidden}, {"revision", r.revision}});
  }));
  routes->get("/api/selection/bounds", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, to_json(app.selection_bounds()));
  }));
  routes->get("/api/export", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    check_params(req, {"format"});
    const std::string f = req.has_param("format") ? param(req, "format") : "ply";
    if (f != "ply" && f != "compressed.ply" && f != "splat" && f != "spz" && f != "sog")
      bad_request("format: expected ply, compressed.ply, splat, spz or sog");
    const std::vector<uint8_t> bytes = app.export_bytes(output_format_for_path("edited." + f));
    res.set_header("Content-Disposition", "attachment; filename=\"edited." + f + "\"");
    res.set_header("Cache-Control", "no-store");
    res.set_content(reinterpret_cast<const char*>(bytes.data()), bytes.size(), "application/octet-stream");
  }));
  routes->get(R"(/api/jobs/(\d{1,18}))", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const JobStatus s = app.jobs().find(std::stoull(req.matches[1].str()));
    if (s.state.empty()) throw HttpError(404, "no job " + req.matches[1].str());
    send_json(res, to_json(s));
  }));

  routes->post("/api/click", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const uint64_t id = app.click(click_from_json(parse_body(req.body)));
    send_json(res, {{"job", id}}, 202);
  }));
  // The camera the user looks at: the views a click there would use are built ahead.
  routes->post("/api/focus", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const json body = parse_body(req.body);
    if (!body.is_object() || !body.contains("view") || !body["view"].is_number_integer())
      bad_request("focus: expected {\"view\": camera index}");
    const long long view = body["view"].get<long long>();
    if (view < 0 || view >= (long long)app.camera_count()) bad_request("view: no camera " + std::to_string(view));
    app.focus(int(view));
    send_json(res, {{"focus", view}}, 202);
  }));
  // The last click's mask one step larger or smaller: {"step": 1 | -1}.
  routes->post("/api/click/granularity", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const json body = parse_body(req.body);
    json_only_keys(body, {"step"});
    send_json(res, {{"job", app.granularity(json_integer(body, "step", -1, 1))}}, 202);  // 0: refused by the job's check
  }));
  routes->post("/api/click/undo", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, {{"job", app.undo_click()}}, 202);
  }));
  routes->post("/api/click/redo", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, {{"job", app.redo_click()}}, 202);
  }));
  routes->post("/api/settings", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    send_json(res, {{"job", app.set_settings(settings_from_json(parse_body(req.body)))}}, 202);
  }));
  routes->post(R"(/api/select/([a-z]{1,16}))", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const json body = req.body.empty() ? json::object() : parse_body(req.body);
    send_json(res, to_json(app.select(select_from_json(req.matches[1].str(), body))));
  }));
  // The one history of clicks, selections and edits; 200 with the step walked (its kind,
  // and a job when it was a click).
  routes->post("/api/undo", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, to_json(app.undo()));
  }));
  routes->post("/api/redo", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, to_json(app.redo()));
  }));
  routes->post("/api/edit/undo", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, to_json(app.undo_edit()));
  }));
  routes->post("/api/edit/redo", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, to_json(app.redo_edit()));
  }));
  routes->post(R"(/api/edit/([a-z]{1,16}))", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const json body = req.body.empty() ? json::object() : parse_body(req.body);
    send_json(res, to_json(app.edit(edit_from_json(req.matches[1].str(), body), scene_source_from_json(body))));
  }));
  // Scenes to combine: the data folder's and the uploaded ones; an upload is the raw file.
  routes->get("/api/files", guarded([&app](const httplib::Request&, httplib::Response& res) {
    send_json(res, {{"data_dir", app.data_folder()},
                    {"files", to_json(app.data_files())},
                    {"uploads", to_json(app.uploads())},
                    {"max_upload_bytes", app.options().max_upload_bytes}});
  }));
  routes->post("/api/upload", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    check_params(req, {"name"});
    if (!req.has_param("name")) bad_request("missing parameter 'name' (the file's name, e.g. scene.spz)");
    send_json(res, to_json(app.upload(param(req, "name"), req.body)));
  }));
  routes->post("/api/export", guarded([&app](const httplib::Request& req, httplib::Response& res) {
    const json body = parse_body(req.body);
    json_only_keys(body, {"path"});
    send_json(res, to_json(app.export_to(json_string(body, "path", 200))));
  }));

  server.set_error_handler([routes](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    if (res.status == 404) {
      const std::string allow = routes->allowed(req.path);
      if (!allow.empty()) {
        res.set_header("Allow", allow);
        send_error(res, 405, req.method.substr(0, 16) + " is not allowed on " + req.path.substr(0, 100) +
                                 " (allowed: " + allow + ")");
        return;
      }
      send_error(res, 404, "no such endpoint: " + req.method.substr(0, 16) + " " + req.path.substr(0, 100));
      return;
    }
    std::string what = "request failed";
    if (res.status == 400) what = "malformed request (request line, headers or body could not be read)";
    else if (res.status == 413) what = "request body too large";
    else if (res.status == 414) what = "request URI too long";
    send_error(res, res.status, what);
  });
}

}  // namespace isegman::server
