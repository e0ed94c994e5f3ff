// `raystep export-vtk`: every file it writes read back with VTK's own XML readers, the block names, the cell
// counts against the structures built here (kd nodes, BVH nodes, occupied grid cells) and against the
// trace files `raystep trace` writes (rays, the cells and nodes each ray's events name, their order and
// intervals), the arrays docs/vtk-export.md names; bad input exits 2 with one line and writes nothing.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLMultiBlockDataReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "cli_test_util.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/bsp_cell.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/structure_options.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/trace_file.h"
#include "raystep/vtk_export/vtk_export.h"

namespace raystep::clitest {
namespace {

namespace fs = std::filesystem;

class ExportVtkTest : public CliTest {
 protected:
  ExportVtkTest() : CliTest("export_vtk_") {}
};

vtkSmartPointer<vtkMultiBlockDataSet> read_vtm(const std::string& dir) {
  auto reader = vtkSmartPointer<vtkXMLMultiBlockDataReader>::New();
  reader->SetFileName((fs::path(dir) / "raystep.vtm").c_str());
  reader->Update();
  vtkSmartPointer<vtkMultiBlockDataSet> mb = vtkMultiBlockDataSet::SafeDownCast(reader->GetOutput());
  EXPECT_NE(mb, nullptr) << dir;
  return mb;
}

std::vector<std::string> block_names(vtkMultiBlockDataSet* mb) {
  std::vector<std::string> names;
  for (unsigned i = 0; i < mb->GetNumberOfBlocks(); ++i) {
    const char* n = mb->HasMetaData(i) ? mb->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()) : nullptr;
    names.push_back(n ? n : "");
  }
  return names;
}

vtkDataObject* block(vtkMultiBlockDataSet* mb, const std::string& name) {
  const std::vector<std::string> names = block_names(mb);
  for (unsigned i = 0; i < names.size(); ++i)
    if (names[i] == name) return mb->GetBlock(i);
  ADD_FAILURE() << "no block " << name;
  return nullptr;
}

// A named cell-data array as numbers; a failure if it is missing or of another length.
std::vector<double> cell_values(vtkDataSet* ds, const std::string& name) {
  std::vector<double> v;
  vtkDataArray* a = ds ? ds->GetCellData()->GetArray(name.c_str()) : nullptr;
  EXPECT_NE(a, nullptr) << "cell array " << name;
  if (!a) return v;
  EXPECT_EQ(a->GetNumberOfTuples(), ds->GetNumberOfCells()) << name;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) v.push_back(a->GetTuple1(i));
  return v;
}

bool names_cell_or_node(EventType t) {
  return t == EventType::cell || t == EventType::node || t == EventType::push || t == EventType::pop ||
         t == EventType::leaf || t == EventType::box_test || t == EventType::skip;
}

// Every piece file (raystep/*.vtp, *.vtu) read with its own reader: the cell counts, sorted, equal those of
// the leaf blocks the .vtm gave.
void expect_pieces_readable(const std::string& dir, vtkMultiBlockDataSet* mb) {
  std::vector<vtkIdType> from_vtm, from_files;
  std::vector<vtkMultiBlockDataSet*> todo{mb};
  while (!todo.empty()) {
    vtkMultiBlockDataSet* m = todo.back();
    todo.pop_back();
    for (unsigned i = 0; i < m->GetNumberOfBlocks(); ++i) {
      if (auto* sub = vtkMultiBlockDataSet::SafeDownCast(m->GetBlock(i)))
        todo.push_back(sub);
      else if (auto* ds = vtkDataSet::SafeDownCast(m->GetBlock(i)))
        from_vtm.push_back(ds->GetNumberOfCells());
    }
  }
  for (const auto& e : fs::recursive_directory_iterator(fs::path(dir) / "raystep")) {
    if (e.path().extension() == ".vtp") {
      auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
      r->SetFileName(e.path().c_str());
      r->Update();
      from_files.push_back(r->GetOutput()->GetNumberOfCells());
    } else if (e.path().extension() == ".vtu") {
      auto r = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
      r->SetFileName(e.path().c_str());
      r->Update();
      from_files.push_back(r->GetOutput()->GetNumberOfCells());
    } else {
      ADD_FAILURE() << "unexpected file " << e.path();
    }
  }
  std::sort(from_vtm.begin(), from_vtm.end());
  std::sort(from_files.begin(), from_files.end());
  EXPECT_EQ(from_vtm, from_files);
}

// The triangles the geometry block must have: each triangle, and 320 per sphere (icosphere of 2
// subdivisions).
size_t expected_triangles(const Geometry& g) {
  return g.triangle_count() + 320 * (g.size() - g.triangle_count());
}

std::unique_ptr<Accelerator> built(const std::string& name, const Geometry& g, StructureOptions o = {}) {
  auto a = make_accelerator(name, o);
  a->build(g);
  return a;
}

