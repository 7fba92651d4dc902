#include "clutch/friction_radius.hpp"

#include <cmath>
#include <stdexcept>

namespace shudder::clutch {

const char* radius_convention_name(RadiusConvention c) {
  return c == RadiusConvention::kUniformWear ? "uniform_wear" : "uniform_pressure";
}

bool parse_radius_convention(std::string_view name, RadiusConvention& out) {
  if (name == "uniform_pressure")
    out = RadiusConvention::kUniformPressure;
  else if (name == "uniform_wear")
    out = RadiusConvention::kUniformWear;
  else
    return false;
  return true;
}

double uniform_pressure_radius(double ri, double ro) {
  if (!(ro > ri && ri >= 0.0)) throw std::invalid_argument("friction annulus: the outer radius must exceed the inner");
  return 2.0 / 3.0 * (ro * ro * ro - ri * ri * ri) / (ro * ro - ri * ri);
}

double model_friction_radius_m(const ThermalModel& thermal) {
  return thermal.ring_radius_m().dot(thermal.ring_area_m2()) / thermal.contact_area_m2();
}

double model_friction_radius_m(const ThermalParams& thermal) { return model_friction_radius_m(ThermalModel(thermal)); }

double mu_from_torque(double torque_Nm, double force_N, double radius_m, int interfaces) {
  const double denom = force_N * radius_m * interfaces;
  return denom > 0.0 ? torque_Nm / denom : 0.0;
}

double torque_from_mu(double mu, double force_N, double radius_m, int interfaces) {
  return mu * force_N * radius_m * interfaces;
}

namespace {

// mu(v) = k · law(k v).
class RadiusScaledFriction final : public FrictionLaw {
 public:
  RadiusScaledFriction(std::shared_ptr<const FrictionLaw> law, double k) : law_(std::move(law)), k_(k) {}
  double mu(double v, double temp_C, double load_N) const override { return k_ * law_->mu(k_ * v, temp_C, load_N); }
  double dmu_dv_per_mm_s(double v, double temp_C, double load_N) const override {
    return k_ * k_ * law_->dmu_dv_per_mm_s(k_ * v, temp_C, load_N);
  }
  double min_speed_mm_s() const override { return law_->min_speed_mm_s() / k_; }
  double max_speed_mm_s() const override { return law_->max_speed_mm_s() / k_; }
  std::pair<double, double> temp_range_C() const override { return law_->temp_range_C(); }
  std::pair<double, double> load_range_N() const override { return law_->load_range_N(); }
  bool speed_curve(double temp_C, double load_N, SpeedCurve& out) const override {
    if (!law_->speed_curve(temp_C, load_N, out)) return false;
    // k (a tanh(b k v) + c (k v)^0.1 + d), k v clamped to [vmin, vmax] <=> v to [vmin, vmax] / k.
    for (double& a : out.tanh_weight) a *= k_;
    for (double& b : out.tanh_rate) b *= k_;
    out.power_weight *= k_ * std::pow(k_, 0.1);
    out.offset *= k_;
    out.min_speed_mm_s /= k_;
    out.max_speed_mm_s /= k_;
    return true;
  }

 private:
  std::shared_ptr<const FrictionLaw> law_;
  double k_;
};

}  // namespace

std::shared_ptr<const FrictionLaw> friction_at_radius(std::shared_ptr<const FrictionLaw> law, double law_radius_mm,
                                                      double model_radius_mm) {
  if (!(law_radius_mm > 0.0) || !(model_radius_mm > 0.0))
    throw std::invalid_argument("friction radius conversion needs positive radii");
  return std::make_shared<RadiusScaledFriction>(std::move(law), law_radius_mm / model_radius_mm);
}

Fluid with_friction_radius(Fluid fluid, double model_radius_mm) {
  if (!(fluid.friction_radius_mm > 0.0)) return fluid;
  if (std::abs(fluid.friction_radius_mm / model_radius_mm - 1.0) <= 1e-9) return fluid;
  fluid.friction = friction_at_radius(fluid.friction, fluid.friction_radius_mm, model_radius_mm);
  fluid.friction_radius_mm = model_radius_mm;
  fluid.friction_radius_convention = radius_convention_name(RadiusConvention::kUniformPressure);
  return fluid;
}

}  // namespace shudder::clutch
