// OBJ meshes (io/obj.h) and triangle meshes in the geometry (scene/triangle_mesh.h): the primitive id
// contract (file order, fan split), relative indices, vertex normals, transforms, and every bad input
// reported with its line.
#include <gtest/gtest.h>

#include <tiny_obj_loader.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "raystep/io/obj.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  std::string path = ::testing::TempDir() + "raystep_obj_test_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The InputError that parsing `text` throws (fails the test if none).
InputError obj_error(const std::string& text) {
  try {
    parse_obj(text, "m.obj");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return InputError("", 0, "");
}

const char* kSquareVertices =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n";

TEST(Obj, PolygonsSplitAsFansInFileOrder) {
  TriangleMesh m = parse_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\n"
      "f 1 2 3\n"        // id 0
      "f 1 2 3 4\n"      // ids 1, 2
      "f 1 2 3 4 5\n",   // ids 3, 4, 5
      "m.obj");
  std::vector<glm::uvec3> expected = {{0, 1, 2}, {0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  EXPECT_EQ(m.triangles, expected);
  EXPECT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.positions[4], glm::vec3(-1.f, 0.5f, 0.f));
  EXPECT_TRUE(m.normal_triangles.empty());
}

TEST(Obj, FileOrderIsKeptAcrossObjectsGroupsAndMaterials) {
  // Each face starts at a different vertex, so its first index names it: face k starts at vertex k.
  std::string text = "mtllib missing.mtl\n";
  for (int i = 0; i < 12; ++i) text += "v " + std::to_string(i) + " 0 0\n";
  const char* separators[] = {"", "o first\n", "g a b\n", "usemtl red\n", "usemtl green\n", "g\n",
                              "o second\n", "usemtl red\n", "s 1\n", "g c\n"};
  for (int f = 0; f < 10; ++f)
    text += std::string(separators[f]) + "f " + std::to_string(f + 1) + " " + std::to_string(f + 2) + " " +
            std::to_string(f + 3) + "\n";
  TriangleMesh m = parse_obj(text, "m.obj");
  ASSERT_EQ(m.triangles.size(), 10u);
  for (uint32_t f = 0; f < 10; ++f) EXPECT_EQ(m.triangles[f], glm::uvec3(f, f + 1, f + 2)) << "face " << f;
}

TEST(Obj, NegativeIndicesCountBackFromTheLastVertexSoFar) {
  TriangleMesh m = parse_obj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "vn 0 0 1\n"
      "f -3//-1 -2//-1 -1//-1\n"
      "v 5 5 5\n"
      "f -1 -2 -3\n"
      "f -4 2 -1\n",
      "m.obj");
  std::vector<glm::uvec3> expected = {{0, 1, 2}, {3, 2, 1}, {0, 1, 3}};
  EXPECT_EQ(m.triangles, expected);
  ASSERT_EQ(m.normal_triangles.size(), 3u);
  EXPECT_EQ(m.normal_triangles[0], glm::uvec3(0, 0, 0));
  EXPECT_EQ(m.normal_triangles[1], glm::uvec3(kNoNormal));
}

TEST(Obj, NormalsOnlyWhenEveryVertexOfTheFaceHasANonZeroOne) {
  TriangleMesh m = parse_obj(std::string(kSquareVertices) +
                                 "vn 0 0 1\nvn 0 0.6 0.8\nvn 0 0 0\n"
                                 "f 1//1 2//2 3//1 4//2\n"  // all have: both fan triangles keep them
                                 "f 1/1/1 2/2/2 3/3/1\n"    // v/vt/vn form
                                 "f 1//1 2 3\n"             // one vertex without: none
                                 "f 1//1 2//3 3//1\n"       // a zero normal: none
                                 "f 1 2 3\n",
                             "m.obj");
  ASSERT_EQ(m.triangles.size(), 6u);
  ASSERT_EQ(m.normal_triangles.size(), 6u);
  EXPECT_EQ(m.normal_triangles[0], glm::uvec3(0, 1, 0));
  EXPECT_EQ(m.normal_triangles[1], glm::uvec3(0, 0, 1));
  EXPECT_EQ(m.normal_triangles[2], glm::uvec3(0, 1, 0));
  for (int i = 3; i < 6; ++i) EXPECT_EQ(m.normal_triangles[i], glm::uvec3(kNoNormal)) << i;
  EXPECT_NEAR(m.normals[1].y, 0.6f, 1e-7f);
}

