#include "raystep/report/hardcases.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "raystep/report/hardcase_reference.h"
#include "raystep/util/error.h"
#include "timing.h"

namespace raystep {
namespace {

using report_timing::Clock;
using report_timing::seconds_since;

// What a child reports through its pipe: a family begun, then its result. Plain bytes: both ends are the
// same program.
struct Record {
  int32_t kind = 0;  // 0: family begun, 1: family done
  int32_t family = 0;
  uint64_t rays = 0, leaks = 0, disagreements = 0;
  double ms = 0.0;
  int32_t issue_kind = 0;  // 0 none, 1 leak, 2 disagreement (nearest), 3 disagreement (any hit)
  int32_t issue_set = -1;
  int64_t issue_ray = -1;
};

struct Battery {
  const std::vector<HardCaseSet>& sets;
  std::vector<std::vector<ReferenceHit>> references;  // per set, per ray
  std::vector<HardCaseFamily> families;               // present, in enum order
};

// Structures built in this process, by set index, for the sets that share a geometry (same_geometry_as).
using BuiltStructures = std::map<size_t, std::unique_ptr<Accelerator>>;

Record run_family(const std::string& structure, const StructureFactory& factory, const Battery& b,
                  HardCaseFamily family, BuiltStructures& built) {
  Record rec;
  rec.kind = 1;
  rec.family = int32_t(family);
  const Clock::time_point t0 = Clock::now();
  for (size_t s = 0; s < b.sets.size(); ++s) {
    const HardCaseSet& set = b.sets[s];
    if (set.family != family) continue;
    std::unique_ptr<Accelerator> own;
    const Accelerator* acc;
    if (set.same_geometry_as >= 0 && built.count(size_t(set.same_geometry_as))) {
      acc = built[size_t(set.same_geometry_as)].get();
    } else {
      own = factory(structure);
      own->build(set.geometry);
      acc = own.get();
    }
    for (size_t i = 0; i < set.rays.size(); ++i) {
      const ReferenceHit& ref = b.references[s][i];
      Hit hit;
      const bool found = acc->intersect(set.rays[i], &hit);
      const bool occluded = acc->occluded(set.rays[i]);
      int issue = 0;
      if (set.must_hit[i] && !found)
        issue = 1, ++rec.leaks;
      else if (found != hit.found() || !agrees_with_reference(ref, hit))
        issue = 2, ++rec.disagreements;
      else if (occluded != ref.hit)
        issue = 3, ++rec.disagreements;
      if (issue && rec.issue_kind == 0)
        rec.issue_kind = issue, rec.issue_set = int32_t(s), rec.issue_ray = int64_t(i);
    }
    rec.rays += set.rays.size();
    if (own) {
      bool shared = false;
      for (const HardCaseSet& other : b.sets) shared |= other.same_geometry_as == int(s);
      if (shared) built[s] = std::move(own);
    }
  }
  rec.ms = 1e3 * seconds_since(t0);
  return rec;
}

bool write_all(int fd, const void* data, size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    ssize_t w = ::write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w, n -= size_t(w);
  }
  return true;
}

// Reads one record; false at the end of the pipe (or a torn record, when the child died mid-write).
bool read_record(int fd, Record* rec) {
  char* p = reinterpret_cast<char*>(rec);
  size_t n = sizeof(Record);
  while (n > 0) {
    ssize_t r = ::read(fd, p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r, n -= size_t(r);
  }
  return true;
}

std::string describe_ray(const Ray& r) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "o = (%.9g, %.9g, %.9g), d = (%.9g, %.9g, %.9g), t in (%g, %g)",
                double(r.origin.x), double(r.origin.y), double(r.origin.z), double(r.direction.x),
                double(r.direction.y), double(r.direction.z), double(r.tmin), double(r.tmax));
  return buf;
}

std::string describe_issue(const Battery& b, const Record& rec) {
  if (rec.issue_kind == 0) return "";
  const char* what = rec.issue_kind == 1   ? "leak (a miss where a hit is certain)"
                     : rec.issue_kind == 2 ? "nearest hit disagrees with the reference"
                                           : "any-hit query disagrees with the reference";
  const HardCaseSet& set = b.sets[size_t(rec.issue_set)];
  return set.name + ", ray " + std::to_string(rec.issue_ray) + ": " + what + "; " +
         describe_ray(set.rays[size_t(rec.issue_ray)]);
}

