// Input errors: everything a user can get wrong (scene, mesh, ray file, trace, command line) throws
// InputError naming the file and, where known, the line. The command line prints
// "error: FILE:LINE: what" and exits with code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace raystep {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, const std::string& what)
      : std::runtime_error(format(file, line, what)), file_(std::move(file)), line_(line), what_(what) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }  // 0 when unknown
  const std::string& detail() const { return what_; }

 private:
  static std::string format(const std::string& file, int line, const std::string& what) {
    std::string s = file;
    if (line > 0) s += ":" + std::to_string(line);
    if (!s.empty()) s += ": ";
    return s + what;
  }
  std::string file_;
  int line_;
  std::string what_;
};

}  // namespace raystep
