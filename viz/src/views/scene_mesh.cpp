#include "views/scene_mesh.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include <vtkCellArray.h>
#include <vtkQuadricClustering.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>

#include "raystep/scene/scene.h"
#include "raystep/trace/trace_file.h"

namespace raystep::viz {

PrimShape shapeOf(const Geometry& g, uint32_t id) {
  PrimShape p;
  if (g.type(id) == PrimType::sphere) {
    p.sphere = true;
    p.v[0] = g.sphere(id).center;
    p.radius = g.sphere(id).radius;
  } else {
    for (int k = 0; k < 3; ++k) p.v[k] = g.vertex(id, k);
  }
  return p;
}

PrimShape shapeOf(const TracePrimitive& tp) {
  PrimShape p;
  p.sphere = tp.type == PrimType::sphere;
  for (int k = 0; k < 3; ++k) p.v[k] = tp.v[k];
  p.radius = tp.radius;
  return p;
}

void sphereMesh(const glm::vec3& c, float r, std::vector<glm::vec3>* points,
                std::vector<int32_t>* triangles) {
  const int32_t base = int32_t(points->size());
  for (int i = 0; i <= kSphereStacks; ++i) {
    const double th = M_PI * i / kSphereStacks;
    for (int j = 0; j < kSphereSlices; ++j) {
      const double ph = 2 * M_PI * j / kSphereSlices;
      points->emplace_back(c.x + r * std::sin(th) * std::cos(ph), c.y + r * std::cos(th),
                           c.z + r * std::sin(th) * std::sin(ph));
    }
  }
  for (int i = 0; i < kSphereStacks; ++i)
    for (int j = 0; j < kSphereSlices; ++j) {
      const int32_t a = base + i * kSphereSlices + j, b = base + i * kSphereSlices + (j + 1) % kSphereSlices;
      const int32_t below_a = a + kSphereSlices, below_b = b + kSphereSlices;
      triangles->insert(triangles->end(), {a, below_a, b, b, below_a, below_b});
    }
}

namespace {

// The colour as VTK shows it: the linear colour encoded with gamma 2.2.
std::array<unsigned char, 3> displayColor(const glm::vec3& c) {
  std::array<unsigned char, 3> rgb{};
  for (int k = 0; k < 3; ++k)
    rgb[size_t(k)] =
        (unsigned char)std::lround(255.0 * std::pow(std::clamp(double(c[k]), 0.0, 1.0), 1 / 2.2));
  return rgb;
}

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "points are copied as packed floats");

// A triangle vertex's position, bit for bit: triangles that share a vertex share its point.
struct VertexKey {
  uint32_t bits[3];
  bool operator==(const VertexKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};
struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    uint64_t h = k.bits[0] * 0x9E3779B97F4A7C15ull;
    h = (h ^ k.bits[1]) * 0xC2B2AE3D27D4EB4Full;
    h = (h ^ k.bits[2]) * 0x165667B19E3779F9ull;
    return size_t(h ^ (h >> 29));
  }
};

// The arrays, each written in place (no per-cell insertion). The triangles of a mesh share their vertices'
// points, as the OBJ file did: a 2-million-triangle mesh has 1.1 million points, not 6.7 million, and
// the first draw copies and transforms a sixth as many.
template <class Indices, class ShapeOf, class ColorOf, class IdOf>
void fill(size_t count, const ShapeOf& shapeOf, const ColorOf& colorOf, const IdOf& idOf, size_t cells,
          vtkPolyData* out, std::vector<int32_t>* cellPrim) {
  using Index = typename Indices::ValueType;
  vtkNew<Indices> offsets;
  offsets->SetNumberOfValues(vtkIdType(cells + 1));
  vtkNew<Indices> conn;
  conn->SetNumberOfValues(vtkIdType(3 * cells));
  Index* o = offsets->GetPointer(0);
  Index* c = conn->GetPointer(0);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(vtkIdType(cells));
  unsigned char* rgb = colors->GetPointer(0);
  cellPrim->resize(cells);
  int32_t* prim = cellPrim->data();

  std::vector<glm::vec3> points;
  std::unordered_map<VertexKey, Index, VertexKeyHash> shared;
  shared.reserve(count);
  auto pointOf = [&](const glm::vec3& v) {
    VertexKey key;
    std::memcpy(key.bits, &v.x, sizeof key.bits);
    auto [it, added] = shared.try_emplace(key, Index(points.size()));
    if (added) points.push_back(v);
    return it->second;
  };
  std::vector<glm::vec3> spherePoints;
  std::vector<int32_t> sphereTris;
  Index cell = 0;
  auto addTriangle = [&](Index a, Index b, Index d, const std::array<unsigned char, 3>& col, int32_t id) {
    o[cell] = 3 * cell;
    c[3 * cell] = a;
    c[3 * cell + 1] = b;
    c[3 * cell + 2] = d;
    std::copy(col.begin(), col.end(), rgb + 3 * cell);
    prim[cell] = id;
    ++cell;
  };
  for (size_t i = 0; i < count; ++i) {
    const PrimShape s = shapeOf(i);
    const auto col = colorOf(i);
    const int32_t id = idOf(i);
    if (s.sphere) {
      spherePoints.clear();
      sphereTris.clear();
      sphereMesh(s.v[0], s.radius, &spherePoints, &sphereTris);
      const Index first = Index(points.size());
      points.insert(points.end(), spherePoints.begin(), spherePoints.end());
      for (size_t t = 0; t < sphereTris.size(); t += 3)
        addTriangle(first + sphereTris[t], first + sphereTris[t + 1], first + sphereTris[t + 2], col, id);
    } else {
      addTriangle(pointOf(s.v[0]), pointOf(s.v[1]), pointOf(s.v[2]), col, id);
    }
  }
  o[cell] = 3 * cell;
  shared = {};
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToFloat();
  pts->SetNumberOfPoints(vtkIdType(points.size()));
  if (!points.empty())
    std::memcpy(static_cast<vtkFloatArray*>(pts->GetData())->GetPointer(0), points.data(),
                points.size() * sizeof(glm::vec3));
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, conn);
  out->SetPoints(pts);
  out->SetPolys(polys);
  out->GetCellData()->SetScalars(colors);
}

}  // namespace

