#include "plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

extern char** environ;

namespace raystep::cli {

namespace {

namespace fs = std::filesystem;

std::string header(const std::string& output, int width, int height) {
  std::ostringstream s;
  s << "set terminal pngcairo size " << width << "," << height << " font 'sans,11' noenhanced\n"
    << "set output '" << output << "'\n";
  return s.str();
}

// Runs `gnuplot SCRIPT` with DIR as its working directory; stderr goes to err_path. The exit status, or -1
// when gnuplot could not be started.
int run_gnuplot(const std::string& dir, const std::string& script, const std::string& err_path) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0600);
  std::vector<char*> argv = {const_cast<char*>("gnuplot"), const_cast<char*>(script.c_str()), nullptr};
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status) == 127 ? -1 : WEXITSTATUS(status);
  return 1;
}

std::string first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t^") != std::string::npos) return line;
  return "";
}

}  // namespace

bool gnuplot_available() {
  const std::string err =
      (fs::temp_directory_path() / ("raystep-gnuplot-" + std::to_string(::getpid()))).string();
  std::error_code ec;
  const fs::path script =
      fs::temp_directory_path() / ("raystep-gnuplot-" + std::to_string(::getpid()) + ".gp");
  { std::ofstream(script) << "exit\n"; }
  const bool ok = run_gnuplot(fs::temp_directory_path().string(), script.string(), err) == 0;
  fs::remove(script, ec);
  fs::remove(err, ec);
  return ok;
}

PlotResult plot_png(const std::string& dir, const std::string& name, const std::string& body, int width,
                    int height) {
  // The script the student keeps draws straight to NAME.png; the run draws to a temporary name first.
  write_file_atomically((fs::path(dir) / (name + ".gp")).string(),
                        [&](std::ostream& out) { out << header(name + ".png", width, height) << body; });
  const std::string tag = std::to_string(::getpid());
  const std::string temp_png = "." + name + ".png.tmp." + tag;
  const fs::path temp_script = fs::path(dir) / ("." + name + ".gp.tmp." + tag);
  const fs::path err = fs::path(dir) / ("." + name + ".err.tmp." + tag);
  {
    std::ofstream out(temp_script);
    out << header(temp_png, width, height) << body;
    if (!out) throw InputError(temp_script.string(), 0, "cannot write the plot script");
  }
  PlotResult result;
  const int rc = run_gnuplot(dir, temp_script.filename().string(), err.string());
  std::error_code ec;
  if (rc == -1) {
    result.message = "gnuplot not found: install gnuplot-nox, then run `gnuplot " + name + ".gp` in " + dir;
  } else if (rc != 0) {
    result.message = "gnuplot failed on " + name + ".gp: " + first_line(err.string());
  } else {
    fs::rename(fs::path(dir) / temp_png, fs::path(dir) / (name + ".png"), ec);
    if (ec)
      result.message = "cannot rename the plot to " + name + ".png: " + ec.message();
    else
      result.drawn = true;
  }
  fs::remove(temp_script, ec);
  fs::remove(err, ec);
  fs::remove(fs::path(dir) / temp_png, ec);
  return result;
}

}  // namespace raystep::cli
