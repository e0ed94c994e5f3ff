// The JSON tape against nlohmann-json's DOM, which it stands in for: on every text, hand-made edge cases and
// random mutations of a trace, JsonTape::parse (nlohmann's SAX parser filling the tape) gives the same
// values, number kinds and member order as nlohmann::json::parse, or throws the same exception with the same
// message and byte.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include <nlohmann/json.hpp>

#include "raystep/scene/json_tape.h"

namespace raystep {
namespace {

using nlohmann::json;

// Empty when equal, else where they differ.
std::string compare(const JsonValue& v, const json& j, const std::string& at = "/") {
  using K = JsonValue::Kind;
  auto kind_of = [](const json& x) {
    switch (x.type()) {
      case json::value_t::null:
        return K::null;
      case json::value_t::boolean:
        return K::boolean;
      case json::value_t::number_integer:
        return K::number_integer;
      case json::value_t::number_unsigned:
        return K::number_unsigned;
      case json::value_t::number_float:
        return K::number_float;
      case json::value_t::string:
        return K::string;
      case json::value_t::array:
        return K::array;
      case json::value_t::object:
        return K::object;
      default:
        return K::null;
    }
  };
  if (!v.exists()) return at + ": absent";
  if (v.kind() != kind_of(j)) return at + ": kind differs (" + j.dump() + ")";
  switch (v.kind()) {
    case K::boolean:
      if (v.get_bool() != j.get<bool>()) return at + ": boolean differs";
      break;
    case K::number_integer:
    case K::number_unsigned:
      if (v.get_int64() != j.get<int64_t>()) return at + ": integer differs";
      break;
    case K::number_float: {
      double a = v.get_double(), b = j.get<double>();
      if (std::memcmp(&a, &b, sizeof a) != 0) return at + ": double differs (" + j.dump() + ")";
      break;
    }
    case K::string:
      if (v.get_string() != j.get<std::string>()) return at + ": string differs";
      break;
    case K::array:
      if (v.size() != j.size()) return at + ": array size differs";
      for (size_t i = 0; i < v.size(); ++i) {
        std::string d = compare(v[i], j[i], at + std::to_string(i) + "/");
        if (!d.empty()) return d;
      }
      break;
    case K::object: {
      auto members = v.members();
      if (members.size() != j.size()) return at + ": member count differs";
      size_t i = 0;
      for (auto it = j.begin(); it != j.end(); ++it, ++i) {
        if (members[i].first != it.key()) return at + ": key " + it.key() + " differs";
        if (!v.contains(it.key())) return at + ": find misses " + it.key();
        std::string d = compare(v.find(it.key()), it.value(), at + it.key() + "/");
        if (!d.empty()) return d;
        d = compare(members[i].second, it.value(), at + it.key() + "/");
        if (!d.empty()) return d;
      }
      if (v.find("no such key \x01").exists()) return at + ": found a key that is not there";
      break;
    }
    case K::null:
      break;
  }
  return "";
}

// The outcome of nlohmann's parse and of the tape's, in words: equal words, equal outcomes.
std::string outcome(const std::string& text) {
  json dom;
  std::string expected;
  try {
    dom = json::parse(text);
  } catch (const json::parse_error& e) {
    expected = "parse_error " + std::to_string(e.byte) + " " + e.what();
  } catch (const json::exception& e) {
    expected = std::string("exception ") + e.what();
  }
  std::string got;
  try {
    JsonTape tape = JsonTape::parse(text);
    if (!expected.empty()) return "tape accepted what nlohmann refuses: " + expected;
    std::string d = compare(tape.root(), dom);
    return d.empty() ? "same" : d;
  } catch (const json::parse_error& e) {
    got = "parse_error " + std::to_string(e.byte) + " " + e.what();
  } catch (const json::out_of_range& e) {
    got = std::string("exception ") + e.what();
  }
  return got == expected ? "same" : "tape: " + got + " | nlohmann: " + expected;
}

void expect_same(const std::string& text) {
  EXPECT_EQ(outcome(text), "same") << text;
}

TEST(JsonTape, EdgeCasesReadAsNlohmannReadsThem) {
  const char* cases[] = {
      // numbers: kinds, signs, limits, overflow and underflow, grammar errors
      "0", "-0", "1", "-1", "0.0", "-0.0", "1e0", "1E+2", "1e-2", "3.4028234663852886e38", "0.1",
      "1.7976931348623157e308", "1.7976931348623159e308", "1e400", "-1e400", "1e-400", "4.9e-324",
      "2.2250738585072014e-308", "1e-310", "0.000000000000000000000000000000000000000000000001",
      "18446744073709551615", "18446744073709551616", "9223372036854775807", "9223372036854775808",
      "-9223372036854775808", "-9223372036854775809", "123456789012345678901234567890", "0.36198219656944275",
      "01", "-01", "1.", ".5", "+1", "-", "1e", "1e+", "--1", "0x10", "1.5e3.2", "Infinity", "NaN", "[1,]",
      "[,1]", "[1 2]", "1 2",
      // literals
      "true", "false", "null", "tru", "nul", "truex", "[true,false,null]", "True",
      // strings: escapes, unicode, control characters, invalid UTF-8
      "\"\"", "\"abc\"", "\"a\\\"b\"", "\"\\u0041\\n\\t\\/\"", "\"\\ud83d\\ude00\"", "\"\\ud83d\"", "\"\\x\"",
      "\"caf\xc3\xa9\"", "\"\xff\"", "\"\xc3\"", "\"a\tb\"", "\"a\x01\"", "\"\x7f\"", "\"abc", "\"",
      "\"\xc0\x80\"", "\"\xc1\xbf\"", "\"\xe0\x80\x80\"", "\"\xe0\xa0\x80\"", "\"\xed\xa0\x80\"",
      "\"\xed\x9f\xbf\"", "\"\xf0\x8f\xbf\xbf\"", "\"\xf0\x90\x80\x80\"", "\"\xf4\x8f\xbf\xbf\"",
      "\"\xf4\x90\x80\x80\"", "\"\xf5\x80\x80\x80\"", "\"\xe2\x82\"", "\"\xe2\x82", "\"\x80\"", "\"\\",
      "\"\\\"", "\"a\\qb\"", "\"\\u12\"", "\"\\ud800\\udc00\"",
      // containers, nesting, duplicate keys, key order, whitespace, BOM, trailing text
      "{}", "[]", "[[]]", "{\"a\":{}}", "{\"b\":1,\"a\":2}", "{\"a\":1,\"a\":2}",
      "{\"a\":1,\"b\":2,\"a\":[3]}", "{\"\":0}", "{\"a\"}", "{\"a\":}", "{\"a\" 1}", "{1:2}", "{\"a\":1,}",
      "{,}", "[", "]", "{", "}", "", " ", " \t\r\n[ 1 , { \"k\" : [ ] } ] \n", "\xef\xbb\xbf[1]",
      "\xef\xbb[1]", "[1]x", "[1] ]", "[1]\0", "{\"a\":1}{}", "[\"a\",\"\\u00e9\",\"z\"]",
      "{\"\xc3\xa9\":1,\"z\":2,\"a\":3}", "{\"B\":1,\"a\":2,\"_\":3}",
      "[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]", "/* c */ 1", "[1,2,3,\"inf\",\"-inf\",-1.5e-7]"};
  for (const char* c : cases) expect_same(c);
  expect_same(std::string("[1]\0", 4));
  expect_same(std::string("\"a\0b\"", 5));
  // Deep nesting: no recursion, no limit.
  expect_same(std::string(1000, '[') + std::string(1000, ']'));
  expect_same(std::string(100000, '['));
  JsonTape deep = JsonTape::parse(std::string(100000, '[') + std::string(100000, ']'));
  JsonValue v = deep.root();
  for (int depth = 1; depth < 100000; ++depth) {
    ASSERT_EQ(v.size(), 1u);
    v = v[0];
  }
  EXPECT_TRUE(v.is_array());
  EXPECT_EQ(v.size(), 0u);
}

TEST(JsonTape, RandomMutationsOfATraceReadAsNlohmannReadsThem) {
  const std::string base =
      "{\n \"format\": \"raystep-trace\",\n \"version\": 1,\n \"scene\": "
      "{\"path\":\"a\",\"hash\":\"b\",\"primitives\":2},\n"
      " \"structure\": {\"kind\":\"grid\",\"bounds_min\":[0.0,-1.0,0.0],\"bounds_max\":[3.0,2.0,1.0],"
      "\"resolution\":[3,1,1],\"density\":3.0,\"insert\":\"exact\",\"references\":4.0},\n"
      " \"rays\": [\n  {\"origin\":[-1.0,0.5,0.5],\"direction\":[1.0,0.0,0.0],\"tmin\":0.0,\"tmax\":\"inf\","
      "\"kind\":\"primary\",\"depth\":0,\"pixel\":[12,7],\n   \"events\": [\n"
      "    {\"seq\":0,\"type\":\"ray_begin\"},\n"
      "    "
      "{\"seq\":1,\"type\":\"cell\",\"cell\":[0,0,0],\"t_enter\":1.0,\"t_exit\":2.0,\"t_max\":[2.0,\"inf\","
      "\"inf\"],"
      "\"t_delta\":[1.0,\"inf\",\"inf\"],\"next_axis\":\"x\"},\n"
      "    {\"seq\":2,\"type\":\"prim_test\",\"prim\":0,\"hit\":true,\"t\":3.5},\n"
      "    {\"seq\":3,\"type\":\"ray_end\",\"prim\":1,\"t\":2.5e-3}\n   ]}\n ],\n"
      " \"geometry\": {\"cells\": [], \"primitives\": "
      "[{\"id\":0,\"type\":\"triangle\",\"vertices\":[[0.0,-1.0,0.0],"
      "[0.0,2.0,0.0],[3.0,0.5,0.6000000238418579]]}]}\n}\n";
  expect_same(base);
  const std::string alphabet =
      "{}[],:\"\\ 0123456789.-+eE\ntrufalsnbu/\x01\x7f\xc3\xa9\xe2\x82\xac\xed\xa0\xf0\x9f\xff";
  std::mt19937 rng(12345);
  int valid = 0;
  const int trials = 4000;
  for (int trial = 0; trial < trials; ++trial) {
    std::string text = base;
    int edits = 1 + int(rng() % 3);
    for (int k = 0; k < edits && !text.empty(); ++k) {
      size_t at = rng() % text.size();
      char c = alphabet[rng() % alphabet.size()];
      switch (rng() % 4) {
        case 0:
          text[at] = c;
          break;
        case 1:
          text.erase(at, 1 + rng() % 4);
          break;
        case 2:
          text.insert(at, 1, c);
          break;
        case 3:
          text.resize(at);
          break;
      }
    }
    ASSERT_EQ(outcome(text), "same") << text;
    valid += nlohmann::json::accept(text);
  }
  EXPECT_GT(valid, trials / 20);  // some mutations stay valid JSON: values are compared, not only errors
}

// Streaming: the arrays the handler asks for never enter the tape; each element reaches the handler as it is
// parsed, equal to what the whole document's DOM holds there, with the indices of the arrays around it; the
// rest of the tape is as without streaming. From a file, the same.
struct Collect final : JsonStreamHandler {
  std::vector<std::string> paths;
  std::vector<std::pair<std::vector<size_t>, json>> elements;
  std::vector<std::pair<size_t, size_t>> ends;
  std::vector<size_t> arrays;
  bool stream(std::string_view path) override {
    paths.emplace_back(path);
    return path == "rays[].events" || path == "walks[].rays[].events";
  }
  void element(size_t array, const std::vector<size_t>& where, const JsonValue& v) override {
    arrays.push_back(array);
    // The element as text, parsed back: compare() against the DOM below.
    json j = json::parse(dump(v));
    elements.emplace_back(where, j);
  }
  void end(size_t array, size_t count) override { ends.emplace_back(array, count); }
  static std::string dump(const JsonValue& v) {
    using K = JsonValue::Kind;
    switch (v.kind()) {
      case K::null:
        return "null";
      case K::boolean:
        return v.get_bool() ? "true" : "false";
      case K::number_integer:
      case K::number_unsigned:
        return std::to_string(v.get_int64());
      case K::number_float:
        return json(v.get_double()).dump();
      case K::string:
        return json(std::string(v.get_string())).dump();
      case K::array: {
        std::string s = "[";
        for (size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + dump(v[i]);
        return s + "]";
      }
      case K::object: {
        std::string s = "{";
        bool first = true;
        for (const auto& [k, m] : v.members())
          s += (first ? "" : ",") + json(std::string(k)).dump() + ":" + dump(m), first = false;
        return s + "}";
      }
    }
    return "";
  }
};

TEST(JsonTape, StreamedArraysReachTheHandlerElementByElement) {
  const std::string text =
      R"({"format":"x","rays":[{"o":1,"events":[{"seq":0,"a":[1,2,{"b":null}]},7,"s",[3]]},)"
      R"({"events":[],"x":{"events":[1]}}],"walks":[{"rays":[{"events":[{"k":true}]}]}],"events":[9]})";
  const json dom = json::parse(text);
  Collect c;
  JsonTape tape = JsonTape::parse(text, &c);
  // Only the two paths asked for are streamed: rays[].x.events and the top-level events are kept.
  ASSERT_EQ(c.elements.size(), 5u);
  EXPECT_EQ(c.elements[0].first, (std::vector<size_t>{0, 0}));
  EXPECT_EQ(c.elements[0].second, dom["rays"][0]["events"][0]);
  EXPECT_EQ(c.elements[1].second, dom["rays"][0]["events"][1]);
  EXPECT_EQ(c.elements[2].second, dom["rays"][0]["events"][2]);
  EXPECT_EQ(c.elements[3].first, (std::vector<size_t>{0, 3}));
  EXPECT_EQ(c.elements[3].second, dom["rays"][0]["events"][3]);
  EXPECT_EQ(c.elements[4].first, (std::vector<size_t>{0, 0, 0}));
  EXPECT_EQ(c.elements[4].second, dom["walks"][0]["rays"][0]["events"][0]);
  EXPECT_EQ(c.ends, (std::vector<std::pair<size_t, size_t>>{{0, 4}, {1, 0}, {2, 1}}));
  EXPECT_EQ(c.arrays, (std::vector<size_t>{0, 0, 0, 0, 2}));
  const JsonValue root = tape.root();
  const JsonValue events = root.find("rays")[0].find("events");
  EXPECT_TRUE(events.is_streamed());
  EXPECT_EQ(events.stream_number(), 0u);
  EXPECT_EQ(events.size(), 4u);
  EXPECT_FALSE(events[0].exists());
  EXPECT_EQ(root.find("rays")[1].find("events").stream_number(), 1u);
  EXPECT_FALSE(root.find("rays")[1].find("x").find("events").is_streamed());
  EXPECT_EQ(root.find("rays")[1].find("x").find("events")[0].get_int64(), 1);
  EXPECT_EQ(root.find("events")[0].get_int64(), 9);
  EXPECT_EQ(root.find("rays")[0].find("o").get_int64(), 1);
  EXPECT_EQ(root.find("format").get_string(), "x");
  // From a file: the same elements and the same tape.
  const std::string path = ::testing::TempDir() + "/json_tape_stream.json";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  Collect fc;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr);
  JsonTape from_file = JsonTape::parse_file(f, &fc);
  std::fclose(f);
  EXPECT_EQ(fc.elements, c.elements);
  EXPECT_EQ(fc.ends, c.ends);
  EXPECT_EQ(Collect::dump(from_file.root().find("walks")), Collect::dump(root.find("walks")));
  // A bad text throws as without streaming, at the same byte.
  Collect b;
  const std::string bad = R"({"rays":[{"events":[{"a":1},{"a":]}]})";
  size_t expected_byte = 0;
  try {
    const json parsed = json::parse(bad);
    ADD_FAILURE() << "the damaged text parsed: " << parsed.dump();
  } catch (const json::parse_error& e) {
    expected_byte = e.byte;
  }
  try {
    JsonTape::parse(bad, &b);
    ADD_FAILURE() << "no error";
  } catch (const json::parse_error& e) {
    EXPECT_EQ(e.byte, expected_byte);
  }
  EXPECT_EQ(b.elements.size(), 1u);
}

}  // namespace
}  // namespace raystep
