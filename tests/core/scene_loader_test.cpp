// Scene files (io/scene_loader.h, scene/json_locate.h): defaults, every field, every error with its
// line, the scenes/ folder, and bare meshes as scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "raystep/scene/json_locate.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

namespace fs = std::filesystem;

std::string temp_dir() {
  fs::path dir = fs::path(::testing::TempDir()) / "raystep_scene_loader_test";
  fs::create_directories(dir / "meshes");
  return dir.string();
}

std::string write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

const char* kSphere = R"({"type": "sphere", "center": [0, 0, 0], "radius": 1})";

// A scene of one sphere plus `extra` top-level members.
std::string scene_with(const std::string& extra) {
  return std::string("{\"objects\": [") + kSphere + "]" + (extra.empty() ? "" : ",\n" + extra) + "}";
}

InputError scene_error(const std::string& text) {
  try {
    parse_scene(text, "scene.json");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return InputError("", 0, "");
}

void expect_vec3(const glm::vec3& a, const glm::vec3& b, float tol = 1e-6f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(SceneLoader, EverythingButTheGeometryHasADefault) {
  Scene s = parse_scene(scene_with(""), "dir/scene.json");
  EXPECT_EQ(s.path, "dir/scene.json");
  Camera c;
  EXPECT_EQ(s.camera.type, CameraType::pinhole);
  EXPECT_EQ(s.camera.eye, c.eye);
  EXPECT_EQ(s.camera.look_at, c.look_at);
  EXPECT_EQ(s.camera.up, c.up);
  EXPECT_EQ(s.camera.fov_deg, c.fov_deg);
  // No "lights": one white point light at the eye.
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::point);
  EXPECT_EQ(s.lights[0].position, s.camera.eye);
  EXPECT_EQ(s.lights[0].color, glm::vec3(1.f));
  EXPECT_EQ(s.lights[0].intensity, 1.f);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  EXPECT_EQ(s.materials[0].diffuse, Material().diffuse);
  RenderSettings r;
  EXPECT_EQ(s.render.width, r.width);
  EXPECT_EQ(s.render.height, r.height);
  EXPECT_EQ(s.render.aa.mode, AntiAliasing::Mode::none);
  EXPECT_EQ(s.render.max_depth, r.max_depth);
  EXPECT_EQ(s.render.min_weight, r.min_weight);
  EXPECT_EQ(s.render.background, r.background);
  EXPECT_EQ(s.render.ambient, r.ambient);
  EXPECT_EQ(s.render.seed, r.seed);
  ASSERT_EQ(s.geometry.size(), 1u);
  EXPECT_EQ(s.geometry.type(0), PrimType::sphere);
  EXPECT_EQ(s.geometry.material(0), 0u);
  EXPECT_EQ(s.geometry.objects()[0].name, "sphere");
}

TEST(SceneLoader, EveryFieldIsRead) {
  Scene s = parse_scene(R"({
    "description": "all fields",
    "camera": {"type": "pinhole", "eye": [1, 2, 3], "look_at": [0, 1, 0], "up": [0, 0, 1], "fov": 55.5},
    "lights": [
      {"type": "point", "position": [4, 5, 6], "color": [0.5, 0.25, 1], "intensity": 2},
      {"type": "directional", "direction": [0, -1, 0], "color": 0.5, "intensity": 0.75}
    ],
    "materials": {
      "shiny": {"diffuse": [0.1, 0.2, 0.3], "specular": 0.5, "shininess": 64, "mirror": 0.25,
                "transparency": 0.5, "ior": 1.33},
      "default": {"diffuse": 0.5}
    },
    "objects": [
      {"type": "sphere", "name": "ball", "center": [1, 2, 3], "radius": 0.5, "material": "shiny"},
      {"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]},
      {"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "material": "default"},
      {"type": "box", "min": [0, 0, 0], "max": [1, 2, 3], "material": "shiny"}
    ],
    "render": {"size": [640, 480], "aa": "jitter:3", "max_depth": 7, "min_weight": 0.05,
               "background": [0.1, 0.2, 0.3], "ambient": 0.2, "seed": 18446744073709551615}
  })",
                        "scene.json");
  expect_vec3(s.camera.eye, {1, 2, 3});
  expect_vec3(s.camera.look_at, {0, 1, 0});
  expect_vec3(s.camera.up, {0, 0, 1});
  EXPECT_FLOAT_EQ(s.camera.fov_deg, 55.5f);
  ASSERT_EQ(s.lights.size(), 2u);
  expect_vec3(s.lights[0].position, {4, 5, 6});
  expect_vec3(s.lights[0].color, {0.5f, 0.25f, 1});
  EXPECT_EQ(s.lights[0].intensity, 2.f);
  EXPECT_EQ(s.lights[1].type, LightType::directional);
  expect_vec3(s.lights[1].direction, {0, -1, 0});
  expect_vec3(s.lights[1].color, glm::vec3(0.5f));
  EXPECT_EQ(s.lights[1].intensity, 0.75f);
  // "default" replaces material 0; the others follow.
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "default");
  expect_vec3(s.materials[0].diffuse, glm::vec3(0.5f));
  const Material& m = s.materials[1];
  EXPECT_EQ(m.name, "shiny");
  expect_vec3(m.diffuse, {0.1f, 0.2f, 0.3f});
  expect_vec3(m.specular, glm::vec3(0.5f));
  EXPECT_EQ(m.shininess, 64.f);
  EXPECT_EQ(m.mirror, 0.25f);
  EXPECT_EQ(m.transparency, 0.5f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  // Objects: ids in order, 1 + 1 + 2 + 12 primitives.
  const Geometry& g = s.geometry;
  ASSERT_EQ(g.size(), 16u);
  ASSERT_EQ(g.objects().size(), 4u);
  EXPECT_EQ(g.objects()[0].name, "ball");
  EXPECT_EQ(g.objects()[1].name, "triangle");
  EXPECT_EQ(g.objects()[2].first_prim, 2u);
  EXPECT_EQ(g.objects()[2].prim_count, 2u);
  EXPECT_EQ(g.objects()[3].first_prim, 4u);
  EXPECT_EQ(g.objects()[3].prim_count, 12u);
  EXPECT_EQ(g.material(0), 1u);
  EXPECT_EQ(g.material(1), 0u);
  EXPECT_EQ(g.material(2), 0u);
  EXPECT_EQ(g.material(15), 1u);
  EXPECT_EQ(g.sphere(0).radius, 0.5f);
  expect_vec3(g.sphere(0).center, {1, 2, 3});
  // The quad's second triangle is (v0, v2, v3).
  expect_vec3(g.vertex(3, 1), {1, 1, 0});
  expect_vec3(g.vertex(3, 2), {0, 1, 0});
  expect_vec3(g.objects()[3].bounds.hi, {1, 2, 3});
  EXPECT_EQ(s.render.width, 640);
  EXPECT_EQ(s.render.height, 480);
  EXPECT_EQ(s.render.aa.mode, AntiAliasing::Mode::jitter);
  EXPECT_EQ(s.render.aa.k, 3);
  EXPECT_EQ(s.render.max_depth, 7);
  EXPECT_EQ(s.render.min_weight, 0.05f);
  expect_vec3(s.render.background, {0.1f, 0.2f, 0.3f});
  expect_vec3(s.render.ambient, glm::vec3(0.2f));
  EXPECT_EQ(s.render.seed, 18446744073709551615ull);
}

// Regression input of the scene fuzzer (fuzz/scene_fuzz.cpp): a material name holding "\u0000" was looked up
// again by its C string, cut at the NUL, and nlohmann's out_of_range escaped instead of an InputError or a
// scene. The name is kept whole, and an object names it.
TEST(SceneLoader, MaterialNameWithANulCharacterIsReadWhole) {
  const std::string text = R"({"materials": {"solid": {"diffuse": 0.5}, "a\u0000b": {"diffuse": [0.9, 0.1, 0.1]}},
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "a\u0000b"}]})";
  Scene s = parse_scene(text, "scene.json");
  ASSERT_EQ(s.materials.size(), 3u);  // the default, then by name: "a\0b" sorts before "solid"
  EXPECT_EQ(s.materials[1].name, std::string("a\0b", 3));
  expect_vec3(s.materials[1].diffuse, glm::vec3(0.9f, 0.1f, 0.1f));
  EXPECT_EQ(s.geometry.material(0), 1u);
  // A material of that name that is not an object is refused as any other would be.
  InputError e = scene_error(R"({"materials": {"a\u0000b": 7}, "objects": [)" + std::string(kSphere) + "]}");
  EXPECT_NE(std::string(e.what()).find("scene.json"), std::string::npos) << e.what();
}

