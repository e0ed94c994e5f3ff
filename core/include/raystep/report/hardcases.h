// The hard-case report: every structure on the hard-case battery (report/hardcase_battery.h), judged by the
// double-precision brute-force reference (report/hardcase_reference.h). Per structure and family: rays,
// leaks (a miss where a hit is certain), disagreements with the reference (hit or miss, or a primitive that
// is not one of the nearest ties; an any-hit query that disagrees counts too), crashes and time. Each
// structure runs in a child process (POSIX fork) so that a crash or a hang is counted, not fatal: a signal,
// a non-zero exit or the time limit counts as a crash of the family it was in, and the next family starts
// in a fresh child. `raystep hardcases` prints and writes it.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/report/hardcase_battery.h"

namespace raystep {

struct HardCaseRow {
  std::string structure;
  HardCaseFamily family = HardCaseFamily::inside;
  uint64_t rays = 0;
  uint64_t leaks = 0;
  uint64_t disagreements = 0;
  uint64_t crashes = 0;
  double ms = 0.0;          // building the family's geometries and tracing its rays (twice: nearest, any hit)
  std::string first_issue;  // the first leak, disagreement or crash: set, ray index, what
};

struct HardCaseReport {
  std::string mesh;  // the mesh file, or "built-in"
  std::string note;  // families skipped and why
  std::vector<std::string> structures;
  uint64_t sets = 0, reference_rays = 0;
  double reference_ms = 0.0;
  std::vector<HardCaseRow> rows;  // structure-major, the families present in the battery in enum order
  uint64_t leaks() const;
  uint64_t disagreements() const;
  uint64_t crashes() const;
  bool clean() const { return leaks() == 0 && disagreements() == 0 && crashes() == 0; }
};

// Makes a structure by name (tests plant broken ones); the default is make_accelerator.
using StructureFactory = std::function<std::unique_ptr<Accelerator>(const std::string&)>;

struct HardCaseRunOptions {
  std::vector<std::string> structures;  // empty: the default list below
  double time_limit_seconds = 300.0;    // per child (one structure, the families not yet run): then a crash
  bool isolate = true;                  // fork a child per structure; false: in this process (no crash count)
  StructureFactory factory;             // empty: make_accelerator
};

// brute, grid, kd, bvh, bvh-sbvh, bvh4, bvh8, bvh8-sbvh, octree, bsp (accelerator_names() has the variants too).
std::vector<std::string> default_hardcase_structures();

// Throws InputError("", 0, ...) for an unknown structure name.
HardCaseReport run_hardcases(const std::vector<HardCaseSet>& battery, const HardCaseRunOptions& options);

// A table (structure x family: rays, leaks, disagreements, crashes, ms), the first issues, and a verdict
// line.
std::string hardcases_table(const HardCaseReport& report);
std::string hardcases_verdict(const HardCaseReport& report);
std::string hardcases_csv(const HardCaseReport& report);
std::string hardcases_json(const HardCaseReport& report);

}  // namespace raystep
