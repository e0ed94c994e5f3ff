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

double pixel_tent_coverage(const std::vector<glm::dvec2>& polygon, int x, int y) {
  const glm::dvec2 c(x + 0.5, y + 0.5);
  double total = 0.0;
  for (int sy = -1; sy <= 1; sy += 2)
    for (int sx = -1; sx <= 1; sx += 2) {
      const glm::dvec2 lo(sx < 0 ? c.x - 1.0 : c.x, sy < 0 ? c.y - 1.0 : c.y);
      const std::vector<glm::dvec2> q = clip_to_box(polygon, lo, lo + glm::dvec2(1.0));
      if (q.size() < 3) continue;
      // Moments of the clipped polygon about the centre, by its edges: c_i = u_i v_(i+1) - u_(i+1) v_i,
      // area = sum c_i / 2, int u = sum (u_i + u_(i+1)) c_i / 6, likewise v, and
      // int uv = sum (u_i v_(i+1) + 2 u_i v_i + 2 u_(i+1) v_(i+1) + u_(i+1) v_i) c_i / 24.
      double a = 0.0, mu = 0.0, mv = 0.0, muv = 0.0;
      for (size_t i = 0, n = q.size(); i < n; ++i) {
        const glm::dvec2 p = q[i] - c, r = q[(i + 1) % n] - c;
        const double ci = p.x * r.y - r.x * p.y;
        a += ci;
        mu += (p.x + r.x) * ci;
        mv += (p.y + r.y) * ci;
        muv += (p.x * r.y + 2.0 * p.x * p.y + 2.0 * r.x * r.y + r.x * p.y) * ci;
      }
      a /= 2.0;
      mu /= 6.0;
      mv /= 6.0;
      muv /= 24.0;
      // In this quadrant |u| = sx u and |v| = sy v; a clockwise polygon has every moment negated.
      const double w = a - sx * mu - sy * mv + sx * sy * muv;
      total += a < 0.0 ? -w : w;
    }
  return total;
}

}  // namespace raystep
