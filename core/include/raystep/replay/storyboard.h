// The storyboard: the replay's states as versioned JSON (docs/replay-format.md), what any front end that is
// not the Qt debugger reads (a browser player, a 2D view, a student's script): after each event of a traced
// ray, the current cell or node, the stack, the mailbox, the primitives of the current cell or leaf, the
// nearest hit, the counters, the choice at an inner node and the Why text, each as the debugger's state panel
// shows it. `raystep replay` writes it; a human form of the same states is storyboard_text.
#pragma once

#include <ostream>
#include <string>

#include "raystep/replay/replay_state.h"
#include "raystep/trace/multi_trace.h"

namespace raystep::replay {

constexpr const char* kStoryboardFormat = "raystep-replay";
constexpr int kStoryboardVersion = 1;

// Which states: walk and ray -1 for all of them; step -1 for every event, else the one step (clamped to each
// ray's events).
struct StoryboardRequest {
  int walk = -1;
  int ray = -1;
  int step = -1;
};

// One state as a one-line JSON object (docs/replay-format.md, "state").
std::string state_json(const Trace& trace, const TracedRay& ray, const ReplayState& s);

// The whole document: {"format", "version", "source", "walks": [{"structure", "rays": [{..., "states":
// [...]}]}]}, one state a line, written as it goes (a long ray's storyboard is never held whole). Throws
// InputError("", 0,
// ...) for a walk or ray the trace does not have.
void write_storyboard(std::ostream& out, const MultiTrace& trace, const std::string& source,
                      const StoryboardRequest& request);

// One state for a reader: its event's line, then where the walk is, the stack, the nearest hit, the counters
// and the Why text, a line each ("\n"-terminated).
std::string state_text(const Trace& trace, const TracedRay& ray, const ReplayState& s);
// Every state of the request for a reader: per ray a header line, then each state_text after an empty line.
void write_storyboard_text(std::ostream& out, const MultiTrace& trace, const StoryboardRequest& request);

}  // namespace raystep::replay
