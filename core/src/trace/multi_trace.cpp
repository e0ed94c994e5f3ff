#include "raystep/trace/multi_trace.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "raystep/accel/bounding_volumes.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "trace_file_detail.h"

namespace raystep {

MultiTrace record_walks(const Geometry& geometry, const std::vector<const Accelerator*>& accels,
                        const std::vector<RayRequest>& rays, const std::string& scene_path,
                        const std::string& scene_hash) {
  if (accels.size() < size_t(kMinWalks) || accels.size() > size_t(kMaxWalks))
    throw InputError("", 0,
                     "a multi-walk trace holds " + std::to_string(kMinWalks) + " to " +
                         std::to_string(kMaxWalks) + " structures, not " + std::to_string(accels.size()));
  MultiTrace m;
  m.scene_path = scene_path;
  m.scene_hash = scene_hash;
  m.scene_primitives = geometry.size();
  m.walks.reserve(accels.size());
  for (const Accelerator* accel : accels)
    m.walks.push_back(record_trace(geometry, *accel, rays, scene_path, scene_hash));
  return m;
}

std::vector<std::string> parse_walk_list(const std::string& list, const std::string& where, int min_count,
                                         int max_count) {
  std::vector<std::string> names;
  size_t start = 0;
  while (true) {
    const size_t comma = list.find(',', start);
    names.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (names.size() > size_t(max_count))
    throw InputError(
        "", 0,
        where + ": " + std::to_string(names.size()) + " structures, at most " + std::to_string(max_count));
  const std::vector<std::string> known = accelerator_names();
  std::set<std::string> seen;
  for (const std::string& n : names) {
    if (n.empty()) throw InputError("", 0, where + ": an empty name (names are separated by single commas)");
    if (std::find(known.begin(), known.end(), n) == known.end() && !parse_bvol_kind(n)) {
      std::string all;
      for (const std::string& k : known) all += (all.empty() ? "" : ", ") + k;
      throw InputError("", 0, where + ": unknown structure '" + n + "' (one of " + all + ")");
    }
    if (!seen.insert(n).second) throw InputError("", 0, where + ": " + n + " is listed twice");
    if (!records_events(*make_accelerator(n)))
      throw InputError(
          "", 0,
          where + ": " + n +
              " records no events (use " + recorded_structure_list() + ")");
  }
  if (names.size() < size_t(min_count))
    throw InputError("", 0,
                     where + ": give " + std::to_string(min_count) + " to " + std::to_string(max_count) +
                         " structures, separated by commas");
  return names;
}

std::string multi_trace_to_json(const MultiTrace& m) {
  using ordered = nlohmann::ordered_json;
  std::ostringstream out;
  out << "{\n";
  out << " \"format\": " << ordered(kTraceFormat).dump() << ",\n";
  out << " \"version\": " << kMultiTraceVersion << ",\n";
  out << " \"scene\": "
      << ordered({{"path", m.scene_path}, {"hash", m.scene_hash}, {"primitives", m.scene_primitives}}).dump()
      << ",\n";
  // Each walk is laid out as a single trace's part below its scene (trace_json_rest), so that the two forms
  // read alike: one event, node or primitive per line.
  out << " \"walks\": [";
  for (size_t w = 0; w < m.walks.size(); ++w) {
    std::string rest = trace_json_rest(m.walks[w]);
    rest.pop_back();  // the newline after its closing brace
    out << (w ? ", {\n" : "{\n") << rest;
  }
  out << "]\n}\n";
  return out.str();
}

void write_multi_trace_json(const std::string& path, const MultiTrace& trace) {
  std::string text = multi_trace_to_json(trace);
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

void write_multi_trace_csv(const std::string& path, const MultiTrace& trace) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "walk," << detail::kTraceCsvHeader;
    for (size_t w = 0; w < trace.walks.size(); ++w)
      detail::write_trace_csv_rows(out, trace.walks[w], std::to_string(w) + ",");
  });
}

namespace {
MultiTrace from_walks(int version, std::vector<Trace> walks) {
  MultiTrace m;
  m.version = version;
  m.scene_path = walks.front().scene_path;
  m.scene_hash = walks.front().scene_hash;
  m.scene_primitives = walks.front().scene_primitives;
  m.walks = std::move(walks);
  return m;
}
}  // namespace

MultiTrace parse_multi_trace_json(const std::string& text, const std::string& name) {
  std::vector<Trace> walks;
  int version = detail::parse_trace_document(text, name, true, &walks);
  if (version != kMultiTraceVersion)
    throw InputError(name, 0,
                     "version: a single structure's trace (version " + std::to_string(version) +
                         "), not a multi-walk trace (version " + std::to_string(kMultiTraceVersion) + ")");
  return from_walks(version, std::move(walks));
}

