// Tests of validation/json_reader.h: every message names the file, the JSON path, the value and
// the allowed range; unknown keys fail.
#include "vgroove/support/json_reader.h"

#include "tests/test_files.h"
#include "tests/user_error_of.h"

#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <utility>

namespace vgroove::support {
namespace {

using nlohmann::json;
using testing_files::TempDir;
using testing_files::user_error_of;
using testing_files::write_text;

TEST(JsonObject, ReadsRequiredAndOptionalValues) {
  const json j = json::parse(R"({"name": "x", "n": 3, "v": 0.5, "sub": {"a": 1}, "pick": "b"})");
  JsonObject o(j, "f.json", "");
  EXPECT_EQ(o.string("name"), "x");
  EXPECT_EQ(o.integer("n", 1, 10), 3);
  EXPECT_EQ(o.number("v", 0.0, false, 1.0, true), 0.5);
  EXPECT_EQ(o.string_or("absent", "dflt"), "dflt");
  EXPECT_EQ(o.number_or("absent2", 7.0, 0.0, true, 10.0, true), 7.0);
  EXPECT_EQ(o.integer_or("absent3", 4, 0, 10), 4);
  EXPECT_EQ(o.one_of("pick", {"a", "b"}), "b");
  JsonObject sub = o.object("sub");
  EXPECT_EQ(sub.pointer(), "/sub");
  EXPECT_EQ(sub.integer("a", 0, 1), 1);
  sub.finish();
  EXPECT_NO_THROW(o.finish());
}

// A path with a NUL byte (Python strings may hold one) is refused, not opened up to the NUL (the
// file "a" here, which exists), and named whole: the NUL as the text \x00, not the end of what().
TEST(JsonFile, APathWithANulByteIsRefusedAndNamedWhole) {
  TempDir dir;
  const std::string a = dir.file("a");
  write_text(a, "{}");
  EXPECT_EQ(user_error_of([&] { read_json_file(a + '\0' + "b.json"); }),
            a + "\\x00b.json: a file name cannot hold a NUL byte");
}

TEST(JsonObject, MissingRequiredKeyNamesFileAndPath) {
  const json j = json::parse(R"({"groove": {}})");
  JsonObject o(j, "s.json", "");
  JsonObject g = o.object("groove");
  const std::string m = user_error_of([&] { g.string("type"); });
  EXPECT_CONTAINS(m, "s.json: /groove/type");
  EXPECT_CONTAINS(m, "missing");
}

TEST(JsonObject, OutOfRangeNumberNamesValueAndRange) {
  const json j = json::parse(R"({"t": {"x": 195}})");
  JsonObject o(j, "s.json", "");
  JsonObject t = o.object("t");
  const std::string m = user_error_of([&] { t.number("x", 0.0, false, 180.0, true); });
  EXPECT_CONTAINS(m, "s.json: /t/x = 195 is out of range (0, 180]");
}

TEST(JsonObject, OpenAndClosedBoundsAreRespected) {
  const json j = json::parse(R"({"lo": 0, "hi": 180, "neg": -90})");
  JsonObject o(j, "s.json", "");
  EXPECT_CONTAINS(user_error_of([&] { o.number("lo", 0.0, false, 180.0, true); }), "(0, 180]");
  EXPECT_EQ(o.number("hi", 0.0, false, 180.0, true), 180.0);
  EXPECT_CONTAINS(user_error_of([&] { o.number("neg", -90.0, false, 90.0, false); }),
                  "/neg = -90 is out of range (-90, 90)");
  EXPECT_EQ(o.number("lo", 0.0, true, 1.0, true), 0.0);
}

TEST(JsonObject, WrongTypesAreNamed) {
  const json j = json::parse(R"({"s": 3, "n": "three", "i": 2.5, "o": [1]})");
  JsonObject o(j, "s.json", "");
  EXPECT_CONTAINS(user_error_of([&] { o.string("s"); }), "s.json: /s = 3 must be a string");
  EXPECT_CONTAINS(user_error_of([&] { o.number("n", 0, true, 1, true); }), "s.json: /n = \"three\" must be a number");
  EXPECT_CONTAINS(user_error_of([&] { o.integer("i", 0, 10); }), "s.json: /i = 2.5 must be an integer");
  EXPECT_CONTAINS(user_error_of([&] { o.object("o"); }), "s.json: /o must be a JSON object, found array");
}

TEST(JsonObject, IntegerRangeIncludesHugeUnsignedValues) {
  const json j = json::parse(R"({"big": 18446744073709551615, "neg": -1})");
  JsonObject o(j, "s.json", "");
  EXPECT_CONTAINS(user_error_of([&] { o.integer("big", 1, 1000); }),
                  "/big = 18446744073709551615 is out of range [1, 1000]");
  EXPECT_CONTAINS(user_error_of([&] { o.integer("neg", 1, 1000); }), "/neg = -1 is out of range [1, 1000]");
}

TEST(JsonObject, OneOfListsTheAllowedValues) {
  const json j = json::parse(R"({"sampling": "stratifed"})");
  JsonObject o(j, "s.json", "");
  EXPECT_CONTAINS(user_error_of([&] {
                    o.one_of("sampling", {"stratified", "random"});
                  }),
                  "s.json: /sampling = \"stratifed\" is not one of \"stratified\", \"random\"");
}

TEST(JsonObject, UnknownKeyFailsOnFinish) {
  const json j = json::parse(R"({"roughness": 0.1, "roughnes": 0.2})");
  JsonObject o(j, "s.json", "/m");
  o.number_or("roughness", 0.0, 0.0, true, 1.0, true);
  const std::string m = user_error_of([&] { o.finish(); });
  EXPECT_CONTAINS(m, "s.json: /m/roughnes is not a known key");
  EXPECT_CONTAINS(m, "roughness");  // the keys that are known here
}

TEST(JsonObject, AskedAboutButAbsentKeysAreKnown) {
  // An optional key that was looked up and absent does not make finish() fail, and a key that
  // was asked about but absent is listed among the known ones.
  const json j = json::parse(R"({"a": 1, "zzz": 2})");
  JsonObject o(j, "s.json", "");
  o.integer("a", 0, 5);
  o.integer_or("b", 0, 0, 5);
  const std::string m = user_error_of([&] { o.finish(); });
  EXPECT_CONTAINS(m, "/zzz is not a known key");
  EXPECT_CONTAINS(m, "a, b");
}

TEST(ReadJsonFile, MissingFileIsNamed) {
  TempDir dir;
  const std::string f = dir.file("nope.json");
  const std::string m = user_error_of([&] { read_json_file(f); });
  EXPECT_CONTAINS(m, f + ": cannot open");
}

TEST(ReadJsonFile, InvalidJsonIsNamed) {
  TempDir dir;
  const std::string f = dir.file("bad.json");
  write_text(f, "{\"name\": \"x\",, }");
  const std::string m = user_error_of([&] { read_json_file(f); });
  EXPECT_CONTAINS(m, f + ": not valid JSON");
}

TEST(ParseJsonText, DuplicateKeysAreNamedWithTheirPath) {
  EXPECT_CONTAINS(user_error_of([] { parse_json_text(R"({"rays": 1000, "x": 1, "rays": 5})", "f.json"); }),
                  "f.json: /rays is given twice");
  EXPECT_CONTAINS(user_error_of([] { parse_json_text(R"({"a": [0, {"b": {"c": 1, "c": 1}}]})", "f.json"); }),
                  "f.json: /a/1/b/c is given twice");
  EXPECT_CONTAINS(user_error_of([] { parse_json_text(R"({"a/b~": {"k": 1, "k": 2}})", "f.json"); }),
                  "/a~1b~0/k is given twice");
  // The same key in different objects is fine.
  EXPECT_EQ(parse_json_text(R"({"a": {"k": 1}, "b": {"k": 2}, "c": [{"k": 3}, {"k": 4}]})", "f.json")["c"][1]["k"], 4);
}

TEST(ParseJsonText, NestingIsBounded) {
  const auto deep = [](int n) {
    return std::string(static_cast<std::size_t>(n), '[') + std::string(static_cast<std::size_t>(n), ']');
  };
  EXPECT_NO_THROW(parse_json_text(deep(kMaxJsonDepth), "f.json"));
  const std::string m = user_error_of([&] { parse_json_text(deep(kMaxJsonDepth + 1), "f.json"); });
  EXPECT_CONTAINS(m, "is nested more than 64 levels deep");
  EXPECT_LT(m.size(), 400u);
  // 10^5 levels (the crash of the issue): refused quickly, a short message.
  const std::string m2 = user_error_of([&] { parse_json_text("{\"rays\": " + deep(100000) + "}", "f.json"); });
  EXPECT_CONTAINS(m2, "f.json: /rays/0/0/0");
  EXPECT_LT(m2.size(), 400u);
}

TEST(ParseJsonText, NumbersPastTheDoubleRangeAreNotJson) {
  EXPECT_CONTAINS(user_error_of([] { parse_json_text(R"({"rays": 1e400})", "f.json"); }), "f.json: not valid JSON");
  EXPECT_CONTAINS(user_error_of([] { parse_json_text(R"([-1e400])", "f.json"); }), "not valid JSON");
}

TEST(ReadJsonFile, DirectoriesAndHugeFilesAreRefused) {
  TempDir dir;
  EXPECT_CONTAINS(user_error_of([&] { read_json_file(dir.path().string()); }), "is a directory");
  // /dev/zero never ends: the read stops at the limit.
  EXPECT_CONTAINS(user_error_of([] { read_json_file("/dev/zero"); }), "is larger than 64 MB");
}

TEST(ValueText, IsShortAndOnOneLine) {
  EXPECT_EQ(value_text(json(5)), "5");
  EXPECT_EQ(value_text(json("a\nb")), "\"a\\nb\"");
  EXPECT_EQ(value_text(json::parse(R"({"a": [1, 2]})")), R"({"a": [1, 2]})");
  json big = json::array();
  for (int i = 0; i < 100000; ++i) big.push_back(i);
  EXPECT_LE(value_text(big).size(), 63u);
  EXPECT_EQ(value_text(json(std::string(1000, 'x'))).size(), 63u);
  json deep = json::array();
  for (int i = 0; i < 10000; ++i) {  // each level moved in, not copied (a copy makes this O(n^2))
    json next = json::array();
    next.push_back(std::move(deep));
    deep = std::move(next);
  }
  EXPECT_LE(value_text(deep).size(), 63u);  // bounded recursion: stops with the budget
}

TEST(NumberText, ShortestRoundTrip) {
  EXPECT_EQ(number_text(195.0), "195");
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(-89.9), "-89.9");
  EXPECT_EQ(std::stod(number_text(std::numbers::pi)), std::numbers::pi);
  EXPECT_EQ(interval_text(0, false, 180, true), "(0, 180]");
  EXPECT_EQ(interval_text(-90, false, 90, false), "(-90, 90)");
  EXPECT_EQ(interval_text(1, true, 2.5, true), "[1, 2.5]");
}

}  // namespace
}  // namespace vgroove::support
