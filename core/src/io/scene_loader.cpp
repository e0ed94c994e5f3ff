// The JSON scene reader. The schema lives in tables (allowed keys per section and per kind of camera,
// light and object), so an unknown key is caught in one place, and each value is read by one converter
// that knows its range. Errors name the file, the line (found by json_locate only when reporting) and the
// path of the value. docs/scene-format.md documents every field; keep the two in step.
#include "raystep/io/scene_loader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_set>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include "raystep/io/obj.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/scene/flatland.h"
#include "raystep/scene/json_locate.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr size_t kMaxSceneBytes = 64u << 20;  // scenes are small; big geometry belongs in OBJ files
constexpr int kMaxImageSide = 16384;
constexpr int kMaxDepth = 32;

// The keys each part of the file may have. Anything else is an error, so that a misspelt key never
// silently leaves a default in place.
using Keys = std::vector<const char*>;
const Keys kTopKeys = {"description", "dimensions", "camera", "lights", "materials",
                       "objects",     "render",     "ray",    "frame"};
const Keys kFlatRayKeys = {"origin", "direction"};
const Keys kMaterialKeys = {"diffuse", "specular", "shininess", "mirror", "transparency", "ior"};
const Keys kRenderKeys = {"size", "aa", "max_depth", "min_weight", "background", "ambient", "seed"};
const Keys kTransformKeys = {"translate", "rotate", "scale", "matrix"};
const Keys kRotateKeys = {"axis", "degrees"};

struct CameraKind {
  const char* type;
  CameraType camera_type;
  Keys keys;
};
const CameraKind kCameraKinds[] = {
    {"pinhole", CameraType::pinhole, {"type", "eye", "look_at", "up", "fov"}},
    {"orthographic", CameraType::orthographic, {"type", "eye", "look_at", "up", "height"}},
};

struct LightKind {
  const char* type;
  LightType light_type;
  Keys keys;
};
const LightKind kLightKinds[] = {
    {"point", LightType::point, {"type", "position", "color", "intensity"}},
    {"directional", LightType::directional, {"type", "direction", "color", "intensity"}},
};

// Value ranges; `expected` completes "expected ...".
struct Range {
  double lo, hi;
  bool lo_open, hi_open;
  const char* expected;
  bool contains(double v) const { return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi); }
};
constexpr double kInf = std::numeric_limits<double>::infinity();
const Range kAnyNumber{-kInf, kInf, false, false, "a number"};
const Range kPositive{0, kInf, true, false, "a positive number"};
const Range kNonNegative{0, kInf, false, false, "a non-negative number"};
const Range kUnit{0, 1, false, false, "a number in [0, 1]"};
const Range kFov{0, 180, true, true, "a number of degrees in (0, 180)"};

std::string join(const Keys& keys) {
  std::string s;
  for (const char* k : keys) s += (s.empty() ? "" : ", ") + std::string(k);
  return s;
}

// A value of the document and where it is.
struct Node {
  const json& value;
  JsonPath path;
  bool has(const char* key) const { return value.is_object() && value.contains(key); }
  Node at(const char* key) const { return {value.at(key), path.child(key)}; }
  Node at(size_t i) const { return {value.at(i), path.child(i)}; }
};

class SceneReader {
 public:
  SceneReader(const std::string& text, const std::string& path) : text_(text), path_(path) {
    folder_ = fs::path(path).parent_path();
  }

  Scene read(const json& root) {
    Node top{root, JsonPath()};
    check_keys(top, kTopKeys);
    if (top.has("description")) text_value(top.at("description"));
    Scene scene;
    scene.path = path_;
    read_materials(top, &scene);
    const int dimensions = top.has("dimensions") ? integer(top.at("dimensions"), 2, 3) : 3;
    if (dimensions == 2) {
      if (top.has("render")) scene.render = read_render(top.at("render"));  // the camera frames its size
      read_flat(top, &scene);
    } else {
      for (const char* key : {"ray", "frame"})
        if (top.has(key))
          fail(top.path.child(key), std::string("'") + key + "' belongs to a 2D scene (\"dimensions\": 2)");
      read_objects(top, &scene);
      if (top.has("camera")) scene.camera = read_camera(top.at("camera"));
    }
    read_lights(top, &scene);
    if (top.has("render")) scene.render = read_render(top.at("render"));
    return scene;
  }