TEST(SceneLoader, OrthographicCameraAndNoLights) {
  Scene s = parse_scene(scene_with(R"("camera": {"type": "orthographic", "eye": [0, 0, 1], "height": 48},
                                      "lights": [])"),
                        "scene.json");
  EXPECT_EQ(s.camera.type, CameraType::orthographic);
  EXPECT_EQ(s.camera.ortho_height, 48.f);
  EXPECT_TRUE(s.lights.empty());
}

TEST(SceneLoader, TransformsApplyScaleThenRotateThenTranslate) {
  // The point (1, 0, 0): scaled by 2 -> (2, 0, 0); turned 90 degrees about z -> (0, 2, 0); moved -> (10, 2, 0).
  Scene s = parse_scene(R"({"objects": [
      {"type": "triangle", "vertices": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
       "transform": {"translate": [10, 0, 0], "scale": 2, "rotate": {"axis": [0, 0, 3], "degrees": 90}}},
      {"type": "triangle", "vertices": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
       "transform": {"scale": [1, 2, 3]}},
      {"type": "triangle", "vertices": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
       "transform": {"matrix": [[1, 0, 0, 5], [0, 2, 0, 6], [0, 0, 3, 7], [0, 0, 0, 1]]}}]})",
                        "scene.json");
  ASSERT_EQ(s.geometry.size(), 3u);
  expect_vec3(s.geometry.vertex(0, 0), {10, 2, 0}, 1e-5f);
  expect_vec3(s.geometry.vertex(0, 1), {8, 0, 0}, 1e-5f);
  expect_vec3(s.geometry.vertex(0, 2), {10, 0, 2}, 1e-5f);
  expect_vec3(s.geometry.vertex(1, 1), {0, 2, 0});
  expect_vec3(s.geometry.vertex(1, 2), {0, 0, 3});
  // The matrix is written row by row and applied to column vectors: p' = M p.
  expect_vec3(s.geometry.vertex(2, 0), {6, 6, 7});
  expect_vec3(s.geometry.vertex(2, 2), {5, 6, 10});
}

