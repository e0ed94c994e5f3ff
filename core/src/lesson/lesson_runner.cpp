// Entering a lesson step headless (lesson_runner.h): the same loading, building and tracing as the debugger's
// session (viz/src/app/session.cpp: loadSceneData, buildStructureData, tracePixel), the event and node
// resolved as its scripted mode does, with its messages. Scene, structure and trace are kept while their
// inputs are unchanged.
#include "raystep/lesson/lesson_runner.h"

#include <algorithm>
#include <cstdio>

#include "raystep/io/scene_loader.h"
#include "raystep/lesson/lesson_facts.h"
#include "raystep/lesson/tree_nodes.h"
#include "raystep/report/bvol_report.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/scene/flatland.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

// A failure and the settings that caused it, so that check_lesson can point at the line that set one of them.
class StepError : public InputError {
 public:
  StepError(std::vector<std::string> keys, const std::string& what)
      : InputError("", 0, what), keys_(std::move(keys)) {}
  const std::vector<std::string>& keys() const { return keys_; }

 private:
  std::vector<std::string> keys_;
};

[[noreturn]] void fail(std::vector<std::string> keys, const std::string& what) {
  throw StepError(std::move(keys), what);
}

// The accelerator keeps the scene alive: it refers to the scene's geometry.
struct Built {
  std::shared_ptr<const Scene> scene;
  std::unique_ptr<Accelerator> accel;
};

}  // namespace

struct LessonRunner::Cache {
  std::string scene_path, scene_hash;
  std::shared_ptr<const Scene> scene;
  std::string structure;
  std::shared_ptr<const Accelerator> accel;
  std::string trace_key;
  std::shared_ptr<const Trace> trace;
};

QuestionContext StepWorld::context() const {
  QuestionContext c;
  c.scene = scene.get();
  c.accel = accel.get();
  c.trace = trace.get();
  c.ray = ray;
  c.step = step;
  c.node = node;
  c.aa = aa;
  c.width = width;
  c.height = height;
  if (pixel) c.pixel = *pixel;
  return c;
}

