// Reading a trace's pixel section (version 2): every index in range, every sample where its pattern puts it, the
// adaptive tree well formed; and the line of an error's path.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "raystep/render/pixel_filter.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/scene/json_locate.h"
#include "trace_reader.h"

namespace raystep::detail {

const std::string& TraceText::text() const {
  if (text_) return *text_;
  if (!have_) {
    std::ifstream in(path_, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    read_ = s.str();
    have_ = true;
  }
  return read_;
}

// The line of a value named in display form ("rays[0].events[3].prim"): converted to a JSON pointer.
int Reader::line_of(const std::string& path) const {
  std::string pointer;
  std::string rest = path.rfind("trace", 0) == 0 ? path.substr(5) : path;
  for (char c : rest) {
    if (c == '.' || c == '[')
      pointer += '/';
    else if (c != ']')
      pointer += c;
  }
  if (!pointer.empty() && pointer[0] != '/') pointer.insert(pointer.begin(), '/');
  return json_line_of(text_.text(), pointer);
}

// The pixel section (version 2): every index in range, every sample where its pattern puts it, the adaptive
// tree well formed (parents before children, each child naming its parent).
TracePixel read_pixel(const Reader& rd, const Value& jp, const Path& pp, Capped capped) {
  TracePixel p;
  PixelSampling& s = p.sampling;
  constexpr int64_t kMaxSide = 1 << 15;  // render_image's limit
  p.width = int(rd.integer_at(jp, pp, "width", 1, kMaxSide));
  p.height = int(rd.integer_at(jp, pp, "height", 1, kMaxSide));
  s.x = int(rd.integer_at(jp, pp, "x", 0, p.width - 1));
  s.y = int(rd.integer_at(jp, pp, "y", 0, p.height - 1));
  const Value seed = rd.member(jp, pp, "seed");
  if (!seed.is_number_integer() || (seed.kind() != Value::Kind::number_unsigned && seed.get_int64() < 0))
    rd.fail(pp.key("seed"), "expected an integer in 0..2^64-1");
  p.seed = uint64_t(seed.get_int64());
  const std::string spec = rd.text_at(jp, pp, "aa");
  try {
    s.aa = parse_antialiasing(spec);
  } catch (const InputError& e) {
    rd.fail(pp.key("aa"), e.detail());
  }
  s.value = rd.vec_at(jp, pp, "value");
  if (jp.contains("exact")) p.exact = rd.vec_at(jp, pp, "exact");

  // Samples: as many as the pattern casts, each inside the pixel, labelled with its stratum or lattice point.
  using Mode = AntiAliasing::Mode;
  const Value samples = rd.array_at(jp, pp, "samples");
  const Path sp = pp.key("samples");
  const size_t count = samples.size();
  const bool stratified = s.aa.mode == Mode::regular || s.aa.mode == Mode::jitter;
  const bool adaptive = s.aa.mode == Mode::adaptive;
  const size_t expected = stratified                  ? size_t(s.aa.k) * size_t(s.aa.k)
                          : s.aa.mode == Mode::random ? size_t(s.aa.k)
                          : s.aa.mode == Mode::none   ? 1
                                                      : 0;
  if (adaptive ? count < 5 || count > max_samples_per_pixel(s.aa) : count != expected)
    rd.fail(sp,
            std::to_string(count) + " samples, but " + spec + " casts " +
                (adaptive ? "5.." + std::to_string(max_samples_per_pixel(s.aa)) : std::to_string(expected)));
  const int n = 2 << s.aa.max_depth;  // adaptive: lattice steps per pixel side
  auto pair = [&](const Value& v, const Path& path, int64_t hi) {
    if (!v.is_array() || v.size() != 2) rd.fail(path, "expected [i, j]");
    return std::array<int, 2>{int(rd.integer(v[0], path.at(0), 0, hi)),
                              int(rd.integer(v[1], path.at(1), 0, hi))};
  };
  s.samples.reserve(capped(count));
  for (size_t i = 0; i < count; ++i) {
    const Path ip = sp.at(i);
    const Value js = samples[i];
    PixelSample ps;
    ps.px = rd.real_at(js, ip, "px");
    ps.py = rd.real_at(js, ip, "py");
    if (!(ps.px >= float(s.x) && ps.px <= float(s.x + 1)))
      rd.fail(ip.key("px"), "outside pixel " + std::to_string(s.x) + "'s span [x, x+1]");
    if (!(ps.py >= float(s.y) && ps.py <= float(s.y + 1)))
      rd.fail(ip.key("py"), "outside pixel row " + std::to_string(s.y) + "'s span [y, y+1]");
    ps.colour = rd.vec_at(js, ip, "colour");
    if (stratified) {
      const std::array<int, 2> c = pair(rd.member(js, ip, "stratum"), ip.key("stratum"), s.aa.k - 1);
      ps.stratum[0] = c[0];
      ps.stratum[1] = c[1];
    } else if (js.contains("stratum")) {
      rd.fail(ip.key("stratum"), "only regular and jittered samples have a stratum");
    }
    if (adaptive) {
      const std::array<int, 2> c = pair(rd.member(js, ip, "lattice"), ip.key("lattice"), n);
      ps.lattice[0] = c[0];
      ps.lattice[1] = c[1];
    } else if (js.contains("lattice")) {
      rd.fail(ip.key("lattice"), "only adaptive samples lie on the lattice");
    }
    s.samples.push_back(ps);
  }

  // The tent filter: each sample's weight from its place, and the neighbours' samples it reaches.
  const bool tent = s.aa.filter == AntiAliasing::Filter::tent;
  const float cx = float(s.x) + 0.5f, cy = float(s.y) + 0.5f;
  auto check_weight = [&](PixelSample& ps, const Value& js, const Path& ip) {
    ps.weight = tent_weight(ps.px - cx, ps.py - cy);
    if (js.contains("weight") && !(std::fabs(rd.real_at(js, ip, "weight") - ps.weight) <= 1e-6f))
      rd.fail(ip.key("weight"), "not the tent's weight (1 - |dx|)(1 - |dy|) at the sample, " +
                                    std::to_string(ps.weight));
  };
  if (tent)
    for (size_t i = 0; i < count; ++i) check_weight(s.samples[i], samples[i], sp.at(i));
  s.box_value = tent && jp.contains("box_value") ? rd.vec_at(jp, pp, "box_value") : s.value;
  if (jp.contains("neighbours") && !tent) rd.fail(pp.key("neighbours"), "only the tent filter has neighbours");
  if (tent) {
    const Value nb = rd.array_at(jp, pp, "neighbours");
    const Path np = pp.key("neighbours");
    if (nb.size() > 8 * expected) rd.fail(np, std::to_string(nb.size()) + " neighbours' samples, but eight "
                                                  "neighbours of " + spec + " cast at most " +
                                                  std::to_string(8 * expected));
    s.neighbours.reserve(capped(nb.size()));
    for (size_t i = 0; i < nb.size(); ++i) {
      const Path ip = np.at(i);
      const Value js = nb[i];
      PixelSample ps;
      ps.px = rd.real_at(js, ip, "px");
      ps.py = rd.real_at(js, ip, "py");
      ps.colour = rd.vec_at(js, ip, "colour");
      const bool inside = ps.px >= float(s.x) && ps.px < float(s.x + 1) && ps.py >= float(s.y) &&
                          ps.py < float(s.y + 1);
      if (inside || !(tent_weight(ps.px - cx, ps.py - cy) > 0.f))
        rd.fail(ip, "not a neighbour's sample within the tent's reach (outside the pixel, less than one "
                    "pixel from its centre on each axis)");
      check_weight(ps, js, ip);
      s.neighbours.push_back(ps);
    }
  }

  // Adaptive squares, depth first.
  const Value squares = jp.contains("squares") ? rd.array_at(jp, pp, "squares") : Value();
  const Path qp = pp.key("squares");
  const size_t nsq = squares.exists() ? squares.size() : 0;
  if (adaptive && nsq == 0) rd.fail(qp, "adaptive sampling has at least the whole pixel's square");
  if (!adaptive && nsq > 0) rd.fail(qp, "only adaptive sampling has squares");
  s.squares.reserve(capped(nsq));
  for (size_t i = 0; i < nsq; ++i) {
    const Path ip = qp.at(i);
    const Value jq = squares[i];
    AdaptiveSquare q;
    q.parent = int(rd.integer_at(jq, ip, "parent", i == 0 ? -1 : 0, int64_t(i) - 1));
    q.depth = int(rd.integer_at(jq, ip, "depth", 0, s.aa.max_depth));
    q.i0 = int(rd.integer_at(jq, ip, "i0", 0, n));
    q.j0 = int(rd.integer_at(jq, ip, "j0", 0, n));
    q.size = int(rd.integer_at(jq, ip, "size", 1, n));
    const Value idx = rd.array_at(jq, ip, "samples");
    const Path xp = ip.key("samples");
    if (idx.size() != 5) rd.fail(xp, "expected the 5 sample indices (4 corners, then the centre)");
    for (int k = 0; k < 5; ++k) q.samples[k] = int(rd.integer(idx[k], xp.at(k), 0, int64_t(count) - 1));
    q.new_samples = int(rd.integer_at(jq, ip, "new_samples", 0, 5));
    q.contrast = rd.vec_at(jq, ip, "contrast");
    const std::string_view outcome = rd.view_at(jq, ip, "outcome");
    const int o = name_index(outcome, kOutcomes);
    if (o < 0)
      rd.fail(ip.key("outcome"),
              "unknown outcome \"" + std::string(outcome) + "\" (agree, depth_limit, subdivided)");
    q.outcome = AdaptiveSquare::Outcome(o);
    const Value ch = rd.array_at(jq, ip, "children");
    const Path cp = ip.key("children");
    if (ch.size() != 4) rd.fail(cp, "expected 4 children (-1 for none)");
    const bool split = q.outcome == AdaptiveSquare::Outcome::subdivided;
    for (int k = 0; k < 4; ++k)
      q.children[k] = int(split ? rd.integer(ch[k], cp.at(k), int64_t(i) + 1, int64_t(nsq) - 1)
                                : rd.integer(ch[k], cp.at(k), -1, -1));
    q.value = rd.vec_at(jq, ip, "value");
    if (q.parent >= 0) {
      const AdaptiveSquare& parent = s.squares[size_t(q.parent)];
      if (parent.outcome != AdaptiveSquare::Outcome::subdivided ||
          std::find(parent.children, parent.children + 4, int(i)) == parent.children + 4)
        rd.fail(ip.key("parent"), "square " + std::to_string(q.parent) + " does not list it as a child");
    }
    s.squares.push_back(q);
  }
  for (size_t i = 0; i < s.squares.size(); ++i)
    for (int c : s.squares[i].children)
      if (c >= 0 && s.squares[size_t(c)].parent != int(i))
        rd.fail(qp.at(size_t(c)).key("parent"), "expected " + std::to_string(i) + ", the square listing it");
  return p;
}

}  // namespace raystep::detail