TEST(SceneLoader, MeshesAreFoundBesideTheSceneFile) {
  std::string dir = temp_dir();
  write_file(dir + "/meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 4\n");
  std::string path = write_file(dir + "/mesh_scene.json", R"({
    "materials": {"red": {"diffuse": [1, 0, 0]}},
    "objects": [
      {"type": "mesh", "file": "meshes/tri.obj", "material": "red"},
      {"type": "mesh", "file": "meshes/tri.obj", "name": "moved", "transform": {"translate": [0, 0, -2]}}
    ]})");
  Scene s = load_scene(path);
  ASSERT_EQ(s.geometry.size(), 4u);
  EXPECT_EQ(s.geometry.objects()[0].name, "mesh meshes/tri.obj");
  EXPECT_EQ(s.geometry.objects()[1].name, "moved");
  EXPECT_EQ(s.geometry.material(1), 1u);
  EXPECT_EQ(s.geometry.material(2), 0u);
  EXPECT_TRUE(s.geometry.has_vertex_normals(0));
  EXPECT_FALSE(s.geometry.has_vertex_normals(1));
  expect_vec3(s.geometry.vertex(3, 2), {0, 0, -1});
}

TEST(SceneLoader, ABareObjIsASceneWithACameraThatFramesIt) {
  std::string path = write_file(temp_dir() + "/bare.OBJ",
                                "v -1 0 0\nv 3 0 0\nv 3 2 0\nv -1 2 -4\nf 1 2 3 4\n");
  Scene s = load_scene(path);
  EXPECT_EQ(s.path, path);
  ASSERT_EQ(s.geometry.size(), 2u);
  ASSERT_EQ(s.materials.size(), 1u);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].position, s.camera.eye);
  EXPECT_EQ(s.camera.type, CameraType::pinhole);
  // Looks at the centre of the bounds, from the front (+z), above (+y) and right (+x).
  Bounds3 b = s.geometry.bounds();
  expect_vec3(s.camera.look_at, b.center());
  glm::vec3 view = s.camera.look_at - s.camera.eye;
  EXPECT_LT(view.x, 0.f);
  EXPECT_LT(view.y, 0.f);
  EXPECT_LT(view.z, 0.f);
  // The whole bounding sphere lies inside the vertical field of view: r / d <= sin(fov / 2).
  float r = 0.5f * glm::length(b.extent()), d = glm::length(view);
  EXPECT_LE(r / d, std::sin(glm::radians(s.camera.fov_deg / 2)));
  EXPECT_GT(r / d, 0.8f * std::sin(glm::radians(s.camera.fov_deg / 2)));  // and fills most of it
  // Every corner of the bounds is within fov/2 of the view direction.
  for (int i = 0; i < 8; ++i) {
    glm::vec3 corner(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
    float angle = std::acos(glm::dot(glm::normalize(corner - s.camera.eye), glm::normalize(view)));
    EXPECT_LT(angle, glm::radians(s.camera.fov_deg / 2));
  }
  EXPECT_EQ(scene_from_mesh(path).geometry.size(), 2u);
}