 private:
  [[noreturn]] void fail(const JsonPath& at, const std::string& what) const {
    std::string where = at.display();
    throw InputError(path_, json_line_of(text_, at), where.empty() ? what : where + ": " + what);
  }

  // Section checks ---------------------------------------------------------------------------------

  void check_keys(const Node& n, const Keys& allowed) const {
    if (!n.value.is_object()) fail(n.path, "expected an object");
    for (auto it = n.value.begin(); it != n.value.end(); ++it) {
      bool known = std::any_of(allowed.begin(), allowed.end(), [&](const char* k) { return it.key() == k; });
      if (!known)
        fail(n.path.child(it.key()), "unknown key '" + it.key() + "' (expected " + join(allowed) + ")");
    }
  }

  Node required(const Node& n, const char* key) const {
    if (!n.has(key)) fail(n.path, std::string("missing '") + key + "'");
    return n.at(key);
  }

  // The "type" member, looked up in a table of kinds.
  template <class Kind, size_t N>
  const Kind& kind_of(const Node& n, const Kind (&kinds)[N], const char* fallback) const {
    if (!n.value.is_object()) fail(n.path, "expected an object");
    std::string names;
    for (const Kind& k : kinds) names += (names.empty() ? "" : ", ") + std::string(k.type);
    if (!n.has("type") && !fallback) fail(n.path, "missing 'type' (one of " + names + ")");
    std::string type = n.has("type") ? text_value(n.at("type")) : fallback;
    for (const Kind& k : kinds)
      if (type == k.type) return k;
    fail(n.path.child("type"), "unknown type '" + type + "' (expected one of " + names + ")");
  }

  // A scene's object or shape: its kind, and its keys checked (the kind's own, type, name and material).
  template <class Kind, size_t N>
  const Kind& object_kind(const Node& n, const Kind (&kinds)[N]) const {
    const Kind& kind = kind_of(n, kinds, nullptr);
    Keys keys = kind.keys;
    keys.insert(keys.end(), {"type", "name", "material"});
    check_keys(n, keys);
    return kind;
  }

  // Converters -------------------------------------------------------------------------------------

  float number(const Node& n, const Range& r) const {
    if (!n.value.is_number()) fail(n.path, std::string("expected ") + r.expected);
    double v = n.value.get<double>();  // nlohmann rejects NaN, Inf and doubles that overflow; floats may
    if (std::fabs(v) > std::numeric_limits<float>::max())
      fail(n.path, std::string("expected ") + r.expected + " (" + n.value.dump() +
                       " is not finite in single precision)");
    if (!r.contains(v)) fail(n.path, std::string("expected ") + r.expected);
    return float(v);
  }

  float number(const Node& obj, const char* key, float fallback, const Range& r) const {
    return obj.has(key) ? number(obj.at(key), r) : fallback;
  }

  int integer(const Node& n, int lo, int hi) const {
    std::string expected = "expected an integer in " + std::to_string(lo) + ".." + std::to_string(hi);
    if (!n.value.is_number_integer()) fail(n.path, expected);
    if (n.value.is_number_unsigned() && n.value.get<uint64_t>() > uint64_t(hi)) fail(n.path, expected);
    int64_t v = n.value.get<int64_t>();
    if (v < lo || v > hi) fail(n.path, expected);
    return int(v);
  }

  std::string text_value(const Node& n) const {
    if (!n.value.is_string()) fail(n.path, "expected a string");
    return n.value.get<std::string>();
  }

  glm::vec3 vec3(const Node& n, const Range& each = kAnyNumber) const {
    if (!n.value.is_array() || n.value.size() != 3) fail(n.path, "expected [x, y, z]");
    return glm::vec3(number(n.at(size_t(0)), each), number(n.at(1), each), number(n.at(2), each));
  }

  glm::vec3 vec3(const Node& obj, const char* key, const glm::vec3& fallback) const {
    return obj.has(key) ? vec3(obj.at(key)) : fallback;
  }

  glm::vec3 nonzero_vec3(const Node& n) const {
    glm::vec3 v = vec3(n);
    if (v == glm::vec3(0.f)) fail(n.path, "expected a non-zero vector");
    return v;
  }