MultiTrace read_multi_trace_json(const std::string& path) {
  std::vector<Trace> walks;
  int version = detail::read_trace_document(path, true, &walks);
  if (version != kMultiTraceVersion)
    throw InputError(path, 0,
                     "version: a single structure's trace (version " + std::to_string(version) +
                         "), not a multi-walk trace (version " + std::to_string(kMultiTraceVersion) + ")");
  return from_walks(version, std::move(walks));
}

MultiTrace read_any_trace_json(const std::string& path) {
  std::vector<Trace> walks;
  int version = detail::read_trace_document(path, true, &walks);
  return from_walks(version, std::move(walks));
}

}  // namespace raystep

namespace raystep {

namespace {
std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}
}  // namespace

std::string multi_trace_summary(const MultiTrace& m, const CostModel& model, bool own_costs) {
  std::ostringstream out;
  const size_t nrays = m.walks.empty() ? 0 : m.walks.front().rays.size();
  out << "multi-walk trace: " << m.walks.size() << " structures, " << nrays << " ray(s) each, scene "
      << m.scene_path << " (" << m.scene_primitives << " primitives)\n";
  if (own_costs) {
    out << "cost: t_t per step (a cell or node visited) + t_i per primitive test, each structure's own "
           "(t_t/t_i:";
    for (const Trace& w : m.walks) {
      const CostModel own = structure_cost_model(w.structure);
      out << " " << w.structure.kind << " " << fmt("%g", own.t_t) << "/" << fmt("%g", own.t_i);
    }
    out << ")\n";
  } else
    out << "cost: " << fmt("%g", model.t_t) << " per step (a cell or node visited) + " << fmt("%g", model.t_i)
        << " per primitive test, the same for every structure\n";
  for (size_t r = 0; r < nrays; ++r) {
    const TracedRay& ray = m.walks.front().rays[r];
    out << "ray " << r << ": " << ray_kind_name(ray.kind) << ", depth " << ray.depth;
    if (ray.has_pixel) out << ", pixel " << ray.pixel[0] << "," << ray.pixel[1];
    if (ray.sample >= 0) out << ", sample " << ray.sample;
    out << "\n";
    std::vector<WalkCost> costs;
    float t_lo = kInfinity, t_hi = -kInfinity;
    for (const Trace& w : m.walks) {
      costs.push_back(walk_cost(w.rays[r], own_costs ? structure_cost_model(w.structure) : model));
      for (const CostPoint& p : costs.back().points)
        if (std::isfinite(p.t)) {
          t_lo = std::min(t_lo, std::max(p.t, ray.ray.tmin));
          t_hi = std::max(t_hi, p.t);
        }
    }
    // Four t values from the first entry to the furthest position any walk reached (a hit, or where it left).
    std::vector<float> ts;
    if (t_lo <= t_hi)
      for (int k = 1; k <= 4; ++k) ts.push_back(t_lo + (t_hi - t_lo) * float(k) / 4.f);
    char line[256];
    std::snprintf(line, sizeof line, "  %-11s %6s %6s %8s %6s %-14s %9s", "structure", "steps", "tests",
                  "mailbox", "boxes", "hit", "cost");
    out << line;
    for (float t : ts) {
      std::snprintf(line, sizeof line, " %10s ", fmt("t=%.4g", t).c_str());
      out << line;
    }
    out << "\n";
    auto cheapest = [&](auto value) {
      double best = kInfinity;
      for (size_t w = 0; w < costs.size(); ++w) best = std::min(best, value(w));
      return best;
    };
    const double best_total = cheapest([&](size_t w) { return costs[w].total; });
    for (size_t w = 0; w < costs.size(); ++w) {
      const WalkCost& c = costs[w];
      const std::string hit = c.hit ? "t=" + fmt("%.6g", c.t_hit) : "miss";
      std::snprintf(line, sizeof line, "  %-11s %6u %6u %8u %6u %-14s %8s%s",
                    m.walks[w].structure.kind.c_str(), c.steps, c.prim_tests, c.mailbox_hits, c.box_tests,
                    hit.c_str(), fmt("%.6g", c.total).c_str(), c.total == best_total ? "*" : " ");
      out << line;
      for (float t : ts) {
        const double v = cost_at(c, t);
        const double best = cheapest([&](size_t i) { return cost_at(costs[i], t); });
        std::snprintf(line, sizeof line, " %10s%s", fmt("%.6g", v).c_str(), v == best ? "*" : " ");
        out << line;
      }
      out << "\n";
    }
  }
  // The columns' padding leaves spaces at the ends of lines: not in the output.
  std::string text = out.str(), trimmed;
  for (char c : text) {
    if (c == '\n')
      while (!trimmed.empty() && trimmed.back() == ' ') trimmed.pop_back();
    trimmed += c;
  }
  return trimmed;
}

}  // namespace raystep
