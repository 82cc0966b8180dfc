// io: JSON configuration loading, --set overrides and ConfigNode's typed, path-naming access.
#include <gtest/gtest.h>

#include "input_error.hpp"
#include "scratch_dir.hpp"

#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "anisodyn/core/error.hpp"
#include "anisodyn/tool/json_config.hpp"

using namespace anisodyn;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

class JsonFiles : public anisodyn::testing_support::ScratchDirTest {
 protected:
  JsonFiles() : ScratchDirTest("io-json") {}
  std::string write(const std::string& name, const std::string& content) const {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << content;
    return path;
  }
  std::string dir_;
};

using anisodyn::testing_support::input_error;

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

}  // namespace

// ---- loading -----------------------------------------------------------------------------------------

TEST_F(JsonFiles, LoadsValidFile) {
  const auto path = write("ok.json", R"({"a": 1, "b": [1, 2]})");
  const json j = tool::load_json_file(path);
  EXPECT_EQ(j["a"], 1);
  EXPECT_EQ(j["b"].size(), 2u);
}

TEST_F(JsonFiles, MalformedFileNamesLineAndColumn) {
  const auto path = write("bad.json", "{\n  \"a\": 1,\n  \"b\": ,\n  \"c\": 3\n}\n");
  const InputError e = input_error([&] { tool::load_json_file(path); });
  EXPECT_EQ(e.file(), path);
  const std::string msg = e.what();
  EXPECT_TRUE(contains(msg, path + ": invalid JSON at line 3, column 8:")) << msg;
  EXPECT_FALSE(contains(msg, "[json.exception")) << msg;
}

TEST_F(JsonFiles, TruncatedFileNamesLastLine) {
  const auto path = write("trunc.json", "{\n  \"a\": [1, 2,\n");
  const std::string msg = input_error([&] { tool::load_json_file(path); }).what();
  EXPECT_TRUE(contains(msg, "invalid JSON at line 3")) << msg;
}

TEST_F(JsonFiles, MissingFileSaysCannotOpen) {
  const InputError e = input_error([&] { tool::load_json_file(dir_ + "/nope.json"); });
  EXPECT_EQ(e.file(), dir_ + "/nope.json");
  EXPECT_TRUE(contains(e.what(), "cannot open file: No such file or directory")) << e.what();
  EXPECT_TRUE(contains(input_error([&] { tool::load_json_file(dir_); }).what(), "cannot open file"));
}

// ---- --set -------------------------------------------------------------------------------------------

TEST(Override, CreatesNestedObjects) {
  json j = json::object();
  tool::apply_override(j, "mc.compression.target=0.55");
  EXPECT_EQ(j["mc"]["compression"]["target"], 0.55);
  tool::apply_override(j, "mc.steps=1000");
  EXPECT_EQ(j["mc"]["steps"], 1000);
  EXPECT_EQ(j["mc"]["compression"]["target"], 0.55);
}

TEST(Override, ArrayIndexInBracketsOrDots) {
  json j = json::parse(R"({"species": [{"mass": 1}, {"mass": 2, "shape": {"edges": [1, 2, 3]}}]})");
  tool::apply_override(j, "species[1].mass=2.5");
  EXPECT_EQ(j["species"][1]["mass"], 2.5);
  tool::apply_override(j, "species.0.mass=7");
  EXPECT_EQ(j["species"][0]["mass"], 7);
  tool::apply_override(j, "species[1].shape.edges[2]=9");
  EXPECT_EQ(j["species"][1]["shape"]["edges"], json::parse("[1, 2, 9]"));
  tool::apply_override(j, "species[1].shape.edges=[4,5,6]");
  EXPECT_EQ(j["species"][1]["shape"]["edges"], json::parse("[4, 5, 6]"));
}

TEST(Override, ValueParsedAsJsonOtherwiseString) {
  json j = json::object();
  tool::apply_override(j, "name=hello world");
  EXPECT_EQ(j["name"], "hello world");
  tool::apply_override(j, "flag=true");
  EXPECT_EQ(j["flag"], true);
  tool::apply_override(j, "quoted=\"42\"");
  EXPECT_EQ(j["quoted"], "42");
  tool::apply_override(j, "n=42");
  EXPECT_EQ(j["n"], 42);
  tool::apply_override(j, "path=results/a=b.h5");  // only the first '=' separates
  EXPECT_EQ(j["path"], "results/a=b.h5");
  tool::apply_override(j, "empty=");
  EXPECT_EQ(j["empty"], "");
  tool::apply_override(j, "obj={\"x\": [1]}");
  EXPECT_EQ(j["obj"]["x"][0], 1);
}

