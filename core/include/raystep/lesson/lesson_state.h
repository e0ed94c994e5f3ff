// The debugger state a lesson step shows, in the scripted mode's vocabulary (docs/lesson-format.md): one
// setting per key, applied on top of the previous step's state. The same keys and values as the options of
// `raystep-gui`, so a step is always one equivalent scripted-mode command line.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "raystep/accel/structure_options.h"
#include "raystep/record/events.h"

namespace raystep {

// The current event: none (event 0 after a new pixel or ray), by index, or the K-th (1-based) of a kind.
struct EventSpec {
  enum class By { start, index, nth } by = By::start;
  int index = 0;
  EventType type = EventType::cell;
  int k = 1;
  std::string text;  // as written ("12", "cell:3"), for messages and the command line
};

// The selected tree node: none, by id, or by its path from the root (L/R, or octant digits: tree_nodes.h).
struct NodeSpec {
  enum class By { none, id, path } by = By::none;
  int id = -1;
  std::string path;
};

struct LessonState {
  std::string scene;  // the path as resolved against the lesson file's folder ("" before the first scene)
  std::string accel = "grid";
  StructureOptions structure;  // grid, kd-tree and BVH options, as the command line sets them
  std::string aa;              // "" : the scene's anti-aliasing
  std::optional<std::array<int, 2>> size;   // none: the scene's
  std::string heat;  // "": no overlay; else cells | tests | mailbox | boxes | samples | error
  std::optional<std::array<int, 2>> pixel;  // none: no traced pixel
  bool secondary = false;
  int ray = 0;
  EventSpec event;
  std::string panel;  // "", "sah" or "kd"
  NodeSpec node;
  bool follow = false, translucent = false;
  // The kd-tree's build so far in the 3D view: the split planes of the nodes made before the selected one.
  bool build_planes = false;
  // A 2D scene's 2D view: Crofton's random lines at the selected node; the pixels' anti-aliasing instead of
  // the walk (viz/src/flatland/flat_view.h).
  bool crofton_lines = false, flat_aa = false;
  std::optional<double> zoom;   // none: the window's default; 0: fit
  std::string show = "window";  // the step's figure: window | 3d | tree | chart | picture | report (lesson_figure.h)
  // The report windows the step opens and runs on the scene: "aa", "grid-sweep", "bvol" (the kinds of
  // bounding volumes), comma-separated; "": none. Not carried over: the next step closes them unless it names
  // them.
  std::string report;
  // The pixel inspector (an anti-aliased pixel's samples): open or not, the sample whose ray is replayed
  // (none: the ray named by `ray`), the adaptive square stepped to (none: the whole pixel), and the image
  // view's sample pattern over each pixel at 8x zoom and more.
  bool inspect = false;
  std::optional<int> sample;
  std::optional<int> square;
  bool sample_overlay = false;

  // The equivalent raystep-gui command line (scene first, then options in a fixed order), without --quit or
  // outputs: `raystep-gui ARGS --dump-state s.json --quit` shows what entering the step shows.
  std::vector<std::string> scripted_args() const;
};

// Applies one setting `key: value` to the state. `base_dir` resolves a relative scene path. Throws
// InputError("", 0, "what") for an unknown key or a bad value (the caller adds the file and line). `ask` is not
// a state setting: apply_setting rejects it (lesson.h reads it).
void apply_setting(LessonState& state, const std::string& key, const std::string& value,
                   const std::string& base_dir);

// Every key apply_setting knows, in the documented order.
const std::vector<std::string>& lesson_setting_keys();

}  // namespace raystep
