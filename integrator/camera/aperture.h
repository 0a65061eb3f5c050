// Aperture: the shape of the lens stop, sampled uniformly over its area.
//
// | parameter | unit | default | meaning |
// |-----------|------|---------|---------|
// | diameter  | m    | f/N     | entrance-pupil diameter D of the circular stop |
// | blades    | —    | 0       | 0: circular; N ≥ 3: a regular N-gon |
// | rotation  | rad  | 0       | polygon orientation: a vertex at angle `rotation` from +x (camera right), counter-clockwise towards +y (up) |
// | diffraction | —  | on      | the stop's Fraunhofer PSF blurs the image (Diffraction, diffraction.h) |
//
// A polygonal stop has the same area as the circle of diameter D = f/N, so exposure
// follows the f-number whatever the blade count: circumradius R = D/2 · √(2π / (N sin(2π/N))).
#pragma once

#include <glm/vec2.hpp>

namespace camsim {

// The stop as a scene describes it: its shape. Its diameter is not stored but follows
// from the f-number and focal length (PhysicalCameraParams::apertureDiameter), so a changed
// f-number changes the stop.
struct ApertureShape {
  int blades = 0;         // 0: circular; N >= 3: a regular N-gon
  double rotation = 0.0;  // rad, as Aperture's
  // camera.aperture.diffraction: the stop diffracts (on by default: at f/8 on a 5 µm pixel it
  // changes most pixels of a sharp edge; docs/camera.md, "Diffraction at the stop").
  bool diffraction = true;
};

class Aperture {
 public:
  Aperture(double diameter, int blades, double rotation);

  double area() const { return area_; }  // m²
  int blades() const { return blades_; }
  double circumradius() const { return radius_; }
  double rotation() const { return rotation_; }
  // Uniform point on the stop (camera-space x right, y up, metres) from u in [0,1)².
  glm::vec2 sample(glm::vec2 u) const;

 private:
  int blades_;
  double rotation_;
  double radius_;  // circle radius, or polygon circumradius
  double area_;
};

}  // namespace camsim
