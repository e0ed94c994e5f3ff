// `raystep export-html`: a trace, a 2D scene's ray through a structure or a lesson as one self-contained page
// that steps through the walk in a browser (web/include/raystep/web/player_page.h, lesson_page.h), and a
// folder of lessons as a small site with an index.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "commands.h"
#include "output_folder.h"
#include "raystep/accel/plane_outline.h"
#include "raystep/io/scene_loader.h"
#include "raystep/lesson/lesson.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"
#include "raystep/web/lesson_page.h"
#include "raystep/web/player_page.h"

namespace raystep::cli {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// A trace names its format near its start ("format": "raystep-trace"); a scene does not.
bool looks_like_trace(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the file");
  std::string head(4096, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  return head.find("\"raystep-trace\"") != std::string::npos;
}

std::string file_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

// A folder of lessons: a page each and an index, in a folder written atomically.
int export_lesson_site(const ExportHtmlArgs& a) {
  const std::vector<std::string> files = lesson_files(a.input);
  if (files.empty()) throw InputError(a.input, 0, "no lessons (*.md) in the folder");
  std::vector<Lesson> lessons;
  for (const std::string& f : files)
    lessons.push_back(parse_lesson(f));  // every one parses before any is built
  ReportFolder site(a.output);
  std::vector<std::pair<std::string, std::string>> index;
  for (const Lesson& lesson : lessons) {
    std::string name = file_name(lesson.path);
    name = name.substr(0, name.size() - 3) + ".html";
    const std::string page = web::lesson_page(lesson, a.width);
    write_file_atomically(site.file(name), [&](std::ostream& out) { out << page; });
    index.push_back({lesson.title, name});
    std::printf("  %s (%.1f KiB)\n", name.c_str(), double(page.size()) / 1024.0);
  }
  const std::string html = web::lesson_site_index(a.title.value_or("raystep lessons"), index);
  write_file_atomically(site.file("index.html"), [&](std::ostream& out) { out << html; });
  site.commit();
  std::printf("wrote %s (%zu lessons and index.html)\n", a.output.c_str(), lessons.size());
  return 0;
}

int run_export_html(const ExportHtmlArgs& a) {
  if (std::filesystem::is_directory(a.input)) {
    if (a.ray) throw InputError("", 0, "export-html: --ray draws a 2D scene's ray; a lesson has its own");
    return export_lesson_site(a);
  }
  if (!ends_with(a.output, ".html") && !ends_with(a.output, ".htm"))
    throw InputError(
        "", 0,
        "export-html: -o " + a.output + ": the page is written as .html (a folder of lessons: a folder)");
  check_output_folder(a.output);
  if (ends_with(a.input, ".md")) {  // a lesson
    if (a.ray) throw InputError("", 0, "export-html: --ray draws a 2D scene's ray; a lesson has its own");
    const Lesson lesson = parse_lesson(a.input);
    const std::string page = web::lesson_page(lesson, a.width);
    write_file_atomically(a.output, [&](std::ostream& out) { out << page; });
    std::printf("wrote %s (%zu steps, %.1f KiB)\n", a.output.c_str(), lesson.steps.size(),
                double(page.size()) / 1024.0);
    return 0;
  }
  web::PlayerInput in;
  in.source = a.input;
  in.picture_width = a.width;
  MultiTrace trace;
  Scene scene;
  std::unique_ptr<Accelerator> accel;
  PlaneOutline outline;
  if (looks_like_trace(a.input)) {
    if (a.ray) throw InputError("", 0, "export-html: --ray draws a 2D scene's ray; a trace has its rays");
    trace = read_any_trace_json(a.input);
    // The trace's scene under its walk in the page's 3D view, where it can be found (as named, or beside the
    // trace); without it the boxes and the ray alone.
    for (const std::string& candidate :
         {trace.scene_path, (std::filesystem::path(a.input).parent_path() / trace.scene_path).string()}) {
      if (trace.scene_path.empty() || !std::filesystem::is_regular_file(candidate)) continue;
      try {
        scene = load_scene(candidate);
        if (!scene.flat) in.scene3d = &scene;
      } catch (const InputError&) {
        // a scene changed since the trace: the walk without it
      }
      break;
    }
    std::string kinds;
    for (const Trace& t : trace.walks) kinds += (kinds.empty() ? "" : ", ") + t.structure.kind;
    std::string title = kinds + (trace.walks.size() > 1 ? " walks" : " walk");
    if (!trace.scene_path.empty()) title += " through " + file_name(trace.scene_path);
    const Trace& first = trace.walks.front();
    if (!first.rays.empty() && first.rays[0].has_pixel)
      title += ", pixel (" + std::to_string(first.rays[0].pixel[0]) + ", " +
               std::to_string(first.rays[0].pixel[1]) + ")";
    in.title = a.title.value_or(title);
  } else {
    scene = load_scene(a.input);
    if (!scene.flat)
      throw InputError(
          a.input, 0,
          "a 3D scene: export-html plays a trace (raystep trace ... -o walk.json) or a 2D scene's ray");
    accel = build_structure(a.structure);
    TraceArgs ray_args;
    ray_args.ray = a.ray;
    const RayRequest request = trace_ray_by_hand(ray_args, scene);
    check_build_memory(a.input, a.structure.accel, scene.geometry.size());
    accel->build(scene.geometry);
    trace.walks.push_back(
        record_trace(scene.geometry, *accel, {request}, a.input, file_content_hash(a.input)));
    in.flat_scene = &scene;
    if (has_plane_outline(*accel)) {
      outline = plane_outline(*accel);
      in.outlines = {&outline};
    }
    in.title = a.title.value_or(accel->name() + " walk in the plane: " + file_name(a.input));
  }
  in.trace = &trace;
  const std::string page = web::player_page(in);
  write_file_atomically(a.output, [&](std::ostream& out) { out << page; });
  size_t events = 0;
  for (const Trace& t : trace.walks)
    for (const TracedRay& r : t.rays) events += r.events.size();
  std::printf("wrote %s (%zu events, %.1f KiB)\n", a.output.c_str(), events, double(page.size()) / 1024.0);
  return 0;
}

}  // namespace raystep::cli
