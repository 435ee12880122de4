// A deterministic synthetic scene for the demo and for tests with known ground truth:
// a textured ground plane, several distinctly coloured objects built from surface-
// aligned flat Gaussians, and orbit cameras around them. World z points up.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman {

struct DemoObject {
  std::string name;
  Vec3 center;
  float radius;  // bounding sphere
};

struct DemoScene {
  SceneBundle bundle;
  std::vector<int> labels;  // per Gaussian: -1 ground, otherwise index into objects
  std::vector<DemoObject> objects;
};

struct DemoSceneOptions {
  int cameras = 24;            // orbit cameras (two rings)
  int width = 640, height = 480;
  float density = 1.0f;        // multiplies the number of Gaussians (~30k at 1.0)
  int sh_degree = 3;
  unsigned seed = 7;
};

DemoScene make_demo_scene(const DemoSceneOptions& options = {});

// Per-Gaussian membership of one object.
std::vector<bool> demo_object_mask(const DemoScene& demo, int object);

// Puts the Gaussians, and their labels, in a fixed random order (std::shuffle with
// mt19937_64(seed)): a trained scene keeps its Gaussians in no spatial order, where the demo
// builds them object by object.
void scatter_gaussian_order(DemoScene& demo, uint64_t seed);
// A click on an object: the first camera (from `first_camera` on, wrapping) in which the
// object's centre projects inside the image and is what that pixel shows. Returns the
// camera index and the pixel (SAM convention: pixel x, y), or false when none sees it.
bool demo_click(const DemoScene& demo, int object, int& camera, double& x, double& y, int first_camera = 0);

}  // namespace isegman