TEST(Override, MalformedAssignmentsAreInputErrors) {
  for (const std::string bad : {"novalue", "=3", "a..b=1", "a.=1", ".a=1", "a[x]=1", "a[1=2", "a]=1", "[0]=1", "a[]=1"}) {
    json j = json::parse(R"({"a": [1, 2]})");
    const InputError e = input_error([&] { tool::apply_override(j, bad); });
    EXPECT_EQ(e.file(), "--set") << bad;
    EXPECT_TRUE(contains(e.what(), "expected key.path=value, got '" + bad + "'")) << e.what();
  }
}

TEST(Override, BadPathsNameThePath) {
  json j = json::parse(R"({"a": 5, "list": [1, 2]})");
  const InputError through_scalar = input_error([&] { tool::apply_override(j, "a.b=1"); });
  EXPECT_EQ(through_scalar.json_path(), "a.b");
  EXPECT_TRUE(contains(through_scalar.what(), "'a' is a number, not an object")) << through_scalar.what();
  const InputError out_of_range = input_error([&] { tool::apply_override(j, "list[5]=1"); });
  EXPECT_EQ(out_of_range.json_path(), "list[5]");
  EXPECT_TRUE(contains(out_of_range.what(), "out of range")) << out_of_range.what();
  const InputError index_on_object = input_error([&] { tool::apply_override(j, "missing[0]=1"); });
  EXPECT_TRUE(contains(index_on_object.what(), "not an array")) << index_on_object.what();
}

// ---- ConfigNode --------------------------------------------------------------------------------------

TEST(ConfigNode, TypedAccessWithDefaults) {
  const json j = json::parse(R"({
    "phi": 0.3, "steps": 1e6, "n": 12, "flag": true, "name": "run",
    "mode": "npt", "edges": [1, 2, 3], "list": [0.5, 1.5], "unset": null, "_comment": "ignored"})");
  tool::ConfigNode c(j, "config.json");
  EXPECT_EQ(c.positive("phi"), 0.3);
  EXPECT_EQ(c.positive_integer("steps"), 1000000);
  EXPECT_EQ(c.integer("n"), 12);
  EXPECT_TRUE(c.boolean("flag"));
  EXPECT_EQ(c.string("name"), "run");
  EXPECT_EQ(c.choice("mode", {"nvt", "npt"}), "npt");
  EXPECT_EQ(c.positive_vec3("edges"), Vec3(1, 2, 3));
  EXPECT_EQ(c.numbers("list"), (std::vector<double>{0.5, 1.5}));
  EXPECT_EQ(c.number("unset", 4.0), 4.0);  // null means "use the default"
  EXPECT_EQ(c.number("absent", -1.0), -1.0);
  EXPECT_EQ(c.string("absent_name", "x"), "x");
  EXPECT_FALSE(c.has("unset"));
  EXPECT_FALSE(c.has("absent"));
  EXPECT_TRUE(c.has("phi"));
  EXPECT_NO_THROW(c.finish());
}

TEST(ConfigNode, WrongTypeNamesFilePathExpectationAndValue) {
  const json j = json::parse(R"({"species": [{"shape": {"edges": "abc"}}]})");
  tool::ConfigNode c(j, "config.json");
  auto species = c.objects("species");
  ASSERT_EQ(species.size(), 1u);
  auto shape = species[0].object("shape");
  const InputError e = input_error([&] { shape.positive_vec3("edges"); });
  EXPECT_EQ(std::string(e.what()), R"(config.json: at species[0].shape.edges: expected an array of 3 positive numbers, got "abc")");
  EXPECT_EQ(e.file(), "config.json");
  EXPECT_EQ(e.json_path(), "species[0].shape.edges");
}

TEST(ConfigNode, RangeAndKindErrors) {
  const json j = json::parse(R"({"zero": 0, "neg": -1, "frac": 1.5, "word": "x", "mode": "nve", "v": [1, 2],
                                 "list": [1, "a"], "arr": [{"a": 1}, 3], "huge": 1e30})");
  tool::ConfigNode c(j, "c.json");
  EXPECT_TRUE(contains(input_error([&] { c.positive("zero"); }).what(), "at zero: expected a positive number, got 0"));
  EXPECT_TRUE(contains(input_error([&] { c.non_negative("neg"); }).what(), "expected a non-negative number, got -1"));
  EXPECT_TRUE(contains(input_error([&] { c.integer("frac"); }).what(), "expected an integer, got 1.5"));
  EXPECT_TRUE(contains(input_error([&] { c.integer("huge"); }).what(), "expected an integer"));
  EXPECT_TRUE(contains(input_error([&] { c.positive_integer("zero"); }).what(), "expected a positive integer"));
  EXPECT_TRUE(contains(input_error([&] { c.number("word"); }).what(), "expected a number, got \"x\""));
  EXPECT_TRUE(contains(input_error([&] { c.boolean("word", false); }).what(), "expected true or false"));
  EXPECT_TRUE(contains(input_error([&] { c.choice("mode", {"nvt", "npt"}, "nvt"); }).what(),
                       R"(at mode: expected one of "nvt", "npt", got "nve")"));
  EXPECT_TRUE(contains(input_error([&] { c.vec3("v"); }).what(), "expected an array of 3 numbers, got [1,2]"));
  EXPECT_TRUE(contains(input_error([&] { c.numbers("list"); }).what(), "expected an array of numbers"));
  EXPECT_TRUE(contains(input_error([&] { c.object("word"); }).what(), "expected an object"));
  const InputError element = input_error([&] { c.objects("arr"); });
  EXPECT_EQ(element.json_path(), "arr[1]");
  EXPECT_TRUE(contains(input_error([&] { c.fail("zero", "expected a volume fraction in (0, 0.74)"); }).what(),
                       "c.json: at zero: expected a volume fraction in (0, 0.74), got 0"));
}