  // A colour: [r, g, b], or one number for a grey.
  glm::vec3 color(const Node& obj, const char* key, const glm::vec3& fallback, const Range& r) const {
    if (!obj.has(key)) return fallback;
    Node n = obj.at(key);
    if (n.value.is_number()) return glm::vec3(number(n, r));
    if (!n.value.is_array() || n.value.size() != 3)
      fail(n.path, std::string("expected [r, g, b] or one number"));
    return vec3(n, r);
  }

  // Sections ---------------------------------------------------------------------------------------

  void read_materials(const Node& top, Scene* scene) {
    scene->materials.assign(1, Material());  // index 0: the default material (a scene may redefine it)
    if (!top.has("materials")) return;
    Node all = top.at("materials");
    if (!all.value.is_object()) fail(all.path, "expected an object of named materials");
    for (auto it = all.value.begin(); it != all.value.end(); ++it) {  // nlohmann keeps keys sorted
      // The member itself, not a second look-up by the key's C string: a name may hold "\u0000" (a fuzz
      // finding: the look-up cut it at the NUL and nlohmann's out_of_range escaped).
      Node n{it.value(), all.path.child(it.key())};
      check_keys(n, kMaterialKeys);
      Material m;
      m.name = it.key();
      m.diffuse = color(n, "diffuse", m.diffuse, kUnit);
      m.specular = color(n, "specular", m.specular, kUnit);
      m.shininess = number(n, "shininess", m.shininess, kNonNegative);
      m.mirror = number(n, "mirror", m.mirror, kUnit);
      m.transparency = number(n, "transparency", m.transparency, kUnit);
      m.ior = number(n, "ior", m.ior, kPositive);
      if (m.name == "default")
        scene->materials[0] = m;
      else
        scene->materials.push_back(m);
    }
  }

  Camera read_camera(const Node& n) const {
    const CameraKind& kind = kind_of(n, kCameraKinds, "pinhole");
    check_keys(n, kind.keys);
    Camera c;
    c.type = kind.camera_type;
    c.eye = vec3(n, "eye", c.eye);
    c.look_at = vec3(n, "look_at", c.look_at);
    if (n.has("up")) c.up = nonzero_vec3(n.at("up"));
    c.fov_deg = number(n, "fov", c.fov_deg, kFov);
    c.ortho_height = number(n, "height", c.ortho_height, kPositive);
    glm::vec3 view = c.look_at - c.eye;
    if (view == glm::vec3(0.f))
      fail(n.has("look_at") ? n.path.child("look_at") : n.path, "look_at must differ from eye");
    // |view x up| relative to |view| |up|: zero when up is parallel to the view direction.
    float s = glm::length(glm::cross(glm::normalize(view), glm::normalize(c.up)));
    if (!(s > 1e-4f))
      fail(n.has("up") ? n.path.child("up") : n.path, "up must not be parallel to look_at - eye");
    return c;
  }

  void read_lights(const Node& top, Scene* scene) const {
    if (!top.has("lights")) {
      // No "lights" key: one white point light at the eye. An empty list means no lights at all.
      Light headlight;
      headlight.type = LightType::point;
      headlight.position = scene->camera.eye;
      scene->lights.push_back(headlight);
      return;
    }
    Node all = top.at("lights");
    if (!all.value.is_array()) fail(all.path, "expected an array of lights");
    for (size_t i = 0; i < all.value.size(); ++i) {
      Node n = all.at(i);
      const LightKind& kind = kind_of(n, kLightKinds, nullptr);
      check_keys(n, kind.keys);
      Light l;
      l.type = kind.light_type;
      l.position = vec3(n, "position", l.position);
      if (n.has("direction")) l.direction = nonzero_vec3(n.at("direction"));
      l.color = color(n, "color", l.color, kNonNegative);
      l.intensity = number(n, "intensity", l.intensity, kNonNegative);
      scene->lights.push_back(l);
    }
  }

