// The 3D view's mesh (viz/src/views/scene_mesh.h), made without a display: triangles share their vertices'
// points, a sphere is its UV tessellation, and each cell keeps its primitive's id and its material's colour.
#include <gtest/gtest.h>

#include <cmath>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIdList.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include "raystep/scene/scene.h"
#include "raystep/trace/trace_file.h"
#include "views/scene_mesh.h"

namespace raystep::viz {
namespace {

constexpr size_t kSpherePoints = size_t(kSphereStacks + 1) * kSphereSlices;
constexpr size_t kSphereCells = 2 * size_t(kSphereStacks) * kSphereSlices;

// A quad of two triangles sharing an edge (material 0, red), a lone triangle (material 1, a mirror) and a
// sphere (material 0).
Scene quadTriangleAndSphere() {
  Scene s;
  s.materials.resize(2);
  s.materials[0].diffuse = glm::vec3(1.f, 0.f, 0.f);
  s.materials[1].mirror = 0.8f;
  s.geometry.begin_object("quad", 0);
  s.geometry.add_triangle(glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0));
  s.geometry.add_triangle(glm::vec3(0, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0));
  s.geometry.begin_object("mirror", 1);
  s.geometry.add_triangle(glm::vec3(5, 0, 0), glm::vec3(6, 0, 0), glm::vec3(5, 1, 0));
  s.geometry.begin_object("sphere", 0);
  s.geometry.add_sphere(Sphere{glm::vec3(0, 0, 3), 0.5f});
  return s;
}

glm::vec3 pointOf(vtkPolyData* d, vtkIdType id) {
  double p[3];
  d->GetPoints()->GetPoint(id, p);
  return glm::vec3(float(p[0]), float(p[1]), float(p[2]));
}

TEST(SceneMesh, TrianglesShareTheirVerticesAndSpheresAreTessellated) {
  const Scene scene = quadTriangleAndSphere();
  auto mesh = SceneMesh::fromScene(scene);
  vtkPolyData* d = mesh->data();
  // The quad's 4 corners (2 shared), the mirror's 3, the sphere's rings.
  EXPECT_EQ(d->GetNumberOfPoints(), vtkIdType(4 + 3 + kSpherePoints));
  ASSERT_EQ(d->GetNumberOfCells(), vtkIdType(3 + kSphereCells));
  ASSERT_EQ(mesh->cellPrim().size(), 3 + kSphereCells);
  EXPECT_EQ(mesh->cellPrim()[0], 0);
  EXPECT_EQ(mesh->cellPrim()[1], 1);
  EXPECT_EQ(mesh->cellPrim()[2], 2);
  for (size_t c = 3; c < mesh->cellPrim().size(); ++c) ASSERT_EQ(mesh->cellPrim()[c], 3) << c;

  // Every triangle cell has its primitive's vertices, in order.
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < 3; ++c) {
    d->GetPolys()->GetCellAtId(c, ids);
    ASSERT_EQ(ids->GetNumberOfIds(), 3);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(pointOf(d, ids->GetId(k)), scene.geometry.vertex(uint32_t(c), k));
  }
  d->GetPolys()->GetCellAtId(0, ids);
  const vtkIdType corner0 = ids->GetId(0), corner2 = ids->GetId(2);
  d->GetPolys()->GetCellAtId(1, ids);
  EXPECT_EQ(ids->GetId(0), corner0);  // (0, 0, 0), shared
  EXPECT_EQ(ids->GetId(1), corner2);  // (1, 1, 0), shared

  // The sphere's points lie on it.
  for (vtkIdType c = 3; c < d->GetNumberOfCells(); ++c) {
    d->GetPolys()->GetCellAtId(c, ids);
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(glm::length(pointOf(d, ids->GetId(k)) - glm::vec3(0, 0, 3)), 0.5f, 1e-5f) << c;
  }

  // Colours: red for the quad and the sphere, a mirror's grey-blue, encoded with gamma 2.2.
  auto* colors = vtkUnsignedCharArray::SafeDownCast(d->GetCellData()->GetScalars());
  ASSERT_NE(colors, nullptr);
  ASSERT_EQ(colors->GetNumberOfComponents(), 3);
  auto encoded = [](float v) { return int(std::lround(255.0 * std::pow(double(v), 1 / 2.2))); };
  const int red[3] = {255, encoded(0.12f), encoded(0.12f)};
  const int metal[3] = {encoded(0.55f), encoded(0.6f), encoded(0.7f)};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(colors->GetValue(0 * 3 + k), red[k]);
    EXPECT_EQ(colors->GetValue(1 * 3 + k), red[k]);
    EXPECT_EQ(colors->GetValue(2 * 3 + k), metal[k]);
    EXPECT_EQ(colors->GetValue(vtkIdType(3 + kSphereCells - 1) * 3 + k), red[k]);
  }
  EXPECT_EQ(mesh->bounds().lo, scene.geometry.bounds().lo);
  EXPECT_EQ(mesh->bounds().hi, scene.geometry.bounds().hi);
}

TEST(SceneMesh, ATracesPrimitivesKeepTheirIds) {
  Trace t;
  TracePrimitive a;
  a.id = 41;
  a.v[0] = glm::vec3(0, 0, 0);
  a.v[1] = glm::vec3(1, 0, 0);
  a.v[2] = glm::vec3(0, 1, 0);
  TracePrimitive b;
  b.id = 7;
  b.type = PrimType::sphere;
  b.v[0] = glm::vec3(2, 0, 0);
  b.radius = 1.f;
  t.primitives = {a, b};
  t.structure.bounds = Bounds3(glm::vec3(-1.f), glm::vec3(3.f));
  auto mesh = SceneMesh::fromTrace(t);
  EXPECT_EQ(mesh->data()->GetNumberOfPoints(), vtkIdType(3 + kSpherePoints));
  ASSERT_EQ(mesh->cellPrim().size(), 1 + kSphereCells);
  EXPECT_EQ(mesh->cellPrim().front(), 41);
  EXPECT_EQ(mesh->cellPrim().back(), 7);
  EXPECT_EQ(mesh->bounds().hi, glm::vec3(3.f));
}

TEST(SceneMesh, AnEmptySceneIsAnEmptyMesh) {
  Scene s;
  s.materials.resize(1);
  auto mesh = SceneMesh::fromScene(s);
  EXPECT_EQ(mesh->data()->GetNumberOfPoints(), 0);
  EXPECT_EQ(mesh->data()->GetNumberOfCells(), 0);
  EXPECT_TRUE(mesh->cellPrim().empty());
}

}  // namespace
}  // namespace raystep::viz
