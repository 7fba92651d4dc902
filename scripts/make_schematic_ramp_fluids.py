#!/usr/bin/env python3
"""Write the SCHEMATIC ramp fluids (scenarios/fluids/schematic_ramp_*.toml).

These are not measured fluids. They are made so that a slow speed ramp on the rig crosses the
stability boundary at a well-defined speed (prediction against simulation). Speeds v
are in rpm at the file's 46 mm mean radius and T is in degC. At T_ref the law is:

    1 rpm <= v <= v_j   log-linear rise of `rise` up to the parabola (steep positive slope);
    v_j <= v <= v_i     mu = mu_p - b (v - v_p)^2: a maximum at v_p, then a fall whose isothermal
                        slope -2 b (v - v_p) is LINEAR in speed;
    v_i <= v <= v_m     the mirrored parabola, mu = mu_p - 2 b (v_i - v_p)^2 + b (v_m - v)^2, which
                        levels off to a flat minimum at v_m = 2 v_i - v_p;
    v > v_m             held (flat).

The temperature slope is alpha(v) = alpha_0 + gamma (v - v_p) on [v_j, v_m] and is held
outside it, so the slope on [v_j, v_i] is dmu/dv = -2 b (v - v_p) + gamma (T - T_ref). That is
still linear in speed, but its zero moves by gamma/(2 b) rpm per K.

Why this shape:
  * Each ring of the clutch slides at (r_i / 46 mm) v, that is 0.83 v to 1.23 v for the
    38.1-56.4 mm clutch. While every ring is on [v_j, v_i], the clutch's torque slope
    dM/d|dw| = sum_i F_i r_i^2 dmu/dv_i is linear in speed. Along a linear speed ramp the rig's
    growth rate then rises linearly in time. The log amplitude of the oscillation is then a
    parabola in time, and its vertex is the onset.
  * The parabola's range is wide. It runs from v_j <= 0.83 x (the lowest onset) to
    v_i >= 1.23 x (the highest onset + the speed gained while the oscillation grows). The
    growth is therefore linear throughout.
  * The steep rising branch below v_j and the flat top above v_m damp. They bound the grown
    vibration, so the slip stays above zero (vibration, not stick-slip).

The [linear] law interpolates linearly in ln(v) between the tabulated speeds
(clutch/linear_friction.hpp). The parabolas are tabulated every 6 % in speed (40 points a
decade). Within a segment the interpolated slope departs from the parabola's by a few per cent,
and the rings' spread of speeds smooths that out. The prediction evaluates the same tabulated
law, so the tabulation does not bias the comparison.

Standard library only. Usage: scripts/make_schematic_ramp_fluids.py [--outdir scenarios/fluids]
"""

import argparse
import math
import os

T_REF_C = 40.0
STEP_RATIO = 10.0 ** (1.0 / 40.0)

# v_j, v_p, v_i (rpm): start of the parabola, maximum, inflection; mu_p: mu at v_p and T_ref;
# b: curvature (1/rpm^2); rise: mu(v_j) - mu(1 rpm); alpha0 (1/degC); gamma (1/(degC rpm)).
FLUIDS = [
    dict(name="schematic_ramp_peak10", v_j=7.0, v_p=10.0, v_i=40.0, mu_p=0.130, b=7.5e-6,
         rise=0.03, alpha0=-2.0e-4, gamma=0.0,
         what="friction maximum at 10 rpm, gentle fall above it"),
    dict(name="schematic_ramp_peak20", v_j=16.0, v_p=20.0, v_i=42.0, mu_p=0.125, b=1.0e-5,
         rise=0.03, alpha0=-2.0e-4, gamma=0.0,
         what="friction maximum at 20 rpm, steeper fall above it"),
    dict(name="schematic_ramp_thermal", v_j=10.0, v_p=16.0, v_i=44.0, mu_p=0.120, b=6.0e-6,
         rise=0.03, alpha0=-2.0e-4, gamma=-1.0e-5,
         what="friction maximum at 16 rpm at 40 degC, moving to lower speed as it warms"),
]


def v_m(f):
    """End of the fall (rpm): the slope is back to zero there, and the law is held above it."""
    return 2.0 * f["v_i"] - f["v_p"]


def speeds(f):
    v = [1.0, f["v_j"]]
    x = f["v_j"]
    while x * STEP_RATIO < v_m(f) * (1 - 1e-3):
        x *= STEP_RATIO
        v.append(x)
    v.append(v_m(f))
    return v