  RenderSettings read_render(const Node& n) const {
    check_keys(n, kRenderKeys);
    RenderSettings r;
    if (n.has("size")) {
      Node size = n.at("size");
      if (!size.value.is_array() || size.value.size() != 2) fail(size.path, "expected [width, height]");
      r.width = integer(size.at(size_t(0)), 1, kMaxImageSide);
      r.height = integer(size.at(1), 1, kMaxImageSide);
    }
    if (n.has("aa")) {
      Node aa = n.at("aa");
      std::string spec = text_value(aa);
      try {
        r.aa = parse_antialiasing(spec);
      } catch (const InputError& e) {
        fail(aa.path, e.detail());
      }
    }
    if (n.has("max_depth")) r.max_depth = integer(n.at("max_depth"), 0, kMaxDepth);
    r.min_weight = number(n, "min_weight", r.min_weight, kUnit);
    r.background = color(n, "background", r.background, kNonNegative);
    r.ambient = color(n, "ambient", r.ambient, kNonNegative);
    if (n.has("seed")) {
      Node seed = n.at("seed");
      if (!seed.value.is_number_integer() ||
          (!seed.value.is_number_unsigned() && seed.value.get<int64_t>() < 0))
        fail(seed.path, "expected a non-negative integer");
      r.seed = seed.value.get<uint64_t>();
    }
    return r;
  }

  // Objects ----------------------------------------------------------------------------------------

  struct ObjectKind {
    const char* type;
    Keys keys;  // besides type, name and material
    void (SceneReader::*add)(const Node&, Geometry&);
  };
  static const ObjectKind kObjectKinds[5];

  void read_objects(const Node& top, Scene* scene) {
    Node all = required(top, "objects");
    if (!all.value.is_array() || all.value.empty()) fail(all.path, "expected a non-empty array of objects");
    for (size_t i = 0; i < all.value.size(); ++i) {
      Node n = all.at(i);
      const ObjectKind& kind = object_kind(n, kObjectKinds);
      uint32_t material = 0;
      if (n.has("material")) material = material_index(n.at("material"), *scene);
      std::string name = n.has("name") ? text_value(n.at("name")) : std::string(kind.type);
      if (!n.has("name") && n.has("file")) name += " " + text_value(n.at("file"));
      scene->geometry.begin_object(name, material);
      (this->*kind.add)(n, scene->geometry);
    }
  }

  uint32_t material_index(const Node& n, const Scene& scene) const {
    std::string name = text_value(n);
    std::string known;
    for (uint32_t m = 0; m < scene.materials.size(); ++m) {
      if (scene.materials[m].name == name) return m;
      known += (known.empty() ? "" : ", ") + scene.materials[m].name;
    }
    fail(n.path, "unknown material '" + name + "' (defined: " + known + ")");
  }

  // Scale, then rotate, then translate; or a 4x4 affine matrix written row by row.
  glm::mat4 transform(const Node& obj) const {
    if (!obj.has("transform")) return glm::mat4(1.f);
    Node n = obj.at("transform");
    check_keys(n, kTransformKeys);
    glm::mat4 m(1.f);
    if (n.has("matrix")) {
      if (n.has("translate") || n.has("rotate") || n.has("scale"))
        fail(n.path.child("matrix"), "a matrix cannot be combined with translate, rotate or scale");
      Node rows = n.at("matrix");
      if (!rows.value.is_array() || rows.value.size() != 4) fail(rows.path, "expected 4 rows of 4 numbers");
      for (size_t r = 0; r < 4; ++r) {
        Node row = rows.at(r);
        if (!row.value.is_array() || row.value.size() != 4) fail(row.path, "expected a row of 4 numbers");
        for (size_t c = 0; c < 4; ++c)
          m[int(c)][int(r)] = number(row.at(c), kAnyNumber);  // glm: m[column][row]
      }
      if (glm::vec4(m[0][3], m[1][3], m[2][3], m[3][3]) != glm::vec4(0, 0, 0, 1))
        fail(rows.path.child(3), "expected [0, 0, 0, 1]: only affine transforms are allowed");
    } else {
      if (n.has("translate")) m = glm::translate(m, vec3(n.at("translate")));
      if (n.has("rotate")) {
        Node rot = n.at("rotate");
        check_keys(rot, kRotateKeys);
        glm::vec3 axis = nonzero_vec3(required(rot, "axis"));
        float degrees = number(required(rot, "degrees"), kAnyNumber);
        m = glm::rotate(m, glm::radians(degrees), axis);
      }
      if (n.has("scale")) {
        Node s = n.at("scale");
        glm::vec3 scale = s.value.is_number() ? glm::vec3(number(s, kAnyNumber)) : vec3(s);
        if (scale.x == 0.f || scale.y == 0.f || scale.z == 0.f) fail(s.path, "expected a non-zero scale");
        m = glm::scale(m, scale);
      }
    }
    float det = glm::determinant(glm::mat3(m));
    if (!(std::fabs(det) > 0.f) || !std::isfinite(det)) fail(n.path, "the transform is singular");
    return m;
  }

