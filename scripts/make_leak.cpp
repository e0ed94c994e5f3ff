// Writes scenes/meshes/leak_octahedron.obj: a tilted octahedron whose front edges pass within rounding of pixel
// rays of scenes/leak.json, at least two of them where Möller–Trumbore rejects both triangles sharing the edge
// while the watertight test hits (lesson 14). C++, not python: the leak must be found by the very tests the
// debugger runs, compiled as the library compiles them.
//
// The search: octahedron.obj (radius 15, centre (32.3, 23.6, 0)) turned by angles drawn near (0.45, 0.35, 0.3)
// rad about x, y, z; its front vertex F (+z); for each equator vertex E, the pixel centre P nearest the edge's
// midpoint in x, y; E moved along the line from F through P (same length of edge in x, y) and rounded to float,
// then its x and y nudged by up to 6 ulps each at random. The first turn with two leaking edges is written.
// Deterministic (std::mt19937, seed 1): running it again gives the committed file.
//
//   g++ -O2 -std=c++17 -Icore/include scripts/make_leak.cpp build/core/libraystep_core.a \
//       -lgmpxx -lgmp -o /tmp/make_leak && /tmp/make_leak > scenes/meshes/leak_octahedron.obj
#include <cmath>
#include <cstdio>
#include <random>

#include <glm/glm.hpp>

#include "raystep/geometry/triangle.h"
#include "raystep/geometry/triangle_moller.h"
#include "raystep/render/camera.h"
#include "raystep/scene/scene.h"

using namespace raystep;

// octahedron.obj's faces (1-based): 5 is the front vertex, 6 the back one, 1-4 the equator.
const int kFaces[8][3] = {{1, 3, 5}, {3, 2, 5}, {2, 4, 5}, {4, 1, 5}, {3, 1, 6}, {2, 3, 6}, {4, 2, 6}, {1, 4, 6}};

int main() {
  // scenes/leak.json's camera: pixel (i, j) looks along -z through (i + 0.5, 47.5 - j).
  Camera cam;
  cam.type = CameraType::orthographic;
  cam.eye = {32, 24, 40};
  cam.look_at = {32, 24, 0};
  cam.up = {0, 1, 0};
  cam.ortho_height = 48;
  ProjectiveCamera camera(cam, 64, 48);
  const double radius = 15;
  const glm::dvec3 centre(32.3, 23.6, 0);
  const glm::dvec3 unit[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 1000000; ++trial) {
    // The turn: Rz(g) Rx(a) Ry(b) (glm matrices are column-major).
    double a = 0.45 + 0.05 * U(rng), b = 0.35 + 0.05 * U(rng), g = 0.3 + 0.05 * U(rng);
    glm::dmat3 rx(1, 0, 0, 0, std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a));
    glm::dmat3 ry(std::cos(b), 0, -std::sin(b), 0, 1, 0, std::sin(b), 0, std::cos(b));
    glm::dmat3 rz(std::cos(g), std::sin(g), 0, -std::sin(g), std::cos(g), 0, 0, 0, 1);
    glm::dvec3 turned[6];
    for (int i = 0; i < 6; ++i) turned[i] = rz * rx * ry * unit[i] * radius + centre;

    // F and the back vertex as turned; each equator vertex moved so that its edge to F passes near a pixel ray.
    glm::vec3 v[6];
    v[4] = glm::vec3(turned[4]);
    v[5] = glm::vec3(turned[5]);
    int px[4], py[4];
    glm::dvec2 f(v[4].x, v[4].y);
    for (int i = 0; i < 4; ++i) {
      glm::dvec2 mid = 0.5 * (f + glm::dvec2(turned[i]));
      px[i] = int(std::floor(mid.x));
      py[i] = int(std::floor(48 - mid.y));
      glm::dvec2 p(px[i] + 0.5, 47.5 - py[i]);
      glm::dvec2 e = f + (p - f) * (glm::length(glm::dvec2(turned[i]) - f) / glm::length(p - f));
      int jx = int(std::lround(6 * U(rng))), jy = int(std::lround(6 * U(rng)));
      float ex = float(e.x), ey = float(e.y);
      for (int k = 0; k < std::abs(jx); ++k) ex = std::nextafter(ex, jx > 0 ? 1e9f : -1e9f);
      for (int k = 0; k < std::abs(jy); ++k) ey = std::nextafter(ey, jy > 0 ? 1e9f : -1e9f);
      v[i] = glm::vec3(ex, ey, float(turned[i].z));
    }

    // An edge F-E leaks when both front triangles sharing it reject the pixel's ray under Möller–Trumbore
    // while the watertight test hits one of them.
    int leaks = 0;
    bool leak[4] = {};
    for (int i = 0; i < 4; ++i) {
      Ray r = camera.generate(float(px[i]) + 0.5f, float(py[i]) + 0.5f);
      int sharing = 0, moller_misses = 0, watertight_hits = 0;
      for (const auto& face : kFaces) {
        bool has_f = face[0] == 5 || face[1] == 5 || face[2] == 5;
        bool has_e = face[0] == i + 1 || face[1] == i + 1 || face[2] == i + 1;
        if (!has_f || !has_e) continue;
        glm::vec3 p0 = v[face[0] - 1], p1 = v[face[1] - 1], p2 = v[face[2] - 1];
        if (glm::cross(p1 - p0, p2 - p0).z <= 0) sharing = -100;  // a front face must face the camera
        ++sharing;
        TriangleHit h;
        if (!intersect_triangle_moller(r, p0, p1, p2, &h)) ++moller_misses;
        if (intersect_triangle(r, p0, p1, p2, &h)) ++watertight_hits;
      }
      leak[i] = sharing == 2 && moller_misses == 2 && watertight_hits >= 1;
      leaks += leak[i];
    }
    if (leaks < 2) continue;

    std::printf(
        "# A tilted octahedron (6 shared vertices, 8 triangles, every edge shared by two): octahedron.obj's faces, "
        "its\n# vertices turned and moved, and its front edges nudged so that they pass within rounding of pixel "
        "rays of\n# scenes/leak.json; at the pixels");
    for (int i = 0; i < 4; ++i)
      if (leak[i]) std::printf(" (%d, %d)", px[i], py[i]);
    std::printf(
        " Möller–Trumbore rejects both triangles that\n# share the edge. Written by scripts/make_leak.cpp "
        "(trial %d): scenes/README.md.\n",
        trial);
    for (const glm::vec3& p : v) std::printf("v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    for (const auto& face : kFaces) std::printf("f %d %d %d\n", face[0], face[1], face[2]);
    return 0;
  }
  std::fprintf(stderr, "no octahedron with two leaking edges found\n");
  return 1;
}