TEST(SceneLoader, CameraFramingOfAPointStillWorks) {
  Camera c = camera_framing(Bounds3(glm::vec3(2.f), glm::vec3(2.f)));
  expect_vec3(c.look_at, glm::vec3(2.f));
  EXPECT_GT(glm::length(c.eye - c.look_at), 0.f);
}

struct BadScene {
  std::string text;
  int line;
  std::string message;  // the message after "scene.json:LINE: "
};

TEST(SceneLoader, EveryErrorNamesFileLineAndPath) {
  const std::string sphere = kSphere;
  const BadScene cases[] = {
      // syntax, numbers nlohmann cannot hold, duplicate keys
      {"{\n\"objects\": [\n" + sphere + ",\n]\n}", 4, "syntax error while parsing value - unexpected ']'"},
      {"{\n\"objects\": [\n" + sphere + "\n]\n", 4, "syntax error while parsing object - unexpected end of input"},
      {"", 1, "syntax error while parsing value - unexpected end of input"},
      {scene_with("\"render\": {\n\"min_weight\":\n1e999}"), 4, "number overflow parsing '1e999'"},
      {scene_with("\"render\": {\"seed\": 1,\n \"seed\": 2}"), 3, "render.seed: duplicate key"},
      {"[1, 2]", 1, "expected an object"},
      // unknown keys, at every level
      {scene_with("\"lihgts\": []"), 2, "lihgts: unknown key 'lihgts' (expected description, dimensions, "
                                        "camera, lights, materials, objects, render, ray, frame)"},
      {scene_with("\"camera\": {\"fov\": 30,\n\"height\": 2}"), 3,
       "camera.height: unknown key 'height' (expected type, eye, look_at, up, fov)"},
      {scene_with("\"camera\": {\"type\": \"orthographic\",\n\"fov\": 30}"), 3, "camera.fov: unknown key 'fov'"},
      {scene_with("\"materials\": {\"a\":\n{\"difuse\": 1}}"), 3, "materials.a.difuse: unknown key 'difuse'"},
      {scene_with("\"render\": {\n\"width\": 3}"), 3, "render.width: unknown key 'width'"},
      {scene_with("\"lights\": [{\"type\": \"directional\",\n \"position\": [0, 1, 0]}]"), 3,
       "lights[0].position: unknown key 'position' (expected type, direction, color, intensity)"},
      {"{\"objects\": [" + sphere + ",\n" + R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "transform": {}})" +
           "]}",
       2, "objects[1].transform: unknown key 'transform' (expected center, radius, type, name, material)"},
      {R"({"objects": [{"type": "box", "min": [0, 0, 0], "max": [1, 1, 1],)" "\n" R"("transform": {"shear": 1}}]})",
       2, "objects[0].transform.shear: unknown key 'shear'"},
      // wrong types and ranges
      {scene_with("\"camera\": {\n\"fov\": \"wide\"}"), 3, "camera.fov: expected a number of degrees in (0, 180)"},
      {scene_with("\"camera\": {\n\"fov\": 0}"), 3, "camera.fov: expected a number of degrees in (0, 180)"},
      {scene_with("\"camera\": {\n\"fov\": 180}"), 3, "camera.fov: expected a number of degrees in (0, 180)"},
      {scene_with("\"camera\": {\"type\": \"orthographic\", \"height\":\n-2}"), 3, "camera.height: expected a positive number"},
      {scene_with("\"camera\": {\n\"type\": \"fisheye\"}"), 3, "camera.type: unknown type 'fisheye' (expected one of pinhole, orthographic)"},
      {scene_with("\"camera\": {\"eye\": [1, 2],\n\"fov\": 30}"), 2, "camera.eye: expected [x, y, z]"},
      {scene_with("\"camera\": {\"eye\": [1,\n\"2\", 3]}"), 3, "camera.eye[1]: expected a number"},
      {scene_with("\"camera\": {\"eye\": [0, 0, 5],\n\"look_at\": [0, 0, 5]}"), 3, "camera.look_at: look_at must differ from eye"},
      {scene_with("\"camera\": {\"eye\": [0, 0, 5],\n\"up\": [0, 0, -2]}"), 3, "camera.up: up must not be parallel"},
      {scene_with("\"camera\": {\n\"up\": [0, 0, 0]}"), 3, "camera.up: expected a non-zero vector"},
      {"{\"objects\": [\n{\"type\": \"sphere\", \"center\": [0, 0, 0],\n\"radius\": -1}]}", 3,
       "objects[0].radius: expected a positive number"},
      {"{\"objects\": [\n{\"type\": \"sphere\", \"center\": [0, 0, 0],\n\"radius\": 0}]}", 3,
       "objects[0].radius: expected a positive number"},
      {"{\"objects\": [\n{\"type\": \"sphere\", \"center\": [0, 0, 0],\n\"radius\": 1e39}]}", 3,
       "objects[0].radius: expected a positive number (1e+39 is not finite in single precision)"},
      {"{\"objects\": [\n{\"type\": \"sphere\",\n\"radius\": 1}]}", 2, "objects[0]: missing 'center'"},
      {scene_with("\"render\": {\"size\":\n[0, 10]}"), 3, "render.size[0]: expected an integer in 1..16384"},
      {scene_with("\"render\": {\"size\": [10,\n-1]}"), 3, "render.size[1]: expected an integer in 1..16384"},
      {scene_with("\"render\": {\"size\": [10,\n16385]}"), 3, "render.size[1]: expected an integer in 1..16384"},
      {scene_with("\"render\": {\"size\": [10.5,\n10]}"), 2, "render.size[0]: expected an integer in 1..16384"},
      {scene_with("\"render\": {\n\"size\": [10]}"), 3, "render.size: expected [width, height]"},
      {scene_with("\"render\": {\n\"max_depth\": 33}"), 3, "render.max_depth: expected an integer in 0..32"},
      {scene_with("\"render\": {\n\"seed\": -1}"), 3, "render.seed: expected a non-negative integer"},
      {scene_with("\"render\": {\n\"min_weight\": 2}"), 3, "render.min_weight: expected a number in [0, 1]"},
      {scene_with("\"render\": {\n\"aa\": \"jitter:100\"}"), 3, "render.aa: bad anti-aliasing 'jitter:100': expected"},
      {scene_with("\"render\": {\n\"aa\": 4}"), 3, "render.aa: expected a string"},
      {scene_with("\"render\": {\n\"background\": [0, 0, -1]}"), 3, "render.background[2]: expected a non-negative number"},
      {scene_with("\"materials\": {\"a\": {\n\"diffuse\": 1.5}}"), 3, "materials.a.diffuse: expected a number in [0, 1]"},
      {scene_with("\"materials\": {\"a\": {\n\"diffuse\": \"red\"}}"), 3, "materials.a.diffuse: expected [r, g, b] or one number"},
      {scene_with("\"materials\": {\"a\": {\n\"ior\": 0}}"), 3, "materials.a.ior: expected a positive number"},
      {scene_with("\"materials\":\n[]"), 3, "materials: expected an object of named materials"},
      {scene_with("\"lights\": [{\n\"position\": [0, 1, 0]}]"), 2, "lights[0]: missing 'type' (one of point, directional)"},
      {scene_with("\"lights\": [{\"type\": \"point\",\n\"intensity\": -1}]"), 3, "lights[0].intensity: expected a non-negative number"},
      {scene_with("\"lights\": [{\"type\": \"directional\",\n\"direction\": [0, 0, 0]}]"), 3,
       "lights[0].direction: expected a non-zero vector"},
      {scene_with("\"description\":\n7"), 3, "description: expected a string"},
      // objects
      {"{\"materials\": {\"red\": {}},\n\"objects\": [\n{\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1,\n"
       "\"material\": \"blue\"}]}",
       4, "objects[0].material: unknown material 'blue' (defined: default, red)"},
      {"{\"objects\": [\n{\"type\": \"cone\"}]}", 2, "objects[0].type: unknown type 'cone' (expected one of mesh, "
                                                    "sphere, triangle, quad, box)"},
      {"{\"objects\": [\n{\"center\": [0, 0, 0]}]}", 2, "objects[0]: missing 'type'"},
      {"{\"camera\": {}}", 1, "missing 'objects'"},
      {"{\"objects\":\n[]}", 2, "objects: expected a non-empty array of objects"},
      {"{\"objects\": [{\"type\": \"quad\",\n\"vertices\": [[0, 0, 0], [1, 0, 0], [1, 1, 0]]}]}", 2,
       "objects[0].vertices: expected 4 vertices [x, y, z]"},
      {"{\"objects\": [{\"type\": \"box\", \"min\": [0, 0, 0],\n\"max\": [1, -1, 1]}]}", 2,
       "objects[0].max: expected max >= min on every axis"},
      {"{\"objects\": [{\"type\": \"box\", \"min\": [0, 0, 0], \"max\": [1, 1, 1], \"transform\": {\"translate\": [1, 0, 0],\n"
       "\"matrix\": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}}]}",
       2, "objects[0].transform.matrix: a matrix cannot be combined with translate, rotate or scale"},
      {"{\"objects\": [{\"type\": \"box\", \"min\": [0, 0, 0], \"max\": [1, 1, 1], \"transform\": {\"matrix\":\n"
       "[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0],\n[0, 0, 1, 1]]}}]}",
       3, "objects[0].transform.matrix[3]: expected [0, 0, 0, 1]: only affine transforms are allowed"},
      {"{\"objects\": [{\"type\": \"box\", \"min\": [0, 0, 0], \"max\": [1, 1, 1],\n\"transform\": {\"matrix\":\n"
       "[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0], [0, 0, 0, 1]]}}]}",
       2, "objects[0].transform: the transform is singular"},
      {"{\"objects\": [{\"type\": \"box\", \"min\": [0, 0, 0], \"max\": [1, 1, 1], \"transform\": {\n\"scale\": [1, 0, 1]}}]}",
       2, "objects[0].transform.scale: expected a non-zero scale"},
      {"{\"objects\": [{\"type\": \"box\", \"min\": [0, 0, 0], \"max\": [1, 1, 1], \"transform\": {\"rotate\":\n"
       "{\"axis\": [0, 0, 0], \"degrees\": 5}}}]}",
       2, "objects[0].transform.rotate.axis: expected a non-zero vector"},
      {"{\"objects\": [{\"type\": \"mesh\",\n\"file\": \"no_such_mesh.obj\"}]}", 2,
       "objects[0].file: cannot open mesh '" + (fs::path(temp_dir()) / "no_such_mesh.obj").string() + "': no such file"},
      {"{\"objects\": [{\"type\": \"mesh\",\n\"file\": 3}]}", 2, "objects[0].file: expected a string"},
  };
  for (const BadScene& c : cases) {
    InputError e("", 0, "");
    try {
      parse_scene(c.text, temp_dir() + "/scene.json");
      ADD_FAILURE() << "no error for:\n" << c.text;
      continue;
    } catch (const InputError& err) {
      e = err;
    }
    EXPECT_EQ(e.file(), temp_dir() + "/scene.json");
    EXPECT_EQ(e.line(), c.line) << c.text << "\n" << e.what();
    EXPECT_EQ(e.detail().substr(0, c.message.size()), c.message) << c.text << "\n" << e.what();
  }
}

