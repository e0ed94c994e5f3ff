#include "raystep/render/camera.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "raystep/geometry/bounds.h"
#include "raystep/util/error.h"

namespace raystep {

ProjectiveCamera::ProjectiveCamera(const Camera& camera, int width, int height)
    : type_(camera.type), width_(width), height_(height), eye_(camera.eye) {
  if (width <= 0 || height <= 0)
    throw InputError("", 0, "camera: image size must be positive, got " + std::to_string(width) + " x " +
                                std::to_string(height));
  glm::vec3 forward = camera.look_at - camera.eye;
  if (!is_finite(camera.eye) || !is_finite(forward) || glm::dot(forward, forward) == 0.f)
    throw InputError("", 0, "camera: eye and look_at must be finite and distinct");
  // Frame (Gram-Schmidt): w backwards, u = up x w, v = w x u.
  w_ = -glm::normalize(forward);
  glm::vec3 right = glm::cross(camera.up, w_);
  float right_length = glm::length(right);
  if (!(right_length > 1e-6f * glm::length(camera.up)) || !std::isfinite(right_length))
    throw InputError("", 0, "camera: up must not be parallel to the view direction");
  u_ = right / right_length;
  v_ = glm::cross(w_, u_);

  float aspect = float(width) / float(height);
  if (type_ == CameraType::pinhole) {
    if (!(camera.fov_deg > 0.f && camera.fov_deg < 180.f))
      throw InputError("", 0, "camera: fov must lie in (0, 180) degrees");
    half_height_ = std::tan(glm::radians(camera.fov_deg) * 0.5f);
  } else {
    if (!(camera.ortho_height > 0.f) || !std::isfinite(camera.ortho_height))
      throw InputError("", 0, "camera: orthographic view height must be positive");
    half_height_ = 0.5f * camera.ortho_height;
  }
  half_width_ = half_height_ * aspect;
}

Ray ProjectiveCamera::generate(float px, float py) const {
  // Raster -> screen: x in [-half_width, half_width] left to right, y in [-half_height, half_height] upwards.
  float sx = (2.f * px / float(width_) - 1.f) * half_width_;
  float sy = (1.f - 2.f * py / float(height_)) * half_height_;
  Ray ray;
  if (type_ == CameraType::pinhole) {
    ray.origin = eye_;
    ray.direction = glm::normalize(sx * u_ + sy * v_ - w_);
  } else {
    ray.origin = eye_ + sx * u_ + sy * v_;
    ray.direction = -w_;
  }
  return ray;
}

bool ProjectiveCamera::project(const glm::vec3& p, glm::dvec2* raster) const {
  glm::dvec3 d = glm::dvec3(p) - glm::dvec3(eye_);
  double sx = glm::dot(d, glm::dvec3(u_)), sy = glm::dot(d, glm::dvec3(v_));
  if (type_ == CameraType::pinhole) {
    double depth = -glm::dot(d, glm::dvec3(w_));
    if (!(depth > 0.0)) return false;
    sx /= depth;
    sy /= depth;
  }
  raster->x = (sx / half_width_ + 1.0) * 0.5 * width_;
  raster->y = (1.0 - sy / half_height_) * 0.5 * height_;
  return true;
}

std::vector<Ray> camera_rays(const Camera& camera, int width, int height) {
  ProjectiveCamera cam(camera, width, height);
  std::vector<Ray> rays;
  rays.reserve(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) rays.push_back(cam.generate(float(x) + 0.5f, float(y) + 0.5f));
  return rays;
}

}  // namespace raystep
