// Private to core/src/trace: the parts of the trace reader and CSV writer that the multi-walk form
// (multi_trace.cpp) shares with the single trace, so that both are validated and written by the same code.
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "raystep/trace/multi_trace.h"
#include "raystep/trace/trace_file.h"

namespace raystep::detail {

// The format's names (trace_names.cpp), by enum value.
// Names to enums without building strings: the index of name in names, or -1.
template <size_t N>
int name_index(std::string_view name, const char* const (&names)[N]) {
  for (size_t i = 0; i < N; ++i)
    if (name == names[i]) return int(i);
  return -1;
}

extern const char* const kEventNames[kEventTypeCount];
extern const char* const kReasonNames[kAcceptReasonCount];
extern const char* const kRayKinds[4];
extern const char* const kAxes[3];
extern const char* const kOutcomes[3];

// A ray's counters from its events (the writer's "counters", trace-info's summary).
RayCounters count_events(const std::vector<Event>& events);

// Reads a trace document: versions 1 to 4 give one walk; version 5 (only when walks_allowed) kMinWalks to
// kMaxWalks walks, each validated as a version 4 trace. Returns the version; throws InputError.
int parse_trace_document(const std::string& text, const std::string& name, bool walks_allowed,
                         std::vector<Trace>* walks);
// The same from a file, streamed (its text is never held whole): InputError for a missing file, a directory,
// a device, or a file too big for the memory limit.
int read_trace_document(const std::string& path, bool walks_allowed, std::vector<Trace>* walks);

extern const char* const kTraceCsvHeader;  // the single trace's CSV header line, with its newline
// The CSV rows of a trace, each opened by prefix (the multi-walk file's "walk," column).
void write_trace_csv_rows(std::ostream& out, const Trace& t, const std::string& prefix);

}  // namespace raystep::detail
