// Where a structure may cut, and how it weighs a box (lecture: "p = S_child / S by Crofton"). By Crofton's
// theorem the share of random lines meeting a convex set that also meet a convex subset is, in space, the
// ratio of their surface areas and, in the plane, the ratio of their perimeters. A 3D scene is cut on x, y
// and z and a box weighs its surface area. A flatland scene (walls standing on the plane z = 0, every
// primitive spanning the same z) is cut on x and y only and a box weighs its perimeter in the plane: its
// structures are the lecture's 2D pictures, built and walked by the same code as in 3D.
#pragma once

#include "raystep/geometry/bounds.h"

namespace raystep {

struct SplitSpace {
  int axes = 3;  // 3: x, y and z; 2: x and y, the plane

  bool plane() const { return axes == 2; }
  // Surface area in space, perimeter in the plane: 2 (e_x e_y + e_y e_z + e_z e_x) or 2 (e_x + e_y).
  float measure(const Bounds3& b) const {
    if (axes == 3) return b.surface_area();
    const glm::vec3 e = b.extent();
    return 2.f * (e.x + e.y);
  }
  // The longest of the axes it cuts (the first of equals).
  int longest_axis(const Bounds3& b) const {
    if (axes == 3) return b.max_axis();
    const glm::vec3 e = b.extent();
    return e.x >= e.y ? 0 : 1;
  }
};

// The measures of the two children of a box cut on one axis at `position`, as a linear function of it:
// measure = 2 (cross + e_a sum) with e_a the child's extent on the axis and the other extents the box's. In
// space cross = e_u e_v and sum = e_u + e_v (the surface area); in the plane cross = e_u (the other axis of
// the plane) and sum = 1 (the perimeter).
struct SplitMeasure {
  int axis;
  float lo, hi, cross, sum, node;
  SplitMeasure(const Bounds3& box, int a, SplitSpace space) : axis(a), lo(box.lo[a]), hi(box.hi[a]) {
    const glm::vec3 e = box.extent();
    if (space.plane()) {
      cross = e[1 - a];
      sum = 1.f;
    } else {
      const float eu = e[(a + 1) % 3], ev = e[(a + 2) % 3];
      cross = eu * ev;
      sum = eu + ev;
    }
    node = space.measure(box);
  }
  float below(float position) const { return 2.f * (cross + (position - lo) * sum); }
  float above(float position) const { return 2.f * (cross + (hi - position) * sum); }
};

}  // namespace raystep
