// summary.json: round trip of every value type, strict reading, atomic replacement.
#include "output/summary_json.hpp"
#include "support/summary_parser.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace rockcut::coupler {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::path(ROCKCUT_TEST_TMP) / "output" / "summary" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

TEST(SummaryJson, RoundTripsEveryValueType) {
  const auto dir = scratch("roundtrip");
  Summary s;
  s.set("pi", 3.141592653589793);
  s.set("third", 1.0 / 3.0);
  s.set("whole_double", 2.0);  // must come back as double, not int64
  s.set("negative_zero", -0.0);
  s.set("tiny", std::numeric_limits<double>::denorm_min());
  s.set("huge", std::numeric_limits<double>::max());
  s.set("count", std::int64_t{-9223372036854775807LL - 1});
  s.set("big", std::int64_t{9223372036854775807LL});
  s.set("ok", true);
  s.set("failed", false);
  s.set("text", std::string("quote \" backslash \\ slash / tab \t newline \n cr \r "
                            "bell \a nul-free \x01 \x1f del \x7f utf8 \xc3\xa9 \xe2\x82\xac"));
  s.set("key with \"quotes\"\n", std::string(""));
  s.set("nan", std::numeric_limits<double>::quiet_NaN());
  s.set("inf", std::numeric_limits<double>::infinity());
  s.write(dir / "summary.json");

  const Summary r = coupler::read_summary(dir / "summary.json");
  ASSERT_EQ(r.entries().size(), s.entries().size());
  for (std::size_t i = 0; i < s.entries().size(); ++i) {
    const auto& [key, value] = s.entries()[i];
    SCOPED_TRACE(key);
    EXPECT_EQ(r.entries()[i].first, key);  // order preserved
    const SummaryValue& back = r.entries()[i].second;
    ASSERT_EQ(back.index(), value.index());
    if (const auto* d = std::get_if<double>(&value)) {
      const double b = std::get<double>(back);
      if (std::isfinite(*d)) {
        EXPECT_EQ(b, *d);  // bit-exact round trip, not just close
        EXPECT_EQ(std::signbit(b), std::signbit(*d));
      } else {
        EXPECT_TRUE(std::isnan(b));  // written as null
      }
    } else {
      EXPECT_EQ(back, value);
    }
  }
  const std::string json = read_text(dir / "summary.json");
  EXPECT_NE(json.find("\"nan\": null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"inf\": null"), std::string::npos) << json;
  EXPECT_NE(json.find("\"whole_double\": 2.0"), std::string::npos) << json;
  EXPECT_NE(json.find("\\u0001"), std::string::npos) << json;
}

TEST(SummaryJson, PrettyPrintsOneKeyPerLineInInsertionOrder) {
  Summary s;
  s.set("b", std::int64_t{1});
  s.set("a", 0.5);
  s.set("b", std::int64_t{2});  // replaced in place, keeps its position
  EXPECT_EQ(s.to_json(), "{\n  \"b\": 2,\n  \"a\": 0.5\n}\n");
  ASSERT_TRUE(s.get("b").has_value());
  EXPECT_EQ(std::get<std::int64_t>(*s.get("b")), 2);
  EXPECT_FALSE(s.get("c").has_value());
  EXPECT_EQ(Summary().to_json(), "{\n}\n");
}

TEST(SummaryJson, ReadsHandWrittenJsonWithEscapes) {
  const auto dir = scratch("handwritten");
  write_text(dir / "s.json",
             "  {\"a\":1,\"b\" : -2.5e-3 ,\r\n\t\"c\":\"\\u00e9\\ud83d\\ude00\\/\",\"d\":null,"
             "\"e\":1E2,\"f\":true}  \n");
  const Summary r = coupler::read_summary(dir / "s.json");
  ASSERT_EQ(r.entries().size(), 6u);
  EXPECT_EQ(std::get<std::int64_t>(*r.get("a")), 1);
  EXPECT_EQ(std::get<double>(*r.get("b")), -2.5e-3);
  EXPECT_EQ(std::get<std::string>(*r.get("c")), "\xc3\xa9\xf0\x9f\x98\x80/");
  EXPECT_TRUE(std::isnan(std::get<double>(*r.get("d"))));
  EXPECT_EQ(std::get<double>(*r.get("e")), 100.0);
  EXPECT_EQ(std::get<bool>(*r.get("f")), true);
}

TEST(SummaryJson, RejectsMalformedInputWithAPosition) {
  const auto dir = scratch("malformed");
  const std::vector<std::string> bad = {
      "",
      "[]",
      "{",
      "{\"a\":1,}",
      "{\"a\" 1}",
      "{a:1}",
      "{\"a\":01}",
      "{\"a\":1.}",
      "{\"a\":-}",
      "{\"a\":1e}",
      "{\"a\":tru}",
      "{\"a\":nul}",
      "{\"a\":\"x}",
      "{\"a\":\"\\q\"}",
      "{\"a\":\"\\u12\"}",
      "{\"a\":\"\\ud800\"}",
      "{\"a\":\"line\nbreak\"}",
      "{\"a\":{\"b\":1}}",
      "{\"a\":[1]}",
      "{\"a\":1} x",
      "{\"a\":1}{}",
      "{\"a\":99999999999999999999}",
      "{\"a\":1e999}",
      "{\"a\":+1}",
  };
  for (const std::string& text : bad) {
    SCOPED_TRACE(text);
    write_text(dir / "bad.json", text);
    try {
      (void)coupler::read_summary(dir / "bad.json");
      ADD_FAILURE() << "accepted malformed input";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("line "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
  }
  try {
    write_text(dir / "bad.json", "{\n  \"a\": 1,\n  \"b\": ?\n}\n");
    (void)coupler::read_summary(dir / "bad.json");
    ADD_FAILURE() << "accepted '?'";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 3, column 8"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)coupler::read_summary(dir / "missing.json"), std::runtime_error);
}

TEST(SummaryJson, WriteReplacesAtomicallyAndLeavesNoTemporary) {
  const auto dir = scratch("atomic");
  const auto target = dir / "summary.json";
  Summary old_summary;
  old_summary.set("version", std::int64_t{1});
  old_summary.write(target);
  Summary new_summary;
  new_summary.set("version", std::int64_t{2});
  new_summary.set("note", std::string("replaced"));
  new_summary.write(target);

  EXPECT_EQ(read_text(target), new_summary.to_json());
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(names, std::vector<std::string>{"summary.json"});

  // A failed write (directory missing) throws and leaves the old file untouched.
  EXPECT_THROW(new_summary.write(dir / "no_such_dir" / "summary.json"), std::runtime_error);
  EXPECT_EQ(read_text(target), new_summary.to_json());
}

TEST(SummaryJson, APlantedLinkAtTheTemporaryNameIsNotFollowed) {
  // summary.json.tmp.<pid> (and run.xdmf's, the same writer) is created fresh and exclusively: a
  // link planted there by another user is removed, its target left as it was.
  const auto dir = scratch("planted");
  const auto victim = dir / "victim.txt";
  write_text(victim, "not yours");
  const auto target = dir / "summary.json";
  std::filesystem::create_symlink(victim, dir / ("summary.json.tmp." + std::to_string(::getpid())));
  Summary s;
  s.set("version", std::int64_t{3});
  s.write(target);
  EXPECT_EQ(read_text(target), s.to_json());
  EXPECT_EQ(read_text(victim), "not yours");
  EXPECT_FALSE(std::filesystem::is_symlink(target));
}

}  // namespace
}  // namespace rockcut::coupler
