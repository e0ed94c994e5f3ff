// A lesson as a page of the browser player (raystep export-html LESSON.md, and a site of every lesson): the
// narration step by step (Markdown rendered by cmark), each step's walk shown at its event (the lesson
// runner's state: the scene, structure, pixel and event the presenter shows), and its question as choices
// that say, when clicked, whether they are right and why not (core's prediction_matches and
// prediction_feedback, computed when the page is written), then the answer and its reason.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "raystep/lesson/lesson.h"

namespace raystep::web {

// The page. Throws InputError(lesson path, line, ...) when a step's state cannot be reached (as `raystep
// lesson check` does).
std::string lesson_page(const Lesson& lesson, int picture_width = 560);

// The site's index: each lesson's title linking to its page (pairs of title and file name), in order.
std::string lesson_site_index(const std::string& title,
                              const std::vector<std::pair<std::string, std::string>>& pages);

}  // namespace raystep::web
