// `shudder screen` through the real CLI: the indices table, the slope and
// stability summaries and the verdict on fluid C and on the schematic negative-slope fluid; the
// JSON output parsed by a minimal reader (arrays aligned with temperatures_C); bad input exits 2
// with one line and leaves no JSON behind.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/cli.hpp"

using namespace shudder::test;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// ---- A minimal JSON reader (RFC 8259 subset: no \u escapes beyond passing them through) ----
struct Json {
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject } type = Type::kNull;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Json> items;        // array items or object values
  std::vector<std::string> keys;  // object keys, aligned with items

  const Json& at(const std::string& key) const {
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] == key) return items[i];
    throw std::runtime_error("JSON: no key '" + key + "'");
  }
  bool has(const std::string& key) const { return std::find(keys.begin(), keys.end(), key) != keys.end(); }
};

class JsonReader {
 public:
  explicit JsonReader(const std::string& text) : s_(text) {}
  Json document() {
    Json v = value();
    skip();
    if (p_ != s_.size()) fail("trailing text");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error("JSON: " + why + " at offset " + std::to_string(p_));
  }
  void skip() {
    while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
  }
  bool eat(char c) {
    skip();
    if (p_ < s_.size() && s_[p_] == c) {
      ++p_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }
  std::string str() {
    expect('"');
    std::string out;
    while (p_ < s_.size() && s_[p_] != '"') {
      const char c = s_[p_++];
      if (static_cast<unsigned char>(c) < 0x20) fail("raw control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (p_ >= s_.size()) fail("dangling escape");
      const char e = s_[p_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'n': out += '\n'; break;
        case 't': out += '\t'; break;
        case 'r': out += '\r'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'u':
          if (p_ + 4 > s_.size()) fail("short \\u escape");
          out += static_cast<char>(std::stoi(s_.substr(p_, 4), nullptr, 16));
          p_ += 4;
          break;
        default: fail("bad escape");
      }
    }
    if (p_ >= s_.size()) fail("unterminated string");
    ++p_;
    return out;
  }
  Json value() {
    skip();
    if (p_ >= s_.size()) fail("unexpected end");
    Json v;
    const char c = s_[p_];
    if (c == '{') {
      ++p_;
      v.type = Json::Type::kObject;
      if (eat('}')) return v;
      do {
        skip();
        v.keys.push_back(str());
        expect(':');
        v.items.push_back(value());
      } while (eat(','));
      expect('}');
    } else if (c == '[') {
      ++p_;
      v.type = Json::Type::kArray;
      if (eat(']')) return v;
      do v.items.push_back(value());
      while (eat(','));
      expect(']');
    } else if (c == '"') {
      v.type = Json::Type::kString;
      v.string = str();
    } else if (s_.compare(p_, 4, "true") == 0 || s_.compare(p_, 5, "false") == 0) {
      v.type = Json::Type::kBool;
      v.boolean = s_[p_] == 't';
      p_ += v.boolean ? 4 : 5;
    } else if (s_.compare(p_, 4, "null") == 0) {
      p_ += 4;
    } else {
      // Number: JSON grammar only (no nan/inf, no leading '+').
      const std::size_t start = p_;
      if (s_[p_] == '-') ++p_;
      if (p_ >= s_.size() || !std::isdigit(static_cast<unsigned char>(s_[p_]))) fail("bad number");
      while (p_ < s_.size() && std::strchr("0123456789.eE+-", s_[p_])) ++p_;
      v.type = Json::Type::kNumber;
      v.number = std::stod(s_.substr(start, p_ - start));
    }
    return v;
  }

  const std::string& s_;
  std::size_t p_ = 0;
};

const char* const kIndexKeys[] = {"mu1_over_mu50",           "mu100_over_mu300",     "yoshizawa_mu1_over_mu20",
                                  "miyazaki_mu6_over_mu180", "murakami_dmu_dV50",    "murakami_dmu_dV150",
                                  "mercon_v_2_over_20",      "mercon_v_40_over_120", "jaso_dmu_dv_0_3",
                                  "jaso_dmu_dv_0_9"};

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// Checks the shape of a screen JSON and returns it parsed.
Json check_screen_json(const std::filesystem::path& file, std::size_t n_temps) {
  const std::string text = slurp(file);
  Json doc;
  EXPECT_NO_THROW(doc = JsonReader(text).document()) << text.substr(0, 400);
  EXPECT_EQ(doc.at("format").string, "shudder-screen/1");
  const Json& temps = doc.at("temperatures_C");
  EXPECT_EQ(temps.items.size(), n_temps);
  for (const char* key : kIndexKeys) {
    SCOPED_TRACE(key);
    EXPECT_EQ(doc.at(key).type, Json::Type::kArray);
    EXPECT_EQ(doc.at(key).items.size(), n_temps);
    EXPECT_EQ(doc.at("clamped").at(key).items.size(), n_temps);
    for (const auto& b : doc.at("clamped").at(key).items) EXPECT_EQ(b.type, Json::Type::kBool);
  }
  EXPECT_EQ(doc.at("temperature_outside_data").items.size(), n_temps);
  // Slope map and stability maps share the grid: (n_speeds x n_temps).
  const Json& slope = doc.at("slope_map");
  const std::size_t ns = slope.at("speeds_rpm").items.size(), nt = slope.at("temps_C").items.size();
  EXPECT_EQ(slope.at("dmu_dv_s_per_m").items.size(), ns);
  EXPECT_EQ(slope.at("dmu_dv_s_per_m").items.front().items.size(), nt);
  for (const auto& rig : doc.at("stability").at("rigs").items) {
    EXPECT_EQ(rig.at("margin_per_s").items.size(), ns);
    EXPECT_EQ(rig.at("margin_per_s").items.back().items.size(), nt);
  }
  EXPECT_EQ(doc.at("verdict").type, Json::Type::kString);
  EXPECT_FALSE(std::filesystem::exists(file.string() + ".tmp"));
  return doc;
}

TEST(CliScreen, FluidCDefaultRigs) {
  const auto dir = scratch_dir("screen_fluid_c");
  const auto r =
      run_cli("screen " + quoted(source_path("scenarios/fluids/lsc_fluid_c.toml")) + " --json out.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Fluid lsc-fluid-c"));
  EXPECT_THAT(r.out, HasSubstr("1 rpm = 4.817 mm/s"));
  EXPECT_THAT(r.out, HasSubstr("mu1/mu50 (Ohtani)"));
  EXPECT_THAT(r.out, HasSubstr("JASO dmu/dv 0.9 m/s"));
  EXPECT_THAT(r.out, HasSubstr("rig (100 Hz bar)"));
  EXPECT_THAT(r.out, HasSubstr("rig (500 Hz bar)"));
  EXPECT_THAT(r.out, HasSubstr("Verdict: "));

  const Json doc = check_screen_json(dir / "out.json", 3);
  EXPECT_EQ(doc.at("fluid").string, "lsc-fluid-c");
  EXPECT_EQ(doc.at("load_N").number, 20000.0);
  EXPECT_EQ(doc.at("temperatures_C").items[0].number, 40.0);
  EXPECT_EQ(doc.at("temperatures_C").items[2].number, 120.0);
  // mu1/mu50 < 1 at every temperature, from the held 6 mm/s value: flagged.
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT(doc.at("mu1_over_mu50").items[i].number, 1.0);
    EXPECT_TRUE(doc.at("clamped").at("mu1_over_mu50").items[i].boolean);
    EXPECT_FALSE(doc.at("clamped").at("mercon_v_2_over_20").items[i].boolean);
  }
  EXPECT_EQ(doc.at("stability").at("rigs").items.size(), 3u);
  // The map spans the matrix' rows, -40–200 °C.
  EXPECT_EQ(doc.at("slope_map").at("temps_C").items.front().number, -40.0);
  EXPECT_EQ(doc.at("slope_map").at("temps_C").items.back().number, 200.0);
}

