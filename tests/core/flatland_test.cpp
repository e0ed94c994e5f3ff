// 2D scenes (scene/flatland.h, "dimensions": 2 in the scene format): the shapes and their extrusion, the
// camera that looks down on them, every error with its line, and rays in the plane walked by every structure:
// the same hits as brute force, at the t of the exact 2D intersection, and no ray through a polygon's corner.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "raystep/accel/structure_options.h"
#include "raystep/io/scene_loader.h"
#include "raystep/render/camera.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

namespace fs = std::filesystem;

const std::string kFlatDir = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/flatland";

const char* kScene = R"({
  "dimensions": 2,
  "materials": { "red": { "diffuse": [1, 0, 0] } },
  "objects": [
    { "type": "segment", "points": [[0, 0], [4, 0]] },
    { "type": "polyline", "name": "zigzag", "points": [[0, 1], [1, 2], [2, 1]] },
    { "type": "polygon", "material": "red", "fill": true, "points": [[5, 0], [8, 0], [8, 3], [5, 3]] },
    { "type": "circle", "center": [2, 5], "radius": 1 }
  ],
  "ray": { "origin": [-1, 0.5], "direction": [1, 0] },
  "render": { "size": [200, 100] }
})";

InputError scene_error(const std::string& text) {
  try {
    parse_scene(text, "flat.json");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return InputError("", 0, "");
}

// The exact 2D intersection of a ray in the plane with segment ab: its t (double), or -1 for a miss.
double segment_t(const Ray& r, const glm::vec2& a, const glm::vec2& b) {
  const double ox = r.origin.x, oy = r.origin.y, dx = r.direction.x, dy = r.direction.y;
  const double ex = double(b.x) - a.x, ey = double(b.y) - a.y;
  const double det = dx * (-ey) - dy * (-ex);
  if (det == 0.0) return -1.0;
  const double px = double(a.x) - ox, py = double(a.y) - oy;
  const double t = (px * (-ey) - py * (-ex)) / det, u = (dx * py - dy * px) / det;
  return u >= -1e-7 && u <= 1.0 + 1e-7 && t > 0.0 ? t : -1.0;  // a ray aimed at a corner: either wall
}

std::vector<std::string> flat_scenes() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(kFlatDir))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Flatland, ShapesBecomeWallsCirclesAndCaps) {
  Scene s = parse_scene(kScene, "flat.json");
  ASSERT_TRUE(s.flat);
  const Flatland& f = *s.flat;
  ASSERT_EQ(f.shapes.size(), 4u);
  EXPECT_EQ(f.shapes[0].name, "segment 0");
  EXPECT_EQ(f.shapes[1].name, "zigzag");
  // A segment: one wall of two triangles; the polyline: two walls; the filled square: four walls and a cap of
  // two triangles; the circle: one sphere.
  const uint32_t counts[] = {2, 4, 10, 1};
  uint32_t first = 0;
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(f.shapes[i].first_prim, first) << i;
    EXPECT_EQ(f.shapes[i].prim_count, counts[i]) << i;
    for (uint32_t p = first; p < first + counts[i]; ++p) EXPECT_EQ(f.shape_of(p), int(i)) << p;
    first += counts[i];
  }
  EXPECT_EQ(s.geometry.size(), first);
  EXPECT_EQ(f.shape_of(first), -1);
  EXPECT_EQ(s.geometry.type(first - 1), PrimType::sphere);
  EXPECT_EQ(s.geometry.material(f.shapes[2].first_prim), 1u);
  EXPECT_EQ(f.lo, glm::vec2(0.f, 0.f));
  EXPECT_EQ(f.hi, glm::vec2(8.f, 6.f));
  EXPECT_EQ(f.half_height, 4.f);  // half the larger side
  EXPECT_TRUE(f.has_ray);
  EXPECT_EQ(f.ray_origin, glm::vec2(-1.f, 0.5f));
  // Every wall stands across z in [-h, h]; the cap lies at z = h.
  for (uint32_t p = 0; p < f.shapes[2].first_prim + 8; ++p)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(std::fabs(s.geometry.vertex(p, k).z), 4.f);
  for (uint32_t p = f.shapes[2].first_prim + 8; p < f.shapes[2].first_prim + 10; ++p)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s.geometry.vertex(p, k).z, 4.f);
}

