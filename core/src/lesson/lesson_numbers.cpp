// A lesson's numbers (lesson_numbers.h): the {{...}} tokens found outside code fences, their expressions
// parsed by muparser over the lesson facts, their literals read as a reader reads them (1,024, 40%, −0.75,
// 8.9e-08) with the tolerance their written digits state.
#include "raystep/lesson/lesson_numbers.h"

#include <muParser.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <regex>

#include "raystep/lesson/markdown_fence.h"
#include "raystep/lesson/lesson_facts.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

constexpr size_t kMaxExpression = 300;  // a number in a sentence; anything longer is not one

[[noreturn]] void fail(int line, const std::string& what) { throw InputError("", line, what); }

// Where `c` occurs in `s` outside "..." strings, searching from the end (last) or the start.
size_t find_outside_quotes(const std::string& s, char c, bool last) {
  size_t found = std::string::npos;
  bool quoted = false;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '"') quoted = !quoted;
    if (!quoted && s[i] == c) {
      found = i;
      if (!last) return i;
    }
  }
  return found;
}

// The position of the '=' that separates a checked number's literal: one not part of ==, <=, >= or !=.
size_t find_equals(const std::string& s) {
  bool quoted = false;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '"') quoted = !quoted;
    if (quoted || s[i] != '=') continue;
    const char before = i > 0 ? s[i - 1] : ' ', after = i + 1 < s.size() ? s[i + 1] : ' ';
    if (after == '=') {
      ++i;
      continue;
    }
    if (before == '<' || before == '>' || before == '!' || before == '=') continue;
    return i;
  }
  return std::string::npos;
}

bool valid_format(const std::string& f) {
  static const std::regex re(R"(,|%|\.[0-9]{1,2}[fge%])");
  return std::regex_match(f, re);
}

// A written literal: digits with thousands commas, a decimal point, an exponent, a leading minus (ASCII or
// U+2212) and a trailing %; its value and half a unit of its last written digit.
bool read_literal(std::string text, double* value, double* half_unit) {
  text = fence_trim(text);
  const std::string minus = "\xE2\x88\x92";  // U+2212
  if (text.compare(0, minus.size(), minus) == 0) text = "-" + text.substr(minus.size());
  double scale = 1.0;
  if (!text.empty() && text.back() == '%') {
    text = fence_trim(text.substr(0, text.size() - 1));
    scale = 0.01;
  }
  static const std::regex re(R"(([+-]?)([0-9]{1,3}(?:,[0-9]{3})+|[0-9]+)(?:\.([0-9]+))?(?:[eE]([+-]?[0-9]+))?)");
  std::smatch m;
  if (!std::regex_match(text, m, re)) return false;
  std::string digits = m[2].str();
  digits.erase(std::remove(digits.begin(), digits.end(), ','), digits.end());
  const std::string fraction = m[3].str();
  const int exponent = m[4].matched ? std::atoi(m[4].str().c_str()) : 0;
  const double mantissa = std::strtod((digits + (fraction.empty() ? "" : "." + fraction)).c_str(), nullptr);
  const double sign = m[1].str() == "-" ? -1.0 : 1.0;
  *value = sign * mantissa * std::pow(10.0, exponent) * scale;
  *half_unit = 0.5 * std::pow(10.0, exponent - int(fraction.size())) * scale;
  return true;
}

// The parser for one expression: fact names as variables, the fact functions taking a text.
struct Binding {
  LessonFacts* facts = nullptr;  // null while only checking the syntax
  std::string name;
};
double call_fact(void* data, const char* arg) {
  auto* b = static_cast<Binding*>(data);
  if (!b->facts) return 0.0;
  return b->facts->call(b->name, arg);
}
double cube_root(double x) { return std::cbrt(x); }

struct Expression {
  mu::Parser parser;
  std::vector<std::unique_ptr<Binding>> bindings;
  std::map<std::string, double> values;
  explicit Expression(const std::string& expr, LessonFacts* facts) {
    parser.DefineNameChars("0123456789_.abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ");
    parser.DefineFun("cbrt", cube_root);
    for (const LessonFactInfo& f : lesson_fact_list()) {
      if (!f.function) continue;
      bindings.push_back(std::make_unique<Binding>(Binding{facts, f.name}));
      parser.DefineFunUserData(f.name, call_fact, bindings.back().get(), false);
    }
    parser.SetExpr(expr);
  }
};

std::string mu_message(const mu::Parser::exception_type& e) { return e.GetMsg(); }

}  // namespace