// Ray r's "visited" block against the trace's events: one cell per event naming a cell or node, in order,
// with its seq, type and interval.
void expect_walk_matches(vtkMultiBlockDataSet* mb, const Trace& trace, size_t r) {
  const TracedRay& ray = trace.rays[r];
  auto* ray_block = vtkMultiBlockDataSet::SafeDownCast(block(mb, "ray " + std::to_string(r)));
  ASSERT_NE(ray_block, nullptr);
  EXPECT_EQ(block_names(ray_block), (std::vector<std::string>{"path", "visited", "tests"}));
  auto* path = vtkPolyData::SafeDownCast(block(ray_block, "path"));
  auto* visited = vtkUnstructuredGrid::SafeDownCast(block(ray_block, "visited"));
  ASSERT_NE(path, nullptr);
  ASSERT_NE(visited, nullptr);

  // The path: one polyline from the origin, its end at the hit when there is one.
  EXPECT_EQ(path->GetNumberOfLines(), 1);
  EXPECT_GE(path->GetNumberOfPoints(), 2);
  vtkDataArray* t = path->GetPointData()->GetArray("t");
  ASSERT_NE(t, nullptr);
  const Event& end = ray.events.back();
  EXPECT_EQ(cell_values(path, "hit"), std::vector<double>{double(end.hit)});
  EXPECT_EQ(cell_values(path, "prim"), std::vector<double>{double(end.hit ? end.prim : -1)});
  EXPECT_EQ(cell_values(path, "ray"), std::vector<double>{double(r)});
  if (end.hit) EXPECT_FLOAT_EQ(float(t->GetTuple1(t->GetNumberOfTuples() - 1)), end.t);
  for (vtkIdType i = 1; i < t->GetNumberOfTuples(); ++i) EXPECT_GT(t->GetTuple1(i), t->GetTuple1(i - 1));

  std::vector<const Event*> named;
  for (const Event& e : ray.events)
    if (names_cell_or_node(e.type)) named.push_back(&e);
  ASSERT_EQ(visited->GetNumberOfCells(), vtkIdType(named.size()));
  const std::vector<double> seq = cell_values(visited, "seq"), event = cell_values(visited, "event"),
                            step = cell_values(visited, "step"), t_enter = cell_values(visited, "t_enter"),
                            t_exit = cell_values(visited, "t_exit");
  ASSERT_EQ(seq.size(), named.size());
  for (size_t i = 0; i < named.size(); ++i) {
    EXPECT_EQ(seq[i], named[i]->seq);
    EXPECT_EQ(event[i], int(named[i]->type));
    EXPECT_EQ(step[i], double(i));
    if (named[i]->type == EventType::cell) {
      EXPECT_FLOAT_EQ(float(t_enter[i]), named[i]->t_enter);
      EXPECT_FLOAT_EQ(float(t_exit[i]), named[i]->t_exit);
    } else if (named[i]->type != EventType::box_test || named[i]->hit) {
      EXPECT_FLOAT_EQ(float(t_enter[i]), named[i]->t_min_node);
      EXPECT_FLOAT_EQ(float(t_exit[i]), named[i]->t_max_node);
    }
  }
  EXPECT_NE(visited->GetFieldData()->GetAbstractArray("event_names"), nullptr);

  // The primitives tested, in event order: a triangle each, a sphere's 320.
  auto* tests = vtkPolyData::SafeDownCast(block(ray_block, "tests"));
  ASSERT_NE(tests, nullptr);
  std::vector<const Event*> tested;
  for (const Event& e : ray.events)
    if (e.type == EventType::prim_test || e.type == EventType::mailbox_hit) tested.push_back(&e);
  const std::vector<double> test_step = cell_values(tests, "step"), test_seq = cell_values(tests, "seq"),
                            test_prim = cell_values(tests, "prim"), test_hit = cell_values(tests, "hit"),
                            test_event = cell_values(tests, "event");
  cell_values(tests, "t");
  size_t c = 0;
  for (size_t i = 0; i < tested.size(); ++i) {
    const Event& e = *tested[i];
    ASSERT_LT(c, test_seq.size());
    const auto shape = std::find_if(trace.primitives.begin(), trace.primitives.end(),
                                    [&](const TracePrimitive& p) { return p.id == e.prim; });
    ASSERT_NE(shape, trace.primitives.end());
    const size_t n = shape->type == PrimType::triangle ? 1 : 320;
    for (size_t k = 0; k < n; ++k, ++c) {
      EXPECT_EQ(test_step[c], double(i));
      EXPECT_EQ(test_seq[c], double(e.seq));
      EXPECT_EQ(test_prim[c], double(e.prim));
      EXPECT_EQ(test_hit[c], double(e.hit));
      EXPECT_EQ(test_event[c], double(int(e.type)));
    }
  }
  EXPECT_EQ(c, test_seq.size());
}

