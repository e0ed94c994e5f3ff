// What every harness asserts: the reader accepts the input, or refuses it with raystep's InputError whose
// message names the file (and a line inside the input where it gives one). Any other exception, or a refusal
// that does not say where, is a finding: the harness aborts so that libFuzzer saves the input.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "raystep/util/error.h"

namespace raystep::fuzz {

[[noreturn]] inline void finding(const char* reader, const std::string& what) {
  std::fprintf(stderr, "\nFINDING (%s): %s\n", reader, what.c_str());
  std::fflush(stderr);
  std::abort();
}

// Runs read(). `name` must appear in an InputError's message; `lines` (0: not a text input) bounds its line.
template <typename Read>
void expect_contract(const char* reader, const std::string& name, size_t lines, Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.find(name) == std::string::npos)
      finding(reader, "InputError without the name '" + name + "': " + message);
    if (lines > 0 && e.line() > 0 && size_t(e.line()) > lines)
      finding(reader, "InputError at line " + std::to_string(e.line()) + " of a " + std::to_string(lines) +
                          "-line input: " + message);
    if (e.line() < 0) finding(reader, "InputError with a negative line: " + message);
  } catch (const std::exception& e) {
    finding(reader, std::string("an exception other than InputError: ") + e.what());
  } catch (...) {
    finding(reader, "a non-standard exception");
  }
}

// The most lines a text can have: '\n' and a lone '\r' (old Mac files, which the OBJ reader counts as editors
// do) both end a line, and a last line without either counts.
inline size_t line_count(const std::string& text) {
  size_t n = 1;
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'))) ++n;
  return n;
}

// A private folder for the run (in /dev/shm when it exists, so that writing an input per run costs no disk),
// holding the files that inputs may refer to: mesh.obj (one triangle) and scene.json (a scene of it).
inline const std::string& scratch_folder() {
  static const std::string folder = [] {
    std::string tmpl =
        (access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp") + std::string("/raystep-fuzz-XXXXXX");
    if (!mkdtemp(tmpl.data())) finding("setup", "cannot create a scratch folder");
    std::ofstream(tmpl + "/mesh.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(tmpl + "/scene.json")
        << R"({"camera": {"type": "pinhole", "eye": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 45},)"
        << R"( "objects": [{"type": "mesh", "file": "mesh.obj"}]})";
    return tmpl;
  }();
  return folder;
}

// Writes the input to a file of the scratch folder, for the readers that take a path only.
inline std::string write_input(const std::string& file_name, const uint8_t* data, size_t size) {
  std::string path = scratch_folder() + "/" + file_name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  if (!out) finding("setup", "cannot write " + path);
  return path;
}

}  // namespace raystep::fuzz