TEST(Flatland, TheCameraLooksDownOnTheFrame) {
  Scene s = parse_scene(kScene, "flat.json");
  EXPECT_EQ(s.camera.type, CameraType::orthographic);
  EXPECT_EQ(s.camera.look_at, glm::vec3(4.f, 3.f, 0.f));
  EXPECT_GT(s.camera.eye.z, s.flat->half_height);
  // 200 x 100: the 8 units of width need a height of 4; the 6 of height win, with a 5% margin.
  EXPECT_FLOAT_EQ(s.camera.ortho_height, 6.3f);
  // From above, the centre pixel of the filled square sees its cap, one of the segment's wall sees nothing.
  ProjectiveCamera cam(s.camera, 200, 100);
  auto accel = make_accelerator("bvh", StructureOptions{});
  accel->build(s.geometry);
  glm::dvec2 at;
  ASSERT_TRUE(cam.project(glm::vec3(6.5f, 1.5f, 0.f), &at));
  Hit h;
  ASSERT_TRUE(accel->intersect(cam.generate(float(at.x), float(at.y)), &h));
  EXPECT_EQ(s.flat->shape_of(uint32_t(h.prim)), 2);
  EXPECT_EQ(s.camera.up, glm::vec3(0.f, 1.f, 0.f));
  // A frame fixes the view: one unit per pixel.
  Scene framed = parse_scene(
      std::string(kScene).replace(std::string(kScene).find("\"ray\""), 0, "\"frame\": [[0, 0], [20, 10]],\n"),
      "flat.json");
  EXPECT_EQ(framed.camera.look_at, glm::vec3(10.f, 5.f, 0.f));
  EXPECT_EQ(framed.camera.ortho_height, 10.f);
}

TEST(Flatland, BadShapesNameTheirLine) {
  struct Case {
    std::string text, message;
    int line;
  };
  const Case cases[] = {
      {"{\"dimensions\": 2,\n\"camera\": {},\n\"objects\": [{\"type\": \"circle\", \"center\": [0, 0], "
       "\"radius\": 1}]}",
       "camera: a 2D scene has no camera", 2},
      {"{\"dimensions\": 2, \"objects\": [\n{\"type\": \"segment\", \"points\": [[0, 0, 0], [1, 0]]}]}",
       "objects[0].points[0]: expected [x, y]", 2},
      {"{\"dimensions\": 2, \"objects\": [\n{\"type\": \"segment\", \"points\": [[0, 0], [1, 0], [2, 0]]}]}",
       "objects[0].points: expected 2 points", 2},
      {"{\"dimensions\": 2, \"objects\": [{\"type\": \"polyline\",\n \"points\": [[0, 0], [1, 1],\n [1, "
       "1]]}]}",
       "objects[0].points[2]: the same point as the one before it", 3},
      {"{\"dimensions\": 2, \"objects\": [{\"type\": \"polygon\",\n \"points\": [[0, 0], [1, 1], [2, 2]]}]}",
       "objects[0].points: the polygon has no area", 2},
      {"{\"dimensions\": 2, \"objects\": [{\"type\": \"polygon\", \"fill\": true,\n \"points\": [[0, 0], [3, "
       "0], "
       "[0, 2], [2, 3]]}]}",
       "objects[0].points: the polygon crosses itself", 2},
      {"{\"dimensions\": 2, \"objects\": [{\"type\": \"polygon\", \"fill\": 1, \"points\": [[0, 0], [1, 0], "
       "[0, "
       "1]]}]}",
       "objects[0].fill: expected true or false", 1},
      {"{\"dimensions\": 2, \"objects\": [{\"type\": \"sphere\", \"center\": [0, 0], \"radius\": 1}]}",
       "objects[0].type: unknown type 'sphere' (expected one of segment, polyline, polygon, circle)", 1},
      {"{\"dimensions\": 2, \"objects\": [{\"type\": \"circle\", \"center\": [0, 0], \"radius\": 0}]}",
       "objects[0].radius: expected a positive number", 1},
      {"{\"dimensions\": 2, \"objects\": [{\"type\": \"circle\", \"center\": [0, 0], \"radius\": 1}],\n"
       "\"ray\": {\"origin\": [0, 0], \"direction\": [0, 0]}}",
       "ray.direction: expected a non-zero vector", 2},
      {"{\"dimensions\": 4, \"objects\": []}", "dimensions: expected an integer in 2..3", 1},
      {"{\"objects\": [{\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1}],\n\"ray\": {}}",
       "ray: 'ray' belongs to a 2D scene", 2},
      {"{\"dimensions\": 2, \"objects\": [{\"type\": \"circle\", \"center\": [0, 0], \"radius\": 1}],\n"
       "\"frame\": [[0, 0], [0, 1]]}",
       "frame[1]: expected x1 > x0 and y1 > y0", 2},
  };
  for (const Case& c : cases) {
    InputError e = scene_error(c.text);
    EXPECT_EQ(e.file(), "flat.json");
    EXPECT_NE(e.detail().find(c.message), std::string::npos) << e.detail() << "\n" << c.text;
    EXPECT_EQ(e.line(), c.line) << c.message;
  }
}

