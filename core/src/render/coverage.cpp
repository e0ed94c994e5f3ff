#include "raystep/render/coverage.h"

#include <cmath>

namespace raystep {

double signed_area(const std::vector<glm::dvec2>& polygon) {
  double twice = 0.0;
  for (size_t i = 0, n = polygon.size(); i < n; ++i) {
    const glm::dvec2 &a = polygon[i], &b = polygon[(i + 1) % n];
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * twice;
}

std::vector<glm::dvec2> clip_to_box(const std::vector<glm::dvec2>& polygon, const glm::dvec2& lo,
                                    const glm::dvec2& hi) {
  std::vector<glm::dvec2> out = polygon, in;
  // One clip edge at a time: keep the half-plane axis * side <= bound * side.
  for (int edge = 0; edge < 4 && !out.empty(); ++edge) {
    const int axis = edge % 2;
    const double side = edge < 2 ? -1.0 : 1.0;  // edges 0, 1: x >= lo.x, y >= lo.y; 2, 3: x <= hi.x, y <= hi.y
    const double bound = edge < 2 ? lo[axis] : hi[axis];
    auto inside = [&](const glm::dvec2& p) { return side * (p[axis] - bound) <= 0.0; };
    in.swap(out);
    out.clear();
    for (size_t i = 0, n = in.size(); i < n; ++i) {
      const glm::dvec2 &s = in[(i + n - 1) % n], &e = in[i];  // polygon edge from s to e
      const bool s_in = inside(s), e_in = inside(e);
      if (s_in != e_in) {  // the edge crosses the clip line: emit the intersection
        const double t = (bound - s[axis]) / (e[axis] - s[axis]);
        glm::dvec2 q = s + t * (e - s);
        q[axis] = bound;  // exactly on the line
        out.push_back(q);
      }
      if (e_in) out.push_back(e);
    }
  }
  return out;
}

double pixel_coverage(const std::vector<glm::dvec2>& polygon, int x, int y) {
  const glm::dvec2 lo(x, y), hi(x + 1.0, y + 1.0);
  return std::fabs(signed_area(clip_to_box(polygon, lo, hi)));
}

}  // namespace raystep
