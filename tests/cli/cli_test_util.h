// What the `raystep` end-to-end tests share: a fresh folder per test, the executable run with its stdout and
// stderr captured, the check of a refused input (exit 2 and one line "error: ..."), and the reports' CSV
// files read as rows of named fields. Header-only, for the tests/cli files.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace raystep::clitest {

struct Outcome {
  int code;
  std::string out, err;
};

inline std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A shipped scene, scenes/NAME in the source tree.
inline std::string scene(const std::string& name) {
  return std::string(RAYSTEP_SOURCE_DIR) + "/scenes/" + name;
}

// A CSV file as rows of named fields (quoted fields may hold commas).
using CsvRow = std::map<std::string, std::string>;

inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted)
      fields.emplace_back();
    else
      fields.back() += c;
  }
  return fields;
}

// Every row must have as many fields as the header.
inline std::vector<CsvRow> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<CsvRow> rows;
  if (!std::getline(in, line)) return rows;
  const std::vector<std::string> header = split_csv_line(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split_csv_line(line);
    EXPECT_EQ(f.size(), header.size()) << line;
    CsvRow row;
    for (size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

// A test with a folder of its own, made empty before and removed after. The folder's name holds the test
// file's prefix, the test's name and the pid: two checkouts' test runs at once never share a folder.
class CliTest : public ::testing::Test {
 protected:
  explicit CliTest(std::string prefix) : prefix_(std::move(prefix)) {}

  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           (prefix_ + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }

  // `raystep ARGS` with no stdin; its stdout and stderr pass through files in the test folder.
  Outcome run(const std::string& args) const {
    const std::string out = path("stdout.txt"), err = path("stderr.txt");
    const std::string cmd = std::string(RAYSTEP_EXE) + " " + args + " >" + out + " 2>" + err + " </dev/null";
    const int status = std::system(cmd.c_str());
    Outcome r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
  }

  // Exit code 2 and a single line "error: <prefix>..." on stderr.
  void expect_error(const Outcome& r, const std::string& prefix) const {
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("error: " + prefix, 0), 0u) << "stderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr: " << r.err;
  }

  // The same, and no output file.
  void expect_error(const Outcome& r, const std::string& prefix, const std::string& output) const {
    expect_error(r, prefix);
    EXPECT_FALSE(std::filesystem::exists(output)) << output;
  }

  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace raystep::clitest
