// The handout of a lesson: for each step the figure its `show:` names (the window, the 3D view, the SAH chart
// or the picture) as step-N.png, and one index.html a student can read alone: the title, the introduction,
// each step's narration, its figure, and each question with the computed answer folded away (<details>).
// Written into a temporary folder beside DIR and renamed over it, so DIR is never half written.
#pragma once

#include <QString>

namespace raystep::viz {

class MainWindow;
class Presenter;

// Enters every step of the presenter's lesson in turn. Throws InputError on a step that cannot be entered or
// a file that cannot be written (DIR is then left as it was).
void exportHandout(MainWindow& window, Presenter& presenter, const QString& dir);

}  // namespace raystep::viz
