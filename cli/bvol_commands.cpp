// `raystep bvol-report`: the kinds of bounding volumes side by side on each scene's camera rays, as a CSV
// file and a Markdown table (see commands.h and core/report/bvol_report.h).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <ostream>

#include "commands.h"
#include "raystep/report/bvol_report.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep::cli {

namespace fs = std::filesystem;

int run_bvol_report(const BvolReportArgs& args) {
  BvolReportOptions options;
  options.reps = args.reps;
  if (args.size) parse_size(*args.size, &options.camera_width, &options.camera_height);
  std::vector<std::string> scenes = args.scenes;
  if (scenes.empty()) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator("scenes", ec))
      if (e.path().extension() == ".json") scenes.push_back(e.path().string());
    std::sort(scenes.begin(), scenes.end());
    if (scenes.empty()) throw InputError("", 0, "bvol-report: no scenes given and no scenes/*.json here");
  }
  if (options.reps < 1 || options.reps > 100)
    throw InputError("", 0, "bvol-report: --reps must be in 1..100");

  std::vector<BvolReportRow> rows;
  for (const std::string& path : scenes) {
    const Scene scene = load_scene(path);
    std::vector<BvolReportRow> r = run_bvol_report(scene, options);
    rows.insert(rows.end(), r.begin(), r.end());
  }
  const std::string table = bvol_report_markdown(rows);
  std::fputs(table.c_str(), stdout);
  if (!args.output.empty()) {
    std::error_code ec;
    fs::create_directories(args.output, ec);
    if (ec) throw InputError(args.output, 0, "cannot create the report folder: " + ec.message());
    const std::string csv_path = (fs::path(args.output) / "bvol_report.csv").string();
    const std::string md_path = (fs::path(args.output) / "bvol_report.md").string();
    write_file_atomically(csv_path, [&](std::ostream& out) { out << bvol_report_csv(rows); });
    write_file_atomically(md_path, [&](std::ostream& out) { out << table; });
    std::printf("wrote %s and %s\n", csv_path.c_str(), md_path.c_str());
  }
  return 0;
}

}  // namespace raystep::cli
