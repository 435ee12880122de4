// The HTTP API of the web app: routes from URLs to AppState, with every input validated
// (validation.h, api_json.h) and every failure answered as {"error": message} with a
// 4xx/5xx status (AppError kinds map to codes here).
//
//   GET  /, /index.html, /js/*.js, /style.css    the page (embedded)
//   GET  /api/scene                              cameras, bounds, sizes
//   GET  /api/status                             jobs, segmentation, edit state, log
//   GET  /api/render?view=K|eye=..&target=..&up=..&fov=..&width=..&height=..
//                   [&size=N|full][&highlight=0|1][&format=jpeg|png][&bg=#rrggbb]
//   GET  /api/thumb?index=K                      evidence thumbnail of a segmentation view
//   GET  /api/selection/bounds                   box/sphere of the selection (or scene)
//   GET  /api/export?format=ply|splat            download of the edited scene
//   POST /api/click {view | camera, x, y, label} a segmentation round (a job)
//   POST /api/click/undo, /api/click/redo        (jobs)
//   POST /api/settings {tau, views, mode, inspection}   (a job)
//   POST /api/select/{box,sphere,invert,clear,all}
//   POST /api/edit/{remove,extract,colorize,scale,copy,transform,combine} (edit/edit_op.h;
//        `move` = transform), /api/edit/undo, /api/edit/redo; combine reads inside --data-dir
//   POST /api/export {path}                      writes under the output directory
//   GET  /api/jobs/{id}                          one job's state
#pragma once

namespace httplib {
class Server;
}

namespace isegman::server {

class AppState;

void register_routes(httplib::Server& server, AppState& app);

}  // namespace isegman::server