SceneMesh::SceneMesh() : data_(vtkPolyData::New()) {}

size_t SceneMesh::displayTriangles() const {
  return size_t(data_->GetNumberOfCells());
}

SceneMesh::~SceneMesh() {
  data_->Delete();
}

namespace {

constexpr size_t kSpherePoints = size_t(kSphereStacks + 1) * kSphereSlices;
constexpr size_t kSphereCells = 2 * size_t(kSphereStacks) * kSphereSlices;

template <class ShapeOf, class ColorOf, class IdOf>
void build(size_t count, const ShapeOf& shapeOf, const ColorOf& colorOf, const IdOf& idOf, size_t spheres,
           vtkPolyData* out, std::vector<int32_t>* cellPrim) {
  const size_t cells = (count - spheres) + kSphereCells * spheres;
  // 32-bit indices while they fit (half the connectivity's memory), 64-bit beyond.
  if (3 * cells < size_t(INT32_MAX) && 3 * (count - spheres) + kSpherePoints * spheres < size_t(INT32_MAX))
    fill<vtkTypeInt32Array>(count, shapeOf, colorOf, idOf, cells, out, cellPrim);
  else
    fill<vtkTypeInt64Array>(count, shapeOf, colorOf, idOf, cells, out, cellPrim);
}

}  // namespace

std::shared_ptr<const SceneMesh> SceneMesh::fromScene(const Scene& scene) {
  std::shared_ptr<SceneMesh> mesh(new SceneMesh);
  const Geometry& g = scene.geometry;
  size_t spheres = 0;
  for (uint32_t id = 0; id < g.size(); ++id) spheres += g.type(id) == PrimType::sphere;
  // One colour per material, as the view shows it.
  std::vector<std::array<unsigned char, 3>> colors;
  for (const Material& m : scene.materials) {
    glm::vec3 diffuse = m.mirror > 0.f ? glm::vec3(0.55f, 0.6f, 0.7f) : m.diffuse;  // a mirror reads as metal
    colors.push_back(displayColor(glm::max(diffuse, glm::vec3(0.12f))));
  }
  build(
      g.size(), [&](size_t i) { return raystep::viz::shapeOf(g, uint32_t(i)); },
      [&](size_t i) { return colors[g.material(uint32_t(i))]; }, [](size_t i) { return int32_t(i); }, spheres,
      mesh->data_, &mesh->cellPrim_);
  mesh->bounds_ = g.bounds();
  mesh->sceneTriangles_ = size_t(mesh->data_->GetNumberOfCells());
  if (mesh->sceneTriangles_ > kDisplayTriangles) mesh->decimate();
  return mesh;
}

void SceneMesh::decimate() {
  // The primitive ids travel with the colours as cell data: quadric clustering keeps one input cell's data
  // for each output cell.
  vtkNew<vtkTypeInt32Array> ids;
  ids->SetName("prim");
  ids->SetNumberOfValues(vtkIdType(cellPrim_.size()));
  std::copy(cellPrim_.begin(), cellPrim_.end(), ids->GetPointer(0));
  data_->GetCellData()->AddArray(ids);
  // 96 bins on the longest side (the others as many as make the bins cubes): the clustering holds a quadric
  // of 88 bytes for every bin, at most 96^3 of them (78 MB, for the time of the call); a closed surface
  // crosses a few times 96^2 bins, two output triangles each.
  const int divisions = 96;
  vtkNew<vtkQuadricClustering> cluster;
  cluster->SetInputData(data_);
  cluster->SetNumberOfDivisions(divisions, divisions, divisions);
  cluster->AutoAdjustNumberOfDivisionsOn();  // cubical bins over the mesh's bounds
  cluster->CopyCellDataOn();
  cluster->Update();
  vtkPolyData* out = cluster->GetOutput();
  vtkDataArray* prims = out->GetCellData()->GetArray("prim");
  if (!prims || out->GetNumberOfCells() == 0) return;  // keep the full copy
  cellPrim_.resize(size_t(out->GetNumberOfCells()));
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c) cellPrim_[size_t(c)] = int32_t(prims->GetTuple1(c));
  out->GetCellData()->RemoveArray("prim");
  out->GetCellData()->SetScalars(out->GetCellData()->GetArray(0));
  data_->Delete();
  data_ = vtkPolyData::New();
  data_->ShallowCopy(out);
  decimated_ = true;
}

std::shared_ptr<const SceneMesh> SceneMesh::fromTrace(const Trace& trace) {
  std::shared_ptr<SceneMesh> mesh(new SceneMesh);
  size_t spheres = 0;
  for (const TracePrimitive& tp : trace.primitives) spheres += tp.type == PrimType::sphere;
  const auto grey = displayColor(glm::vec3(0.6f));
  build(
      trace.primitives.size(), [&](size_t i) { return raystep::viz::shapeOf(trace.primitives[i]); },
      [&](size_t) { return grey; }, [&](size_t i) { return trace.primitives[i].id; }, spheres, mesh->data_,
      &mesh->cellPrim_);
  mesh->bounds_ = trace.structure.bounds;
  return mesh;
}

}  // namespace raystep::viz
