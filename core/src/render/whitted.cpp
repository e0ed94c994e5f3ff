#include "raystep/render/whitted.h"

#include <cmath>

#include "raystep/geometry/spawn.h"

namespace raystep {

namespace {

// What shading needs to know about a hit point.
struct SurfaceHit {
  glm::vec3 p;        // hit point
  glm::vec3 p_error;  // its absolute error bound per axis, for spawning rays (geometry/spawn.h)
  glm::vec3 ng;       // unit geometric normal, turned towards the incoming ray
  glm::vec3 ns;       // unit shading normal (interpolated vertex normals, else ng), turned towards the ray
  bool entering;      // the ray arrived on the side the surface's own normal points to (outside)
};

SurfaceHit surface_at(const Geometry& geometry, const Ray& ray, const Hit& hit) {
  SurfaceHit s;
  uint32_t id = uint32_t(hit.prim);
  glm::vec3 n_geometric, n_shading;
  if (geometry.type(id) == PrimType::triangle) {
    const glm::vec3 &p0 = geometry.vertex(id, 0), &p1 = geometry.vertex(id, 1), &p2 = geometry.vertex(id, 2);
    TriangleHit th{hit.t, 1.f - hit.b1 - hit.b2, hit.b1, hit.b2};
    s.p = triangle_point(th, p0, p1, p2, &s.p_error);
    n_geometric = triangle_normal(p0, p1, p2);  // outside = counter-clockwise winding
    n_shading = n_geometric;
    if (geometry.has_vertex_normals(id)) {
      glm::vec3 n = th.b0 * geometry.vertex_normal(id, 0) + th.b1 * geometry.vertex_normal(id, 1) +
                    th.b2 * geometry.vertex_normal(id, 2);
      if (glm::dot(n, n) > 0.f && is_finite(n)) n_shading = n;
    }
  } else {
    const Sphere& sphere = geometry.sphere(id);
    s.p = sphere_point(ray, sphere, hit.t, &s.p_error);
    n_geometric = s.p - sphere.center;  // outside = away from the centre
    n_shading = n_geometric;
  }
  n_geometric = glm::normalize(n_geometric);
  n_shading = glm::normalize(n_shading);
  s.entering = glm::dot(ray.direction, n_geometric) < 0.f;
  s.ng = s.entering ? n_geometric : -n_geometric;
  s.ns = glm::dot(ray.direction, n_shading) < 0.f ? n_shading : -n_shading;
  return s;
}

bool is_zero(const glm::vec3& v) { return v.x == 0.f && v.y == 0.f && v.z == 0.f; }

}  // namespace

glm::vec3 WhittedTracer::trace_primary(const Ray& ray, RayCounts* counts) const {
  ++counts->primary;
  notify(ray, RayKind::primary, 0);
  return trace(ray, 0, 1.f, counts);
}

glm::vec3 WhittedTracer::trace(const Ray& ray, int depth, float weight, RayCounts* counts) const {
  const RenderSettings& settings = scene_.render;

  // Nearest hit; a ray that leaves the scene sees the background.
  Hit hit;
  if (!accel_.intersect(ray, &hit)) return settings.background;
  const SurfaceHit s = surface_at(scene_.geometry, ray, hit);
  const Material& m = scene_.materials[scene_.geometry.material(uint32_t(hit.prim))];
  const glm::vec3 d = glm::normalize(ray.direction);
  const glm::vec3 v = -d;  // towards the viewer

  // Local shading: ambient, then diffuse and Phong specular from every light a shadow ray reaches.
  glm::vec3 L = settings.ambient * m.diffuse;
  const bool has_specular = !is_zero(m.specular);
  if (!is_zero(m.diffuse) || has_specular) {
    for (const Light& light : scene_.lights) {
      const glm::vec3 power = light.color * light.intensity;  // unattenuated (Whitted)
      if (is_zero(power)) continue;
      glm::vec3 l;  // unit vector towards the light
      Ray shadow;
      if (light.type == LightType::point) {
        l = glm::normalize(light.position - s.p);
        shadow = spawn_ray_to(s.p, s.p_error, s.ng, light.position);
      } else {
        l = -glm::normalize(light.direction);
        shadow = spawn_ray(s.p, s.p_error, s.ng, l);
      }
      const float n_dot_l = glm::dot(s.ns, l);
      if (!(n_dot_l > 0.f)) continue;  // the light is behind the surface (or undefined): no shadow ray
      ++counts->shadow;
      notify(shadow, RayKind::shadow, depth + 1);
      if (accel_.occluded(shadow)) continue;
      glm::vec3 c = m.diffuse * n_dot_l;
      if (has_specular) {
        const glm::vec3 r = reflect(-l, s.ns);  // the light's mirror direction
        c += m.specular * std::pow(glm::max(0.f, glm::dot(r, v)), m.shininess);
      }
      L += c * power;
    }
  }

  // Recursion: only below the depth limit.
  if (depth >= settings.max_depth) return L;

  // Refraction (Snell's law); under total internal reflection the transmitted part is reflected instead.
  float mirror_weight = m.mirror;
  if (m.transparency > 0.f) {
    const float eta = s.entering ? 1.f / m.ior : m.ior;  // eta_incident / eta_transmitted
    glm::vec3 t;
    if (refract(d, s.ns, eta, &t)) {
      const float w = weight * m.transparency;
      if (w >= settings.min_weight) {  // adaptive ray termination
        ++counts->refracted;
        const Ray refracted = spawn_ray(s.p, s.p_error, s.ng, t);
        notify(refracted, RayKind::refracted, depth + 1);
        L += m.transparency * trace(refracted, depth + 1, w, counts);
      }
    } else {
      mirror_weight += m.transparency;
    }
  }

  // Mirror reflection.
  if (mirror_weight > 0.f) {
    const float w = weight * mirror_weight;
    if (w >= settings.min_weight) {  // adaptive ray termination
      ++counts->reflected;
      const Ray reflected = spawn_ray(s.p, s.p_error, s.ng, reflect(d, s.ns));
      notify(reflected, RayKind::reflected, depth + 1);
      L += mirror_weight * trace(reflected, depth + 1, w, counts);
    }
  }
  return L;
}

}  // namespace raystep
