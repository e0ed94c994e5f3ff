#include "raystep/accel/random_lines.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace raystep {

Ray random_line(Pcg32& rng, const glm::vec3& centre, float radius) {
  // An isotropic direction (z uniform in [-1, 1], the azimuth uniform), then a point uniform on the disc.
  const float z = 1.f - 2.f * rng.uniform(), phi = 6.2831853f * rng.uniform();
  const float s = std::sqrt(std::max(0.f, 1.f - z * z));
  const glm::vec3 d(s * std::cos(phi), s * std::sin(phi), z);
  const glm::vec3 axis = std::fabs(d.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = glm::normalize(glm::cross(d, axis));
  const glm::vec3 v = glm::cross(d, u);
  const float r = radius * std::sqrt(rng.uniform()), a = 6.2831853f * rng.uniform();
  Ray ray;
  ray.origin = centre + r * (std::cos(a) * u + std::sin(a) * v) - 2.f * radius * d;
  ray.direction = d;
  return ray;
}

float line_radius(const Bounds3& box, SplitSpace space) {
  const glm::vec3 e = box.extent();
  return 0.5f * (space.plane() ? std::hypot(e.x, e.y) : glm::length(e));
}

Ray random_plane_line(Pcg32& rng, const glm::vec3& centre, float radius) {
  // A uniform direction in the plane, then an offset uniform across the disc's diameter perpendicular to it.
  const float phi = 6.2831853f * rng.uniform(), r = radius * (2.f * rng.uniform() - 1.f);
  const glm::vec3 d(std::cos(phi), std::sin(phi), 0.f), across(-d.y, d.x, 0.f);
  Ray ray;
  ray.origin = centre + r * across - 2.f * radius * d;
  ray.direction = d;
  return ray;
}

LinesMeetingBox lines_meeting_box(const Bounds3& box, size_t lines, uint64_t seed, SplitSpace space) {
  LinesMeetingBox out;
  if (box.empty()) return out;
  const glm::vec3 centre = box.center();
  const float radius = line_radius(box, space);
  if (!(radius > 0.f)) return out;
  out.predicted = space.plane() ? double(space.measure(box)) / (2.0 * M_PI * double(radius))
                                : double(box.surface_area()) / 4.0 / (M_PI * double(radius) * double(radius));
  if (lines == 0) return out;
  Pcg32 rng(seed, 0);
  size_t met = 0;
  for (size_t i = 0; i < lines; ++i)
    met += intersect_slabs(box, SlabRay(random_line(rng, centre, radius, space)), nullptr, nullptr);
  out.measured = double(met) / double(lines);
  return out;
}

LinesMeetingChildren lines_meeting_children(const Bounds3& node, const std::vector<Bounds3>& children,
                                            size_t lines, uint64_t seed, SplitSpace space, size_t kept) {
  LinesMeetingChildren out;
  out.meeting_child.assign(children.size(), 0);
  out.share.assign(children.size(), 0.0);
  out.ratio.assign(children.size(), 0.0);
  if (node.empty()) return out;
  const double whole = double(space.measure(node));
  for (size_t c = 0; c < children.size(); ++c)
    out.ratio[c] = whole > 0.0 && !children[c].empty() ? double(space.measure(children[c])) / whole : 0.0;
  const glm::vec3 centre = node.center();
  const float radius = line_radius(node, space);
  if (!(radius > 0.f)) return out;
  Pcg32 rng(seed, 0);
  for (size_t i = 0; i < lines; ++i) {
    const Ray r = random_line(rng, centre, radius, space);
    const SlabRay slab(r);
    float t0 = 0.f, t1 = 0.f;
    ++out.thrown;
    if (!intersect_slabs(node, slab, &t0, &t1)) continue;
    ++out.meeting_node;
    for (size_t c = 0; c < children.size(); ++c)
      out.meeting_child[c] += !children[c].empty() && intersect_slabs(children[c], slab, nullptr, nullptr);
    if (out.kept.size() < kept) out.kept.push_back({r.at(t0), r.at(t1)});
  }
  for (size_t c = 0; c < children.size(); ++c)
    out.share[c] = out.meeting_node ? double(out.meeting_child[c]) / double(out.meeting_node) : 0.0;
  return out;
}

}  // namespace raystep
