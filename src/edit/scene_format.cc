#include "edit/scene_format.h"

namespace isegman::edit {

GaussianScene read_scene_file(const std::string& path, SceneFormat* format, std::vector<std::string>* notes) {
  LoadedGaussians l = load_gaussians(path);
  if (format) *format = l.format;
  if (notes) notes->insert(notes->end(), l.notes.begin(), l.notes.end());
  return std::move(l.scene);
}

}  // namespace isegman::edit
