// Camera rays: centre, edges and corners against the field of view, raster orientation, the orthographic
// view height, and project() as the inverse of generate().
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "raystep/render/camera.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

Camera pinhole(float fov) {
  Camera c;
  c.type = CameraType::pinhole;
  c.eye = glm::vec3(1.f, 2.f, 3.f);
  c.look_at = glm::vec3(1.f, 2.f, -7.f);  // looking down -z
  c.up = glm::vec3(0.f, 1.f, 0.f);
  c.fov_deg = fov;
  return c;
}

float angle_between(const glm::vec3& a, const glm::vec3& b) {
  return std::acos(glm::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.f, 1.f));
}

TEST(Camera, PinholeCentreAndFieldOfView) {
  const int w = 200, h = 100;
  ProjectiveCamera cam(pinhole(60.f), w, h);
  Ray centre = cam.generate(w / 2.f, h / 2.f);
  EXPECT_NEAR(glm::length(centre.direction), 1.f, 1e-6f);
  EXPECT_NEAR(centre.direction.z, -1.f, 1e-6f);
  EXPECT_EQ(centre.origin, glm::vec3(1.f, 2.f, 3.f));
  // Top edge centre: half the vertical fov above the axis; y = 0 is the top row.
  Ray top = cam.generate(w / 2.f, 0.f);
  EXPECT_NEAR(angle_between(top.direction, centre.direction), glm::radians(30.f), 1e-5f);
  EXPECT_GT(top.direction.y, 0.f);
  Ray bottom = cam.generate(w / 2.f, float(h));
  EXPECT_LT(bottom.direction.y, 0.f);
  // Right edge: tan(horizontal half angle) = aspect * tan(vertical half angle); x grows to the right.
  Ray right = cam.generate(float(w), h / 2.f);
  EXPECT_GT(right.direction.x, 0.f);
  EXPECT_NEAR(std::tan(angle_between(right.direction, centre.direction)), 2.f * std::tan(glm::radians(30.f)),
              1e-5f);
}

TEST(Camera, PixelCentresAreSymmetric) {
  const int w = 7, h = 5;
  ProjectiveCamera cam(pinhole(45.f), w, h);
  // Pixel (x, y) covers [x, x+1): the centres of mirrored pixels give mirrored rays.
  for (int x = 0; x < w; ++x) {
    Ray a = cam.generate(x + 0.5f, 2.5f), b = cam.generate(w - 1 - x + 0.5f, 2.5f);
    EXPECT_NEAR(a.direction.x, -b.direction.x, 1e-6f);
    EXPECT_NEAR(a.direction.y, 0.f, 1e-6f);  // the middle row is on the axis
  }
}

TEST(Camera, OrthographicViewHeight) {
  Camera c;
  c.type = CameraType::orthographic;
  c.eye = glm::vec3(0.f, 0.f, 5.f);
  c.look_at = glm::vec3(0.f);
  c.ortho_height = 4.f;
  ProjectiveCamera cam(c, 300, 200);  // view 6 x 4 world units
  Ray corner = cam.generate(0.f, 0.f);
  EXPECT_NEAR(corner.origin.x, -3.f, 1e-6f);
  EXPECT_NEAR(corner.origin.y, 2.f, 1e-6f);
  EXPECT_NEAR(corner.origin.z, 5.f, 1e-6f);
  EXPECT_EQ(corner.direction, glm::vec3(0.f, 0.f, -1.f));
  Ray far_corner = cam.generate(300.f, 200.f);
  EXPECT_NEAR(far_corner.origin.x, 3.f, 1e-6f);
  EXPECT_NEAR(far_corner.origin.y, -2.f, 1e-6f);
  EXPECT_EQ(far_corner.direction, corner.direction);
}

TEST(Camera, ProjectInvertsGenerate) {
  for (CameraType type : {CameraType::pinhole, CameraType::orthographic}) {
    Camera c = pinhole(50.f);
    c.type = type;
    c.up = glm::vec3(0.3f, 1.f, 0.2f);  // not orthogonal to the view: Gram-Schmidt must fix it
    ProjectiveCamera cam(c, 64, 48);
    EXPECT_NEAR(glm::dot(cam.u(), cam.v()), 0.f, 1e-6f);
    EXPECT_NEAR(glm::dot(cam.u(), cam.w()), 0.f, 1e-6f);
    for (float px : {0.f, 10.25f, 63.9f})
      for (float py : {0.f, 17.5f, 47.f}) {
        Ray r = cam.generate(px, py);
        glm::dvec2 raster;
        ASSERT_TRUE(cam.project(r.at(3.7f), &raster));
        EXPECT_NEAR(raster.x, px, 1e-3);
        EXPECT_NEAR(raster.y, py, 1e-3);
      }
    glm::dvec2 raster;
    if (type == CameraType::pinhole) EXPECT_FALSE(cam.project(c.eye + glm::vec3(0.f, 0.f, 1.f), &raster));
  }
}

TEST(Camera, DegenerateCamerasThrow) {
  Camera c = pinhole(40.f);
  EXPECT_THROW(ProjectiveCamera(c, 0, 10), InputError);
  EXPECT_THROW(ProjectiveCamera(c, 10, -1), InputError);
  Camera same = c;
  same.look_at = same.eye;
  EXPECT_THROW(ProjectiveCamera(same, 10, 10), InputError);
  Camera parallel = c;
  parallel.up = glm::vec3(0.f, 0.f, 2.f);
  EXPECT_THROW(ProjectiveCamera(parallel, 10, 10), InputError);
  Camera wide = c;
  wide.fov_deg = 180.f;
  EXPECT_THROW(ProjectiveCamera(wide, 10, 10), InputError);
  Camera flat = c;
  flat.type = CameraType::orthographic;
  flat.ortho_height = 0.f;
  EXPECT_THROW(ProjectiveCamera(flat, 10, 10), InputError);
  Camera nan_eye = c;
  nan_eye.eye.x = std::nanf("");
  EXPECT_THROW(ProjectiveCamera(nan_eye, 10, 10), InputError);
}

}  // namespace
}  // namespace raystep
