// A scene as the tracer sees it: camera, lights, materials, primitives and render settings.
// Every field but the geometry has a default (documented in docs/scene-format.md), so a scene file names
// only what it needs; the tracer spawns only the rays the materials call for.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/scene/flatland.h"
#include "raystep/scene/geometry.h"

namespace raystep {

enum class CameraType { pinhole, orthographic };

struct Camera {
  CameraType type = CameraType::pinhole;
  glm::vec3 eye{0.f, 0.f, 5.f};
  glm::vec3 look_at{0.f};
  glm::vec3 up{0.f, 1.f, 0.f};
  float fov_deg = 40.f;       // pinhole: vertical field of view
  float ortho_height = 2.f;   // orthographic: height of the view in world units
};

enum class LightType { point, directional };

struct Light {
  LightType type = LightType::point;
  glm::vec3 position{0.f, 10.f, 10.f};    // point
  glm::vec3 direction{0.f, -1.f, -1.f};   // directional: the direction the light travels
  glm::vec3 color{1.f};
  float intensity = 1.f;                  // point lights are not attenuated (Whitted)
};

struct Material {
  std::string name = "default";
  glm::vec3 diffuse{0.8f};
  glm::vec3 specular{0.f};  // Phong highlight colour; zero: no highlight
  float shininess = 32.f;
  float mirror = 0.f;        // reflectance of the mirror ray, 0..1
  float transparency = 0.f;  // transmittance of the refracted ray, 0..1
  float ior = 1.5f;          // index of refraction (used when transparency > 0)
};

// Anti-aliasing: where the samples go, and the filter that weighs them into a pixel's value.
struct AntiAliasing {
  enum class Mode { none, regular, jitter, random, adaptive };
  Mode mode = Mode::none;
  // box: the mean of the pixel's own samples (every pattern); tent: the samples of the pixel and its eight
  // neighbours weighted by (1 - |dx|)(1 - |dy|) from the pixel's centre (render/pixel_filter.h; not adaptive).
  enum class Filter { box, tent };
  Filter filter = Filter::box;
  int k = 1;                // regular/jitter: k x k samples; random: k samples (N, not a side)
  float threshold = 0.1f;   // adaptive: contrast (max - min) / (max + min) that triggers subdivision
  int max_depth = 3;        // adaptive: subdivision levels
};

struct RenderSettings {
  int width = 320;
  int height = 240;
  AntiAliasing aa;
  int max_depth = 5;              // recursion depth of reflected/refracted rays
  float min_weight = 0.01f;       // adaptive ray termination: stop a path whose weight falls below this
  glm::vec3 background{0.f};
  glm::vec3 ambient{0.f};         // ambient term added to diffuse surfaces (times the diffuse colour)
  uint64_t seed = 0;
};

struct Scene {
  std::string path;   // the file it came from (scene JSON or bare mesh)
  Camera camera;
  std::vector<Light> lights;
  std::vector<Material> materials;  // at least one; primitives refer to them by index
  Geometry geometry;
  RenderSettings render;
  // A 2D scene ("dimensions": 2): its shapes in the plane z = 0, of which `geometry` is the extrusion
  // (flatland.h); the camera looks down on the plane.
  std::optional<Flatland> flat;
};

}  // namespace raystep
