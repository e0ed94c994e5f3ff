#include "raystep/accel/bounding_volumes.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "raystep/geometry/min_sphere.h"

namespace raystep {

const std::vector<std::string>& bvol_kind_names() {
  static const std::vector<std::string> names = {"bvol", "bvol-sphere", "bvol-kdop", "bvol-obb"};
  return names;
}

std::optional<BvolKind> parse_bvol_kind(const std::string& accel_name) {
  const std::vector<std::string>& names = bvol_kind_names();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == accel_name) return BvolKind(i);
  return std::nullopt;
}

// ---- Build: one volume per object, over its triangles' vertices and its spheres ----

namespace {

void object_points(const Geometry& g, const Object& o, std::vector<glm::vec3>* points,
                   std::vector<Sphere>* spheres) {
  points->clear();
  spheres->clear();
  for (uint32_t id = o.first_prim; id < o.first_prim + o.prim_count; ++id) {
    if (g.type(id) == PrimType::sphere) {
      spheres->push_back(g.sphere(id));
    } else {
      for (int k = 0; k < 3; ++k) points->push_back(g.vertex(id, k));
    }
  }
}

double box_area(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  const double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
  return 2.0 * (x * y + y * z + z * x);
}

OrientedBox fit_oriented_box(const std::vector<glm::vec3>& points, const std::vector<Sphere>& spheres) {
  // Principal axes of the vertices (a sphere counts by its centre); kept only where they give a box of
  // smaller surface area than the axis-aligned one, which by Crofton's theorem rays enter less often.
  std::vector<glm::vec3> centres = points;
  for (const Sphere& s : spheres) centres.push_back(s.center);
  const std::array<glm::dvec3, 3> world = {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)};
  auto fit = [&](const std::array<glm::dvec3, 3>& axes) {
    OrientedBox box;
    box.axes = axes;
    for (int k = 0; k < 3; ++k) fit_slab(axes[k], points, spheres, &box.lo[k], &box.hi[k]);
    return box;
  };
  const OrientedBox aligned = fit(world);
  const OrientedBox principal = fit(principal_axes(centres));
  return box_area(principal.lo, principal.hi) < box_area(aligned.lo, aligned.hi) ? principal : aligned;
}

}  // namespace

void BoundingVolumes::build(const Geometry& geometry) {
  geometry_ = &geometry;
  boxes_.clear();
  spheres_.clear();
  kdops_.clear();
  obbs_.clear();
  std::vector<glm::vec3> points;
  std::vector<Sphere> spheres;
  for (const Object& o : geometry.objects()) {
    switch (kind_) {
      case BvolKind::box:
        boxes_.push_back(o.bounds);
        break;
      case BvolKind::sphere:
        object_points(geometry, o, &points, &spheres);
        spheres_.push_back(bounding_sphere(points, spheres));
        break;
      case BvolKind::kdop: {
        object_points(geometry, o, &points, &spheres);
        std::array<double, 14> slabs;
        for (int k = 0; k < 7; ++k)
          fit_slab(kdop_directions()[k], points, spheres, &slabs[2 * k], &slabs[2 * k + 1]);
        kdops_.push_back(slabs);
        break;
      }
      case BvolKind::obb:
        object_points(geometry, o, &points, &spheres);
        obbs_.push_back(fit_oriented_box(points, spheres));
        break;
    }
  }
}

size_t BoundingVolumes::memory_bytes() const {
  return boxes_.capacity() * sizeof(Bounds3) + spheres_.capacity() * sizeof(Sphere) +
         kdops_.capacity() * sizeof(kdops_[0]) + obbs_.capacity() * sizeof(OrientedBox);
}

// ---- The volume tests ----

// The ray prepared once for every object's test: the reciprocal direction for boxes, the seven directions'
// n . o and n . d for k-DOPs.
struct BoundingVolumes::VolumeRay {
  const Ray& ray;
  SlabRay slab;
  std::array<SlabLine, 7> kdop;
  VolumeRay(const Ray& r, BvolKind kind) : ray(r), slab(r) {
    if (kind == BvolKind::kdop && slab.valid)
      for (int k = 0; k < 7; ++k) kdop[k] = SlabLine(kdop_directions()[k], r);
  }
};

template <BvolKind K>
bool BoundingVolumes::enter(uint32_t o, const VolumeRay& vray, float* t_enter, float* t_exit) const {
  if constexpr (K == BvolKind::box) {
    return intersect_slabs(boxes_[o], vray.slab, t_enter, t_exit);
  } else if constexpr (K == BvolKind::sphere) {
    // The near root is the entry (or tmin, from inside).
    if (spheres_[o].radius < 0.f) return false;
    return intersect_bounding_sphere(spheres_[o], vray.ray, t_enter, t_exit);
  } else {
    // The entry is the latest of the slabs' entries, the exit the earliest of their exits.
    double t0 = vray.ray.tmin, t1 = vray.ray.tmax;
    if constexpr (K == BvolKind::kdop) {
      const std::array<double, 14>& s = kdops_[o];
      for (int k = 0; k < 7; ++k)
        if (!clip_slab(vray.kdop[k], s[2 * k], s[2 * k + 1], &t0, &t1)) return false;
    } else {
      const OrientedBox& b = obbs_[o];
      for (int k = 0; k < 3; ++k)
        if (!clip_slab(SlabLine(b.axes[k], vray.ray), b.lo[k], b.hi[k], &t0, &t1)) return false;
    }
    return slab_interval_to_float(t0, t1, vray.ray.tmin, t_enter, t_exit);
  }
}

