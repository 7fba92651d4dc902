#pragma once
// The runners' recorder. A runner declares its channels once, in output order: each has a name
// (dynamics/signal_names.hpp), a unit, and how it is read —
//   sampled:      at every sample, from what the fast side gives (a dynamics::Sample, or just the
//                 sample time where there is no fast side);
//   interpolated: from the slow state (the thermal field, or everything the prescribed-slip
//                 model evaluates at a thermal step's end), at slow-step ends only; each sample
//                 the step added gets the value linear in time between the step's two ends,
//                 x(t) = (1 − w) x_a + w x_b with w = (t − t_a) / (t_b − t_a) (w = 1 for an
//                 empty step), t read from the first channel, which is `time_s` and sampled;
//   refined:      like interpolated at a slow step's ends, but a sample strictly inside a step
//                 is read from the slow state the runner evaluates at that sample's time (step()'s
//                 `inside`) — for channels that move nonlinearly within a step (the friction's
//                 dependence on the slip speed), where a straight line between the ends is not
//                 good enough once a step spans several samples.
// The recorder writes into a dynamics::Recording (signals in declaration order).

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dynamics/recording.hpp"
#include "dynamics/signal_names.hpp"

namespace shudder::components {

template <class Fast, class Slow>
class ChannelRecorder {
 public:
  struct Channel {
    std::string_view name, units;
    std::function<double(const Fast&)> sampled;       // set for a sampled channel
    std::function<double(const Slow&)> interpolated;  // set for an interpolated or refined one
    bool refined = false;
  };
  static Channel sampled(std::string_view name, std::string_view units, std::function<double(const Fast&)> read) {
    return {name, units, std::move(read), {}};
  }
  static Channel interpolated(std::string_view name, std::string_view units, std::function<double(const Slow&)> read) {
    return {name, units, {}, std::move(read)};
  }
  static Channel refined(std::string_view name, std::string_view units, std::function<double(const Slow&)> read) {
    return {name, units, {}, std::move(read), true};
  }

  /// The slow state at sample time t inside a step, w = (t − t_a) / (t_b − t_a) in [0, 1).
  using Inside = std::function<Slow(double t_s, double w)>;

  /// Adds the channels' signals to `rec`, which must outlive the recorder.
  ChannelRecorder(dynamics::Recording& rec, std::vector<Channel> channels)
      : rec_(rec), first_(rec.signals.size()), channels_(std::move(channels)) {
    if (channels_.empty() || channels_.front().name != dynamics::signal_names::kTime || !channels_.front().sampled)
      throw std::logic_error("a recorder's first channel is the sampled time_s");
    for (const auto& c : channels_) rec_.add_signal(std::string(c.name), std::string(c.units));
  }

  /// Records the sampled channels of one sample.
  void sample(const Fast& fast) {
    for (std::size_t c = 0; c < channels_.size(); ++c)
      if (channels_[c].sampled) values(c).push_back(channels_[c].sampled(fast));
  }

  /// The slow state at the start: the samples taken so far get its values.
  void start(const Slow& slow) {
    before_ = read(slow);
    fill(before_, before_, 0.0, 0.0);
  }

  /// The slow state after the step [ta_s, tb_s]: the samples added since the last fill get the
  /// values between the step's two ends; refined channels of samples inside the step are read
  /// from `inside` (once per such sample) when given.
  void step(const Slow& after, double ta_s, double tb_s, const Inside& inside = {}) {
    std::vector<double> b = read(after);
    fill(before_, b, ta_s, tb_s, inside);
    before_ = std::move(b);
  }

 private:
  std::vector<double>& values(std::size_t c) { return rec_.signals[first_ + c].values; }

  std::vector<double> read(const Slow& slow) const {
    std::vector<double> v;
    for (const auto& c : channels_)
      if (c.interpolated) v.push_back(c.interpolated(slow));
    return v;
  }

  // A sample this close to a step's end (relative to the step) is at the end: its values are
  // the end's, up to the interpolation's round-off (sample and step times are accumulated
  // differently), not a fresh evaluation.
  static constexpr double kAtEnd = 1e-9;

  void fill(const std::vector<double>& a, const std::vector<double>& b, double ta, double tb,
            const Inside& inside = {}) {
    const std::vector<double>& t = values(0);
    for (; filled_ < t.size(); ++filled_) {
      const double w = tb > ta ? (t[filled_] - ta) / (tb - ta) : 1.0;
      const bool fresh = inside && w < 1.0 - kAtEnd;
      Slow here{};
      if (fresh) here = inside(t[filled_], w);
      std::size_t k = 0;
      for (std::size_t c = 0; c < channels_.size(); ++c)
        if (channels_[c].interpolated) {
          values(c).push_back(fresh && channels_[c].refined ? channels_[c].interpolated(here)
                                                            : (1 - w) * a[k] + w * b[k]);
          ++k;
        }
    }
  }

  dynamics::Recording& rec_;
  std::size_t first_;  // index of the first channel's signal in rec_
  std::vector<Channel> channels_;
  std::vector<double> before_;  // interpolated channels' values at the last slow-step end
  std::size_t filled_ = 0;      // samples whose interpolated channels are filled
};

}  // namespace shudder::components
