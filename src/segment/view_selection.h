// Voting-view selection for large scenes: instead of every camera, the K views that best
// see the clicked surface point and spread around it (greedy farthest-point sampling on
// the viewing directions towards the point, weighted by how well each camera sees it).
// Per-click time and the per-view caches (prepared frames, votes, SAM embeddings,
// renders) then grow with K, not with the number of cameras.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/math.h"

namespace isegman::segment {

constexpr int kDefaultVotingViews = 20;

// "auto" or "auto:K" (K >= 1); false for any other spec (throws on a malformed "auto:").
bool parse_auto_views(const std::string& spec, int& k);

struct ViewCandidate {
  int camera = -1;
  bool sees = false;        // the point projects inside the frame, in front of the camera
  double distance = 0;      // camera centre to point
  double quality = 0;       // (0, 1]: distance close to the clicked camera's, near the centre
  Vec3 direction;           // unit, point -> camera centre
};

// How each camera sees `point` relative to the clicked camera `clicked`.
std::vector<ViewCandidate> score_views(const std::vector<Camera>& cameras, int clicked, const Vec3& point);

// Up to k cameras that see `point`, chosen greedily for angular spread around it (each
// step takes the candidate maximising quality-weighted angle to the nearest chosen
// direction); `clicked` is always first in. Returned sorted by camera index. When fewer
// than k cameras see the point, only those are returned (plus the clicked one).
std::vector<int> select_views_for_point(const std::vector<Camera>& cameras, int clicked, const Vec3& point, int k);

// How open the line of sight between two points is, in [0, 1] (line_of_sight.h).
using LineOpen = std::function<double(const Vec3& from, const Vec3& to)>;

// What each candidate sees of the clicked object, from `samples` (3D points of it, lifted
// from the clicked view's mask): the mean over them of "inside the frame" times how open the
// line of sight is up to the sphere holding the samples (so that the object's own near side
// does not hide its far side from a camera behind it). Below `min_seen` a camera is not a
// candidate (the clicked one always is); otherwise its quality is scaled by what it sees.
void weigh_by_object(std::vector<ViewCandidate>& candidates, const std::vector<Camera>& cameras, int clicked,
                     const std::vector<Vec3>& samples, const LineOpen& open, double min_seen = 0.25);

// select_views_for_point with the candidates weighed by the object they see: a view where
// the object is hidden behind something or cut by the frame loses to one that shows it.
std::vector<int> select_views_for_object(const std::vector<Camera>& cameras, int clicked, const Vec3& point,
                                         const std::vector<Vec3>& samples, const LineOpen& open, int k);

// Without a surface point: k cameras spread over all of them (farthest-point sampling on
// the camera centres, from `clicked`, or camera 0 when clicked < 0). Sorted.
std::vector<int> spread_views(const std::vector<Camera>& cameras, int clicked, int k);

}  // namespace isegman::segment