def parabola(f, v):
    """mu at T_ref on [v_j, v_m]."""
    if v <= f["v_i"]:
        return f["mu_p"] - f["b"] * (v - f["v_p"]) ** 2
    return f["mu_p"] - 2.0 * f["b"] * (f["v_i"] - f["v_p"]) ** 2 + f["b"] * (v_m(f) - v) ** 2


def line(f, v):
    """(alpha, mu at T_ref) at a tabulated speed v."""
    if v < f["v_j"]:
        w = math.log(v) / math.log(f["v_j"])  # 0 at 1 rpm, 1 at v_j
        return f["alpha0"], parabola(f, f["v_j"]) - f["rise"] * (1.0 - w)
    return f["alpha0"] + f["gamma"] * (v - f["v_p"]), parabola(f, v)


def fmt(values, per_line=6, digits=9):
    rows = []
    for i in range(0, len(values), per_line):
        rows.append("  " + ", ".join(f"{x:.{digits}g}" for x in values[i:i + per_line]))
    return "[\n" + ",\n".join(rows) + ",\n]"


def text(f):
    v = speeds(f)
    alpha, beta = [], []
    for x in v:
        a, mu_ref = line(f, x)
        alpha.append(a)
        beta.append(mu_ref - a * T_REF_C)  # mu at 0 degC
    vm = v_m(f)
    slope_i = -2 * f["b"] * (f["v_i"] - f["v_p"])
    mu_j, mu_m = parabola(f, f["v_j"]), parabola(f, vm)
    if f["gamma"] != 0.0:
        temp_note = (
            f"# alpha(v) = {f['alpha0']:g} + ({f['gamma']:g}) (v - v_p) per degC on [v_j, v_m] (held outside).\n"
            f"# The slope's zero moves by gamma/(2 b) = {f['gamma'] / (2 * f['b']):.3g} rpm per K, so warming moves\n"
            f"# it to LOWER speeds and brings the onset earlier on a ramp (a temperature-driven shift).\n")
    else:
        temp_note = f"# alpha = {f['alpha0']:g} per degC at every speed: temperature shifts mu but not its slope.\n"
    return f"""# SCHEMATIC fluid, not a measured one: {f['what']}.
# Generated by scripts/make_schematic_ramp_fluids.py. Do not edit it; change the script instead.
# Made for speed-ramp shudder onset tests (tests/studies/test_prediction_vs_simulation.cpp).
# At T_ref = {T_REF_C:g} degC, with v the speed in rpm at 46 mm:
#   v_j = {f['v_j']:g} <= v <= v_i = {f['v_i']:g}: mu = {f['mu_p']:g} - {f['b']:g} (v - {f['v_p']:g})^2. The maximum is at
#       v_p = {f['v_p']:g} rpm. The isothermal slope -2 b (v - v_p) is LINEAR in speed, reaching
#       {slope_i:.3g} per rpm at v_i. A linear speed ramp therefore raises the rig's growth rate
#       linearly in time.
#   v_i <= v <= v_m = {vm:g}: the mirrored parabola levels off to a flat minimum, mu = {mu_m:.4g}. The
#       law is held above v_m.
#   1 rpm <= v < v_j: a log-linear rise from {mu_j - f['rise']:.4g} to {mu_j:.4g}. This steep rising
#       branch damps, and with the flat top it bounds the vibration, so the slip stays above zero.
{temp_note}# The parabolas are tabulated every 6 % in speed and interpolated in ln(v), as the [linear] law
# always is. Breakaway equals the 1 rpm kinetic value.

[fluid]
name = "{f['name'].replace('_', '-')}"
description = "Schematic: {f['what']}"
nu40_cSt = 35.0    # as fluid C (schematic)
nu100_cSt = 6.7

[static_friction]
breakaway_ratio = 1.0
source = "schematic: breakaway = kinetic friction at 1 rpm"

[linear]
mean_radius_mm = 46.0
speeds_rpm = {fmt(v)}
alpha_per_C = {fmt(alpha)}
beta = {fmt(beta)}
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--outdir", default=os.path.join(os.path.dirname(__file__), "..", "scenarios", "fluids"))
    args = ap.parse_args()
    for f in FLUIDS:
        path = os.path.join(args.outdir, f["name"] + ".toml")
        with open(path, "w") as out:
            out.write(text(f))
        print("wrote", os.path.normpath(path))


if __name__ == "__main__":
    main()
