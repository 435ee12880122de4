// A click in a camera's image: the one click type from the web page (and the command
// line) through the API and the segmentation session to SAM.
//
// Coordinates are continuous pixel coordinates of that camera's image, x right, y down,
// with the convention of README "Conventions": pixel (i, j) covers [i, i+1) x [j, j+1),
// so its centre is (i + 0.5, j + 0.5) and the image spans [0, width) x [0, height). In
// this convention changing resolution is a plain scale (no half-pixel terms), so a click
// moves between a camera and its resized working view by multiplying. SAM's own point
// convention (pixel indices; its prompt encoder adds the 0.5) is applied inside
// models/sam.cc only.
#pragma once

namespace isegman {

struct Click {
  double x = 0, y = 0;  // continuous pixel coordinates
  int label = 1;        // 1 positive, 0 negative
};

// The centre of pixel (i, j): how integer pixel positions (mask and scribble pixels,
// `segment --click i,j`, prompts.json) become clicks.
inline Click pixel_centre_click(double i, double j, int label) { return {i + 0.5, j + 0.5, label}; }

// The same point in the image resized from (w, h) to (w2, h2).
inline Click rescaled(const Click& c, double w, double h, double w2, double h2) {
  return {c.x * (w2 / w), c.y * (h2 / h), c.label};
}

}  // namespace isegman
