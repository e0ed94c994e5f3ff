#include "raystep/web/lesson_page.h"

#include <cmark.h>

#include <cstdlib>
#include <map>
#include <memory>

#include "player_data.h"
#include "step_figure.h"
#include "raystep/lesson/lesson_runner.h"
#include "raystep/lesson/question.h"
#include "raystep/replay/octree_choice.h"
#include "raystep/replay/replayer.h"
#include "raystep/trace/node_path.h"
#include "raystep/util/error.h"
#include "raystep/util/xml_escape.h"

namespace raystep::web {

namespace {


// The predictions a student can click for the question: every form the kind accepts that the step makes
// sensible (the cells beside the current one, the nodes on the stack, the axes, ...), labels beside the
// forms.
std::vector<std::pair<std::string, std::string>> choices(const Answer& a, const StepWorld& w) {
  std::vector<std::pair<std::string, std::string>> out;  // (form, label)
  auto plain = [&](std::initializer_list<const char*> forms) {
    for (const char* f : forms) out.push_back({f, f});
  };
  const bool flat = w.scene && w.scene->flat;
  auto axes_and = [&](const char* last) {  // the plane's or the space's axes, then one more answer
    for (const char* axis : {"x", "y", "z"})
      if (!flat || axis[0] != 'z') out.push_back({axis, axis});
    out.push_back({last, last});
  };
  std::optional<replay::ReplayState> state;
  if (w.trace && w.ray >= 0 && size_t(w.ray) < w.trace->rays.size())
    state = replay::Replayer(w.trace->rays[size_t(w.ray)]).at(w.step);
  switch (a.kind) {
    case QuestionKind::dda_axis:
      axes_and("none");
      break;
    case QuestionKind::first_child:
    case QuestionKind::next_cell:
      if (a.walk == "octree") {
        for (int o = 0; o < 1 << a.axes; ++o)
          out.push_back({replay::octant_name(o, a.axes), replay::octant_name(o, a.axes)});
        if (a.kind == QuestionKind::next_cell) plain({"stop"});
      } else if (a.kind == QuestionKind::first_child) {
        plain({"below", "above"});
      } else if (state && state->cell_event >= 0) {
        const Event& c = w.trace->rays[size_t(w.ray)].events[size_t(state->cell_event)];
        for (int axis = 0; axis < (flat ? 2 : 3); ++axis)
          for (int d : {-1, 1}) {
            int cell[3] = {c.cell[0], c.cell[1], c.cell[2]};
            cell[axis] += d;
            const std::string f =
                std::to_string(cell[0]) + "," + std::to_string(cell[1]) + "," + std::to_string(cell[2]);
            out.push_back({f, "(" + f + ")"});
          }
        plain({"stop"});
      }
      break;
    case QuestionKind::next_pop:
      if (state)
        for (size_t i = state->stack.size(); i-- > 0;) {
          const int32_t id = state->stack[i].node;
          const std::string path = trace_node_path_text(*w.trace, id);
          out.push_back(
              {std::to_string(id), "node " + std::to_string(id) + (path.empty() ? "" : " (" + path + ")")});
        }
      plain({"stop"});
      break;
    case QuestionKind::sah_plane:
      axes_and("leaf");
      break;
    case QuestionKind::subdivide:
      plain({"yes", "no"});
      break;
    case QuestionKind::bvol_kind:
      plain({"box", "sphere", "14-dop", "oriented box"});
      break;
  }
  return out;
}

ordered question_json(const LessonStep& step, const StepWorld& w) {
  const Answer& a = *w.answer;
  ordered q;
  q["prompt"] = question_prompt(*step.ask, question_walk(w.context()));
  q["answer"] = a.text;
  q["why"] = a.why;
  ordered list = ordered::array();
  bool any_right = false;
  for (const auto& [form, label] : choices(a, w)) {
    try {
      const bool right = prediction_matches(a, form);
      any_right |= right;
      list.push_back(
          {{"label", label}, {"right", right}, {"feedback", right ? "" : prediction_feedback(a, form)}});
    } catch (const InputError&) {
      // a form this answer does not take (e.g. a kind's variant): not offered
    }
  }
  if (any_right) q["choices"] = std::move(list);  // else the answer is only revealed
  return q;
}

}  // namespace

std::string markdown_html(const std::string& markdown) {
  char* html = cmark_markdown_to_html(markdown.data(), markdown.size(), CMARK_OPT_DEFAULT);
  std::string out = html ? html : "";
  std::free(html);
  return out;
}

std::string lesson_page(const Lesson& source, int picture_width) {
  const Lesson lesson = lesson_with_numbers(source);
  LessonRunner runner;
  std::vector<StepWorld> worlds;
  for (const LessonStep& step : lesson.steps) {
    try {
      worlds.push_back(runner.enter(step.state, step.ask));
    } catch (const InputError& e) {
      throw InputError(lesson.path, step.line, "step '" + step.title + "': " + e.detail());
    }
  }
  // Each trace once (steps on one pixel share it), with its 2D scene's outline where it has one.
  std::map<const Trace*, size_t> walk_of;
  std::map<const Accelerator*, std::unique_ptr<PlaneOutline>> outlines;
  ordered walks = ordered::array();
  ordered steps = ordered::array();
  std::map<const Scene*, size_t> scene_of;
  ordered scenes = ordered::array();
  for (size_t i = 0; i < lesson.steps.size(); ++i) {
    const LessonStep& step = lesson.steps[i];
    const StepWorld& w = worlds[i];
    ordered js;
    js["title"] = step.title;
    js["html"] = markdown_html(step.narration);
    js["walk"] = -1;
    if (w.trace && !w.trace->rays.empty()) {
      auto [at, fresh] = walk_of.try_emplace(w.trace.get(), walk_of.size());
      if (fresh) {
        const Scene* flat = w.scene && w.scene->flat ? w.scene.get() : nullptr;
        const PlaneOutline* outline = nullptr;
        if (flat && w.accel && has_plane_outline(*w.accel)) {
          auto& o = outlines[w.accel.get()];
          if (!o) o = std::make_unique<PlaneOutline>(plane_outline(*w.accel));
          outline = o.get();
        }
        ordered jw{{"walk", at->second}, {"structure", w.trace->structure.kind}};
        if (!flat && w.scene) {  // its 3D scene, once for every walk through it
          auto [sat, new_scene] = scene_of.try_emplace(w.scene.get(), scenes.size());
          if (new_scene) scenes.push_back(scene3d_json(*w.scene, kMaxPageTriangles));
          jw["scene"] = sat->second;
        }
        ordered rays = ordered::array();
        for (size_t r = 0; r < w.trace->rays.size(); ++r)
          rays.push_back(ray_json(*w.trace, 0, r, flat, outline, picture_width));
        jw["rays"] = std::move(rays);
        walks.push_back(std::move(jw));
      }
      js["walk"] = at->second;
      js["ray"] = w.ray;
      js["step"] = w.step;
    }
    try {
      if (auto figure = step_figure_json(step, w, picture_width)) js["figure"] = std::move(*figure);
    } catch (const InputError& e) {
      throw InputError(lesson.path, step.line, "step '" + step.title + "': its figure: " + e.detail());
    }
    if (step.ask && w.answer) js["question"] = question_json(step, w);
    steps.push_back(std::move(js));
  }
  ordered d;
  d["format"] = "raystep-player";
  d["version"] = 1;
  d["title"] = lesson.title;
  d["source"] = lesson.path;
  d["walks"] = std::move(walks);
  d["scenes"] = std::move(scenes);
  d["lesson"] = {
      {"title", lesson.title}, {"intro", markdown_html(lesson.intro)}, {"steps", std::move(steps)}};
  return page_html(lesson.title, d);
}

std::string lesson_site_index(const std::string& title,
                              const std::vector<std::pair<std::string, std::string>>& pages) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
      xml_escape(title) +
      "</title>\n<style>\nbody { font: 20px/1.5 system-ui, sans-serif; max-width: 46em; margin: 2em "
      "auto; padding: 0 1em; color: #1a1a1f; }\nli { margin: 0.3em 0; }\n</style>\n</head>\n<body>\n"
      "<h1>" +
      xml_escape(title) +
      "</h1>\n<p>Each lesson steps through real traced walks in the browser, offline: Right / Left "
      "step the walk, Page Down / Page Up the lesson.</p>\n<ol>\n";
  for (const auto& [t, href] : pages)
    html += "<li><a href=\"" + xml_escape(href) + "\">" + xml_escape(t) + "</a></li>\n";
  html += "</ol>\n<p>Made by <code>raystep export-html</code>.</p>\n</body>\n</html>\n";
  return html;
}

}  // namespace raystep::web