std::string describe_status(int status, bool timed_out) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    if (sig == SIGALRM && timed_out) return "time limit reached (a hang?)";
    const char* name = strsignal(sig);
    return std::string("killed by signal ") + std::to_string(sig) + " (" + (name ? name : "?") + ")";
  }
  if (WIFEXITED(status)) return "exit code " + std::to_string(WEXITSTATUS(status));
  return "ended abnormally";
}

HardCaseRow row_from(const std::string& structure, const Battery& b, const Record& rec) {
  HardCaseRow row;
  row.structure = structure;
  row.family = HardCaseFamily(rec.family);
  row.rays = rec.rays;
  row.leaks = rec.leaks;
  row.disagreements = rec.disagreements;
  row.ms = rec.ms;
  row.first_issue = describe_issue(b, rec);
  return row;
}

uint64_t family_rays(const Battery& b, HardCaseFamily f) {
  uint64_t n = 0;
  for (const HardCaseSet& s : b.sets)
    if (s.family == f) n += s.rays.size();
  return n;
}

// One structure over every family, in child processes: a crash ends its family, and the next family starts
// in a new child.
std::vector<HardCaseRow> run_isolated(const std::string& structure, const StructureFactory& factory,
                                      const Battery& b, double time_limit) {
  std::vector<HardCaseRow> rows;
  size_t start = 0;
  while (start < b.families.size()) {
    int fds[2];
    if (::pipe(fds) != 0)
      throw std::runtime_error("hardcases: pipe failed: " + std::string(std::strerror(errno)));
    std::fflush(nullptr);  // nothing buffered is written twice
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("hardcases: fork failed: " + std::string(std::strerror(errno)));
    if (pid == 0) {
      // The child: report each family as it begins and ends; _exit, so that no parent's atexit work runs.
      ::close(fds[0]);
      ::signal(SIGALRM, SIG_DFL);
      ::alarm(unsigned(std::max(1.0, time_limit)));
      int code = 0;
      BuiltStructures built;
      try {
        for (size_t f = start; f < b.families.size(); ++f) {
          Record begin;
          begin.family = int32_t(b.families[f]);
          if (!write_all(fds[1], &begin, sizeof begin)) ::_exit(3);
          Record done = run_family(structure, factory, b, b.families[f], built);
          if (!write_all(fds[1], &done, sizeof done)) ::_exit(3);
        }
      } catch (...) {
        code = 4;  // an exception out of a build or a query: a crash of the family begun
      }
      ::close(fds[1]);
      ::_exit(code);
    }
    ::close(fds[1]);
    const Clock::time_point t0 = Clock::now();
    Record rec;
    int open_family = -1;
    size_t done = start;
    while (read_record(fds[0], &rec)) {
      if (rec.kind == 0) {
        open_family = rec.family;
      } else {
        rows.push_back(row_from(structure, b, rec));
        open_family = -1;
        ++done;
      }
    }
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const bool clean_exit = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (clean_exit && done == b.families.size()) break;
    // A crash: of the family begun and not finished (or the next one, if it died between families).
    const HardCaseFamily family =
        open_family >= 0 ? HardCaseFamily(open_family) : b.families[std::min(done, b.families.size() - 1)];
    HardCaseRow row;
    row.structure = structure;
    row.family = family;
    row.rays = family_rays(b, family);
    row.crashes = 1;
    row.ms = 1e3 * seconds_since(t0);
    row.first_issue = "crash: " + describe_status(status, seconds_since(t0) >= time_limit * 0.99);
    rows.push_back(row);
    start = size_t(std::find(b.families.begin(), b.families.end(), family) - b.families.begin()) + 1;
  }
  return rows;
}

}  // namespace

uint64_t HardCaseReport::leaks() const {
  uint64_t n = 0;
  for (const HardCaseRow& r : rows) n += r.leaks;
  return n;
}
uint64_t HardCaseReport::disagreements() const {
  uint64_t n = 0;
  for (const HardCaseRow& r : rows) n += r.disagreements;
  return n;
}
uint64_t HardCaseReport::crashes() const {
  uint64_t n = 0;
  for (const HardCaseRow& r : rows) n += r.crashes;
  return n;
}

std::vector<std::string> default_hardcase_structures() {
  return {"brute", "grid", "kd", "bvh", "bvh-sbvh", "bvh4", "bvh8", "bvh8-sbvh", "octree", "bsp"};
}