  void add_mesh_object(const Node& n, Geometry& g) {
    Node file = required(n, "file");
    std::string name = text_value(file);
    fs::path resolved = fs::path(name).is_absolute() ? fs::path(name) : folder_ / name;
    std::error_code ec;
    if (!fs::is_regular_file(resolved, ec))
      fail(file.path, "cannot open mesh '" + resolved.string() +
                          "': " + (fs::exists(resolved, ec) ? "not a regular file" : "no such file"));
    auto cached = meshes_.find(resolved.string());
    if (cached == meshes_.end())
      cached = meshes_.emplace(resolved.string(), load_obj(resolved.string())).first;
    add_mesh(g, cached->second, transform(n));
  }

  void add_sphere_object(const Node& n, Geometry& g) {
    Sphere s;
    s.center = vec3(required(n, "center"));
    s.radius = number(required(n, "radius"), kPositive);
    g.add_sphere(s);
  }

  // "vertices": exactly `count` points.
  std::vector<glm::vec3> vertices(const Node& n, size_t count) const {
    Node v = required(n, "vertices");
    if (!v.value.is_array() || v.value.size() != count)
      fail(v.path, "expected " + std::to_string(count) + " vertices [x, y, z]");
    std::vector<glm::vec3> out;
    for (size_t i = 0; i < count; ++i) out.push_back(vec3(v.at(i)));
    return out;
  }

  void add_triangle_object(const Node& n, Geometry& g) {
    std::vector<glm::vec3> v = vertices(n, 3);
    add_mesh(g, make_triangle(v[0], v[1], v[2]), transform(n));
  }

  void add_quad_object(const Node& n, Geometry& g) {
    std::vector<glm::vec3> v = vertices(n, 4);
    add_mesh(g, make_quad(v[0], v[1], v[2], v[3]), transform(n));
  }

  void add_box_object(const Node& n, Geometry& g) {
    glm::vec3 lo = vec3(required(n, "min")), hi = vec3(required(n, "max"));
    if (hi.x < lo.x || hi.y < lo.y || hi.z < lo.z)
      fail(n.path.child("max"), "expected max >= min on every axis");
    add_mesh(g, make_box(lo, hi), transform(n));
  }

  // 2D scenes (flatland.h) ---------------------------------------------------------------------------

  struct FlatKind {
    const char* type;
    FlatShape::Kind kind;
    Keys keys;  // besides type, name and material
  };
  static const FlatKind kFlatKinds[4];

  glm::vec2 vec2(const Node& n) const {
    if (!n.value.is_array() || n.value.size() != 2) fail(n.path, "expected [x, y]");
    return glm::vec2(number(n.at(size_t(0)), kAnyNumber), number(n.at(1), kAnyNumber));
  }

  // "points": at least `min` points [x, y], no two in a row the same (a wall of no width).
  std::vector<glm::vec2> flat_points(const Node& n, size_t min, bool closed) const {
    Node v = required(n, "points");
    if (!v.value.is_array() || v.value.size() < min)
      fail(v.path, "expected at least " + std::to_string(min) + " points [x, y]");
    std::vector<glm::vec2> out;
    for (size_t i = 0; i < v.value.size(); ++i) {
      out.push_back(vec2(v.at(i)));
      if (i > 0 && out[i] == out[i - 1]) fail(v.path.child(i), "the same point as the one before it");
    }
    if (closed && out.back() == out.front())
      fail(v.path.child(out.size() - 1), "the same point as the first (a polygon closes itself)");
    return out;
  }