namespace {

// The lines outside code fences in runs: each run's text (lines joined by '\n') and its lines' numbers, so
// that a number may wrap onto the next line of its paragraph.
struct Run {
  std::string text;
  std::vector<int> at;  // at[i]: the file line of the run's i-th line
  size_t first = 0;     // the run's first line in the input
};
std::vector<Run> runs_outside_fences(const std::vector<std::string>& lines, const std::vector<int>& at) {
  std::vector<Run> runs;
  Fence open;
  bool fenced = false, in_run = false;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (fenced) {
      if (fence_closes(open, line)) fenced = false;
      continue;
    }
    if (fence_of(line, &open)) {
      fenced = true;
      in_run = false;
      continue;
    }
    if (!in_run) {
      runs.push_back(Run{"", {}, i});
      in_run = true;
    } else {
      runs.back().text += '\n';
    }
    runs.back().text += line;
    runs.back().at.push_back(i < at.size() ? at[i] : 0);
  }
  return runs;
}

// The {{...}} tokens of a run: [begin, end) offsets; throws InputError("", line, ...) for an unclosed one.
std::vector<std::pair<size_t, size_t>> tokens_of(const Run& run) {
  std::vector<std::pair<size_t, size_t>> out;
  auto line_at = [&](size_t offset) {
    return run.at[size_t(std::count(run.text.begin(), run.text.begin() + long(offset), '\n'))];
  };
  for (size_t b = run.text.find("{{"); b != std::string::npos; b = run.text.find("{{", b)) {
    const size_t e = run.text.find("}}", b + 2);
    const size_t para = run.text.find("\n\n", b);
    if (e == std::string::npos || (para != std::string::npos && para < e))
      fail(line_at(b), "'{{' without its '}}' in the same paragraph");
    out.push_back({b, e + 2});
    b = e + 2;
  }
  return out;
}

}  // namespace

std::vector<LessonNumber> scan_lesson_numbers(const std::vector<std::string>& lines, const std::vector<int>& at) {
  std::vector<LessonNumber> numbers;
  for (const Run& run : runs_outside_fences(lines, at)) {
    for (const auto& [b, end] : tokens_of(run)) {
      const size_t e = end - 2;
      const std::string& line = run.text;
      const int line_no = run.at[size_t(std::count(run.text.begin(), run.text.begin() + long(b), '\n'))];
      LessonNumber n;
      n.line = line_no;
      n.token = line.substr(b, e + 2 - b);
      std::replace(n.token.begin(), n.token.end(), '\n', ' ');  // shown in messages on one line
      std::string inner = line.substr(b + 2, e - b - 2);
      std::replace(inner.begin(), inner.end(), '\n', ' ');
      const size_t eq = find_equals(inner);
      if (eq != std::string::npos) {
        n.checked = true;
        n.expr = fence_trim(inner.substr(0, eq));
        std::string literal = fence_trim(inner.substr(eq + 1));
        const std::string pm = "\xC2\xB1";  // ±
        const size_t p = literal.find(pm);
        double half_unit = 0;
        const std::string value_text = fence_trim(literal.substr(0, p));
        if (!read_literal(value_text, &n.expected, &half_unit))
          fail(line_no, n.token + ": '" + value_text + "' is not a number as written (e.g. 1,024, 0.41, 40%, 8.9e-08)");
        n.written = value_text;
        n.tolerance = half_unit;
        if (p != std::string::npos) {
          std::string tol = fence_trim(literal.substr(p + pm.size()));
          const bool relative = !tol.empty() && tol.back() == '%';
          double t = 0, unused = 0;
          if (!read_literal(tol, &t, &unused) || t < 0)
            fail(line_no, n.token + ": '" + tol + "' is not a tolerance (e.g. ± 0.05 or ± 5%)");
          n.tolerance = relative ? t * std::abs(n.expected) : t;
        }
      } else {
        const size_t colon = find_outside_quotes(inner, ':', true);
        if (colon != std::string::npos && valid_format(fence_trim(inner.substr(colon + 1)))) {
          n.format = fence_trim(inner.substr(colon + 1));
          inner = inner.substr(0, colon);
        }
        n.expr = fence_trim(inner);
      }
      if (n.expr.empty()) fail(line_no, n.token + ": no expression");
      if (n.expr.size() > kMaxExpression)
        fail(line_no, "a number's expression of " + std::to_string(n.expr.size()) + " characters, more than " +
                          std::to_string(kMaxExpression));
      try {
        Expression x(n.expr, nullptr);
        for (const auto& [name, unused] : x.parser.GetUsedVar()) {
          const LessonFactInfo* f = find_lesson_fact(name);
          if (!f || f->function)
            fail(line_no, n.token + ": '" + name + "' is no lesson fact (`raystep lesson facts` lists them)");
          n.costly = n.costly || f->costly;
        }
      } catch (const mu::Parser::exception_type& ex) {
        fail(line_no, n.token + ": " + mu_message(ex));
      }
      for (const LessonFactInfo& f : lesson_fact_list())
        if (f.function && f.costly && n.expr.find(f.name + "(") != std::string::npos) n.costly = true;
      if (n.costly && !n.checked)
        fail(line_no, n.token + ": a report's number is written out and checked ({{EXPR = VALUE}}): the "
                                "presenter does not run reports");
      numbers.push_back(std::move(n));
    }
  }
  return numbers;
}

