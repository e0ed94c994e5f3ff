// Camera rays for the scene's camera (pbrt-v4's projective cameras, chapter 5, reduced to the lecture's two):
// a pinhole with a vertical field of view, and an orthographic camera with a view height. The aspect ratio
// comes from the image size. Raster coordinates are continuous: (0, 0) is the image's top-left corner and
// pixel (x, y) covers [x, x+1) x [y, y+1), so its centre is (x + 0.5, y + 0.5).
#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/ray.h"
#include "raystep/scene/scene.h"

namespace raystep {

class ProjectiveCamera {
 public:
  // Throws InputError for a degenerate camera: image size not positive, eye == look_at, up parallel to the
  // view direction, fov outside (0, 180) degrees, view height not positive.
  ProjectiveCamera(const Camera& camera, int width, int height);

  // The ray through raster position (px, py); unit direction, t in (0, inf).
  Ray generate(float px, float py) const;
  // The inverse: raster position of world point p. False for a point on or behind the pinhole's eye plane.
  bool project(const glm::vec3& p, glm::dvec2* raster) const;

  CameraType type() const { return type_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // Orthonormal camera frame: u right, v up, w backwards (the camera looks along -w).
  const glm::vec3& eye() const { return eye_; }
  const glm::vec3& u() const { return u_; }
  const glm::vec3& v() const { return v_; }
  const glm::vec3& w() const { return w_; }

 private:
  CameraType type_;
  int width_, height_;
  glm::vec3 eye_, u_, v_, w_;
  // Half extent of the image plane: at distance 1 for the pinhole (tan(fov/2) times aspect), in world
  // units for the orthographic camera.
  float half_width_, half_height_;
};

// One ray through each pixel's centre, row-major from the top-left pixel (`raystep rays --kind camera`).
std::vector<Ray> camera_rays(const Camera& camera, int width, int height);

}  // namespace raystep
