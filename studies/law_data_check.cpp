#include "studies/law_data_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

namespace shudder::studies {

std::vector<std::string> law_above_its_data(const ReplayModel& model, const std::vector<ReplayInputs>& inputs,
                                            const std::vector<std::string>& names) {
  std::vector<std::string> out;
  if (!model.fluid.friction) return out;
  const double top_C = model.fluid.friction->temp_range_C().second;
  if (!std::isfinite(top_C)) return out;
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    ReplayOutput o;
    try {
      o = replay(model, inputs[k]);
    } catch (const std::exception&) {
      continue;
    }
    const auto& t = o.interface_mean_temp_C;
    if (t.empty()) continue;
    const auto above = std::count_if(t.begin(), t.end(), [&](double x) { return x > top_C; });
    const double share = double(above) / double(t.size());
    if (share <= 0.05) continue;
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "run '%s': the model's interface is above the friction law's data (its top row, %.4g °C) on "
                  "%.0f %% of the samples, up to %.4g °C; there the law holds that row's mu, so a torque gap there "
                  "is the law's, not a missing effect (characterise with ramps that start nearer, or keep its hot row)",
                  k < names.size() ? names[k].c_str() : "?", top_C, 100.0 * share,
                  *std::max_element(t.begin(), t.end()));
    out.emplace_back(buf);
  }
  return out;
}

}  // namespace shudder::studies