StepWorld LessonRunner::enter(const LessonState& state, std::optional<QuestionKind> ask) {
  if (!cache_) cache_ = std::make_shared<Cache>();
  Cache& cache = *cache_;
  StepWorld w;

  // The scene, loaded once per file.
  if (state.scene.empty()) fail({"scene"}, "no scene (scene: FILE)");
  if (!cache.scene || cache.scene_path != state.scene) {
    cache = Cache{};
    try {
      auto scene = std::make_shared<Scene>(load_scene(state.scene));
      cache.scene_hash = file_content_hash(state.scene);
      cache.scene = std::move(scene);
      cache.scene_path = state.scene;
    } catch (const InputError& e) {
      fail({"scene"}, std::string("scene: ") + e.what());
    }
  }
  w.scene = cache.scene;

  // The structure, built once per set of options.
  const std::string key = structure_key(state.accel, state.structure);
  if (!cache.accel || cache.structure != key) {
    cache.accel.reset();
    cache.trace.reset();
    cache.trace_key.clear();
    auto built = std::make_shared<Built>();
    built->scene = cache.scene;
    try {
      built->accel = make_accelerator(state.accel, state.structure);
      built->accel->build(cache.scene->geometry);
    } catch (const InputError& e) {
      fail({"accel", "grid-res", "grid-density", "grid-insert", "ti", "tt", "empty-bonus", "max-depth",
            "leaf-size", "mailbox", "bins", "bvh-leaf", "bvh-max-leaf", "bvh-order", "octree-leaf",
            "bsp-directions", "bsp-candidates"},
           std::string("building the ") + state.accel + ": " + e.detail());
    }
    cache.accel = std::shared_ptr<const Accelerator>(built, built->accel.get());
    cache.structure = key;
  }
  w.accel = cache.accel;

  // The picture's size and anti-aliasing.
  w.width = state.size ? (*state.size)[0] : cache.scene->render.width;
  w.height = state.size ? (*state.size)[1] : cache.scene->render.height;
  w.aa = state.aa;
  w.pixel = state.pixel;

  // The pixel's trace, exactly as the debugger records it when the pixel is clicked.
  if (state.pixel) {
    const int px = (*state.pixel)[0], py = (*state.pixel)[1];
    if (px >= w.width || py >= w.height)
      fail({"pixel", "size"}, "pixel " + std::to_string(px) + "," + std::to_string(py) + ": outside the " +
                                  std::to_string(w.width) + "x" + std::to_string(w.height) + " picture");
    // Anti-aliased, the debugger traces every sample's rays (tracePixel): the same pixel trace as
    // `raystep trace --pixel X,Y --aa SPEC`; without anti-aliasing the centre ray.
    AntiAliasing aa = cache.scene->render.aa;
    if (!state.aa.empty() && state.aa != "scene") {
      try {
        aa = parse_antialiasing(state.aa);
      } catch (const InputError& e) {
        fail({"aa"}, std::string("aa: ") + e.detail());
      }
    }
    const bool sampled = aa.mode != AntiAliasing::Mode::none;
    const std::string tkey = std::to_string(w.width) + "x" + std::to_string(w.height) + "@" +
                             std::to_string(px) + "," + std::to_string(py) + (state.secondary ? "+" : "") +
                             (sampled ? " " + to_string(aa) : "");
    if (!cache.trace || cache.trace_key != tkey) {
      if (sampled) {
        try {
          cache.trace = std::make_shared<Trace>(record_pixel_trace(
              *cache.scene, *cache.accel, w.width, w.height, px, py, aa, cache.scene->render.seed,
              state.secondary, cache.scene_path, cache.scene_hash));
        } catch (const InputError& e) {
          fail({"aa", "pixel"}, std::string("tracing the pixel's samples: ") + e.detail());
        }
      } else {
        std::vector<RayRequest> requests =
            pixel_rays(*cache.scene, *cache.accel, w.width, w.height, px, py, state.secondary);
        cache.trace = std::make_shared<Trace>(
            record_trace(cache.scene->geometry, *cache.accel, requests, cache.scene_path, cache.scene_hash));
      }
      cache.trace_key = tkey;
    }
    w.trace = cache.trace;
  } else if (cache.scene->flat && cache.scene->flat->has_ray) {
    // A 2D scene without a pixel: its own ray in the plane, the 2D view's walk (lesson_enter.cpp does the same).
    if (!cache.trace || cache.trace_key != "flat") {
      const Flatland& f = *cache.scene->flat;
      cache.trace = std::make_shared<Trace>(
          record_trace(cache.scene->geometry, *cache.accel,
                       {RayRequest{flat_ray(f.ray_origin, f.ray_direction), RayKind::primary, 0, false, {0, 0}}},
                       cache.scene_path, cache.scene_hash));
      cache.trace_key = "flat";
    }
    w.trace = cache.trace;
  }

  // The inspector's sample and square, with the scripted mode's messages (viz/src/lesson/lesson_enter.cpp).
  int ray = state.ray;
  if (state.sample || state.square) {
    const Trace* t = w.trace.get();
    if (state.sample) {
      const std::string text = "sample " + std::to_string(*state.sample);
      if (!t) fail({"sample"}, text + ": no traced pixel (pixel: X,Y)");
      const int n = t->pixel ? int(t->pixel->sampling.samples.size()) : 1;  // the centre ray: one sample
      if (*state.sample >= n)
        fail({"sample", "aa"}, text + ": the pixel has " + std::to_string(n) + " sample" +
                                   (n == 1 ? "" : "s") + " (0.." + std::to_string(n - 1) + ")");
      ray = -1;
      for (size_t i = 0; i < t->rays.size() && ray < 0; ++i)
        if (t->pixel ? t->rays[i].sample == *state.sample : i == 0) ray = int(i);
      if (ray < 0) fail({"sample"}, text + ": the trace holds no ray of that sample");
    }
    if (state.square) {
      const std::string text = "square " + std::to_string(*state.square);
      if (!t || !t->pixel || t->pixel->sampling.aa.mode != AntiAliasing::Mode::adaptive)
        fail({"square", "aa"}, text + ": the pixel is not sampled adaptively (aa: adaptive:T[:D])");
      const int n = int(t->pixel->sampling.squares.size());
      if (*state.square >= n)
        fail({"square"}, text + ": the pixel's subdivision has " + std::to_string(n) + " squares (0.." +
                             std::to_string(n - 1) + ")");
    }
  }

  // The ray and the event, with the scripted mode's messages.
  if (!w.trace) {
    if (state.ray != 0) fail({"ray"}, "ray " + std::to_string(state.ray) + ": no traced pixel (pixel: X,Y)");
    if (state.event.by != EventSpec::By::start)
      fail({"step", "step-to"}, std::string(state.event.by == EventSpec::By::index ? "step " : "step-to ") +
                                    state.event.text + ": no traced pixel (pixel: X,Y)");
  } else {
    const int rays = int(w.trace->rays.size());
    if (ray >= rays)
      fail({"ray", "secondary", "pixel"},
           "ray " + std::to_string(ray) + ": the pixel's trace has " + std::to_string(rays) +
               (rays == 1 ? " ray (0)" : " rays (0.." + std::to_string(rays - 1) + ")"));
    w.ray = ray;
    const TracedRay& r = w.trace->rays[size_t(w.ray)];
    const int n = int(r.events.size());
    if (state.event.by == EventSpec::By::index) {
      if (state.event.index >= n)
        fail({"step"}, "step " + std::to_string(state.event.index) + ": the ray has " + std::to_string(n) +
                           " events (0.." + std::to_string(n - 1) + ")");
      w.step = state.event.index;
    } else if (state.event.by == EventSpec::By::nth) {
      int seen = 0, found = -1;
      for (int i = 0; i < n && found < 0; ++i)
        if (r.events[size_t(i)].type == state.event.type && ++seen == state.event.k) found = i;
      if (found < 0) fail({"step-to"}, "step-to " + state.event.text + ": the ray has fewer such events");
      w.step = found;
    }
  }

  // The tree's selected node: by id, by path (tree_nodes.h: kd-tree and BSP tree L below, R above; BVH L and
  // R its children; octree a digit per level), or the root for the panel. The ids are the traces' ids.
  if (state.node.by != NodeSpec::By::none || state.panel == "sah" || state.panel == "kd") {
    const char* what = state.node.by == NodeSpec::By::id     ? "node"
                       : state.node.by == NodeSpec::By::path ? "node-path"
                                                             : "panel";
    const LessonTree tree = lesson_tree(*cache.accel);
    if (!tree.name)
      fail({what, "accel"}, std::string(what) + ": no tree (accel: " + recorded_structure_list(true) + ")");
    if (state.node.by == NodeSpec::By::path && !tree.paths)
      fail({"node-path", "accel"}, "node-path: a wide BVH's node is named by id (node: ID)");
    const size_t count = tree.nodes;
    w.node = state.panel == "sah" ? 0 : -1;
    if (state.node.by == NodeSpec::By::id) {
      if (size_t(state.node.id) >= count)
        fail({"node"}, "node " + std::to_string(state.node.id) + ": the " + tree.name + " has " +
                           std::to_string(count) + " nodes (0.." + std::to_string(count - 1) + ")");
      w.node = state.node.id;
    }
    if (state.node.by == NodeSpec::By::path) {
      try {
        w.node = int(lesson_node_by_path(*cache.accel, state.node.path));
      } catch (const InputError& e) {
        fail({"node-path"}, "node-path '" + state.node.path + "': " + e.detail());
      }
    }
  }

  // The report windows the step opens: each needs a scene with primitives; the bounding-volume report is run
  // (on a few rays: it is quick), so that a scene it cannot measure fails here rather than in the classroom.
  if (!state.report.empty()) {
    if (cache.scene->geometry.size() == 0) fail({"report"}, "report: the scene has no primitives");
    if (state.report.find("bvol") != std::string::npos) {
      try {
        BvolReportOptions o;
        o.camera_width = 16;
        o.camera_height = 12;
        o.reps = 1;
        run_bvol_report(*cache.scene, o);
      } catch (const InputError& e) {
        fail({"report"}, std::string("report bvol: ") + e.detail());
      }
    }
  }

  if (ask) {
    try {
      w.answer = answer_question(*ask, w.context());
    } catch (const InputError& e) {
      fail({"ask"}, e.detail());
    }
  }
  return w;
}

