// One way into a debugger state: the scripted mode's options and a lesson's steps are both a core LessonState
// (docs/lesson-format.md: the option names are its keys), and enterState puts one into the window. It sets
// the whole state: what the state does not name goes back to its default (no heat map, the kd panel closed,
// no node, follow and translucent off, the picture fitted, the camera as the scene was framed), so that steps
// entered in order, backwards or by jumping show what a fresh `raystep-gui <state.scripted_args()>` shows.
#pragma once

#include "raystep/lesson/lesson_state.h"

namespace raystep::viz {

class MainWindow;

// Loads, builds, renders and traces only what differs from what the window has (a new scene, other structure
// options, another picture size or anti-aliasing); the pixel is traced again every time (it is cheap, and
// the class may have clicked another one). The work runs in place. Throws InputError("", 0, "--option ...:
// what") when the state cannot be reached (the pixel outside the picture, no such event, ray or node, a node
// without a kd-tree); the window may then be part way.
void enterState(MainWindow& window, const LessonState& state);

}  // namespace raystep::viz