TEST(SceneLoader, MessagesReadFileColonLineColonPath) {
  InputError e = scene_error("{\"objects\": [\n" + std::string(kSphere) + ",\n" +
                             R"({"type": "sphere", "center": [0, 0, 0],)" "\n" R"("radius": -2}]})");
  EXPECT_STREQ(e.what(), "scene.json:4: objects[1].radius: expected a positive number");
}

TEST(SceneLoader, ABadMeshNamesTheMeshFileAndItsLine) {
  std::string dir = temp_dir();
  write_file(dir + "/meshes/bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  std::string path = write_file(dir + "/bad_mesh_scene.json", R"({"objects": [{"type": "mesh", "file": "meshes/bad.obj"}]})");
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (fs::path(dir) / "meshes/bad.obj").string());
    EXPECT_EQ(e.line(), 4);
  }
}

TEST(SceneLoader, MissingSceneFile) {
  try {
    load_scene(temp_dir() + "/none.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.detail(), "cannot open: no such file");
  }
}

// Every scene shipped in scenes/ loads, and the special ones are what their descriptions say.
TEST(SceneLoader, EverySceneInTheScenesFolderLoads) {
  fs::path dir = fs::path(RAYSTEP_SOURCE_DIR) / "scenes";
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    Scene s = load_scene(entry.path().string());
    EXPECT_GT(s.geometry.size(), 0u);
    EXPECT_FALSE(s.geometry.bounds().empty());
    ++count;
  }
  EXPECT_GE(count, 4);
}

