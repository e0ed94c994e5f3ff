// `raystep hardcases [MESH]`: the hard-case battery (core/report/hardcases.h) for every structure, as a
// table, a verdict line and an optional CSV or JSON file. Exit 0 when there are no leaks, disagreements or
// crashes, 1 when there is any, 2 on bad input (see commands.h).
#include <cstdio>
#include <ostream>

#include "commands.h"
#include "raystep/io/obj.h"
#include "raystep/report/hardcases.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep::cli {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= list.size()) {
    size_t comma = list.find(',', start);
    if (comma == std::string::npos) comma = list.size();
    if (comma > start) out.push_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

}  // namespace

int run_hardcases(const HardCasesArgs& args) {
  // Check the output's kind before any work, so that a long run never ends in a refusal.
  const bool json = ends_with(args.output, ".json");
  if (!args.output.empty() && !json && !ends_with(args.output, ".csv"))
    throw InputError(args.output, 0, "hardcases: the report file must end in .csv or .json");
  if (args.rays > 65536) throw InputError("", 0, "hardcases: --rays must be at most 65536");
  if (args.time_limit < 1.0 || args.time_limit > 86400.0)
    throw InputError("", 0, "hardcases: --time-limit must be in 1..86400 seconds");

  HardCaseRunOptions run;
  if (args.accel == "all")
    run.structures = accelerator_names();
  else if (!args.accel.empty())
    run.structures = split_list(args.accel);
  if (!args.accel.empty() && run.structures.empty())
    throw InputError("", 0, "hardcases: --accel lists no structure");
  run.time_limit_seconds = args.time_limit;

  HardCaseOptions options;
  options.mesh_rays = size_t(args.rays);
  options.seed = args.seed;
  TriangleMesh mesh;
  if (!args.mesh.empty()) mesh = load_obj(args.mesh);  // InputError naming the file and line
  std::string note;
  const std::vector<HardCaseSet> battery =
      hardcase_battery(args.mesh.empty() ? nullptr : &mesh, options, &note);

  HardCaseReport report = run_hardcases(battery, run);
  report.mesh = args.mesh.empty() ? "built-in" : args.mesh;
  report.note = note;
  std::printf("hard cases: %s, %llu geometries; reference (double brute force) %llu rays in %.0f ms\n",
              report.mesh.c_str(), (unsigned long long)report.sets, (unsigned long long)report.reference_rays,
              report.reference_ms);
  if (!note.empty()) std::printf("note: %s\n", note.c_str());
  std::fputs(hardcases_table(report).c_str(), stdout);
  std::printf("%s\n", hardcases_verdict(report).c_str());
  if (!args.output.empty()) {
    write_file_atomically(args.output, [&](std::ostream& out) {
      out << (json ? hardcases_json(report) : hardcases_csv(report));
    });
    std::printf("wrote %s\n", args.output.c_str());
  }
  return report.clean() ? 0 : 1;
}

}  // namespace raystep::cli