TEST_F(ExportVtkTest, KdTreeAndAPixelsWalk) {
  const std::string sc = scene("cornell.json");
  const std::string out = path("out");
  Outcome r = run("export-vtk " + sc + " --accel kd --size 32x24 --pixel 16,12 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  Outcome tr = run("trace " + sc + " --accel kd --size 32x24 --pixel 16,12 -o " + path("t.json"));
  ASSERT_EQ(tr.code, 0) << tr.err;
  const Trace trace = read_trace_json(path("t.json"));
  ASSERT_EQ(trace.rays.size(), 1u);

  auto mb = read_vtm(out);
  ASSERT_NE(mb, nullptr);
  EXPECT_EQ(block_names(mb), (std::vector<std::string>{"geometry", "structure", "ray 0"}));
  expect_pieces_readable(out, mb);

  // Geometry: every primitive's triangles with its id, object and material.
  const Scene s = load_scene(sc);
  auto* geometry = vtkPolyData::SafeDownCast(block(mb, "geometry"));
  ASSERT_NE(geometry, nullptr);
  EXPECT_EQ(size_t(geometry->GetNumberOfPolys()), expected_triangles(s.geometry));
  const std::vector<double> prim = cell_values(geometry, "primitive"),
                            object = cell_values(geometry, "object"),
                            material = cell_values(geometry, "material");
  cell_values(geometry, "type");
  // Primitives in id order, each once (a triangle) or 320 times (a tessellated sphere).
  std::vector<size_t> per_prim(s.geometry.size(), 0);
  for (size_t i = 0; i < prim.size(); ++i) {
    ASSERT_GE(prim[i], 0.0);
    ASSERT_LT(prim[i], double(s.geometry.size()));
    if (i > 0) EXPECT_GE(prim[i], prim[i - 1]);
    const uint32_t id = uint32_t(prim[i]);
    ++per_prim[id];
    EXPECT_EQ(object[i], s.geometry.object_of(id));
    EXPECT_EQ(material[i], s.geometry.material(id));
  }
  for (uint32_t id = 0; id < s.geometry.size(); ++id)
    EXPECT_EQ(per_prim[id], s.geometry.type(id) == PrimType::triangle ? 1u : 320u) << id;

  // Structure: every kd node (the tree is small), as built here with the same (default) options.
  auto kd = built("kd", s.geometry);
  const KdTreeData& data = dynamic_cast<const KdTree&>(*kd).data();
  auto* structure = vtkUnstructuredGrid::SafeDownCast(block(mb, "structure"));
  ASSERT_NE(structure, nullptr);
  ASSERT_EQ(size_t(structure->GetNumberOfCells()), data.nodes.size());
  const std::vector<double> node = cell_values(structure, "node"), leaf = cell_values(structure, "leaf"),
                            depth = cell_values(structure, "depth"),
                            prims = cell_values(structure, "primitives"),
                            axis = cell_values(structure, "split_axis");
  cell_values(structure, "cost");
  cell_values(structure, "split_position");
  cell_values(structure, "parent");
  for (size_t i = 0; i < data.nodes.size(); ++i) {
    EXPECT_EQ(node[i], double(i));
    EXPECT_EQ(leaf[i], double(data.nodes[i].is_leaf()));
    EXPECT_EQ(depth[i], data.info[i].depth);
    EXPECT_EQ(axis[i], data.nodes[i].is_leaf() ? -1 : data.nodes[i].axis());
    if (data.nodes[i].is_leaf()) EXPECT_EQ(prims[i], data.nodes[i].prim_count());
  }
  // A node's count is the distinct primitives of the leaves below it (a primitive may be in several).
  std::function<std::set<uint32_t>(size_t)> below = [&](size_t id) {
    const KdNode& n = data.nodes[id];
    if (n.is_leaf())
      return std::set<uint32_t>(data.prim_index.begin() + n.first_prim,
                                data.prim_index.begin() + n.first_prim + n.prim_count());
    std::set<uint32_t> all = below(id + 1), above = below(n.above_child());
    all.insert(above.begin(), above.end());
    return all;
  };
  for (size_t i = 0; i < data.nodes.size(); ++i) EXPECT_EQ(prims[i], double(below(i).size())) << i;
  EXPECT_EQ(prims[0], double(s.geometry.size()));  // the root holds every primitive
  double bounds[6];
  structure->GetCell(0)->GetBounds(bounds);
  EXPECT_FLOAT_EQ(float(bounds[0]), data.info[0].box.lo.x);
  EXPECT_FLOAT_EQ(float(bounds[5]), data.info[0].box.hi.z);

  expect_walk_matches(mb, trace, 0);
}

TEST_F(ExportVtkTest, ATraceFileWithoutRebuildingItsStructure) {
  // A pixel with its secondary rays through the mirror and glass spheres: several rays, a BVH.
  const std::string sc = scene("spheres.json");
  Outcome tr =
      run("trace " + sc + " --accel bvh --size 40x30 --pixel 20,17 --secondary -o " + path("t.json"));
  ASSERT_EQ(tr.code, 0) << tr.err;
  const Trace trace = read_trace_json(path("t.json"));
  ASSERT_GT(trace.rays.size(), 1u);

  const std::string out = path("out");
  Outcome r = run("export-vtk " + sc + " --trace " + path("t.json") + " -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  auto mb = read_vtm(out);
  ASSERT_NE(mb, nullptr);
  std::vector<std::string> want{"geometry", "structure"};
  for (size_t i = 0; i < trace.rays.size(); ++i) want.push_back("ray " + std::to_string(i));
  EXPECT_EQ(block_names(mb), want);
  expect_pieces_readable(out, mb);

  const Scene s = load_scene(sc);
  auto* geometry = vtkPolyData::SafeDownCast(block(mb, "geometry"));
  ASSERT_NE(geometry, nullptr);
  EXPECT_EQ(size_t(geometry->GetNumberOfPolys()), expected_triangles(s.geometry));
  EXPECT_GT(s.geometry.size(), s.geometry.triangle_count());  // the spheres are there, tessellated

  // The structure block is the trace's own nodes.
  auto* structure = vtkUnstructuredGrid::SafeDownCast(block(mb, "structure"));
  ASSERT_NE(structure, nullptr);
  ASSERT_EQ(size_t(structure->GetNumberOfCells()), trace.nodes.size());
  const std::vector<double> node = cell_values(structure, "node"), depth = cell_values(structure, "depth");
  for (size_t i = 0; i < trace.nodes.size(); ++i) {
    EXPECT_EQ(node[i], trace.nodes[i].id);
    EXPECT_EQ(depth[i], trace.nodes[i].depth);
  }
  for (size_t i = 0; i < trace.rays.size(); ++i) expect_walk_matches(mb, trace, i);

  // With --accel as well, the whole BVH is rebuilt (same options) and the walks are the trace's.
  const std::string full = path("full");
  r = run("export-vtk " + sc + " --accel bvh --trace " + path("t.json") + " -o " + full);
  ASSERT_EQ(r.code, 0) << r.err;
  auto mb2 = read_vtm(full);
  ASSERT_NE(mb2, nullptr);
  auto bvh = built("bvh", s.geometry);
  auto* whole = vtkUnstructuredGrid::SafeDownCast(block(mb2, "structure"));
  ASSERT_NE(whole, nullptr);
  EXPECT_EQ(size_t(whole->GetNumberOfCells()), dynamic_cast<const Bvh&>(*bvh).data().nodes.size());
  cell_values(whole, "cost");
  cell_values(whole, "primitives");
  for (size_t i = 0; i < trace.rays.size(); ++i) expect_walk_matches(mb2, trace, i);

  // --pixel --secondary records the same rays as `raystep trace --pixel --secondary`, walk for walk.
  const std::string pixel = path("pixel");
  r = run("export-vtk " + sc + " --accel bvh --size 40x30 --pixel 20,17 --secondary -o " + pixel);
  ASSERT_EQ(r.code, 0) << r.err;
  auto mb3 = read_vtm(pixel);
  ASSERT_NE(mb3, nullptr);
  EXPECT_EQ(block_names(mb3), want);
  for (size_t i = 0; i < trace.rays.size(); ++i) expect_walk_matches(mb3, trace, i);
}

// The grid's primitives per cell, summed over the written cells, equal its references whichever way the
// bound cuts: every cell, the occupied cells, or merged blocks.
TEST_F(ExportVtkTest, GridCellsOccupiedCellsAndMergedBlocks) {
  const std::string sc = scene("spheres.json");
  const Scene s = load_scene(sc);
  StructureOptions o;
  o.grid.resolution = std::array<int, 3>{12, 10, 8};
  auto grid_accel = built("grid", s.geometry, o);
  const auto& grid = dynamic_cast<const UniformGrid&>(*grid_accel);
  const size_t cells = 12 * 10 * 8;
  size_t occupied = 0;
  for (size_t id = 0; id < cells; ++id) occupied += grid.occupied(id);
  ASSERT_LT(occupied, cells);

  std::vector<vtkSmartPointer<vtkMultiBlockDataSet>> keep;  // the datasets the returned blocks belong to
  auto export_grid = [&](const std::string& name, const std::string& extra) -> vtkUnstructuredGrid* {
    Outcome r = run("export-vtk " + sc + " --accel grid --grid-res 12,10,8 " + extra + " -o " + path(name));
    EXPECT_EQ(r.code, 0) << r.err;
    keep.push_back(read_vtm(path(name)));
    if (!keep.back()) return nullptr;
    EXPECT_EQ(block_names(keep.back()), (std::vector<std::string>{"geometry", "structure"}));
    return vtkUnstructuredGrid::SafeDownCast(block(keep.back(), "structure"));
  };
  auto reference_sum = [](vtkUnstructuredGrid* g) {
    double sum = 0;
    for (double p : cell_values(g, "primitives")) sum += p;
    return sum;
  };

  // Every cell, each with its own count.
  vtkUnstructuredGrid* all = export_grid("all", "");
  ASSERT_NE(all, nullptr);
  ASSERT_EQ(size_t(all->GetNumberOfCells()), cells);
  const std::vector<double> prims = cell_values(all, "primitives");
  const std::vector<double> i = cell_values(all, "i"), j = cell_values(all, "j"), k = cell_values(all, "k");
  std::set<std::array<int, 3>> seen;
  for (size_t c = 0; c < prims.size(); ++c) {
    const int ci = int(i[c]), cj = int(j[c]), ck = int(k[c]);
    seen.insert({ci, cj, ck});
    EXPECT_EQ(prims[c], double(grid.cell_end(ci, cj, ck) - grid.cell_begin(ci, cj, ck)));
    double b[6];
    all->GetCell(vtkIdType(c))->GetBounds(b);
    const Bounds3 want = grid.cell_bounds(ci, cj, ck);
    EXPECT_FLOAT_EQ(float(b[0]), want.lo.x);
    EXPECT_FLOAT_EQ(float(b[3]), want.hi.y);
  }
  EXPECT_EQ(seen.size(), cells);
  EXPECT_EQ(size_t(std::count_if(prims.begin(), prims.end(), [](double p) { return p > 0; })), occupied);
  EXPECT_EQ(reference_sum(all), double(grid.reference_count()));

  // Bounded below the lattice: the occupied cells.
  vtkUnstructuredGrid* busy = export_grid("busy", "--max-cells " + std::to_string(cells - 1));
  ASSERT_NE(busy, nullptr);
  EXPECT_EQ(size_t(busy->GetNumberOfCells()), occupied);
  EXPECT_EQ(reference_sum(busy), double(grid.reference_count()));

  // Bounded at 20: merged blocks.
  vtkUnstructuredGrid* blocks = export_grid("small", "--max-cells 20");
  ASSERT_NE(blocks, nullptr);
  EXPECT_LE(blocks->GetNumberOfCells(), 20);
  EXPECT_GT(blocks->GetNumberOfCells(), 0);
  EXPECT_EQ(reference_sum(blocks), double(grid.reference_count()));
  for (double b : cell_values(blocks, "block")) EXPECT_GE(b, 2.0);
}

TEST_F(ExportVtkTest, WideBvhCutByDepth) {
  const std::string sc = scene("spheres.json");
  const Scene s = load_scene(sc);
  auto wide = built("bvh4", s.geometry);
  const WideBvhView view = dynamic_cast<const WideBvh&>(*wide).describe();

  Outcome r = run("export-vtk " + sc + " --accel bvh4 -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto mb = read_vtm(path("out"));
  ASSERT_NE(mb, nullptr);
  auto* all = vtkUnstructuredGrid::SafeDownCast(block(mb, "structure"));
  ASSERT_NE(all, nullptr);
  ASSERT_EQ(size_t(all->GetNumberOfCells()), view.nodes.size());
  const std::vector<double> depth = cell_values(all, "depth"), prims = cell_values(all, "primitives");
  EXPECT_EQ(prims[0], double(s.geometry.size()));
  cell_values(all, "children");

  // A bound of half the nodes: whole levels 0..d, where level d + 1 would not fit.
  const size_t max_cells = view.nodes.size() / 2;
  r = run("export-vtk " + sc + " --accel bvh4 --max-cells " + std::to_string(max_cells) + " -o " +
          path("cut"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("nodes of depth 0.."), std::string::npos) << r.out;
  auto cut = read_vtm(path("cut"));
  ASSERT_NE(cut, nullptr);
  auto* top = vtkUnstructuredGrid::SafeDownCast(block(cut, "structure"));
  ASSERT_NE(top, nullptr);
  const std::vector<double> top_depth = cell_values(top, "depth");
  ASSERT_FALSE(top_depth.empty());
  const double d = *std::max_element(top_depth.begin(), top_depth.end());
  const size_t upto_d = size_t(std::count_if(depth.begin(), depth.end(), [&](double x) { return x <= d; }));
  const size_t upto_d1 =
      size_t(std::count_if(depth.begin(), depth.end(), [&](double x) { return x <= d + 1; }));
  EXPECT_EQ(top_depth.size(), upto_d);
  EXPECT_LE(upto_d, max_cells);
  EXPECT_GT(upto_d1, max_cells);
}

// The octree's cells: every node's cube with its depth, leaf flag, children and primitives (an inner node's:
// those it was split with, which are its leaves' union); a pixel's walk as `raystep trace` records it; the
// trace alone gives its named nodes with their children; --max-cells keeps whole levels.
TEST_F(ExportVtkTest, OctreeCellsAndWalks) {
  const std::string sc = scene("cornell.json");
  const Scene s = load_scene(sc);
  auto octree = built("octree", s.geometry);
  const OctreeData& data = dynamic_cast<const Octree&>(*octree).data();
  ASSERT_GT(data.nodes.size(), 9u);

  Outcome r = run("export-vtk " + sc + " --accel octree --size 32x24 --pixel 16,12 -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  Outcome tr = run("trace " + sc + " --accel octree --size 32x24 --pixel 16,12 -o " + path("t.json"));
  ASSERT_EQ(tr.code, 0) << tr.err;
  const Trace trace = read_trace_json(path("t.json"));
  auto mb = read_vtm(path("out"));
  ASSERT_NE(mb, nullptr);
  EXPECT_EQ(block_names(mb), (std::vector<std::string>{"geometry", "structure", "ray 0"}));
  expect_pieces_readable(path("out"), mb);

  auto* structure = vtkUnstructuredGrid::SafeDownCast(block(mb, "structure"));
  ASSERT_NE(structure, nullptr);
  ASSERT_EQ(size_t(structure->GetNumberOfCells()), data.nodes.size());
  const std::vector<double> node = cell_values(structure, "node"), parent = cell_values(structure, "parent"),
                            depth = cell_values(structure, "depth"), leaf = cell_values(structure, "leaf"),
                            prims = cell_values(structure, "primitives"),
                            children = cell_values(structure, "children"),
                            reason = cell_values(structure, "leaf_reason");
  std::function<std::set<uint32_t>(size_t)> below = [&](size_t id) {
    const OctreeNode& n = data.nodes[id];
    if (n.is_leaf())
      return std::set<uint32_t>(data.prim_index.begin() + n.first,
                                data.prim_index.begin() + n.first + n.prim_count());
    std::set<uint32_t> all;
    for (int c = 0; c < 8; ++c) {
      const std::set<uint32_t> part = below(n.child(c));
      all.insert(part.begin(), part.end());
    }
    return all;
  };
  for (size_t i = 0; i < data.nodes.size(); ++i) {
    const OctreeNode& n = data.nodes[i];
    EXPECT_EQ(node[i], double(i));
    EXPECT_EQ(parent[i], data.info[i].parent);
    EXPECT_EQ(depth[i], data.info[i].depth);
    EXPECT_EQ(leaf[i], double(n.is_leaf()));
    EXPECT_EQ(children[i], n.is_leaf() ? 0.0 : 8.0);
    EXPECT_EQ(reason[i], n.is_leaf() ? double(int(data.info[i].reason)) : -1.0);
    EXPECT_EQ(prims[i], double(below(i).size())) << i;
    double b[6];
    structure->GetCell(vtkIdType(i))->GetBounds(b);
    EXPECT_EQ(std::vector<double>(b, b + 6),
              (std::vector<double>{data.info[i].box.lo.x, data.info[i].box.hi.x, data.info[i].box.lo.y,
                                   data.info[i].box.hi.y, data.info[i].box.lo.z, data.info[i].box.hi.z}))
        << i;
  }
  EXPECT_EQ(prims[0], double(s.geometry.size()));
  expect_walk_matches(mb, trace, 0);

  // The trace alone: its named nodes, each with its 8 (or no) children.
  r = run("export-vtk " + sc + " --trace " + path("t.json") + " -o " + path("named"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto named = read_vtm(path("named"));
  ASSERT_NE(named, nullptr);
  auto* nodes = vtkUnstructuredGrid::SafeDownCast(block(named, "structure"));
  ASSERT_NE(nodes, nullptr);
  ASSERT_EQ(size_t(nodes->GetNumberOfCells()), trace.nodes.size());
  const std::vector<double> named_children = cell_values(nodes, "children");
  for (size_t i = 0; i < trace.nodes.size(); ++i)
    EXPECT_EQ(named_children[i], trace.nodes[i].leaf ? 0.0 : 8.0) << trace.nodes[i].id;
  expect_walk_matches(named, trace, 0);

  // A bound below the node count: the levels 0..d that fit.
  const size_t max_cells = data.nodes.size() - 1;
  r = run("export-vtk " + sc + " --accel octree --max-cells " + std::to_string(max_cells) + " -o " +
          path("cut"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto cut = read_vtm(path("cut"));
  ASSERT_NE(cut, nullptr);
  auto* top = vtkUnstructuredGrid::SafeDownCast(block(cut, "structure"));
  ASSERT_NE(top, nullptr);
  const std::vector<double> top_depth = cell_values(top, "depth");
  ASSERT_FALSE(top_depth.empty());
  const double d = *std::max_element(top_depth.begin(), top_depth.end());
  EXPECT_EQ(top_depth.size(),
            size_t(std::count_if(depth.begin(), depth.end(), [&](double x) { return x <= d; })));
  EXPECT_LE(top_depth.size(), max_cells);
}

// A polyhedron cell's volume from its faces (divergence theorem, faces as fans): positive when every face
// runs counter-clockwise seen from outside.
double polyhedron_volume(vtkCell* cell) {
  double v = 0.0;
  for (int f = 0; f < cell->GetNumberOfFaces(); ++f) {
    vtkCell* face = cell->GetFace(f);
    vtkPoints* p = face->GetPoints();
    double a[3], b[3], c[3];
    p->GetPoint(0, a);
    for (vtkIdType k = 1; k + 1 < p->GetNumberOfPoints(); ++k) {
      p->GetPoint(k, b);
      p->GetPoint(k + 1, c);
      v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
            a[2] * (b[0] * c[1] - b[1] * c[0])) /
           6.0;
    }
  }
  return v;
}

// The BSP tree's cells: every node's convex cell as a VTK polyhedron inside (and up to rounding equal to)
// the box the builder records, the leaves tiling the root box (volumes), each inner node's plane as cell
// data and its polygon in the "planes" block on that plane; a pixel's walk as `raystep trace` records it;
// the trace alone gives its named nodes as cells rebuilt from the planes it carries.
TEST_F(ExportVtkTest, BspCellsPlanesAndWalks) {
  const std::string sc = scene("rotated_box.json");
  const Scene s = load_scene(sc);
  auto bsp = built("bsp", s.geometry);
  const BspTreeData& data = dynamic_cast<const BspTree&>(*bsp).data();
  // Nodes with a cell to draw, and inner nodes whose plane cuts their cell in two (a plane that only grazes
  // its parent's cell, within the cell's rounding tolerance, leaves one child with an empty cell).
  size_t cutting = 0;
  for (size_t i = 0; i < data.nodes.size(); ++i) {
    const BspNode& n = data.nodes[i];
    cutting += !n.is_leaf() && !data.info[i + 1].box.empty() && !data.info[n.above_child()].box.empty();
  }
  ASSERT_GT(cutting, 3u);

  Outcome r = run("export-vtk " + sc + " --accel bsp --size 32x24 --pixel 16,12 -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  Outcome tr = run("trace " + sc + " --accel bsp --size 32x24 --pixel 16,12 -o " + path("t.json"));
  ASSERT_EQ(tr.code, 0) << tr.err;
  const Trace trace = read_trace_json(path("t.json"));
  auto mb = read_vtm(path("out"));
  ASSERT_NE(mb, nullptr);
  EXPECT_EQ(block_names(mb), (std::vector<std::string>{"geometry", "structure", "planes", "ray 0"}));
  expect_pieces_readable(path("out"), mb);

  const Bounds3& root = data.bounds;
  const double scale = glm::length(root.extent());
  auto* structure = vtkUnstructuredGrid::SafeDownCast(block(mb, "structure"));
  ASSERT_NE(structure, nullptr);
  const size_t drawn = size_t(structure->GetNumberOfCells());
  const std::vector<double> node = cell_values(structure, "node"), depth = cell_values(structure, "depth"),
                            leaf = cell_values(structure, "leaf"),
                            prims = cell_values(structure, "primitives"),
                            nx = cell_values(structure, "normal_x"), ny = cell_values(structure, "normal_y"),
                            nz = cell_values(structure, "normal_z"),
                            offset = cell_values(structure, "offset");
  cell_values(structure, "parent");
  cell_values(structure, "cost");
  cell_values(structure, "area");
  cell_values(structure, "plane_source");
  // The nodes not drawn: an empty cell, or a sliver thinner than floats resolve.
  const double sliver = 1e-5 * scale;
  std::vector<bool> is_drawn(data.nodes.size(), false);
  for (double id : node)
    if (id >= 0 && size_t(id) < data.nodes.size()) is_drawn[size_t(id)] = true;
  {
    // Every cell rebuilt here (core's ConvexCell, as the builder cuts them): an undrawn one is empty, tiny,
    // or a sliver whose mean width (volume / area) is below the bound.
    std::vector<ConvexCell> cells(data.nodes.size());
    cells[0] = ConvexCell::box(data.bounds);
    for (size_t i = 0; i < data.nodes.size(); ++i) {
      const BspNode& n = data.nodes[i];
      if (!n.is_leaf())
        cells[i].split(glm::dvec3(n.plane.normal), double(n.plane.offset), &cells[i + 1],
                       &cells[n.above_child()]);
      if (is_drawn[i] || cells[i].empty()) continue;
      double volume = 0.0;
      for (size_t f = 0; f < cells[i].face_count(); ++f) {
        const glm::dvec3* v = cells[i].face(f);
        for (size_t k = 1; k + 1 < cells[i].face_size(f); ++k)
          volume += glm::dot(v[0], glm::cross(v[k], v[k + 1])) / 6.0;
      }
      const glm::vec3 e = cells[i].bounds().extent();
      EXPECT_TRUE(volume <= sliver * cells[i].area() || std::max({e.x, e.y, e.z}) <= sliver)
          << i << ": volume " << volume << ", area " << cells[i].area();
    }
  }
  EXPECT_GT(drawn, data.nodes.size() * 9 / 10);
  size_t both_drawn = 0;
  for (size_t i = 0; i < data.nodes.size(); ++i)
    both_drawn += !data.nodes[i].is_leaf() && is_drawn[i + 1] && is_drawn[data.nodes[i].above_child()];
  double leaf_volume = 0.0;
  for (size_t c = 0; c < drawn; ++c) {
    const size_t i = size_t(node[c]);
    if (c > 0) ASSERT_GT(node[c], node[c - 1]);  // preorder, as the tree's ids
    ASSERT_LT(i, data.nodes.size());
    const BspNode& n = data.nodes[i];
    const Bounds3& box = data.info[i].box;
    ASSERT_FALSE(box.empty()) << i;
    EXPECT_EQ(depth[c], data.info[i].depth);
    EXPECT_EQ(leaf[c], double(n.is_leaf()));
    if (n.is_leaf()) {
      EXPECT_EQ(prims[c], double(n.prim_count()));
      EXPECT_TRUE(std::isnan(nx[c]) && std::isnan(offset[c]));
    } else {
      EXPECT_EQ(float(nx[c]), n.plane.normal.x);
      EXPECT_EQ(float(ny[c]), n.plane.normal.y);
      EXPECT_EQ(float(nz[c]), n.plane.normal.z);
      EXPECT_EQ(float(offset[c]), n.plane.offset);
    }
    vtkCell* cell = structure->GetCell(vtkIdType(c));
    ASSERT_EQ(cell->GetCellType(), VTK_POLYHEDRON);
    double b[6];
    cell->GetBounds(b);
    // Rounded to nearest inside the builder's box, rounded outward: within it, and the same up to rounding.
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(b[2 * a], box.lo[a]) << i;
      EXPECT_LE(b[2 * a + 1], box.hi[a]) << i;
      EXPECT_NEAR(b[2 * a], box.lo[a], 1e-5 * scale) << i;
      EXPECT_NEAR(b[2 * a + 1], box.hi[a], 1e-5 * scale) << i;
    }
    const double volume = polyhedron_volume(cell);
    const glm::dvec3 e = glm::dvec3(root.hi) - glm::dvec3(root.lo);
    const double root_volume = e.x * e.y * e.z;
    EXPECT_GE(volume, -1e-9 * root_volume) << i;
    if (n.is_leaf()) leaf_volume += volume;
  }
  const glm::dvec3 e = glm::dvec3(root.hi) - glm::dvec3(root.lo);
  EXPECT_NEAR(leaf_volume, e.x * e.y * e.z, 1e-6 * e.x * e.y * e.z);
  EXPECT_NEAR(polyhedron_volume(structure->GetCell(0)), e.x * e.y * e.z, 1e-12 * e.x * e.y * e.z);

  // The planes: one polygon per inner node, on its plane, inside its cell's box.
  auto* planes = vtkPolyData::SafeDownCast(block(mb, "planes"));
  ASSERT_NE(planes, nullptr);
  size_t drawn_inner = 0;
  for (size_t i = 0; i < data.nodes.size(); ++i) drawn_inner += is_drawn[i] && !data.nodes[i].is_leaf();
  EXPECT_LE(size_t(planes->GetNumberOfCells()), drawn_inner);
  EXPECT_GE(size_t(planes->GetNumberOfCells()), both_drawn);
  const std::vector<double> plane_node = cell_values(planes, "node");
  cell_values(planes, "depth");
  for (vtkIdType c = 0; c < planes->GetNumberOfCells(); ++c) {
    const size_t id = size_t(plane_node[size_t(c)]);
    ASSERT_LT(id, data.nodes.size());
    ASSERT_FALSE(data.nodes[id].is_leaf());
    EXPECT_TRUE(is_drawn[id]) << id;
    const BspPlane& plane = data.nodes[id].plane;
    vtkPoints* p = planes->GetCell(c)->GetPoints();
    EXPECT_GE(p->GetNumberOfPoints(), 3);
    for (vtkIdType k = 0; k < p->GetNumberOfPoints(); ++k) {
      double x[3];
      p->GetPoint(k, x);
      EXPECT_NEAR(plane.normal.x * x[0] + plane.normal.y * x[1] + plane.normal.z * x[2], plane.offset,
                  1e-5 * scale);
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(x[a], data.info[id].box.lo[a] - 1e-5 * scale);
        EXPECT_LE(x[a], data.info[id].box.hi[a] + 1e-5 * scale);
      }
    }
  }
  expect_walk_matches(mb, trace, 0);
  auto* visited = vtkUnstructuredGrid::SafeDownCast(
      block(vtkMultiBlockDataSet::SafeDownCast(block(mb, "ray 0")), "visited"));
  ASSERT_NE(visited, nullptr);
  ASSERT_GT(visited->GetNumberOfCells(), 0);
  EXPECT_EQ(visited->GetCellType(0), VTK_POLYHEDRON);

  // The trace alone: the named nodes' cells, rebuilt from the root box and the planes the trace carries,
  // bound the boxes the trace records for them; each named inner node's polygon.
  r = run("export-vtk " + sc + " --trace " + path("t.json") + " -o " + path("named"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto named = read_vtm(path("named"));
  ASSERT_NE(named, nullptr);
  expect_pieces_readable(path("named"), named);
  auto* nodes = vtkUnstructuredGrid::SafeDownCast(block(named, "structure"));
  ASSERT_NE(nodes, nullptr);
  std::vector<const TraceNode*> named_drawn;
  const std::vector<double> named_id = cell_values(nodes, "node");
  for (const TraceNode& tn : trace.nodes)
    if (std::find(named_id.begin(), named_id.end(), double(tn.id)) != named_id.end())
      named_drawn.push_back(&tn);
    else if (!tn.box.empty())
      EXPECT_LE(std::min({tn.box.extent().x, tn.box.extent().y, tn.box.extent().z}), sliver) << tn.id;
  ASSERT_EQ(size_t(nodes->GetNumberOfCells()), named_drawn.size());
  ASSERT_GT(named_drawn.size(), 0u);
  const std::vector<double> named_offset = cell_values(nodes, "offset");
  size_t named_inner = 0;
  for (size_t i = 0; i < named_drawn.size(); ++i) {
    const TraceNode& tn = *named_drawn[i];
    named_inner += tn.has_plane;
    if (tn.has_plane) EXPECT_EQ(float(named_offset[i]), tn.offset);
    ASSERT_EQ(nodes->GetCellType(vtkIdType(i)), VTK_POLYHEDRON);
    double b[6];
    nodes->GetCell(vtkIdType(i))->GetBounds(b);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(b[2 * a], tn.box.lo[a], 1e-5 * scale) << tn.id;
      EXPECT_NEAR(b[2 * a + 1], tn.box.hi[a], 1e-5 * scale) << tn.id;
    }
  }
  ASSERT_GT(named_inner, 0u);
  auto* named_planes = vtkPolyData::SafeDownCast(block(named, "planes"));
  ASSERT_NE(named_planes, nullptr);
  EXPECT_LE(size_t(named_planes->GetNumberOfCells()), named_inner);
  EXPECT_GT(named_planes->GetNumberOfCells(), 0);
  expect_walk_matches(named, trace, 0);

  // With --accel as well: the whole tree rebuilt (the trace's parameters), the trace's walk.
  r = run("export-vtk " + sc + " --accel bsp --trace " + path("t.json") + " -o " + path("full"));
  ASSERT_EQ(r.code, 0) << r.err;
  auto full = read_vtm(path("full"));
  ASSERT_NE(full, nullptr);
  auto* whole = vtkUnstructuredGrid::SafeDownCast(block(full, "structure"));
  ASSERT_NE(whole, nullptr);
  EXPECT_EQ(size_t(whole->GetNumberOfCells()), drawn);
  expect_walk_matches(full, trace, 0);

  // A bound below the node count: whole levels, and the planes of the inner nodes written.
  const size_t max_cells = data.nodes.size() / 2;
  r = run("export-vtk " + sc + " --accel bsp --max-cells " + std::to_string(max_cells) + " -o " +
          path("cut"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("nodes of depth 0.."), std::string::npos) << r.out;
  auto cut = read_vtm(path("cut"));
  ASSERT_NE(cut, nullptr);
  auto* top = vtkUnstructuredGrid::SafeDownCast(block(cut, "structure"));
  ASSERT_NE(top, nullptr);
  const std::vector<double> top_depth = cell_values(top, "depth"), top_leaf = cell_values(top, "leaf");
  ASSERT_FALSE(top_depth.empty());
  const double d = *std::max_element(top_depth.begin(), top_depth.end());
  EXPECT_EQ(top_depth.size(),
            size_t(std::count_if(depth.begin(), depth.end(), [&](double x) { return x <= d; })));
  EXPECT_LE(top_depth.size(), max_cells);
  auto* top_planes = vtkPolyData::SafeDownCast(block(cut, "planes"));
  ASSERT_NE(top_planes, nullptr);
  EXPECT_LE(size_t(top_planes->GetNumberOfCells()),
            size_t(std::count(top_leaf.begin(), top_leaf.end(), 0.0)));
  EXPECT_GT(top_planes->GetNumberOfCells(), 0);
}

TEST_F(ExportVtkTest, BadInputExitsTwoWithOneLine) {
  const std::string sc = scene("cornell.json");
  Outcome tr = run("trace " + sc + " --accel kd --size 32x24 --pixel 16,12 -o " + path("t.json"));
  ASSERT_EQ(tr.code, 0) << tr.err;
  const std::string out = path("out");
  expect_error(run("export-vtk " + path("missing.json") + " --accel kd -o " + out), "", out);
  expect_error(run("export-vtk " + sc + " --accel octopus -o " + out), "", out);
  expect_error(run("export-vtk " + sc + " --accel bvol -o " + out),
               "export-vtk: --accel bvol has no VTK export", out);
  expect_error(run("export-vtk " + sc + " -o " + out), "export-vtk: give --accel", out);
  expect_error(run("export-vtk " + sc + " --accel kd --size 32x24 --pixel 32,0 -o " + out),
               "--pixel '32,0': outside", out);
  expect_error(run("export-vtk " + sc + " --accel kd --pixel 1,2,3 -o " + out), "--pixel", out);
  expect_error(run("export-vtk " + sc + " --accel kd --max-cells 0 -o " + out), "--max-cells", out);
  expect_error(run("export-vtk " + sc + " --accel kd --secondary -o " + out), "export-vtk: --secondary", out);
  // A trace of another scene, a damaged one, one of another structure or other build options.
  expect_error(run("export-vtk " + scene("spheres.json") + " --trace " + path("t.json") + " -o " + out),
               path("t.json"), out);
  std::string text = slurp(path("t.json"));
  write("cut.json", text.substr(0, text.size() / 2));
  expect_error(run("export-vtk " + sc + " --trace " + path("cut.json") + " -o " + out), path("cut.json"),
               out);
  expect_error(run("export-vtk " + sc + " --accel grid --trace " + path("t.json") + " -o " + out),
               path("t.json"), out);
  expect_error(run("export-vtk " + sc + " --accel kd --leaf-size 3 --trace " + path("t.json") + " -o " + out),
               path("t.json"), out);
  expect_error(run("export-vtk " + sc + " --accel kd --pixel 1,1 --trace " + path("t.json") + " -o " + out),
               "", out);
  // -o naming a file, or in a folder that does not exist; the file is left alone.
  write("file", "keep");
  expect_error(run("export-vtk " + sc + " --accel kd -o " + path("file")), path("file"));
  EXPECT_EQ(slurp(path("file")), "keep");
  expect_error(run("export-vtk " + sc + " --accel kd -o " + path("no/such/dir")), "");
  // Nothing but the inputs is left behind (no temporary folders).
  std::set<std::string> left;
  for (const auto& e : fs::directory_iterator(dir_)) left.insert(e.path().filename().string());
  EXPECT_EQ(left, (std::set<std::string>{"t.json", "cut.json", "file"}));
}

TEST_F(ExportVtkTest, ReplacesAnOldExportWhole) {
  const std::string sc = scene("cornell.json");
  const std::string out = path("out");
  fs::create_directories(out + "/raystep");
  write("out/stale.txt", "old");
  Outcome r = run("export-vtk " + sc + " --accel bvh8 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(out + "/stale.txt"));
  auto mb = read_vtm(out);
  ASSERT_NE(mb, nullptr);
  EXPECT_EQ(block_names(mb), (std::vector<std::string>{"geometry", "structure"}));
}

// The cell a BSP node will export (structure_cells.h): a convex polytope, written as a VTK polyhedron whose
// corners are shared by its faces. Through the library directly: no structure has such cells yet.
TEST_F(ExportVtkTest, APolytopeCellIsWrittenAsAPolyhedron) {
  const glm::vec3 a(0, 0, 0), b(2, 0, 0), c(0, 3, 0), d(0, 0, 4);
  vtk_export::ConvexCell tetra;
  tetra.faces = {{a, c, b}, {a, b, d}, {a, d, c}, {b, c, d}};
  vtk_export::StructureCells sc;
  sc.kind = "bsp";
  sc.cells.add_polytope(tetra);
  sc.cells.set("depth", 3, true);
  sc.cells.add_polytope(vtk_export::ConvexCell{});  // nothing to draw: an empty cell keeps its place
  sc.cells.set("depth", 4, true);
  sc.cells.finish();
  sc.total = 2;
  Geometry g;
  g.begin_object("triangle", 0);
  g.add_triangle(a, b, c);
  vtk_export::ExportInput in;
  in.geometry = &g;
  in.structure = &sc;
  fs::create_directories(path("out"));
  vtk_export::write_vtk_export(path("out"), in);

  auto mb = read_vtm(path("out"));
  ASSERT_NE(mb, nullptr);
  expect_pieces_readable(path("out"), mb);
  auto* structure = vtkUnstructuredGrid::SafeDownCast(block(mb, "structure"));
  ASSERT_NE(structure, nullptr);
  ASSERT_EQ(structure->GetNumberOfCells(), 2);
  EXPECT_EQ(structure->GetCellType(0), VTK_POLYHEDRON);
  EXPECT_EQ(structure->GetCellType(1), VTK_EMPTY_CELL);
  EXPECT_EQ(structure->GetCell(0)->GetNumberOfPoints(), 4);
  EXPECT_EQ(structure->GetCell(0)->GetNumberOfFaces(), 4);
  double bounds[6];
  structure->GetCell(0)->GetBounds(bounds);
  EXPECT_EQ(std::vector<double>(bounds, bounds + 6), (std::vector<double>{0, 2, 0, 3, 0, 4}));
  EXPECT_EQ(cell_values(structure, "depth"), (std::vector<double>{3, 4}));
}

}  // namespace
}  // namespace raystep::clitest