TEST(ConfigNode, MissingRequiredKey) {
  const json j = json::parse(R"({"species": [{"name": "A"}], "opt": null})");
  tool::ConfigNode c(j, "config.json");
  auto sp = c.objects("species");
  const InputError e = input_error([&] { sp[0].positive("mass"); });
  EXPECT_EQ(e.json_path(), "species[0].mass");
  EXPECT_EQ(std::string(e.what()), "config.json: at species[0].mass: required value is missing (expected a positive number)");
  EXPECT_TRUE(contains(input_error([&] { c.object("box"); }).what(), "at box: required value is missing (expected an object)"));
  EXPECT_TRUE(contains(input_error([&] { c.number("opt"); }).what(), "at opt: expected a number, got null"));
}

TEST(ConfigNode, UnknownKeysAreFoundEverywhereWithSuggestions) {
  {
    const json j = json::parse(R"({"temperature": 1, "temprature": 2})");
    tool::ConfigNode c(j, "config.json");
    c.number("temperature");
    EXPECT_NO_THROW(c.number("pressure", 1.0));
    const InputError e = input_error([&] { c.finish(); });
    EXPECT_EQ(e.json_path(), "temprature");
    EXPECT_TRUE(contains(e.what(), "unknown key 'temprature'")) << e.what();
  }
  {
    const json j = json::parse(R"({"species": [{"name": "A", "mass": 1}, {"name": "B", "diamter": 1}]})");
    tool::ConfigNode c(j, "config.json");
    for (auto& s : c.objects("species")) {
      s.string("name");
      s.number("mass", 1.0);
      s.number("diameter", 1.0);
    }
    const InputError e = input_error([&] { c.finish(); });
    EXPECT_EQ(e.json_path(), "species[1].diamter");
    EXPECT_EQ(std::string(e.what()), "config.json: at species[1].diamter: unknown key 'diamter' (did you mean 'diameter'?)");
  }
  {
    // A whole block that is never read is reported at its own key.
    const json j = json::parse(R"({"a": 1, "mc": {"steps": 3}})");
    tool::ConfigNode c(j, "config.json");
    c.number("a");
    const InputError e = input_error([&] { c.finish(); });
    EXPECT_EQ(e.json_path(), "mc");
    EXPECT_TRUE(contains(e.what(), "known keys here: a")) << e.what();
  }
  {
    // Keys read through a child node, value() and mark_used() count as known; '_' keys are comments.
    const json j = json::parse(R"({"mc": {"steps": 3, "_note": "x"}, "extra": {"free": "form"}, "later": 1})");
    tool::ConfigNode c(j, "config.json");
    c.object("mc").integer("steps");
    c.value("extra");
    c.mark_used("later");
    EXPECT_NO_THROW(c.finish());
  }
}

TEST(ConfigNode, OptionalObjectsAndTemporaries) {
  tool::ConfigNode c(json::parse(R"({"field": {"strength": 2}})"), "cfg.json");  // temporary document
  auto field = c.optional_object("field");
  ASSERT_TRUE(field.has_value());
  EXPECT_EQ(field->path(), "field");
  EXPECT_EQ(field->number("strength"), 2.0);
  EXPECT_FALSE(c.optional_object("dipole").has_value());
  EXPECT_NO_THROW(c.finish());
  EXPECT_THROW(tool::ConfigNode(json::array(), "cfg.json"), InputError);
}

TEST_F(JsonFiles, OverrideThenValidateEndToEnd) {
  const auto path = write("run.json", R"({"species": [{"name": "A", "mass": 1.0}], "steps": 10})");
  json j = tool::load_json_file(path);
  tool::apply_overrides(j, {"species[0].mass=-2", "steps=20"});
  tool::ConfigNode c(j, path);
  EXPECT_EQ(c.positive_integer("steps"), 20);
  auto sp = c.objects("species");
  const InputError e = input_error([&] { sp[0].positive("mass"); });
  EXPECT_EQ(std::string(e.what()), path + ": at species[0].mass: expected a positive number, got -2");
}