  // The shapes, then their walls and circles as geometry; the camera looks straight down on the plane.
  void read_flat(const Node& top, Scene* scene) {
    if (top.has("camera"))
      fail(top.path.child("camera"), "a 2D scene has no camera: it is seen from above, framed by its shapes");
    Flatland flat;
    Node all = required(top, "objects");
    if (!all.value.is_array() || all.value.empty()) fail(all.path, "expected a non-empty array of shapes");
    for (size_t i = 0; i < all.value.size(); ++i) {
      Node n = all.at(i);
      const FlatKind& kind = object_kind(n, kFlatKinds);
      FlatShape s;
      s.kind = kind.kind;
      s.name = n.has("name") ? text_value(n.at("name")) : std::string(kind.type) + " " + std::to_string(i);
      if (n.has("material")) s.material = material_index(n.at("material"), *scene);
      switch (s.kind) {
        case FlatShape::Kind::segment:
          s.points = flat_points(n, 2, false);
          if (s.points.size() != 2)
            fail(n.path.child("points"), "expected 2 points [x, y] (a polyline has more)");
          break;
        case FlatShape::Kind::polyline:
          s.points = flat_points(n, 2, false);
          break;
        case FlatShape::Kind::polygon: {
          s.points = flat_points(n, 3, true);
          double area = 0.0;
          for (size_t k = 0; k < s.points.size(); ++k) {
            const glm::vec2 &a = s.points[k], &b = s.points[(k + 1) % s.points.size()];
            area += double(a.x) * b.y - double(b.x) * a.y;
          }
          if (!(std::fabs(area) > 0.0)) fail(n.path.child("points"), "the polygon has no area");
          if (n.has("fill")) {
            Node f = n.at("fill");
            if (!f.value.is_boolean()) fail(f.path, "expected true or false");
            s.filled = f.value.get<bool>();
          }
          break;
        }
        case FlatShape::Kind::circle:
          s.center = vec2(required(n, "center"));
          s.radius = number(required(n, "radius"), kPositive);
          break;
      }
      if (std::string problem = flat_shape_problem(s); !problem.empty())
        fail(n.path.child("points"), problem);
      flat.shapes.push_back(std::move(s));
    }
    add_flat_shapes(&flat, &scene->geometry);
    if (top.has("ray")) {
      Node r = top.at("ray");
      check_keys(r, kFlatRayKeys);
      flat.has_ray = true;
      flat.ray_origin = vec2(required(r, "origin"));
      flat.ray_direction = vec2(required(r, "direction"));
      if (flat.ray_direction == glm::vec2(0.f)) fail(r.path.child("direction"), "expected a non-zero vector");
    }
    // Orthographic, straight down, on the frame: the scene's "frame" [[x0, y0], [x1, y1]] (the picture's
    // height spans y0..y1, its width follows from the render size), or the shapes' bounds with a 5% margin,
    // the larger of the two spans fitted.
    glm::vec2 centre = 0.5f * (flat.lo + flat.hi);
    float height =
        1.05f * std::max(flat.hi.y - flat.lo.y,
                         (flat.hi.x - flat.lo.x) * float(scene->render.height) / float(scene->render.width));
    if (top.has("frame")) {
      Node f = top.at("frame");
      if (!f.value.is_array() || f.value.size() != 2) fail(f.path, "expected [[x0, y0], [x1, y1]]");
      const glm::vec2 a = vec2(f.at(size_t(0))), b = vec2(f.at(1));
      if (!(b.x > a.x && b.y > a.y)) fail(f.path.child(1), "expected x1 > x0 and y1 > y0");
      centre = 0.5f * (a + b);
      height = b.y - a.y;
    }
    Camera& c = scene->camera;
    c.type = CameraType::orthographic;
    c.look_at = glm::vec3(centre, 0.f);
    c.eye = glm::vec3(centre, 4.f * flat.half_height);
    c.up = glm::vec3(0.f, 1.f, 0.f);
    c.ortho_height = std::max(height, 2e-6f * flat.half_height);
    scene->flat = std::move(flat);
  }

  const std::string& text_;
  std::string path_;
  fs::path folder_;
  std::map<std::string, TriangleMesh> meshes_;  // a mesh used twice is read once
};

const SceneReader::FlatKind SceneReader::kFlatKinds[4] = {
    {"segment", FlatShape::Kind::segment, {"points"}},
    {"polyline", FlatShape::Kind::polyline, {"points"}},
    {"polygon", FlatShape::Kind::polygon, {"points", "fill"}},
    {"circle", FlatShape::Kind::circle, {"center", "radius"}},
};

