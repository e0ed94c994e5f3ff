// What the player's pages share (player_page.cpp, lesson_page.cpp): a traced ray as the page's data, and the
// page around its data.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "raystep/accel/plane_outline.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/trace_file.h"

namespace raystep::web {

using ordered = nlohmann::ordered_json;

// Ray i of walk w (trace t): its header as `raystep replay` writes it, each event's line and each state's
// text (replay::state_text), and for a 2D scene its picture at each step over the outline (null: none).
ordered ray_json(const Trace& t, size_t w, size_t i, const Scene* flat_scene, const PlaneOutline* outline,
                 int picture_width);

// A 3D scene for the page's three.js view: its bounds, its triangles (at most max_triangles; the rest counted
// as omitted) and its spheres.
ordered scene3d_json(const Scene& scene, size_t max_triangles);
constexpr size_t kMaxPageTriangles = 200000;  // about 4 MB of JSON before compression

// Markdown (a lesson's narration, a report's table) as HTML, by cmark.
std::string markdown_html(const std::string& markdown);

// Bytes as base64, in lines of 76 characters or (wrap false: a data: URL's) in one.
std::string base64(const std::string& bytes, bool wrap = true);

// The page: the template with the title, the styles, the script and the data (gzip, base64) filled in.
std::string page_html(const std::string& title, const ordered& data);

}  // namespace raystep::web