TEST(CliScreen, SchematicNegativeSlopeFluidIsARisk) {
  const auto dir = scratch_dir("screen_negative");
  const auto r = run_cli("screen " + quoted(source_path("scenarios/fluids/schematic_negative_slope.toml")) +
                             " --temps 40,60,80 --json out.json",
                         dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The falling branch 10–100 rpm is found (the grid's 10 rpm point sits on the peak).
  EXPECT_THAT(r.out,
              ::testing::ContainsRegex("negative slope \\(risky region\\) at [0-9]+ of [0-9]+ points, 1[01]\u2013"
                                       "99 rpm, 40\u2013120 \u00b0C"));
  EXPECT_THAT(r.out, HasSubstr("Verdict: RISK: negative isothermal slope at 1"));
  EXPECT_THAT(r.out, HasSubstr("predicted unstable at"));

  const Json doc = check_screen_json(dir / "out.json", 3);
  EXPECT_EQ(doc.at("verdict_level").string, "RISK");
  EXPECT_THAT(doc.at("verdict").string, HasSubstr("negative isothermal slope"));
  const auto& region = doc.at("risky_region").items;
  ASSERT_FALSE(region.empty());
  for (const auto& run : region) {
    EXPECT_GE(run.at("from_rpm").number, 10.0);
    EXPECT_LE(run.at("from_rpm").number, 11.0);
    EXPECT_EQ(run.at("to_rpm").number, 99.0);
  }
  // mu(50 rpm) > mu(1 rpm): the low-speed ratio and the 1→50 rpm secant (Murakami) miss the
  // falling branch; the JASO slope at 0.3 m/s (62 rpm) sees it.
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT(doc.at("mu1_over_mu50").items[i].number, 1.0);
    EXPECT_GT(doc.at("murakami_dmu_dV50").items[i].number, 0.0);
    EXPECT_LT(doc.at("jaso_dmu_dv_0_3").items[i].number, 0.0);
    EXPECT_EQ(doc.at("jaso_dmu_dv_0_9").items[i].type, Json::Type::kNull);  // beyond 100 rpm
  }
  // At least one rig is unstable on the falling branch.
  bool unstable = false;
  for (const auto& rig : doc.at("stability").at("rigs").items)
    unstable = unstable || rig.at("unstable_extent").at("points").number > 0;
  EXPECT_TRUE(unstable);
}

TEST(CliScreen, GivenRigScenario) {
  const auto dir = scratch_dir("screen_rig");
  const auto r = run_cli("screen " + quoted(source_path("scenarios/fluids/schematic_negative_slope.toml")) + " --rig " +
                             quoted(source_path("scenarios/rig_shudder_negative_slope.toml")) +
                             " --load-N 15000 --temps 60 --json out.json",
                         dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("rig (378 Hz bar): UNSTABLE"));
  const Json doc = check_screen_json(dir / "out.json", 1);
  EXPECT_EQ(doc.at("load_N").number, 15000.0);
  ASSERT_EQ(doc.at("stability").at("rigs").items.size(), 1u);
  EXPECT_NEAR(doc.at("stability").at("rigs").items[0].at("clutch_side_frequency_Hz").number, 378.0, 1.0);
}

TEST(CliScreen, PaperEFluidAIsLowRisk) {
  const auto dir = scratch_dir("screen_paper_e_a");
  const auto r = run_cli("screen " + quoted(source_path("scenarios/fluids/paper_e_fluid_a.toml")) + " --temps 29", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("0.7984"));  // mu1/mu50 at 29 °C (Paper E Table 4: 0.7985)
  // Friction rises from 1 to 50 rpm and is held beyond: no negative slope, every rig stable.
  EXPECT_THAT(r.out,
              HasSubstr("Verdict: LOW RISK: no negative isothermal slope over 1\u2013120 rpm, 29\u2013120 \u00b0C"));
  EXPECT_THAT(r.out, HasSubstr("every rig predicted stable"));
}

// A fluid whose data lie outside every default screening temperature (a table law measured at
// 20-30 °C): no index is computed, so there is no verdict: "NOT JUDGED", exit 3, never "LOW RISK".
TEST(CliScreen, NoIndexComputedIsNotJudged) {
  const auto dir = scratch_dir("screen_not_judged");
  write_file(dir / "cold.toml",
             "[fluid]\nname = \"cold\"\nnu40_cSt = 35.0\nnu100_cSt = 6.7\n"
             "[static_friction]\nbreakaway_ratio = 1.0\n"
             "[table]\nspeeds_mm_s = [5.0, 50.0, 500.0]\nloads_N = [20000.0]\n"
             "[[table.row]]\ntemp_C = 20.0\nmu = [[0.10, 0.11, 0.12]]\n"
             "[[table.row]]\ntemp_C = 30.0\nmu = [[0.09, 0.10, 0.11]]\n");
  const auto r = run_cli("screen cold.toml --json out.json", dir);
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("no screening temperature inside the law's data; give --temps"));
  EXPECT_THAT(r.out, HasSubstr("Verdict: NOT JUDGED: no anti-shudder index was computed"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("LOW RISK")));
  EXPECT_THAT(slurp(dir / "out.json"), HasSubstr("\"verdict_level\": \"NOT JUDGED\""));
  // Inside the data it is judged.
  const auto in = run_cli("screen cold.toml --temps 25", dir);
  EXPECT_EQ(in.exit_code, 0) << in.err;
  EXPECT_THAT(in.out, HasSubstr("Verdict: LOW RISK"));
}