double evaluate_lesson_number(const LessonNumber& number, LessonFacts& facts) {
  try {
    Expression x(number.expr, &facts);
    for (const auto& [name, unused] : x.parser.GetUsedVar()) x.values[name] = facts.value(name);
    for (auto& [name, value] : x.values) x.parser.DefineVar(name, &value);
    const double v = x.parser.Eval();
    if (!std::isfinite(v)) throw InputError("", 0, number.token + ": the value is not finite");
    return v;
  } catch (const mu::Parser::exception_type& ex) {
    throw InputError("", 0, number.token + ": " + mu_message(ex));
  } catch (const InputError& e) {
    throw InputError("", 0, number.token + ": " + e.detail());
  }
}

bool lesson_number_agrees(const LessonNumber& number, double value) {
  // A hair above the tolerance, so that 0.4135 written for 0.41350000001 agrees.
  return std::abs(value - number.expected) <= number.tolerance * (1 + 1e-9) + 1e-300;
}

std::string format_lesson_number(double value, const std::string& format) {
  char buf[64];
  auto thousands = [](double v) {
    char digits[64];
    std::snprintf(digits, sizeof digits, "%.0f", std::abs(v));
    std::string d = digits, out;
    for (size_t i = 0; i < d.size(); ++i) {
      if (i > 0 && (d.size() - i) % 3 == 0) out += ',';
      out += d[i];
    }
    return (v < 0 && std::round(v) != 0 ? "\xE2\x88\x92" : "") + out;  // a typographic minus, as written
  };
  auto minus = [](std::string s) {
    if (!s.empty() && s[0] == '-') s = "\xE2\x88\x92" + s.substr(1);
    return s;
  };
  if (format.empty()) {
    if (std::abs(value) < 1e15 && value == std::round(value)) return thousands(value);
    std::snprintf(buf, sizeof buf, "%.3g", value);
    return minus(buf);
  }
  if (format == ",") return thousands(value);
  if (format == "%") return thousands(value * 100) + "%";
  const char kind = format.back();
  const int digits = std::atoi(format.c_str() + 1);
  if (kind == '%') {
    std::snprintf(buf, sizeof buf, "%.*f%%", digits, value * 100);
    return minus(buf);
  }
  const char spec[] = {'%', '.', '*', kind, 0};
  std::snprintf(buf, sizeof buf, spec, digits, value);
  return minus(buf);
}

std::string shown_lesson_number(const LessonNumber& number, double value) {
  return number.checked ? number.written : format_lesson_number(value, number.format);
}

std::string fill_lesson_numbers(const std::string& markdown, const std::vector<std::string>& shown) {
  std::vector<std::string> lines;
  size_t pos = 0;
  while (pos <= markdown.size()) {
    size_t end = markdown.find('\n', pos);
    if (end == std::string::npos) end = markdown.size();
    lines.push_back(markdown.substr(pos, end - pos));
    pos = end + 1;
  }
  const bool final_newline = !markdown.empty() && markdown.back() == '\n';
  if (final_newline) lines.pop_back();
  // Each run's tokens replaced, the run put back in place of its lines.
  std::vector<std::string> out_lines = lines;
  std::vector<bool> dropped(lines.size(), false);
  size_t next = 0;
  for (const Run& run : runs_outside_fences(lines, {})) {
    std::vector<std::pair<size_t, size_t>> tokens;
    try {
      tokens = tokens_of(Run{run.text, std::vector<int>(run.at.size(), 0), run.first});
    } catch (const InputError&) {
      continue;  // scan_lesson_numbers has refused such a text already
    }
    if (tokens.empty()) continue;
    std::string filled;
    size_t from = 0;
    for (const auto& [b, e] : tokens) {
      if (next >= shown.size()) break;
      filled += run.text.substr(from, b - from) + shown[next++];
      from = e;
    }
    filled += run.text.substr(from);
    out_lines[run.first] = filled;
    for (size_t i = 1; i < run.at.size(); ++i) dropped[run.first + i] = true;
  }
  std::string out;
  bool first = true;
  for (size_t i = 0; i < out_lines.size(); ++i) {
    if (dropped[i]) continue;
    if (!first) out += '\n';
    first = false;
    out += out_lines[i];
  }
  if (final_newline) out += '\n';
  return out;
}

}  // namespace raystep
