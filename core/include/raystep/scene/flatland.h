// Flatland: the lecture's 2D pictures as scenes. A 2D scene's shapes (segments, polylines, polygons, circles)
// lie in the plane z = 0 and become the 3D geometry that the real structures and kernels take, so a walk in
// the plane is the walk of the same code: a segment is a wall of two triangles across z in [-h, h] (the walls
// of a polygon share their vertical edges exactly, so the watertight test lets no ray through a corner), a
// circle the sphere of its radius centred in the plane (a ray in the plane meets it where it meets the
// circle), and a filled polygon also gets its cap at z = h, which a camera looking down sees as the polygon's
// area (for the pictures of aliasing; a ray in the plane never meets the cap). A ray of a 2D walk lies in the
// plane: origin z = 0, direction z = 0.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "raystep/geometry/ray.h"
#include "raystep/scene/geometry.h"

namespace raystep {

struct FlatShape {
  enum class Kind { segment, polyline, polygon, circle };
  Kind kind = Kind::segment;
  std::string name;
  uint32_t material = 0;
  std::vector<glm::vec2> points;  // segment: 2; polyline: 2 or more, open; polygon: 3 or more, closed
  bool filled = false;            // polygon: its cap too (seen from above)
  glm::vec2 center{0.f};          // circle
  float radius = 0.f;             // circle
  // Where its primitives are in the scene's geometry (set by add_flat_shapes).
  uint32_t object = 0, first_prim = 0, prim_count = 0;
};
const char* flat_kind_name(FlatShape::Kind kind);

struct Flatland {
  std::vector<FlatShape> shapes;
  glm::vec2 lo{0.f}, hi{0.f};  // the shapes' bounds in the plane
  float half_height = 1.f;     // h: the walls span z in [-h, h]
  bool has_ray = false;        // the scene's own ray (the 2D view starts with it)
  glm::vec2 ray_origin{0.f}, ray_direction{1.f, 0.f};
  // The shape a primitive belongs to (-1: none).
  int shape_of(uint32_t prim) const;
};

// The shapes' bounds in the plane (a circle by its centre and radius).
void flat_bounds(const std::vector<FlatShape>& shapes, glm::vec2* lo, glm::vec2* hi);
// h for these bounds: half the larger side (at least 1 unit in 1e6 of the bounds' magnitude, so that a scene
// of one segment along an axis still has walls).
float flat_half_height(const glm::vec2& lo, const glm::vec2& hi);
// Why a shape cannot be filled ("" when it can): a filled polygon must be simple (no two edges meet but
// neighbours at their corner).
std::string flat_shape_problem(const FlatShape& shape);
// Each shape as one object of the geometry, in order; sets flat->lo, hi, half_height and the shapes'
// object and primitive ranges.
void add_flat_shapes(Flatland* flat, Geometry* geometry);
// A ray in the plane z = 0.
Ray flat_ray(const glm::vec2& origin, const glm::vec2& direction, float tmin = 0.f, float tmax = kInfinity);

}  // namespace raystep
