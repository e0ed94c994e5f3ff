// Private to core/src/trace: the parts of the trace reader and CSV writer that the multi-walk form
// (multi_trace.cpp) shares with the single trace, so that both are validated and written by the same code.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "raystep/trace/multi_trace.h"
#include "raystep/trace/trace_file.h"

namespace raystep::detail {

// Reads a trace document: versions 1 to 4 give one walk; version 5 (only when walks_allowed) kMinWalks to
// kMaxWalks walks, each validated as a version 4 trace. Returns the version; throws InputError.
int parse_trace_document(const std::string& text, const std::string& name, bool walks_allowed,
                         std::vector<Trace>* walks);
// A regular file's bytes (InputError for a missing file, a directory, a device).
std::string read_trace_text(const std::string& path);

extern const char* const kTraceCsvHeader;  // the single trace's CSV header line, with its newline
// The CSV rows of a trace, each opened by prefix (the multi-walk file's "walk," column).
void write_trace_csv_rows(std::ostream& out, const Trace& t, const std::string& prefix);

}  // namespace raystep::detail