TEST(SceneLoader, TheDefaultCornellBox) {
  Scene s = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json");
  EXPECT_EQ(s.render.width, 320);
  EXPECT_EQ(s.render.height, 320);
  EXPECT_EQ(s.lights.size(), 1u);
  bool red = false, green = false, mirror = false;
  for (const Material& m : s.materials) {
    red |= m.diffuse.r > 2 * m.diffuse.g;
    green |= m.diffuse.g > 2 * m.diffuse.r;
    mirror |= m.mirror > 0.5f;
  }
  EXPECT_TRUE(red && green && mirror);
  // The light is inside the room, below the ceiling.
  EXPECT_TRUE(s.geometry.bounds().contains(s.lights[0].position));
}

TEST(SceneLoader, TheAliasingSceneShowsCoverageAsPixelValue) {
  Scene s = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/aliasing.json");
  EXPECT_EQ(s.camera.type, CameraType::orthographic);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(s.render.background, glm::vec3(0.f));
  ASSERT_EQ(s.geometry.size(), 1u);
  // Lit only by the ambient term: ambient x diffuse = 1 exactly, no highlight, no reflection.
  const Material& m = s.materials[s.geometry.material(0)];
  EXPECT_EQ(s.render.ambient * m.diffuse, glm::vec3(1.f));
  EXPECT_EQ(m.specular, glm::vec3(0.f));
  EXPECT_EQ(m.mirror, 0.f);
  // The view is 64 x 48 world units, one unit per pixel; the triangle's edges are not axis-aligned.
  EXPECT_EQ(s.camera.ortho_height, float(s.render.height));
  for (int k = 0; k < 3; ++k) {
    glm::vec3 e = s.geometry.vertex(0, (k + 1) % 3) - s.geometry.vertex(0, k);
    EXPECT_NE(e.x, 0.f);
    EXPECT_NE(e.y, 0.f);
  }
}