TEST(Obj, ReadsNumbersTinyobjloaderAccepts) {
  TriangleMesh m = parse_obj(
      "  v\t+1.5e1 -.25 3.\r\n"   // leading blanks, tabs, '+', '.25', '3.', CRLF
      "v 1 2 3 1\r\n"             // w
      "v 1 2 3 0.5 0.5 0.5\r\n"   // vertex colour (tinyobjloader extension)
      "v 1e-400 0 0\n"            // underflow reads as 0
      "# comment\n\n"
      "f 1 2 3 4",                // no final newline
      "m.obj");
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[0], glm::vec3(15.f, -0.25f, 3.f));
  EXPECT_EQ(m.positions[3], glm::vec3(0.f));
  EXPECT_EQ(m.triangles.size(), 2u);
}

TEST(Obj, DegenerateTrianglesAreKept) {
  TriangleMesh m = parse_obj("v 0 0 0\nv 1 1 1\nf 1 1 1\nf 1 2 2\n", "m.obj");
  EXPECT_EQ(m.triangles.size(), 2u);
}

TEST(Obj, PositiveIndicesMayPointForward) {
  // tinyobjloader resolves positive indices at the end; so do we (a vertex defined after its face).
  TriangleMesh m = parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", "m.obj");
  EXPECT_EQ(m.triangles.size(), 1u);
}

TEST(Obj, PolygonsUpTo255Vertices) {
  std::string text;
  for (int i = 0; i < 256; ++i) text += "v " + std::to_string(std::cos(i * 0.02)) + " " + std::to_string(std::sin(i * 0.02)) + " 0\n";
  std::string face = "f";
  for (int i = 1; i <= 255; ++i) face += " " + std::to_string(i);
  TriangleMesh m = parse_obj(text + face + "\nf 1 2 3\n", "m.obj");
  ASSERT_EQ(m.triangles.size(), 254u);
  EXPECT_EQ(m.triangles[252], glm::uvec3(0, 253, 254));
  EXPECT_EQ(m.triangles[253], glm::uvec3(0, 1, 2));
  // 256 vertices would overflow tinyobjloader's unsigned char vertex count: an error, with the line.
  InputError e = obj_error(text + face + " 256\n");
  EXPECT_EQ(e.line(), 257);
  EXPECT_NE(e.detail().find("256 vertices"), std::string::npos) << e.what();
}

TEST(Obj, LoadsFromAFileAndNamesMissingOnes) {
  std::string path = write_temp("square.obj", std::string(kSquareVertices) + "f 1 2 3 4\n");
  TriangleMesh m = load_obj(path);
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.bounds().hi, glm::vec3(1.f, 1.f, 0.f));

  try {
    load_obj(::testing::TempDir() + "raystep_no_such_mesh.obj");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("raystep_no_such_mesh.obj: cannot open: no such file"), std::string::npos)
        << e.what();
  }
  try {
    load_obj(::testing::TempDir());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(e.detail().find("not a regular file"), std::string::npos) << e.what();
  }
}

struct BadObj {
  const char* text;
  int line;
  const char* message;
};

