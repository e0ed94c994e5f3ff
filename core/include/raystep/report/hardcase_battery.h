// The hard-case battery: the rays that break naive ray tracers, generated for a mesh (lecture: "a watertight
// test is only as good as the rays you throw at it"). Rays from inside closed meshes aimed at their edges and
// vertices at four scales, axis-parallel rays with +0 and -0 components along a cube's edges and faces, a
// tessellated plane hit through its vertices and edges, duplicated and coplanar triangles, slivers and
// zero-area triangles, and NaN, infinite, tiny and huge rays. `raystep hardcases` runs it
// (report/hardcases.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/ray.h"
#include "raystep/scene/geometry.h"
#include "raystep/scene/triangle_mesh.h"

namespace raystep {

enum class HardCaseFamily : uint8_t {
  inside,     // from inside closed meshes at their edges and vertices, at four scales: a miss is a leak
  surface,    // the user's mesh from outside, aimed at its edges and vertices (any mesh, closed or not)
  axis,       // axis-parallel rays with +0 / -0 components along a subdivided cube's edges and faces
  plane,      // a tessellated plane hit exactly through its vertices and edges, and grazed in its plane
  overlap,    // identical (also reversed and rotated) and coplanar overlapping triangles: ties
  sliver,     // needle and cap triangles, zero-area (collinear, repeated-vertex) triangles in closed meshes
  nonfinite,  // NaN and infinite origins, directions and bounds; zero directions; |d| = 1e-30 and 1e30
};
constexpr int kHardCaseFamilies = 7;
const char* hardcase_family_name(HardCaseFamily family);

// One geometry and the rays fired at it.
struct HardCaseSet {
  HardCaseFamily family = HardCaseFamily::inside;
  std::string name;  // e.g. "octahedron x1e-06"
  Geometry geometry;
  std::vector<Ray> rays;
  // must_hit[i]: ray i must hit something (it starts inside a closed mesh, or is aimed at a point strictly
  // inside the covered part of a surface): a miss is a leak.
  std::vector<uint8_t> must_hit;
  // The point each ray is aimed at (a vertex or a point on an edge, within rounding), or NaN.
  std::vector<glm::vec3> targets;
  // The index in the battery of an earlier set with the same geometry, whose built structure can be reused
  // (a large mesh is built once for its surface and nonfinite rays), or -1.
  int same_geometry_as = -1;
};

// Is the mesh closed? Edges are keyed by their end points' positions (bit-identical coordinates weld
// vertices that a file repeats); a mesh is closed when it has edges and every edge is used by an even number
// of triangles (two for a manifold mesh). Then every point off the surface is inside or outside by the parity
// of a ray's crossings, and every ray from inside must cross the surface.
struct MeshClosure {
  size_t edges = 0;
  size_t odd_edges = 0;  // edges used by an odd number of triangles (a hole's rim, a T-junction)
  bool closed() const { return edges > 0 && odd_edges == 0; }
};
MeshClosure mesh_closure(const TriangleMesh& mesh);

struct HardCaseOptions {
  // Rays per scale of the inside family and of the surface family; 0: automatic, so that the double
  // reference (one test per ray and triangle) stays near reference_budget tests per family.
  size_t mesh_rays = 0;
  uint64_t reference_budget = 40'000'000;
  uint64_t seed = 1;
  bool built_in_families = true;  // false: only the families on the given mesh (inside, surface, nonfinite)
};

// The four scales of the inside family: x1e-6, x1, x1e6, and x1 moved 1000 times the mesh's extent away.
constexpr int kHardCaseScales = 4;
// The mesh's positions at scale k (0..3), in float as a user would store them.
std::vector<glm::vec3> hardcase_scaled(const std::vector<glm::vec3>& positions, int scale);
std::string hardcase_scale_name(int scale);

// The battery for `mesh` (nullptr: the built-in meshes: octahedron, subdivided cube, icosphere, torus). With
// a mesh: the inside family on it if it is closed (else *note says why it was skipped), the surface family
// on it, and the nonfinite rays on it too; the other families always use their built-in geometry.
std::vector<HardCaseSet> hardcase_battery(const TriangleMesh* mesh, const HardCaseOptions& options,
                                          std::string* note);

// The inside family on one closed mesh: points just inside its triangles (kept when the parity of the
// crossings along two directions, in double with exact edge decisions, says inside), each firing rays at its
// triangle's vertices and edge points and at vertices and edge points elsewhere. About `rays` rays.
HardCaseSet inside_rays_set(const TriangleMesh& mesh, const std::string& name, HardCaseFamily family,
                            size_t rays, uint64_t seed);

}  // namespace raystep