namespace {

// The step's numbers with the introduction's in front of the first step's.
std::vector<const LessonNumber*> step_numbers(const Lesson& lesson, size_t i, bool filled_only) {
  std::vector<const LessonNumber*> out;
  auto add = [&](const std::vector<LessonNumber>& v) {
    for (const LessonNumber& n : v)
      if (!filled_only || !n.checked) out.push_back(&n);
  };
  if (i == 0) add(lesson.intro_numbers);
  add(lesson.steps[i].numbers);
  return out;
}

std::string disagreement(const LessonNumber& n, double value) {
  return n.token + ": the text says " + n.written + ", the tool computes " +
         format_lesson_number(value, ".6g") + " (agreement asked: within " +
         format_lesson_number(n.tolerance, ".3g") + ")";
}

// The step's failure, pointed at the line of its last responsible setting (else its heading).
[[noreturn]] void rethrow_step(const Lesson& lesson, const LessonStep& step, const StepError& e) {
  int line = 0;
  for (const std::string& key : e.keys()) {
    if (key == "ask" && step.ask) line = std::max(line, step.ask_line);
    for (const LessonSetting& s : step.changes)
      if (s.key == key) line = std::max(line, s.line);
  }
  throw InputError(lesson.path, line ? line : step.line, "step '" + step.title + "': " + e.detail());
}

}  // namespace

