#!/usr/bin/python3
"""Study: `shudder diagnose` on runs of the independent simulator (indep_sim.py).

Per case: three Paper G Case 2 runs at 10.4, 25.3 and 14.8 kN from 80 C (the loads of
bench/bench_diagnose.cpp's every-effect-off benchmark; the 14.8 kN run last, held out), noise
seeds 1, 2, 3, with nothing or one effect hidden; diagnosed against
scenarios/paper_g_case2_15kN.toml as shipped, with the model-form tolerance chosen as
docs/diagnosis.md "Choosing a tolerance" says: each channel's RMS gap on the nothing-hidden runs
(`--max-effects 0`, so nothing can stand in). Prints one table row per case:
case, truth, named (with parameters), verdict, outcome, CPU and wall time.

    /usr/bin/python3 tools/independent_sim/study.py --shudder build/app/shudder [--cases a,b]
"""
import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import indep_sim as sim  # noqa: E402

FLUID = os.path.join(ROOT, "scenarios", "fluids", "lsc_fluid_c.toml")
MODEL = os.path.join(ROOT, "scenarios", "paper_g_case2_15kN.toml")
LOADS_N = (10400.0, 25300.0, 14800.0)

# case -> (hidden effects, {effect: {parameter: true value}}); gains are judged on g - 1.
CASES = {
    "none": (sim.Hidden(), {}),
    "lag_0.5s": (sim.Hidden(tc_lag_s=0.5), {"temperature_sensor_lag": {"time_constant_s": 0.5}}),
    "lag_1s": (sim.Hidden(tc_lag_s=1.0), {"temperature_sensor_lag": {"time_constant_s": 1.0}}),
    "rig_150_10": (sim.Hidden(rig_C_J_per_K=150.0, rig_G_W_per_K=10.0),
                   {"rig_heat_capacity": {"heat_capacity_J_per_K": 150.0, "conductance_W_per_K": 10.0}}),
    "rig_300_20": (sim.Hidden(rig_C_J_per_K=300.0, rig_G_W_per_K=20.0),
                   {"rig_heat_capacity": {"heat_capacity_J_per_K": 300.0, "conductance_W_per_K": 20.0}}),
    "bearing_0.005": (sim.Hidden(bearing_mu=0.005), {"bearing_drag": {"equivalent_mu": 0.005}}),
    "torque_gain_1.03": (sim.Hidden(torque_gain=1.03), {"torque_sensor_gain": {"gain": 1.03}}),
    "load_gain_0.95": (sim.Hidden(load_gain=0.95), {"load_sensor_gain": {"gain": 0.95}}),
    "tc_offset_+2K": (sim.Hidden(tc_offset_K=2.0), {"thermocouple_offset": {"offset_K": 2.0}}),
    "torque_offset_3Nm": (sim.Hidden(torque_offset_Nm=3.0), {"torque_sensor_offset": {"offset_Nm": 3.0}}),
}
GAINS = {("torque_sensor_gain", "gain"), ("load_sensor_gain", "gain")}


def write_runs(hidden, folder):
    paths = []
    for seed, force in enumerate(LOADS_N, start=1):
        sig = sim.simulate(sim.Run(force_N=force, start_C=80.0), hidden, FLUID)
        p = os.path.join(folder, f"indep_{force / 1000:.1f}kN.csv")
        sim.write_csv(p, sim.add_noise(sig, seed), seed, repr(hidden))
        paths.append(p)
    return paths


def diagnose(shudder, runs, out_json, extra):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    proc = subprocess.run([shudder, "diagnose", MODEL, *runs, "--json", out_json, *extra],
                          capture_output=True, text=True)
    wall = time.time() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if proc.returncode != 0:
        raise RuntimeError(f"diagnose exit {proc.returncode}: {proc.stderr.strip()}")
    with open(out_json) as f:
        return json.load(f), cpu, wall


