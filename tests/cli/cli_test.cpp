// The `raystep` command end to end: every bad input gives one line "error: FILE:LINE: what", exit code 2 and
// no output file; the good paths write what they say.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;

using namespace raystep::clitest;

class Cli : public CliTest {
 protected:
  Cli() : CliTest("raystep_cli_") {}

  // An octahedron: 8 triangles, closed.
  std::string octahedron() const {
    return write("octa.obj",
                 "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                 "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n");
  }
};

TEST_F(Cli, HelpOnEverySubcommand) {
  for (const char* sub : {"", "render", "cast", "rays", "info"}) {
    Outcome r = run(std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
}

TEST_F(Cli, MissingSceneFile) {
  std::string missing = path("nope.json");
  expect_error(run("render " + missing + " -o " + path("a.png")), missing);
  EXPECT_FALSE(fs::exists(path("a.png")));
}

TEST_F(Cli, MalformedJsonNamesTheLine) {
  std::string scene = write("bad.json", "{\n  \"camera\": {\n    \"fov\": 40,,\n  }\n}\n");
  Outcome r = run("render " + scene + " -o " + path("a.png"));
  expect_error(r, scene + ":3:");
  EXPECT_FALSE(fs::exists(path("a.png")));
}

TEST_F(Cli, WrongTypeNamesTheLine) {
  std::string scene = write("type.json",
                            "{\n  \"objects\": [\n    {\"type\": \"sphere\", \"center\": [0, 0, 0],\n     "
                            "\"radius\": \"big\"}\n  ]\n}\n");
  expect_error(run("info " + scene), scene + ":4:");
}

TEST_F(Cli, UnknownKeyNamesTheLine) {
  std::string scene = write("key.json",
                            "{\n  \"objects\": [ {\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": "
                            "1} ],\n  \"camra\": {}\n}\n");
  Outcome r = run("info " + scene);
  expect_error(r, scene + ":3:");
  EXPECT_NE(r.err.find("camra"), std::string::npos);
}

TEST_F(Cli, ObjIndexOutOfRangeNamesTheLine) {
  std::string mesh = write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
  expect_error(run("render " + mesh + " -o " + path("a.png")), mesh + ":5:");
  EXPECT_FALSE(fs::exists(path("a.png")));
}

TEST_F(Cli, ObjNonFiniteCoordinateNamesTheLine) {
  std::string mesh = write("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
  expect_error(run("info " + mesh), mesh + ":2:");
  std::string inf = write("inf.obj", "v 0 0 0\nv 1 0 0\nv 0 1 inf\nf 1 2 3\n");
  expect_error(run("info " + inf), inf + ":3:");
}

TEST_F(Cli, RayFileOfWrongSize) {
  std::string mesh = octahedron();
  std::string rays = write("bad.rays", std::string(33, '\0'));
  Outcome r = run("cast " + mesh + " --rays " + rays + " --hits " + path("out.hits"));
  expect_error(r, rays);
  EXPECT_FALSE(fs::exists(path("out.hits")));
}

TEST_F(Cli, BadOptions) {
  std::string mesh = octahedron();
  std::string out = path("a.png");
  expect_error(run("render " + mesh + " -o " + out + " --aa jitter:0"), "");
  expect_error(run("render " + mesh + " -o " + out + " --size 0x10"), "--size");
  expect_error(run("render " + mesh + " -o " + out + " --accel octree-of-dreams"), "--accel");
  expect_error(run("render " + mesh + " -o " + path("a.bmp")), path("a.bmp"));
  expect_error(run("render " + mesh + " -o " + path("no/such/dir/a.png")), path("no/such/dir/a.png"));
  expect_error(run("render " + mesh + " -o " + out + " --frobnicate"), "");
  expect_error(run("frobnicate"), "");
  expect_error(run("render " + mesh + " -o " + out + " --threads 100000"), "--threads");
  expect_error(run("render " + mesh + " -o " + out + " --threads -1"), "--threads");
  EXPECT_FALSE(fs::exists(out));
  ASSERT_EQ(run("rays " + mesh + " --kind random --count 10 -o " + path("r.rays")).code, 0);
  expect_error(
      run("cast " + mesh + " --rays " + path("r.rays") + " --hits " + path("h.hits") + " --threads 100000"),
      "--threads");
  EXPECT_FALSE(fs::exists(path("h.hits")));
}

TEST_F(Cli, RenderWritesTheImageAndCountsRays) {
  std::string mesh = octahedron();
  Outcome r = run("render " + mesh + " -o " + path("a.png") + " --size 32x24 --aa jitter:2 --samples-map " +
                  path("s.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("a.png")));
  EXPECT_TRUE(fs::exists(path("s.png")));
  // 32 x 24 pixels x 4 samples: the primary ray count is exact.
  EXPECT_NE(r.out.find("primary=3072 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrote " + path("a.png")), std::string::npos) << r.out;
  // No temporary file is left beside the outputs.
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(Cli, RaysAndCastAgreeAcrossAccelerators) {
  std::string mesh = octahedron();
  ASSERT_EQ(run("rays " + mesh + " --kind random --count 5000 --seed 3 -o " + path("r.rays")).code, 0);
  EXPECT_EQ(fs::file_size(path("r.rays")), 5000u * 32u);
  std::string brute, bvol;
  for (const char* accel : {"brute", "bvol"}) {
    Outcome r = run("cast " + mesh + " --rays " + path("r.rays") + " --hits " +
                    path(std::string(accel) + ".hits") + " --accel " + accel + " --reps 2");
    ASSERT_EQ(r.code, 0) << r.err;
    // The last line is the key=value summary.
    std::string last = r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
    std::regex line("accel=" + std::string(accel) +
                    " prims=8 rays=5000 build_ms=[0-9.]+ trace_ms=[0-9.]+ mrays_per_s=[0-9.]+\n");
    EXPECT_TRUE(std::regex_match(last, line)) << last;
    EXPECT_EQ(fs::file_size(path(std::string(accel) + ".hits")), 5000u * 8u);
  }
  EXPECT_EQ(slurp(path("brute.hits")), slurp(path("bvol.hits")));
}

TEST_F(Cli, CastCoarsensAGridPastTheReferenceBudgetAndSaysSo) {
  // 100,000 copies of one triangle: the density rule's 139^3 grid would need ~10^9 references; the grid is
  // coarsened to the budget, answers as brute force does, and the structure line names the coarsening.
  std::string obj = "v 0 0 0\nv 1 0.2 0.1\nv 0.3 1 1\n";
  for (int i = 0; i < 100000; ++i) obj += "f 1 2 3\n";
  std::string mesh = write("copies.obj", obj);
  ASSERT_EQ(run("rays " + mesh + " --kind camera --size 12x12 -o " + path("r.rays")).code, 0);
  Outcome g = run("cast " + mesh + " --rays " + path("r.rays") + " --hits " + path("g.hits") +
                  " --accel grid --reps 1");
  ASSERT_EQ(g.code, 0) << g.err;
  std::smatch m;
  std::regex line(
      "structure: grid ([0-9]+) x ([0-9]+) x ([0-9]+) cells \\(coarsened from 139 x 139 x 139: "
      "reference budget of 4194304\\), ([0-9]+) references");
  ASSERT_TRUE(std::regex_search(g.out, m, line)) << g.out;
  EXPECT_LT(std::stoi(m[1]), 139);
  EXPECT_LE(std::stoul(m[4]), 4194304u);
  Outcome b = run("cast " + mesh + " --rays " + path("r.rays") + " --hits " + path("b.hits") +
                  " --accel brute --reps 1");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(slurp(path("g.hits")), slurp(path("b.hits")));
  EXPECT_NE(g.out.find("hits: "), std::string::npos);
  EXPECT_EQ(g.out.find("hits: 0 of"), std::string::npos) << g.out;  // the camera sees the triangle
  // An explicit resolution is taken as asked or refused, never changed.
  Outcome x = run("cast " + mesh + " --rays " + path("r.rays") + " --hits " + path("x.hits") +
                  " --accel grid --grid-res 64,64,64");
  expect_error(x, "grid resolution 64x64x64 would test");
  EXPECT_NE(x.err.find("budget of 16777216 for 100000 primitives"), std::string::npos) << x.err;
  EXPECT_FALSE(fs::exists(path("x.hits")));
}

TEST_F(Cli, CastNamesTheStructuresShape) {
  std::string mesh = octahedron();
  ASSERT_EQ(run("rays " + mesh + " --kind random --count 500 --seed 3 -o " + path("r.rays")).code, 0);
  std::smatch m;
  // A 2x2x2 grid of the octahedron: the cells are its octants, and cells are closed. The face (1,0,0),
  // (0,1,0), (0,0,1) touches every octant that one of its corners borders: all but (-,-,-), 7. Its bounding
  // box [0,1]^3 also touches (-,-,-) at the origin: 8.
  size_t refs[2] = {0, 0};
  for (int exact = 0; exact < 2; ++exact) {
    Outcome r = run("cast " + mesh + " --rays " + path("r.rays") + " --hits " + path("g.hits") +
                    " --accel grid --grid-res 2,2,2 --grid-insert " + (exact ? "exact" : "bbox"));
    ASSERT_EQ(r.code, 0) << r.err;
    std::regex line(
        std::string("structure: grid 2 x 2 x 2 cells, ([0-9]+) references \\(([0-9.]+) per primitive\\), ") +
        (exact ? "exact" : "bbox") + " insertion\n");
    ASSERT_TRUE(std::regex_search(r.out, m, line)) << r.out;
    refs[exact] = std::stoul(m[1]);
    EXPECT_NEAR(std::stod(m[2]), refs[exact] / 8.0, 1e-3);
  }
  EXPECT_EQ(refs[1], 8u * 7u);
  EXPECT_EQ(refs[0], 8u * 8u);
  Outcome k = run("cast " + mesh + " --rays " + path("r.rays") + " --hits " + path("k.hits") + " --accel kd");
  ASSERT_EQ(k.code, 0) << k.err;
  ASSERT_TRUE(std::regex_search(k.out, m,
                                std::regex("structure: kd ([0-9]+) nodes \\(([0-9]+) leaves, [0-9]+ "
                                           "empty\\), depth [0-9]+, ([0-9]+) references")))
      << k.out;
  EXPECT_EQ(std::stoul(m[1]), 2 * std::stoul(m[2]) - 1);  // a binary tree
  EXPECT_GE(std::stoul(m[3]), 8u);
}

TEST_F(Cli, CameraRaysOnePerPixel) {
  std::string mesh = octahedron();
  Outcome r = run("rays " + mesh + " --kind camera --size 20x10 -o " + path("c.rays"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(fs::file_size(path("c.rays")), 200u * 32u);
  ASSERT_EQ(run("rays " + mesh + " --kind edges --count 100 -o " + path("e.rays")).code, 0);
  EXPECT_EQ(fs::file_size(path("e.rays")), 100u * 32u);
}

TEST_F(Cli, InfoReportsDegenerateTriangles) {
  std::string mesh = write("deg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n");
  Outcome r = run("info " + mesh);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("primitives: 2 (2 triangles, 0 spheres)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("degenerate triangles: 1"), std::string::npos) << r.out;
}

TEST_F(Cli, EveryShippedSceneRenders) {
  for (const auto& e : fs::directory_iterator(fs::path(RAYSTEP_SOURCE_DIR) / "scenes")) {
    if (e.path().extension() != ".json") continue;
    Outcome r = run("render " + e.path().string() + " -o " + path("s.png") + " --size 40x30 --aa none");
    EXPECT_EQ(r.code, 0) << e.path() << ": " << r.err;
  }
}

TEST_F(Cli, TraceWritesAValidTraceThatTraceInfoReads) {
  std::string mesh = octahedron();
  Outcome r = run("trace " + mesh + " --ray -3,0.1,0.2,1,0,0 -o " + path("t.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::string text = slurp(path("t.json"));
  EXPECT_EQ(text.rfind("{\n \"format\": \"raystep-trace\",\n \"version\": 4,", 0), 0u) << text.substr(0, 80);
  EXPECT_NE(text.find("\"type\":\"cell\""), std::string::npos);
  EXPECT_NE(text.find("\"type\":\"hit_accepted\""), std::string::npos);
  Outcome info = run("trace-info " + path("t.json"));
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("valid raystep trace"), std::string::npos);
  EXPECT_NE(info.out.find("hit primitive"), std::string::npos) << info.out;
  // CSV: a header and one row per event.
  ASSERT_EQ(run("trace " + mesh + " --ray -3,0.1,0.2,1,0,0 --format csv -o " + path("t.csv")).code, 0);
  EXPECT_EQ(slurp(path("t.csv")).rfind("ray,seq,type,i,j,k,", 0), 0u);
}

TEST_F(Cli, TraceOfAPixelWithSecondaryRays) {
  std::string scene = write("mirror.json",
                            "{\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0]},\n"
                            " \"materials\": {\"mirror\": {\"diffuse\": 0.5, \"mirror\": 0.5}},\n"
                            " \"objects\": [{\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1,"
                            " \"material\": \"mirror\"}],\n"
                            " \"render\": {\"size\": [20, 20]}}\n");
  Outcome r = run("trace " + scene + " --pixel 10,10 --secondary -o " + path("t.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::string text = slurp(path("t.json"));
  EXPECT_NE(text.find("\"kind\":\"primary\""), std::string::npos);
  EXPECT_NE(text.find("\"kind\":\"shadow\""), std::string::npos);
  EXPECT_NE(text.find("\"kind\":\"reflected\""), std::string::npos);
  EXPECT_NE(text.find("\"pixel\":[10,10]"), std::string::npos);
}

TEST_F(Cli, TraceRejectsBadRequests) {
  std::string mesh = octahedron();
  std::string out = path("t.json");
  expect_error(run("trace " + mesh + " -o " + out), "trace: give --pixel");
  expect_error(run("trace " + mesh + " --ray 1,2,3 -o " + out), "--ray");
  expect_error(run("trace " + mesh + " --ray 0,0,0,0,0,0 -o " + out), "--ray");
  expect_error(run("trace " + mesh + " --pixel 5000,1 -o " + out), "--pixel");
  expect_error(run("trace " + mesh + " --accel bvol --ray 0,0,-3,0,0,1 -o " + out), "trace: --accel bvol");
  expect_error(run("trace " + mesh + " --ray 0,0,-3,0,0,1 --grid-res 0,1,1 -o " + out), "--grid-res");
  expect_error(run("trace " + mesh + " --ray 0,0,-3,0,0,1 --grid-insert maybe -o " + out), "");
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, MalformedTracesExitTwoWithFileAndLine) {
  std::string mesh = octahedron();
  ASSERT_EQ(run("trace " + mesh + " --ray -3,0.1,0.2,1,0,0 -o " + path("t.json")).code, 0);
  std::string text = slurp(path("t.json"));
  std::string cut = write("cut.json", text.substr(0, text.size() / 2));
  expect_error(run("trace-info " + cut), cut + ":");
  std::string bad = text;
  size_t at = bad.find("\"type\":\"cell\"");
  bad.replace(at, 13, "\"type\":\"warp\"");
  std::string line = std::to_string(1 + std::count(bad.begin(), bad.begin() + at, '\n'));
  std::string unknown = write("unknown.json", bad);
  Outcome r = run("trace-info " + unknown);
  expect_error(r, unknown + ":" + line + ":");
  EXPECT_NE(r.err.find("unknown event type \"warp\""), std::string::npos) << r.err;
  expect_error(run("trace-info " + path("missing.json")), path("missing.json"));
  // Not a regular file: a directory, a FIFO (which would block), a device (which would never end).
  expect_error(run("trace-info " + dir_.string()),
               dir_.string() + ": cannot read the file: not a regular file");
  ASSERT_EQ(::mkfifo(path("fifo.json").c_str(), 0600), 0);
  expect_error(run("trace-info " + path("fifo.json")),
               path("fifo.json") + ": cannot read the file: not a regular file");
  expect_error(run("trace-info /dev/zero"), "/dev/zero: cannot read the file: not a regular file");
}

// A ray that misses the kd-tree's root box enters no node; its trace still lists the (empty) nodes.
TEST_F(Cli, KdTraceOfAMissListsNoNodes) {
  std::string mesh = octahedron();
  ASSERT_EQ(run("trace " + mesh + " --accel kd --ray -3,5,0,1,0,0 -o " + path("t.json")).code, 0);
  std::string text = slurp(path("t.json"));
  EXPECT_NE(text.find("\"nodes\": []"), std::string::npos) << text;
  EXPECT_EQ(run("trace-info " + path("t.json")).code, 0);
}

TEST_F(Cli, HeatMapAndGridOptions) {
  std::string mesh = octahedron();
  Outcome r = run("render " + mesh + " --heatmap tests --size 24x16 -o " + path("heat.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("heat.png")));
  EXPECT_NE(r.out.find("scale: 0"), std::string::npos) << r.out;
  ASSERT_EQ(run("rays " + mesh + " --kind random --count 3000 -o " + path("r.rays")).code, 0);
  ASSERT_EQ(
      run("cast " + mesh + " --rays " + path("r.rays") + " --hits " + path("b.hits") + " --accel brute").code,
      0);
  for (const char* opts : {"--grid-res 4,4,4", "--grid-res 1,7,2 --grid-insert bbox", "--grid-density 0.5"}) {
    Outcome c = run("cast " + mesh + " --rays " + path("r.rays") + " --hits " + path("g.hits") +
                    " --accel grid " + opts);
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_EQ(slurp(path("g.hits")), slurp(path("b.hits"))) << opts;
  }
}

// Rows of a CSV file as fields (no quoting: raystep's CSVs have none).
std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::stringstream ss(line);
    std::string f;
    while (std::getline(ss, f, ',')) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

TEST_F(Cli, KdTreesCastLikeBruteForce) {
  std::string scene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/torus_knot.json";
  ASSERT_EQ(run("rays " + scene + " --kind random --count 5000 --seed 5 -o " + path("r.rays")).code, 0);
  ASSERT_EQ(
      run("cast " + scene + " --rays " + path("r.rays") + " --hits " + path("b.hits") + " --accel brute")
          .code,
      0);
  for (const char* opts : {"--accel kd", "--accel kd-median", "--accel kd --mailbox off --leaf-size 4",
                           "--accel kd --ti 10 --tt 2 --empty-bonus 0.5 --max-depth 12"}) {
    Outcome c = run("cast " + scene + " --rays " + path("r.rays") + " --hits " + path("k.hits") + " " + opts);
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_NE(c.out.find(std::string("accel=") +
                         (std::string(opts).find("median") != std::string::npos ? "kd-median" : "kd ")),
              std::string::npos)
        << c.out;
    EXPECT_EQ(slurp(path("k.hits")), slurp(path("b.hits"))) << opts;
  }
}

TEST_F(Cli, SahCurveFollowsTheLecturesFormula) {
  std::string scene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json";
  for (const char* node : {"--node 0", "--path L", "--path RL"}) {
    Outcome r = run("sah " + scene + " " + node + " --ti 80 --tt 1 --empty-bonus 0 -o " + path("c.csv"));
    ASSERT_EQ(r.code, 0) << r.err;
    auto rows = csv_rows(slurp(path("c.csv")));
    ASSERT_GT(rows.size(), 2u) << node;
    std::string header =
        "axis,position,n_below,n_above,n_planar,area_below,area_above,area_node,cost,chosen\n";
    EXPECT_EQ(slurp(path("c.csv")).substr(0, header.size()), header);
    int chosen = -1;
    double min_cost = 1e30;
    std::set<std::string> axes;
    for (size_t i = 1; i < rows.size(); ++i) {
      const auto& f = rows[i];
      ASSERT_EQ(f.size(), 10u);
      axes.insert(f[0]);
      double nb = std::stod(f[2]), na = std::stod(f[3]), ab = std::stod(f[5]), aa = std::stod(f[6]),
             an = std::stod(f[7]), cost = std::stod(f[8]);
      // C = t_t + p_a N_a t_i + p_b N_b t_i with p = S_child / S_node.
      EXPECT_NEAR(cost, 1.0 + 80.0 * (ab / an * nb + aa / an * na), 1e-4 * cost) << node << " row " << i;
      min_cost = std::min(min_cost, cost);
      if (f[9] == "1") {
        EXPECT_EQ(chosen, -1) << "one chosen row";
        chosen = int(i);
      }
    }
    ASSERT_GT(chosen, 0) << node << ": an inner node has its chosen split";
    EXPECT_EQ(std::stod(rows[size_t(chosen)][8]), min_cost) << node;
    EXPECT_GE(axes.size(), 2u) << node << ": candidates on several axes";
  }
  // A node that stays a leaf: no row chosen, every candidate at least N t_i.
  Outcome leaf = run("sah " + scene + " --node 0 --ti 0.01 --empty-bonus 0 -o " + path("leaf.csv"));
  ASSERT_EQ(leaf.code, 0) << leaf.err;
  EXPECT_NE(leaf.out.find("decision: leaf"), std::string::npos) << leaf.out;
  auto rows = csv_rows(slurp(path("leaf.csv")));
  ASSERT_GT(rows.size(), 2u);
  for (size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][9], "0");
    EXPECT_GE(std::stod(rows[i][8]), 23 * 0.01);
  }
  ASSERT_EQ(run("sah " + scene + " --path L -o " + path("c.json")).code, 0);
  EXPECT_NE(slurp(path("c.json")).find("\"candidates\""), std::string::npos);
}

TEST_F(Cli, SahAndKdOptionsRejectBadInput) {
  std::string scene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json";
  expect_error(run("sah " + scene + " --node 100000 -o " + path("c.csv")), "--node 100000");
  expect_error(run("sah " + scene + " --path LXR -o " + path("c.csv")), "--path");
  expect_error(run("sah " + scene + " --path LLLLLLLLLLLLLLLLLLLL -o " + path("c.csv")), "--path");
  expect_error(run("sah " + scene + " --node 0 -o " + path("c.txt")), path("c.txt"));
  expect_error(run("sah " + scene + " --node 0 --ti -1 -o " + path("c.csv")), "kd-tree");
  expect_error(run("sah " + scene + " --node 0 --empty-bonus 1 -o " + path("c.csv")), "kd-tree");
  expect_error(run("trace " + scene + " --accel kd --pixel 1,1 --max-depth 99 -o " + path("t.json")),
               "kd-tree");
  expect_error(run("trace " + scene + " --accel grid --pixel 1,1 --build-events -o " + path("t.json")),
               "trace: --build-events");
  EXPECT_FALSE(fs::exists(path("c.csv")));
  EXPECT_FALSE(fs::exists(path("t.json")));
}

TEST_F(Cli, KdTreeStatsPredictsEntryProbabilities) {
  std::string scene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/torus_knot.json";
  Outcome r = run("kdtree-stats " + scene + " --lines 20000 --csv " + path("n.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* key : {"nodes:", "depth: max", "primitives per non-empty leaf", "references per primitive",
                          "SAH cost of the tree", "(root)", "leaves by primitive count:", "leaves by depth:",
                          "measured, ", "primitive tests"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
  auto rows = csv_rows(slurp(path("n.csv")));
  ASSERT_GT(rows.size(), 10u);
  EXPECT_EQ(rows[0].size(), 8u);
  // The root is entered by every line; a child's measured fraction is near S_child / S_root (Crofton).
  EXPECT_EQ(rows[1][5], "1");
  EXPECT_EQ(rows[1][6], "1");
  for (size_t i = 2; i < std::min<size_t>(rows.size(), 8); ++i)
    EXPECT_NEAR(std::stod(rows[i][6]), std::stod(rows[i][5]), 0.02) << "node " << rows[i][0];
}

TEST_F(Cli, KdTraceWithBuildEvents) {
  std::string scene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json";
  Outcome r =
      run("trace " + scene + " --accel kd --pixel 100,80 --secondary --build-events -o " + path("t.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::string text = slurp(path("t.json"));
  for (const char* key :
       {"\"build\": [", "\"type\":\"sah_candidate\"", "\"type\":\"split\"", "\"type\":\"leaf_made\"",
        "\"kind\":\"kd\"", "\"nodes\": [", "\"type\":\"push\"", "\"type\":\"leaf\""})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  Outcome info = run("trace-info " + path("t.json"));
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("build: "), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("pushes"), std::string::npos) << info.out;
  // A trace whose events name a node the geometry does not list is refused.
  size_t at = text.find("\"nodes\": [");
  std::string broken = text.substr(0, at) + "\"nodes\": [],\n  \"unused\": [" + text.substr(at + 10);
  expect_error(run("trace-info " + write("broken.json", broken)), path("broken.json") + ":");
}

}  // namespace

// `raystep lesson`: a good lesson checks; a damaged one gives one line naming the file and the setting's
// line.
class LessonCli : public Cli {
 protected:
  std::string lesson(const std::string& name, const std::string& block, const std::string& more = "") const {
    return write(name, "# A lesson\n\nIntro.\n\n## One\n\nText.\n\n```raystep\nscene: " +
                           std::string(RAYSTEP_SOURCE_DIR) +
                           "/scenes/cornell.json\npixel: 160,200\nstep-to: cell:1\n" + block +
                           "```\n\n## Two\n\n```raystep\n" + "ask: dda-axis\n```\n" + more);
  }
};

TEST_F(LessonCli, CheckPassesAGoodLesson) {
  std::string file = lesson("good.md", "");
  Outcome r = run("lesson check " + file);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, file + ": 2 steps, 1 question, 0 numbers: ok\n");
  EXPECT_EQ(r.err, "");
  // A folder: its lessons in name order.
  lesson("another.md", "", "## Three\n\n```raystep\naccel: kd\nstep-to: node:1\nask: first-child\n```\n");
  std::remove(file.c_str());
  r = run("lesson check " + dir_.string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, path("another.md") + ": 3 steps, 2 questions, 0 numbers: ok\n");
}

TEST_F(LessonCli, CheckReportsTheLineOfTheDamage) {
  const std::string src = RAYSTEP_SOURCE_DIR;
  expect_error(run("lesson check " + lesson("unknown.md", "colour: red\n")),
               path("unknown.md") + ":13: unknown setting 'colour' (known: scene, accel,");
  expect_error(run("lesson check " + lesson("pixel.md", "pixel: 3,x\n")),
               path("pixel.md") + ":13: pixel '3,x': expected X,Y whole numbers >= 0, or none");
  expect_error(run("lesson check " + lesson("outside.md", "pixel: 999,3\n")),
               path("outside.md") + ":13: step 'One': pixel 999,3: outside the 320x320 picture");
  expect_error(
      run("lesson check " + lesson("apply.md", "accel: kd\nstep-to: node:1\n")),
      path("apply.md") + ":20: step 'Two': dda-axis: the ray walks a kd-tree, not a grid (accel: grid)");
  expect_error(
      run("lesson check " + write("noscene.md", "# T\n\n## S\n\n```raystep\nscene: missing.json\n```\n")),
      path("noscene.md") + ":6: scene 'missing.json': no such file (" + path("missing.json") + ")");
  expect_error(run("lesson check " + write("fence.md", "# T\n\n## S\n\n```raystep\nscene: x.json\n")),
               path("fence.md") + ":5: unclosed code fence ```raystep");
  // The first failure ends the check: the good lesson before it was reported, nothing after it.
  std::string good = lesson("a.md", "");
  Outcome r = run("lesson check " + good + " " + path("pixel.md") + " " + good);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.out, good + ": 2 steps, 1 question, 0 numbers: ok\n");
  expect_error(r, path("pixel.md") + ":13: ");
  expect_error(run("lesson check " + path("none.md")), path("none.md") + ": no such lesson file or folder");
}

// A shipped lesson's numbers: a copy checks as the lesson does, and a number edited in the copy fails the check
// at its line; `lesson numbers` lists each number with the value the tool computes (the adaptive bound 145).
TEST_F(LessonCli, AnEditedNumberFailsTheCheck) {
  std::ifstream in(std::string(RAYSTEP_SOURCE_DIR) + "/lessons/04-adaptive-sampling.md", std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (size_t at = text.find("../scenes/"); at != std::string::npos; at = text.find("../scenes/", at))
    text.replace(at, 10, std::string(RAYSTEP_SOURCE_DIR) + "/scenes/");
  const std::string copy = write("copy.md", text);
  Outcome r = run("lesson check " + copy);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find(": 10 steps, 5 questions, "), std::string::npos) << r.out;
  r = run("lesson numbers " + copy);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("{{(2^aa.depth + 1)^2 + 4^aa.depth}}  value 145  shown 145  filled"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("{{pixel.squares = 37}}  value 37  shown 37  agrees"), std::string::npos) << r.out;

  const size_t at = text.find("{{pixel.squares = 37}}");
  ASSERT_NE(at, std::string::npos);
  const int line = 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
  std::string edited = text;
  edited.replace(at, 22, "{{pixel.squares = 36}}");
  const std::string bad = write("edited.md", edited);
  expect_error(run("lesson check " + bad),
               bad + ":" + std::to_string(line) +
                   ": step 'The depth limit': {{pixel.squares = 36}}: the text says 36, the tool computes 37");
  r = run("lesson numbers " + bad);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("{{pixel.squares = 36}}  value 37  shown 36  DISAGREES"), std::string::npos) << r.out;
}

TEST_F(LessonCli, CommandPrintsTheStepsGuiArguments) {
  std::string file =
      lesson("good.md", "accel: kd\nzoom: 8\n", "## Three\n\n```raystep\nnode-path: LR\n```\n");
  Outcome r = run("lesson command " + file + " 3");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "raystep-gui " + std::string(RAYSTEP_SOURCE_DIR) +
                "/scenes/cornell.json --accel kd --pixel 160,200 --step-to cell:1 --node-path LR --zoom 8\n");
  expect_error(run("lesson command " + file + " 0"), file + ": step 0: the lesson has 3 steps (1..3)");
  expect_error(run("lesson command " + file + " 4"), file + ": step 4: the lesson has 3 steps (1..3)");
  EXPECT_EQ(run("lesson command " + file + " two").code, 2);
  // A path with a space is quoted for the shell.
  fs::create_directories(dir_ / "my lessons");
  std::string spaced = write(
      "my lessons/x.md",
      "# T\n## S\n```raystep\nscene: " +
          fs::relative(fs::path(RAYSTEP_SOURCE_DIR) / "scenes/cornell.json", dir_ / "my lessons").string() +
          "\n```\n");
  r = run("lesson command '" + spaced + "' 1");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST_F(LessonCli, AnswersPrintsEachQuestion) {
  Outcome r = run("lesson answers " + lesson("good.md", ""));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("step 2 'Two' (dda-axis, line 18): ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\n  tMax = ("), std::string::npos) << r.out;
}

// Bounding volume hierarchies (trace format version 3): `raystep trace --accel bvh` writes a trace with box
// tests and the nodes' children that `trace-info` reads back; the CSV has the parent column; the boxes heat
// map; lesson steps on a BVH.
TEST_F(Cli, TraceThroughABvhReadsBackWithTraceInfo) {
  const std::string cornell = scene("cornell.json");
  for (const char* accel : {"bvh", "bvh-median"}) {
    SCOPED_TRACE(accel);
    Outcome r = run("trace " + cornell + " --accel " + accel + " --bvh-order axis --pixel 160,200 -o " +
                    path("b.json"));
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string text = slurp(path("b.json"));
    EXPECT_NE(text.find("\"kind\":\"" + std::string(accel) + "\""), std::string::npos);
    EXPECT_NE(text.find("\"order\":\"split_axis\""), std::string::npos);
    EXPECT_NE(text.find("\"type\":\"box_test\",\"parent\":-1,\"node\":0,\"depth\":0,\"hit\":true"),
              std::string::npos);
    EXPECT_NE(text.find("\"children\":[1,"), std::string::npos);
    Outcome info = run("trace-info " + path("b.json"));
    ASSERT_EQ(info.code, 0) << info.err;
    EXPECT_NE(info.out.find("valid raystep trace, version 4"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find(" box tests, "), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("hit primitive"), std::string::npos) << info.out;
  }
  // The wide BVH: its nodes have no split axis.
  for (const char* accel : {"bvh4", "bvh8"}) {
    ASSERT_EQ(run("trace " + cornell + " --accel " + accel + " --pixel 160,200 -o " + path("w.json")).code,
              0);
    EXPECT_NE(slurp(path("w.json")).find("\"axis\":null,\"children\":["), std::string::npos);
    Outcome info = run("trace-info " + path("w.json"));
    ASSERT_EQ(info.code, 0) << info.err;
    EXPECT_NE(info.out.find("structure " + std::string(accel)), std::string::npos) << info.out;
  }
  // An anti-aliased pixel's samples, each ray through the BVH.
  ASSERT_EQ(run("trace " + cornell + " --accel bvh --pixel 160,200 --aa jitter:2 -o " + path("p.json")).code,
            0);
  EXPECT_EQ(run("trace-info " + path("p.json")).code, 0);
  // CSV: the box tests' parent in the last column.
  ASSERT_EQ(run("trace " + cornell + " --accel bvh --pixel 160,200 --format csv -o " + path("b.csv")).code,
            0);
  const std::string csv = slurp(path("b.csv"));
  EXPECT_EQ(csv.substr(0, csv.find('\n')).substr(csv.find('\n') - 7), ",parent");
  EXPECT_NE(csv.find(",box_test,"), std::string::npos);
  // A damaged trace: one line, exit code 2.
  std::string bad = slurp(path("b.json"));
  bad.replace(bad.find("\"parent\":-1,\"node\":0"), 20, "\"parent\":-1,\"node\":1");
  const std::string bad_path = write("bad.json", bad);
  expect_error(run("trace-info " + bad_path), bad_path + ":");
  // Heat maps of box tests.
  Outcome heat = run("render " + cornell + " --accel bvh --heatmap boxes --size 40x40 -o " + path("h.png"));
  ASSERT_EQ(heat.code, 0) << heat.err;
  EXPECT_NE(heat.out.find("bounding-box tests"), std::string::npos) << heat.out;
  expect_error(run("render " + cornell + " --heatmap box --size 40x40 -o " + path("h.png")), "--heatmap");
}