TEST(SceneLoader, TheTorusKnotMeshHasOutwardNormalsAgreeingWithItsWinding) {
  Scene s = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/torus_knot.json");
  const Object& knot = s.geometry.objects()[0];
  EXPECT_EQ(knot.prim_count, 4608u);
  for (uint32_t id = knot.first_prim; id < knot.first_prim + knot.prim_count; ++id) {
    ASSERT_TRUE(s.geometry.has_vertex_normals(id));
    glm::vec3 p0 = s.geometry.vertex(id, 0), p1 = s.geometry.vertex(id, 1), p2 = s.geometry.vertex(id, 2);
    glm::vec3 n = s.geometry.vertex_normal(id, 0) + s.geometry.vertex_normal(id, 1) + s.geometry.vertex_normal(id, 2);
    ASSERT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), n), 0.f) << "triangle " << id;
  }
}

// json_locate: the line finder behind every message above.
TEST(JsonLocate, FindsTheLineOfAValueByPointer) {
  const std::string text =
      "{\n"                                   // 1
      "  \"a\": [10,\n"                       // 2
      "        {\"b\": \"x}]\\\"\",\n"        // 3  a string holding } ] \"
      "         \"c/d\": [\n"                 // 4
      "           1]},\n"                     // 5
      "        30],\n"                        // 6
      "  \"\\u00e9t\\u00e9\": 5,\n"          // 7  "été"
      "  \"e\": {}, \"e\":\n"                 // 8  duplicate: the last counts
      "  {\"f\": 1}\n"                        // 9
      "}\n";
  EXPECT_EQ(json_line_of(text, ""), 1);
  EXPECT_EQ(json_line_of(text, "/a"), 2);
  EXPECT_EQ(json_line_of(text, "/a/0"), 2);
  EXPECT_EQ(json_line_of(text, "/a/1"), 3);
  EXPECT_EQ(json_line_of(text, "/a/1/b"), 3);
  EXPECT_EQ(json_line_of(text, "/a/1/c~1d"), 4);
  EXPECT_EQ(json_line_of(text, "/a/1/c~1d/0"), 5);
  EXPECT_EQ(json_line_of(text, "/a/2"), 6);
  EXPECT_EQ(json_line_of(text, "/\xc3\xa9t\xc3\xa9"), 7);
  EXPECT_EQ(json_line_of(text, "/e"), 9);
  EXPECT_EQ(json_line_of(text, "/e/f"), 9);
  // Missing members: the deepest ancestor that exists.
  EXPECT_EQ(json_line_of(text, "/a/1/zzz"), 3);
  EXPECT_EQ(json_line_of(text, "/a/7"), 2);
  EXPECT_EQ(json_line_of(text, "/zzz/0"), 1);
  EXPECT_EQ(json_line_of(text, JsonPath().child("a").child(1).child("c/d")), 4);
  EXPECT_EQ(json_line_of("{\"a\": [1, 2", "/a/1"), 0);  // not JSON
}