def tolerance_from(result, rule):
    """The model-form tolerance per channel from the nothing-hidden runs' baseline RMS.

    rule "rms": the RMS itself (an earlier rule of docs/diagnosis.md); "beyond_noise": the part
    of the RMS beyond the channel's noise, sqrt(RMS^2 - sigma^2) -- the scale, noise and
    tolerance in quadrature, then equals the RMS the true model leaves (J_c = 1 on the
    reference), instead of counting the noise twice."""
    parts = []
    for c in result["channels"]:
        rms = c["baseline_rms"]
        tol = rms if rule == "rms" else max(rms * rms - c["noise"] ** 2, 0.0) ** 0.5
        parts.append(f"{c['signal']}={tol:.3g}")
    return ",".join(parts)


def judge(result, truth):
    """Outcome against the target, and the parameters' relative errors."""
    named = {f["effect"]: f["parameters"] for f in result.get("final_effects", [])}
    verdict = result.get("verdict", "?")
    errors = {}
    for effect, params in truth.items():
        if effect in named:
            for key, true in params.items():
                got = named[effect][key]
                rel = (got - 1) / (true - 1) - 1 if (effect, key) in GAINS else got / true - 1
                errors[f"{effect}.{key}"] = rel
    extra = sorted(set(named) - set(truth))
    found = [e for e in truth if e in named]
    within = all(abs(v) <= 0.2 for v in errors.values())
    if extra:
        outcome = "INVENTED " + "+".join(extra)
    elif not truth:
        outcome = "ok (nothing named)"
    elif len(found) == len(truth) and within:
        outcome = "ok (named, within 20 %)"
    elif len(found) == len(truth):
        outcome = "named, parameter off > 20 %"
    elif verdict == "explained":
        outcome = "MISSED silently (explained)"
    else:
        outcome = f"missed, honest ({verdict})"
    return named, errors, verdict, outcome


def fmt_named(named):
    if not named:
        return "-"
    return "; ".join(e + " " + ", ".join(f"{k}={v:.4g}" for k, v in p.items()) for e, p in named.items())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--shudder", default=os.path.join(ROOT, "build", "app", "shudder"))
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--jobs", default="2")
    ap.add_argument("--keep", help="folder to keep the runs and JSON in")
    ap.add_argument("--tolerance-rule", choices=("rms", "beyond_noise"), default="beyond_noise")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="indep_study_")
    os.makedirs(work, exist_ok=True)
    none_dir = os.path.join(work, "none")
    os.makedirs(none_dir, exist_ok=True)
    runs = write_runs(CASES["none"][0], none_dir)
    ref, _, _ = diagnose(a.shudder, runs, os.path.join(none_dir, "gap.json"), ["--max-effects", "0"])
    tol = tolerance_from(ref, a.tolerance_rule)
    print(f"tolerance (nothing-hidden baseline RMS): {tol}")
    print("| case | truth | named (final parameters) | error vs truth | verdict | outcome | CPU s | wall s |")
    print("|---|---|---|---|---|---|---|---|")
    for name in a.cases.split(","):
        hidden, truth = CASES[name]
        folder = os.path.join(work, name)
        os.makedirs(folder, exist_ok=True)
        runs = write_runs(hidden, folder)
        res, cpu, wall = diagnose(a.shudder, runs, os.path.join(folder, "diagnosis.json"),
                                  ["--jobs", a.jobs, "--tolerance", tol])
        named, errors, verdict, outcome = judge(res, truth)
        truth_s = fmt_named(truth)
        err_s = ", ".join(f"{k.split('.')[-1]} {v:+.0%}" for k, v in errors.items()) or "-"
        print(f"| {name} | {truth_s} | {fmt_named(named)} | {err_s} | {verdict} | {outcome} "
              f"| {cpu:.1f} | {wall:.1f} |", flush=True)
    print(f"(runs and JSON in {work})")


if __name__ == "__main__":
    main()