TEST(Obj, EveryBadInputNamesItsLine) {
  const BadObj cases[] = {
      // indices
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", 4, "f: vertex index 4 out of range (the file has 3)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 0\n", 5, "f: vertex index 0 (OBJ indices start at 1)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", 4, "relative vertex index -4 out of range (3 defined so far)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n", 5, "normal index 2 out of range"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//-2 2 3\n", 4, "relative normal index -2 out of range (0 defined"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/0 2 3\n", 4, "texture index 0"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1.5 2 3\n", 4, "malformed vertex index in '1.5'"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x\n", 4, "malformed vertex index in '3x'"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf a b c\n", 4, "malformed vertex index"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1// 2 3\n", 4, "malformed normal index in '1//'"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n", 4, "malformed vertex '1/2/3/4'"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 99999999999 2 3\n", 4, "vertex index '99999999999' out of range"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 # comment\n", 4, "malformed vertex index in '#'"},
      {"v 0 0 0\nv 1 0 0\nf 1 2\n", 3, "a face needs at least 3 vertices, found 2"},
      // numbers
      {"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", 2, "v: coordinate 'nan' is not a finite number"},
      {"v 0 0 0\nv 0 -inf 0\nv 0 1 0\nf 1 2 3\n", 2, "v: coordinate '-inf' is not a finite number"},
      {"v 0 0 0\nv 0 0 1e999\nv 0 1 0\nf 1 2 3\n", 2, "coordinate '1e999' is not a finite number"},
      {"v 0 0 0\nv 0 0 1e39\nv 0 1 0\nf 1 2 3\n", 2, "'1e39' is not a finite number in single precision"},
      {"v 0 0 0\nv 1 abc 2\nv 0 1 0\nf 1 2 3\n", 2, "v: malformed number 'abc'"},
      {"v 0 0 0\nv 1,5 0 0\nv 0 1 0\nf 1 2 3\n", 2, "v: malformed number '1,5'"},
      {"v 0 0 0\nv 1 2 3 # comment\nv 0 1 0\nf 1 2 3\n", 2, "v: malformed number '#'"},
      {"v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", 2, "v: expected 3 coordinates, found 2"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 NaN\nf 1 2 3\n", 4, "vn: coordinate 'NaN' is not a finite number"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1\nf 1 2 3\n", 4, "vn: expected 3 coordinates, found 2"},
      // line endings: CRLF and a lone CR end a line, as in tinyobjloader
      {"v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 5\r\n", 4, "out of range"},
      {"v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 5\r", 4, "out of range"},
      // lines and points are not used, but tinyobjloader checks their indices: its message, with its line
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nl 0 1\nf 1 2 3\n", 4, "tinyobjloader: Failed parse `l' line"},
      // nothing to render
      {"v 0 0 0\nv 1 0 0\n", 0, "no faces"},
      {"", 0, "no faces"},
  };
  for (const BadObj& c : cases) {
    InputError e = obj_error(c.text);
    EXPECT_EQ(e.file(), "m.obj");
    EXPECT_EQ(e.line(), c.line) << c.text << "\n" << e.what();
    EXPECT_NE(e.detail().find(c.message), std::string::npos) << "expected '" << c.message << "' in " << e.what();
  }
}

// What tinyobjloader 2.0rc10 does on its own with bad input: the reason for the validating scan.
// If a new version changes any of this, re-check obj.cpp's comment.
TEST(Obj, TinyobjloaderQuirksThatTheScanGuardsAgainst) {
  auto tiny = [](const std::string& text, tinyobj::attrib_t* attrib, std::vector<tinyobj::shape_t>* shapes) {
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    std::istringstream in(text);
    return tinyobj::LoadObj(attrib, shapes, &materials, &warn, &err, &in, nullptr, false, false);
  };
  tinyobj::attrib_t a;
  std::vector<tinyobj::shape_t> s;
  // Malformed numbers, "nan" and a missing coordinate silently read as 0.
  ASSERT_TRUE(tiny("v 1 abc nan\nv 1 2\nv 0 0 0\nf 1 2 3\n", &a, &s));
  EXPECT_EQ(a.vertices[1], 0.f);
  EXPECT_EQ(a.vertices[2], 0.f);
  EXPECT_EQ(a.vertices[5], 0.f);
  // "1.5" reads as index 1, and an index out of range passes through.
  a = {};
  s.clear();
  ASSERT_TRUE(tiny("v 0 0 0\nv 1 0 0\nf 1.5 2 7\n", &a, &s));
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].mesh.indices[0].vertex_index, 0);
  EXPECT_EQ(s[0].mesh.indices[2].vertex_index, 6);
  // A face of two vertices is dropped.
  a = {};
  s.clear();
  ASSERT_TRUE(tiny("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n", &a, &s));
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].mesh.num_face_vertices.size(), 1u);
}

TEST(TriangleMesh, QuadSplitsIntoTwoTrianglesSharingTheFirstDiagonal) {
  TriangleMesh q = make_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  std::vector<glm::uvec3> expected = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(q.triangles, expected);
}

TEST(TriangleMesh, BoxHasTwelveOutwardFacingTriangles) {
  glm::vec3 lo(-1.f, 0.f, 2.f), hi(3.f, 0.5f, 4.f);
  TriangleMesh b = make_box(lo, hi);
  ASSERT_EQ(b.triangles.size(), 12u);
  glm::vec3 centre = 0.5f * (lo + hi);
  float area = 0.f;
  for (size_t t = 0; t < 12; ++t) {
    glm::vec3 p0 = b.positions[b.triangles[t][0]], p1 = b.positions[b.triangles[t][1]],
              p2 = b.positions[b.triangles[t][2]];
    glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
    area += 0.5f * glm::length(n);
    // The normal is along one axis and points from the centre towards the face.
    glm::vec3 face_centre = (p0 + p1 + p2) / 3.f;
    EXPECT_GT(glm::dot(n, face_centre - centre), 0.f) << "triangle " << t;
    int axis = int(t / 4);  // faces -x, +x, -y, +y, -z, +z, two triangles each
    EXPECT_EQ(std::fabs(n[axis]), glm::length(n)) << "triangle " << t;
  }
  glm::vec3 e = hi - lo;
  EXPECT_NEAR(area, 2.f * (e.x * e.y + e.y * e.z + e.z * e.x), 1e-5f);
  EXPECT_EQ(b.bounds().lo, lo);
  EXPECT_EQ(b.bounds().hi, hi);
}

TEST(TriangleMesh, AddMeshTransformsPointsAndNormalsByTheInverseTranspose) {
  // A triangle in the plane x + y = 1 with its normal (1, 1, 0)/sqrt(2) at every vertex.
  TriangleMesh m = make_triangle({1, 0, 0}, {0, 1, 0}, {1, 0, 1});
  glm::vec3 n = glm::normalize(glm::vec3(1, 1, 0));
  m.normals = {n};
  m.normal_triangles = {{0, 0, 0}};
  // Scale x by 2, then translate: the plane becomes x/2 + y = 1, with normal (1/2, 1, 0) normalised.
  glm::mat4 t = glm::translate(glm::mat4(1.f), glm::vec3(0, 0, 5)) * glm::scale(glm::mat4(1.f), glm::vec3(2, 1, 1));
  Geometry g;
  g.begin_object("t", 0);
  add_mesh(g, m, t);
  ASSERT_EQ(g.size(), 1u);
  EXPECT_EQ(g.vertex(0, 0), glm::vec3(2, 0, 5));
  EXPECT_EQ(g.vertex(0, 2), glm::vec3(2, 0, 6));
  ASSERT_TRUE(g.has_vertex_normals(0));
  glm::vec3 expected = glm::normalize(glm::vec3(0.5f, 1.f, 0.f));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(g.vertex_normal(0, k).x, expected.x, 1e-6f);
    EXPECT_NEAR(g.vertex_normal(0, k).y, expected.y, 1e-6f);
    EXPECT_NEAR(g.vertex_normal(0, k).z, 0.f, 1e-6f);
    // Still perpendicular to the transformed triangle.
    EXPECT_NEAR(glm::dot(g.vertex_normal(0, k), g.vertex(0, 1) - g.vertex(0, 0)), 0.f, 1e-6f);
  }
}

TEST(TriangleMesh, AMirroringTransformKeepsBoxNormalsPointingOut) {
  Geometry g;
  g.begin_object("box", 0);
  add_mesh(g, make_box({1, 1, 1}, {2, 3, 4}), glm::scale(glm::mat4(1.f), glm::vec3(-1, 1, 1)));
  ASSERT_EQ(g.size(), 12u);
  glm::vec3 centre = g.bounds().center();
  EXPECT_NEAR(centre.x, -1.5f, 1e-6f);
  for (uint32_t id = 0; id < 12; ++id) {
    glm::vec3 p0 = g.vertex(id, 0), p1 = g.vertex(id, 1), p2 = g.vertex(id, 2);
    EXPECT_GT(glm::dot(glm::cross(p1 - p0, p2 - p0), (p0 + p1 + p2) / 3.f - centre), 0.f) << id;
  }
}

TEST(TriangleMesh, TrianglesWithoutNormalsStayWithout) {
  TriangleMesh m = parse_obj(std::string(kSquareVertices) + "vn 0 0 1\nf 1//1 2//1 3//1\nf 1 3 4\n", "m.obj");
  Geometry g;
  g.begin_object("m", 0);
  add_mesh(g, m, glm::mat4(1.f));
  EXPECT_TRUE(g.has_vertex_normals(0));
  EXPECT_FALSE(g.has_vertex_normals(1));
}

}  // namespace
}  // namespace raystep