TEST(JsonLocate, PathsInBothSpellings) {
  JsonPath p = JsonPath().child("objects").child(2).child("a/b~c");
  EXPECT_EQ(p.pointer(), "/objects/2/a~1b~0c");
  EXPECT_EQ(p.display(), "objects[2].a/b~c");
  EXPECT_EQ(JsonPath().display(), "");
}

TEST(JsonLocate, ByteOffsetsAndNumbersAndDuplicates) {
  EXPECT_EQ(json_line_at_byte("{\n\"a\": [1,2,\n}", 14), 3);
  EXPECT_EQ(json_line_at_byte("{\n", 3), 1);  // end of input after the last newline: the last line with text
  EXPECT_EQ(json_line_at_byte("", 1), 1);
  EXPECT_EQ(json_line_of_number("{\"1e999\": 1,\n \"b\": [-1e999,\n 1e999]}", "1e999"), 3);
  JsonDuplicateKey dup;
  EXPECT_FALSE(json_find_duplicate_key("{\"a\": {\"b\": 1}, \"b\": [{\"b\": 2}]}", &dup));
  ASSERT_TRUE(json_find_duplicate_key("{\"a\": [{}, {\"x\": 1,\n\"y\": 2,\n\"x\": 3}]}", &dup));
  EXPECT_EQ(dup.pointer, "/a/1/x");
  EXPECT_EQ(dup.display, "a[1].x");
  EXPECT_EQ(dup.line, 3);
}

TEST(JsonLocate, DeepNestingDoesNotRecurse) {
  std::string deep(50000, '[');
  deep += std::string(50000, ']');
  EXPECT_EQ(json_line_of(deep, "/0/0/0"), 1);
  JsonDuplicateKey dup;
  EXPECT_FALSE(json_find_duplicate_key(deep, &dup));
  // A whole scene that nests deeply: an error, not a stack overflow.
  InputError e = scene_error("{\"objects\": " + deep + "}");
  EXPECT_EQ(e.line(), 1);
  EXPECT_EQ(e.detail(), "objects[0]: expected an object");
}

}  // namespace
}  // namespace raystep