int check_lesson(const Lesson& lesson, int* numbers) {
  LessonRunner runner;
  int questions = 0, computed = 0;
  for (size_t i = 0; i < lesson.steps.size(); ++i) {
    const LessonStep& step = lesson.steps[i];
    StepWorld w;
    try {
      w = runner.enter(step.state, step.ask);
      if (w.answer) ++questions;
    } catch (const StepError& e) {
      rethrow_step(lesson, step, e);
    } catch (const InputError& e) {
      throw InputError(lesson.path, step.line, "step '" + step.title + "': " + e.what());
    }
    LessonFacts facts(w, step.state);
    for (const LessonNumber* n : step_numbers(lesson, i, false)) {
      double v = 0;
      try {
        v = evaluate_lesson_number(*n, facts);
      } catch (const InputError& e) {
        throw InputError(lesson.path, n->line, "step '" + step.title + "': " + e.detail());
      }
      if (n->checked && !lesson_number_agrees(*n, v))
        throw InputError(lesson.path, n->line, "step '" + step.title + "': " + disagreement(*n, v));
      ++computed;
    }
  }
  if (numbers) *numbers = computed;
  return questions;
}

std::vector<LessonNumberResult> compute_lesson_numbers(const Lesson& lesson) {
  LessonRunner runner;
  std::vector<LessonNumberResult> out;
  for (size_t i = 0; i < lesson.steps.size(); ++i) {
    const std::vector<const LessonNumber*> ns = step_numbers(lesson, i, false);
    if (ns.empty()) continue;
    const LessonStep& step = lesson.steps[i];
    std::optional<StepWorld> w;
    std::string step_error;
    try {
      w = runner.enter(step.state, std::nullopt);
    } catch (const InputError& e) {
      step_error = "step '" + step.title + "': " + e.detail();
    }
    std::optional<LessonFacts> facts;
    if (w) facts.emplace(*w, step.state);
    for (const LessonNumber* n : ns) {
      LessonNumberResult r;
      r.number = n;
      r.step = int(i);
      r.error = step_error;
      if (facts) {
        try {
          r.value = evaluate_lesson_number(*n, *facts);
          r.agrees = !n->checked || lesson_number_agrees(*n, r.value);
        } catch (const InputError& e) {
          r.error = e.detail();
        }
      }
      out.push_back(r);
    }
  }
  return out;
}

Lesson lesson_with_numbers(const Lesson& lesson) {
  Lesson out = lesson;
  LessonRunner runner;
  for (size_t i = 0; i < out.steps.size(); ++i) {
    const LessonStep& step = lesson.steps[i];
    std::optional<StepWorld> w;
    std::optional<LessonFacts> facts;
    if (!step_numbers(lesson, i, true).empty()) {
      try {
        w = runner.enter(step.state, std::nullopt);
      } catch (const StepError& e) {
        rethrow_step(lesson, step, e);
      }
      facts.emplace(*w, step.state);
    }
    auto shown = [&](const std::vector<LessonNumber>& ns) {
      std::vector<std::string> texts;
      for (const LessonNumber& n : ns) {
        if (n.checked) {
          texts.push_back(n.written);
          continue;
        }
        try {
          texts.push_back(shown_lesson_number(n, evaluate_lesson_number(n, *facts)));
        } catch (const InputError& e) {
          throw InputError(lesson.path, n.line, "step '" + step.title + "': " + e.detail());
        }
      }
      return texts;
    };
    if (i == 0) out.intro = fill_lesson_numbers(lesson.intro, shown(lesson.intro_numbers));
    out.steps[i].narration = fill_lesson_numbers(step.narration, shown(step.numbers));
  }
  return out;
}

}  // namespace raystep
