#include "io/validation_targets.hpp"

#include "io/toml_reader.hpp"

namespace shudder::io {

namespace {

std::size_t case_named(const ValidationSpec& spec, TomlTable& t, const std::string& key) {
  const std::string name = t.string(key);
  for (std::size_t i = 0; i < spec.cases.size(); ++i)
    if (spec.cases[i].scenario == name) return i;
  std::string list;
  for (const auto& c : spec.cases) list += (list.empty() ? "" : ", ") + c.scenario;
  t.fail(key, "'" + name + "' is not a [[case]]; cases are: " + list);
}

ValidationTarget read_target(const ValidationSpec& spec, TomlTable& t) {
  ValidationTarget g;
  g.case_index = case_named(spec, t, "case");
  g.quantity = t.string("quantity");
  const std::string kind = t.choice_or("kind", "value", {"value", "mean", "rise", "percent_below", "percent_above"});
  g.kind = kind == "mean"            ? TargetKind::kMean
           : kind == "rise"          ? TargetKind::kRise
           : kind == "percent_below" ? TargetKind::kPercentBelow
           : kind == "percent_above" ? TargetKind::kPercentAbove
                                     : TargetKind::kValue;
  g.signal = t.string("signal");
  g.unit = t.string("unit");
  if (g.kind == TargetKind::kMean || g.kind == TargetKind::kRise) {
    g.from_s = t.number("from_s", Range::non_negative());
    g.to_s = t.number("to_s", Range::non_negative());
    if (!(g.to_s > g.from_s)) t.fail("to_s", "must be later than from_s");
  } else {
    g.time_s = t.number("time_s", Range::non_negative());
  }
  if (g.kind == TargetKind::kPercentBelow || g.kind == TargetKind::kPercentAbove)
    g.reference_index = case_named(spec, t, "reference");
  if (t.has("min")) g.min = t.number("min");
  if (t.has("max")) g.max = t.number("max");
  if (t.has("greater_than")) g.greater_than = t.number("greater_than");
  if (g.min && g.max && *g.min > *g.max) t.fail("max", "must not be below min");
  if (g.greater_than && (g.min || g.max)) t.fail("greater_than", "give either greater_than or min/max, not both");
  t.finish();
  return g;
}

}  // namespace

ValidationSpec load_validation_spec(const std::string& path) {
  const toml::table doc = TomlTable::parse_file(path);
  TomlTable root(doc, path, "");
  ValidationSpec spec;
  for (auto& c : root.table_array("case")) {
    spec.cases.push_back({c.string("scenario"), c.string("label")});
    c.finish();
  }
  if (spec.cases.empty()) root.fail("case", "at least one [[case]] is needed");
  for (auto& t : root.table_array("target")) spec.targets.push_back(read_target(spec, t));
  auto d = root.table("document");
  spec.ramp_case = case_named(spec, d, "ramp_case");
  spec.ramp_plot_file = d.string("ramp_plot_file");
  spec.comparison_title = d.string("comparison_title");
  spec.comparison_heading = d.string("comparison_heading");
  spec.comparison_file = d.string("comparison_file");
  for (auto& c : d.table_array("comparison")) {
    const std::size_t index = case_named(spec, c, "case");
    spec.comparison.emplace_back(index, c.string("label"));
    c.finish();
  }
  d.finish();
  root.finish();
  return spec;
}

}  // namespace shudder::io