// Strings are escaped: a fluid name with a quote, a backslash and a tab round-trips.
TEST(CliScreen, JsonEscapesStrings) {
  const auto dir = scratch_dir("screen_escape");
  std::string fluid = slurp(source_path("scenarios/fluids/paper_e_fluid_a.toml"));
  const std::string from = "name = \"paper-e-fluid-a\"";
  ASSERT_NE(fluid.find(from), std::string::npos);
  fluid.replace(fluid.find(from), from.size(), "name = \"odd \\\"name\\\" \\\\ tab\\t end\"");
  write_file(dir / "odd fluid.toml", fluid);
  const auto r = run_cli("screen 'odd fluid.toml' --temps 40 --json out.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json doc = check_screen_json(dir / "out.json", 1);
  EXPECT_EQ(doc.at("fluid").string, "odd \"name\" \\ tab\t end");
  EXPECT_EQ(doc.at("fluid_file").string, "odd fluid.toml");
}

struct Bad {
  CliResult r;
  bool json_exists;
};

Bad run_bad(const std::string& name, const std::string& args) {
  const auto dir = scratch_dir("screen_bad_" + name);
  Bad b;
  b.r = run_cli(args + " --json out.json", dir);
  b.json_exists = std::filesystem::exists(dir / "out.json") || std::filesystem::exists(dir / "out.json.tmp");
  return b;
}

void expect_rejected(const Bad& b, const std::vector<std::string>& fragments) {
  EXPECT_EQ(b.r.exit_code, 2) << b.r.err;
  EXPECT_FALSE(b.json_exists);
  EXPECT_EQ(std::count(b.r.err.begin(), b.r.err.end(), '\n'), 1) << b.r.err;
  for (const auto& f : fragments) EXPECT_THAT(b.r.err, HasSubstr(f));
}

TEST(CliScreen, UnknownFluidFileExits2) {
  expect_rejected(run_bad("nofile", "screen no_such_fluid.toml"),
                  {"no_such_fluid.toml", "no such fluid file", "docs/formats/fluid_file.md"});
}

TEST(CliScreen, BadTemperaturesExit2) {
  const std::string fluid = quoted(source_path("scenarios/fluids/lsc_fluid_c.toml"));
  expect_rejected(run_bad("temps_word", "screen " + fluid + " --temps 40,hot"),
                  {"--temps", "'hot' is not a number", "e.g. 40,80,120"});
  expect_rejected(run_bad("temps_empty", "screen " + fluid + " --temps 40,,80"), {"--temps", "empty entry"});
  expect_rejected(run_bad("temps_cold", "screen " + fluid + " --temps -300"), {"--temps", "outside -273.15..1000"});
}

TEST(CliScreen, BadLoadAndRigExit2) {
  const std::string fluid = quoted(source_path("scenarios/fluids/lsc_fluid_c.toml"));
  expect_rejected(run_bad("load", "screen " + fluid + " --load-N -5"), {"--load-N", "> 0 N"});
  expect_rejected(
      run_bad("rig_type", "screen " + fluid + " --rig " + quoted(source_path("scenarios/paper_g_case1_10kN.toml"))),
      {"paper_g_case1_10kN.toml", "scenario.type", "--rig needs a scenario with type = \"rig\""});
  // A broken fluid file: the loader's message (file, line, key) comes through.
  const auto dir = scratch_dir("screen_bad_fluid_text");
  write_file(dir / "f.toml", "[fluid]\nname = \"x\"\nnu40_cSt = 35.0\nnu100_cSt = 6.7\n");
  const auto r = run_cli("screen f.toml", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("f.toml"));
  EXPECT_THAT(r.out, Not(HasSubstr("Verdict")));
}

}  // namespace
