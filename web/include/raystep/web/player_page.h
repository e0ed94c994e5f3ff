// The browser player (raystep export-html): one self-contained HTML page that steps forwards and backwards
// through a trace's storyboard, computed here in C++ by core's replay model (replay/storyboard.h) and
// inlined in the page: each step's event line, the state as `raystep replay` writes it, the Why text, and
// for a 2D scene the slides' picture at the step (figure/flat_figure.h, as SVG). The page's script only shows
// what it is given; it traverses nothing. Scripts, styles and data are inlined (the data gzip-compressed),
// so the page opens from disk with no network.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/plane_outline.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/multi_trace.h"

namespace raystep::web {

struct PlayerInput {
  std::string title;   // the page's heading
  std::string source;  // the trace's or the scene's file, named on the page
  const MultiTrace* trace = nullptr;
  // A 2D scene: each walk's ray drawn as the slides draw it at each step, over its structure's outline
  // (outlines[w] for walk w; a null outline: the scene without a structure).
  const Scene* flat_scene = nullptr;
  std::vector<const PlaneOutline*> outlines;
  // A 3D trace's scene, drawn under the walk's boxes in the page's 3D view (null: the boxes and the ray
  // only).
  const Scene* scene3d = nullptr;
  int picture_width = 560;  // points
};

// The whole page. Throws InputError("", 0, ...) when there is nothing to play (no trace, no ray).
std::string player_page(const PlayerInput& input);

// The page's data as JSON (what player_page compresses into it): for tests and the curious.
std::string player_data_json(const PlayerInput& input);

}  // namespace raystep::web