// Rays in the plane through every shipped 2D scene, from random points in random directions and aimed at
// every vertex of every shape: every structure gives brute force's primitive and t, and a segment's hit lies
// at the exact 2D intersection's t.
TEST(Flatland, EveryStructureWalksThePlaneAsBruteForce) {
  const std::vector<std::string> scenes = flat_scenes();
  ASSERT_GE(scenes.size(), 3u);
  int rays_total = 0, segment_hits = 0;
  for (const std::string& path : scenes) {
    Scene s = load_scene(path);
    ASSERT_TRUE(s.flat) << path;
    const Flatland& f = *s.flat;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> ux(f.lo.x - 1.f, f.hi.x + 1.f), uy(f.lo.y - 1.f, f.hi.y + 1.f),
        angle(0.f, 6.2831853f);
    std::vector<Ray> rays;
    for (int i = 0; i < 400; ++i) {
      const float a = angle(rng);
      rays.push_back(flat_ray({ux(rng), uy(rng)}, {std::cos(a), std::sin(a)}));
    }
    // Aimed at the vertices too (about 300 of them in the dense scene: every k-th).
    size_t vertices = 0;
    for (const FlatShape& shape : f.shapes) vertices += shape.points.size();
    const size_t stride = std::max<size_t>(1, vertices / 300);
    const glm::vec2 from(f.lo.x - 0.5f, f.lo.y - 0.25f);
    size_t k = 0;
    for (const FlatShape& shape : f.shapes)
      for (const glm::vec2& p : shape.points)
        if (k++ % stride == 0) rays.push_back(flat_ray(from, p - from));
    auto brute = make_accelerator("brute", StructureOptions{});
    brute->build(s.geometry);
    std::vector<Hit> truth(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
      brute->intersect(rays[i], &truth[i]);
      if (!truth[i].found()) continue;
      const int k = f.shape_of(uint32_t(truth[i].prim));
      ASSERT_GE(k, 0);
      const FlatShape& shape = f.shapes[size_t(k)];
      if (shape.kind == FlatShape::Kind::circle) continue;
      // The wall of the triangle hit: walls come two triangles each, in the order of the points.
      const size_t wall = (uint32_t(truth[i].prim) - shape.first_prim) / 2;
      if (wall >= shape.points.size()) continue;  // a filled polygon's cap is never met in the plane
      const glm::vec2 a = shape.points[wall], b = shape.points[(wall + 1) % shape.points.size()];
      const double t = segment_t(rays[i], a, b);
      ASSERT_GT(t, 0.0) << path << " ray " << i;
      EXPECT_NEAR(truth[i].t, t, 1e-5 * (1.0 + t)) << path << " ray " << i;
      ++segment_hits;
    }
    for (const std::string& name : accelerator_names()) {
      auto accel = make_accelerator(name, StructureOptions{});
      accel->build(s.geometry);
      int bad = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        Hit h;
        accel->intersect(rays[i], &h);
        bad += h.prim != truth[i].prim || (h.found() && h.t != truth[i].t);
      }
      EXPECT_EQ(bad, 0) << path << ", " << name;
    }
    rays_total += int(rays.size());
  }
  EXPECT_GT(segment_hits, rays_total / 4);
}

// A closed polygon seen from inside: a ray aimed exactly at a corner, where two walls share their vertical
// edge, meets one of them (the watertight test lets nothing through), with every structure.
TEST(Flatland, NoRayLeavesAClosedPolygonThroughACorner) {
  const char* text = R"({"dimensions": 2, "objects": [{"type": "polygon",
    "points": [[0, 0], [3.1, -0.7], [5.3, 1.9], [4.05, 4.4], [1.3, 3.85], [2.2, 1.7], [-0.35, 2.6]]}]})";
  Scene s = parse_scene(text, "star.json");
  const std::vector<glm::vec2>& p = s.flat->shapes[0].points;
  std::vector<Ray> rays;
  for (const glm::vec2& from : {glm::vec2(2.5f, 0.6f), glm::vec2(3.9f, 2.2f), glm::vec2(1.1f, 1.3f)})
    for (const glm::vec2& corner : p) rays.push_back(flat_ray(from, corner - from));
  for (const std::string& name : accelerator_names()) {
    auto accel = make_accelerator(name, StructureOptions{});
    accel->build(s.geometry);
    for (size_t i = 0; i < rays.size(); ++i) {
      Hit h;
      EXPECT_TRUE(accel->intersect(rays[i], &h)) << name << " ray " << i;
    }
  }
}

}  // namespace
}  // namespace raystep