bool BoundingVolumes::volume_hit(uint32_t o, const Ray& ray, float* t_enter, float* t_exit) const {
  VolumeRay vray(ray, kind_);
  if (!vray.slab.valid) return false;
  float t0, t1;
  bool in = false;
  switch (kind_) {
    case BvolKind::box:
      in = enter<BvolKind::box>(o, vray, &t0, &t1);
      break;
    case BvolKind::sphere:
      in = enter<BvolKind::sphere>(o, vray, &t0, &t1);
      break;
    case BvolKind::kdop:
      in = enter<BvolKind::kdop>(o, vray, &t0, &t1);
      break;
    case BvolKind::obb:
      in = enter<BvolKind::obb>(o, vray, &t0, &t1);
      break;
  }
  if (in && t_enter) *t_enter = t0;
  if (in && t_exit) *t_exit = t1;
  return in;
}

// ---- The walk: objects whose volumes the ray enters, nearest volume first ----

template <BvolKind K, class Recorder>
bool BoundingVolumes::walk(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  *hit = Hit{};
  rec.ray_begin(ray);
  VolumeRay vray(ray, K);
  if (!vray.slab.valid) {
    rec.ray_end(*hit);
    return false;
  }
  // The volumes the ray crosses, by entry distance (a reused per-thread list: no allocation per ray).
  thread_local std::vector<std::pair<float, uint32_t>> entered;
  entered.clear();
  const uint32_t objects = uint32_t(geometry_->objects().size());
  for (uint32_t o = 0; o < objects; ++o) {
    float t0, t1;
    const bool in = enter<K>(o, vray, &t0, &t1);
    rec.volume_test(o, in);
    if (in) entered.emplace_back(t0, o);
  }
  std::sort(entered.begin(), entered.end());
  WatertightRay wray(ray);
  float t_nearest = ray.tmax;
  float t_limit =
      ray.tmax;  // the primitive tests' bound: once there is a hit, just above it, so that ties are seen
  for (const auto& [t_enter, o] : entered) {
    if (t_enter > t_nearest) break;  // every remaining volume starts beyond the nearest hit
    rec.box_entered(o, t_enter);
    const Object& obj = geometry_->objects()[o];
    bool object_hit = false;
    for (uint32_t id = obj.first_prim; id < obj.first_prim + obj.prim_count; ++id) {
      Hit candidate;
      bool found = geometry_->intersect(id, ray, wray, t_limit, &candidate);
      rec.prim_test(id, found, candidate.t);
      if (!found) continue;
      object_hit = true;
      // A tie (the same t: a shared edge between two objects, coincident faces) goes to the lower primitive
      // id, as in brute force, whichever object's volume came first.
      if (candidate.t == t_nearest && int32_t(id) > hit->prim) continue;
      *hit = candidate;
      t_nearest = candidate.t;
      t_limit = next_float_up(t_nearest);
      if (any_hit) {
        rec.ray_end(*hit);
        return true;
      }
    }
    // The volume let the ray in, but the object has no hit before the nearest so far: a false positive.
    if (!object_hit) rec.volume_false_positive(o);
  }
  rec.ray_end(*hit);
  return hit->found();
}

template <class Recorder>
bool BoundingVolumes::walk_kind(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  switch (kind_) {
    case BvolKind::sphere:
      return walk<BvolKind::sphere>(ray, hit, any_hit, rec);
    case BvolKind::kdop:
      return walk<BvolKind::kdop>(ray, hit, any_hit, rec);
    case BvolKind::obb:
      return walk<BvolKind::obb>(ray, hit, any_hit, rec);
    default:
      return walk<BvolKind::box>(ray, hit, any_hit, rec);
  }
}

bool BoundingVolumes::intersect(const Ray& ray, Hit* hit) const {
  NullRecorder rec;
  return walk_kind(ray, hit, false, rec);
}

bool BoundingVolumes::occluded(const Ray& ray) const {
  NullRecorder rec;
  Hit hit;
  return walk_kind(ray, &hit, true, rec);
}

bool BoundingVolumes::intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const {
  return walk_kind(ray, hit, false, counters);
}

bool BoundingVolumes::occluded_counted(const Ray& ray, CountingRecorder& counters) const {
  Hit hit;
  return walk_kind(ray, &hit, true, counters);
}

}  // namespace raystep