const SceneReader::ObjectKind SceneReader::kObjectKinds[5] = {
    {"mesh", {"file", "transform"}, &SceneReader::add_mesh_object},
    {"sphere", {"center", "radius"}, &SceneReader::add_sphere_object},
    {"triangle", {"vertices", "transform"}, &SceneReader::add_triangle_object},
    {"quad", {"vertices", "transform"}, &SceneReader::add_quad_object},
    {"box", {"min", "max", "transform"}, &SceneReader::add_box_object},
};

std::string read_file(const std::string& path, size_t max_bytes) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, 0, "cannot open: no such file");
  if (!fs::is_regular_file(path, ec)) throw InputError(path, 0, "cannot open: not a regular file");
  if (fs::file_size(path, ec) > max_bytes)
    throw InputError(path, 0, "file larger than " + std::to_string(max_bytes >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path, 0, "cannot read");
  return ss.str();
}

// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix.
std::string parse_message(const std::string& what) {
  size_t column = what.find("column ");
  size_t colon = column == std::string::npos ? std::string::npos : what.find(": ", column);
  if (colon != std::string::npos) return what.substr(colon + 2);
  size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

bool has_obj_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".obj";
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& path) {
  // Parse, noting duplicate keys on the way (nlohmann keeps the last silently); the walker finds them.
  bool duplicate = false;
  std::vector<std::unordered_set<std::string>> keys;
  json::parser_callback_t note_duplicates = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start)
      keys.emplace_back();
    else if (event == json::parse_event_t::object_end)
      keys.pop_back();
    else if (event == json::parse_event_t::key && !keys.back().insert(parsed.get<std::string>()).second)
      duplicate = true;
    return true;
  };
  json root;
  try {
    root = json::parse(text, note_duplicates);
  } catch (const json::parse_error& e) {
    throw InputError(path, json_line_at_byte(text, e.byte), parse_message(e.what()));
  } catch (const json::out_of_range& e) {
    // "number overflow parsing '1e999'": no position, so find the literal.
    std::string what = parse_message(e.what());
    size_t q = what.find('\'');
    std::string literal = q == std::string::npos ? "" : what.substr(q + 1, what.rfind('\'') - q - 1);
    throw InputError(path, json_line_of_number(text, literal), what);
  } catch (const json::exception& e) {
    throw InputError(path, 0, parse_message(e.what()));
  }
  if (duplicate) {
    JsonDuplicateKey dup;
    if (json_find_duplicate_key(text, &dup))
      throw InputError(path, dup.line, dup.display + ": duplicate key");
  }
  return SceneReader(text, path).read(root);
}

Scene load_scene(const std::string& path) {
  if (has_obj_extension(path)) return scene_from_mesh(path);
  return parse_scene(read_file(path, kMaxSceneBytes), path);
}

Camera camera_framing(const Bounds3& bounds, float fov_deg) {
  Camera c;
  c.type = CameraType::pinhole;
  c.fov_deg = fov_deg;
  c.look_at = bounds.center();
  float radius = 0.5f * glm::length(bounds.extent());
  if (!(radius > 0.f) || !std::isfinite(radius)) radius = 1.f;  // a point-like mesh: any distance shows it
  // The bounding sphere fills the vertical field of view (with a 10% margin) at distance r / sin(fov/2).
  float distance = 1.1f * radius / std::sin(glm::radians(0.5f * fov_deg));
  c.eye = c.look_at + distance * glm::normalize(glm::vec3(0.5f, 0.5f, 1.f));
  c.up = glm::vec3(0.f, 1.f, 0.f);
  return c;
}

Scene scene_from_mesh(const std::string& obj_path) {
  Scene scene;
  scene.path = obj_path;
  scene.materials.assign(1, Material());
  TriangleMesh mesh = load_obj(obj_path);
  scene.geometry.begin_object("mesh " + fs::path(obj_path).filename().string(), 0);
  add_mesh(scene.geometry, mesh, glm::mat4(1.f));
  scene.camera = camera_framing(scene.geometry.bounds(), scene.camera.fov_deg);
  Light headlight;
  headlight.type = LightType::point;
  headlight.position = scene.camera.eye;
  scene.lights.push_back(headlight);
  return scene;
}

}  // namespace raystep
