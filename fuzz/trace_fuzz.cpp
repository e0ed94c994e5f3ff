// libFuzzer harness for the trace readers: read_any_trace_json (versions 1 to 5, through the file, as the
// debugger and `raystep replay` open one), and the single-structure reader parse_trace_json from text.
#include <cstdint>
#include <string>

#include "contract.h"
#include "raystep/trace/multi_trace.h"
#include "raystep/trace/trace_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const size_t lines = raystep::fuzz::line_count(text);
  const std::string path = raystep::fuzz::write_input("fuzz-trace.json", data, size);
  raystep::fuzz::expect_contract("trace (any version)", path, lines,
                                 [&] { raystep::read_any_trace_json(path); });
  raystep::fuzz::expect_contract("trace (version 1-4)", "fuzz.trace.json", lines,
                                 [&] { raystep::parse_trace_json(text, "fuzz.trace.json"); });
  return 0;
}