HardCaseReport run_hardcases(const std::vector<HardCaseSet>& battery, const HardCaseRunOptions& options) {
  HardCaseReport report;
  report.structures = options.structures.empty() ? default_hardcase_structures() : options.structures;
  const StructureFactory factory =
      options.factory ? options.factory : [](const std::string& n) { return make_accelerator(n); };
  for (const std::string& s : report.structures) factory(s);  // unknown names fail before any work

  Battery b{battery, {}, {}};
  const Clock::time_point t0 = Clock::now();
  b.references.resize(battery.size());
  for (size_t s = 0; s < battery.size(); ++s) {
    for (const Ray& r : battery[s].rays) b.references[s].push_back(reference_nearest(battery[s].geometry, r));
    report.reference_rays += battery[s].rays.size();
  }
  report.reference_ms = 1e3 * seconds_since(t0);
  report.sets = battery.size();
  for (int f = 0; f < kHardCaseFamilies; ++f)
    for (const HardCaseSet& s : battery)
      if (int(s.family) == f) {
        b.families.push_back(HardCaseFamily(f));
        break;
      }

  for (const std::string& structure : report.structures) {
    if (options.isolate) {
      std::vector<HardCaseRow> rows = run_isolated(structure, factory, b, options.time_limit_seconds);
      report.rows.insert(report.rows.end(), rows.begin(), rows.end());
    } else {
      BuiltStructures built;
      for (HardCaseFamily f : b.families)
        report.rows.push_back(row_from(structure, b, run_family(structure, factory, b, f, built)));
    }
  }
  return report;
}

std::string hardcases_verdict(const HardCaseReport& r) {
  uint64_t rays = 0;
  for (const HardCaseRow& row : r.rows) rays += row.rays;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%s: %" PRIu64 " leaks, %" PRIu64 " disagreements, %" PRIu64 " crashes in %" PRIu64
                " rays over %zu structures",
                r.clean() ? "PASS" : "FAIL", r.leaks(), r.disagreements(), r.crashes(), rays,
                r.structures.size());
  return buf;
}

std::string hardcases_table(const HardCaseReport& r) {
  std::ostringstream out;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-10s %-10s %9s %7s %9s %8s %10s\n", "structure", "family", "rays", "leaks",
                "disagree", "crashes", "ms");
  out << buf;
  std::vector<std::string> issues;
  for (const HardCaseRow& row : r.rows) {
    std::snprintf(buf, sizeof buf, "%-10s %-10s %9" PRIu64 " %7" PRIu64 " %9" PRIu64 " %8" PRIu64 " %10.1f\n",
                  row.structure.c_str(), hardcase_family_name(row.family), row.rays, row.leaks,
                  row.disagreements, row.crashes, row.ms);
    out << buf;
    if (!row.first_issue.empty())
      issues.push_back(row.structure + " / " + hardcase_family_name(row.family) + ": " + row.first_issue);
  }
  if (!issues.empty()) {
    out << "first issue of each failing row:\n";
    for (const std::string& s : issues) out << "  " << s << "\n";
  }
  return out.str();
}

std::string hardcases_csv(const HardCaseReport& r) {
  std::ostringstream out;
  out << "structure,family,rays,leaks,disagreements,crashes,ms,first_issue\n";
  for (const HardCaseRow& row : r.rows) {
    std::string issue = row.first_issue;
    std::replace(issue.begin(), issue.end(), '"', '\'');
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s,%s,%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%.3f,",
                  row.structure.c_str(), hardcase_family_name(row.family), row.rays, row.leaks,
                  row.disagreements, row.crashes, row.ms);
    out << buf << '"' << issue << "\"\n";
  }
  return out.str();
}

std::string hardcases_json(const HardCaseReport& r) {
  nlohmann::json j;
  j["mesh"] = r.mesh;
  j["note"] = r.note;
  j["structures"] = r.structures;
  j["sets"] = r.sets;
  j["reference_rays"] = r.reference_rays;
  j["reference_ms"] = r.reference_ms;
  j["leaks"] = r.leaks();
  j["disagreements"] = r.disagreements();
  j["crashes"] = r.crashes();
  j["clean"] = r.clean();
  j["verdict"] = hardcases_verdict(r);
  nlohmann::json rows = nlohmann::json::array();
  for (const HardCaseRow& row : r.rows)
    rows.push_back({{"structure", row.structure},
                    {"family", hardcase_family_name(row.family)},
                    {"rays", row.rays},
                    {"leaks", row.leaks},
                    {"disagreements", row.disagreements},
                    {"crashes", row.crashes},
                    {"ms", row.ms},
                    {"first_issue", row.first_issue}});
  j["rows"] = rows;
  return j.dump(2) + "\n";
}

}  // namespace raystep
