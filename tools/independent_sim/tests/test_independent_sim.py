"""Tests of the independent simulator and a regression of `shudder diagnose` on its runs.

The diagnosis tests need SHUDDER_CLI (set by ctest: tests/CMakeLists.txt `independent_sim`).
"""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import indep_sim as sim  # noqa: E402
import study  # noqa: E402

FLUID = study.FLUID


def law(c, v):
    return c[0] * np.tanh(c[1] * v) + c[2] * v ** 0.1 + c[3]


def test_friction_is_paper_g_eq13_with_the_printed_70C_20kN_set():
    # Paper G Table 2, 70 C / 20 kN: (-0.039, 0.001, 0.077, -0.024); the fluid file keeps that
    # row as printed. Speeds below 6 mm/s are clamped to 6 (Paper G). Exact up to rounding.
    fr = sim.Friction(FLUID)
    v = np.array([1.0, 6.0, 241.0, 590.0])
    expected = law((-0.039, 0.001, 0.077, -0.024), np.maximum(v, 6.0))
    assert np.allclose(fr.mu(v, np.full(4, 70.0), 20000.0), expected, rtol=0, atol=1e-12)


def test_friction_interpolates_mu_between_load_sets_not_the_coefficients():
    # 22.5 kN at 70 C is midway between the printed 20 and 25 kN sets: mu is the mean of their mu
    # values (docs/physics.md section 1). Exact up to rounding.
    fr = sim.Friction(FLUID)
    v = np.array([10.0, 100.0, 400.0])
    expected = 0.5 * (law((-0.039, 0.001, 0.077, -0.024), v) + law((-0.038, 0.002, 0.089, -0.036), v))
    assert np.allclose(fr.mu(v, np.full(3, 70.0), 22500.0), expected, rtol=0, atol=1e-12)


def test_sensor_lag_is_exact_for_a_ramp():
    # y' = (x - y)/tau with x = a t, y(0) = 0: y = a (t - tau (1 - exp(-t/tau))). The
    # first-order-hold update is exact for piecewise-linear input: round-off only.
    t = np.arange(0.0, 5.0, 0.01)
    y = sim.first_order_lag(3.0 * t, 0.7, 0.01)
    assert np.allclose(y, 3.0 * (t - 0.7 * (1.0 - np.exp(-t / 0.7))), rtol=0, atol=1e-10)


def test_calibration_meets_paper_g_case_1():
    # h0 was calibrated so that Case 1 at 10.4 kN from 77 C reads 90 C at 10 s (Paper G Fig. 8);
    # the 25.3 kN run was not used and must land in Paper G's "almost 110 C" band (103-115 C,
    # docs/thermal_model.md) with torque over 105 N m; 10.4 kN torque "about 45 N m" (40-50).
    ramp = dict(time_s=[0.0, 10.0], speed_rpm=[1.0, 100.0])
    low = sim.simulate(sim.Run(force_N=10400.0, start_C=77.0, **ramp), sim.Hidden(), FLUID)
    high = sim.simulate(sim.Run(force_N=25300.0, start_C=77.0, **ramp), sim.Hidden(), FLUID)
    assert low["temp_C"][-1] == pytest.approx(90.0, abs=0.05)  # bisection to 1e-4 of h0
    assert 40.0 <= low["torque_Nm"][-1] <= 50.0
    assert 103.0 <= high["temp_C"][-1] <= 115.0
    assert high["torque_Nm"][-1] >= 105.0


def test_rig_heat_capacity_slows_the_down_ramp_cooling():
    # Paper G Case 2: rig parts that store heat make the measured temperature fall more slowly on
    # the down-ramp. Peak (17 s) to end (30 s) drop with a 300 J/K, 20 W/K mass vs without.
    run = sim.Run(force_N=14800.0, start_C=80.0)
    bare = sim.simulate(run, sim.Hidden(), FLUID)["temp_C"]
    rig = sim.simulate(run, sim.Hidden(rig_C_J_per_K=300.0, rig_G_W_per_K=20.0), FLUID)["temp_C"]
    drop = lambda x: x[1700] - x[-1]  # noqa: E731
    assert rig.max() < bare.max()          # part of the heat goes into the mass
    assert drop(rig) < 0.8 * drop(bare)    # and comes back on the way down (seen: ~0.6)


def test_faults_act_on_the_readings_only():
    # Gains and offsets of the cells change what is recorded, not the physics: exact relations.
    run = sim.Run(force_N=14800.0, start_C=80.0)
    bare = sim.simulate(run, sim.Hidden(), FLUID)
    f = sim.simulate(run, sim.Hidden(torque_gain=1.03, torque_offset_Nm=2.0, tc_offset_K=1.5,
                                      load_gain=0.95, bearing_mu=0.004), FLUID)
    drag = 0.004 * 14800.0 * sim.BEARING_RADIUS_M
    assert np.allclose(f["torque_Nm"], 1.03 * (bare["torque_Nm"] + drag) + 2.0, rtol=0, atol=1e-9)
    assert np.allclose(f["temp_C"], bare["temp_C"] + 1.5, rtol=0, atol=1e-9)
    assert np.allclose(f["normal_force_N"], 0.95 * 14800.0, rtol=0, atol=1e-9)
    assert np.allclose(f["ir_temp_C"], bare["ir_temp_C"], rtol=0, atol=1e-9)


# --- `shudder diagnose` on the independent simulator's runs (docs/diagnosis.md section 6) ---

CLI = os.environ.get("SHUDDER_CLI")
needs_cli = pytest.mark.skipif(not CLI, reason="SHUDDER_CLI not set (ctest sets it)")


@pytest.fixture(scope="module")
def tolerance(tmp_path_factory):
    folder = str(tmp_path_factory.mktemp("none"))
    runs = study.write_runs(sim.Hidden(), folder)
    ref, _, _ = study.diagnose(CLI, runs, os.path.join(folder, "gap.json"), ["--max-effects", "0"])
    return study.tolerance_from(ref, "beyond_noise")


def diagnose(tmp_path, hidden, tolerance):
    runs = study.write_runs(hidden, str(tmp_path))
    res, _, _ = study.diagnose(CLI, runs, str(tmp_path / "d.json"), ["--jobs", "2", "--tolerance", tolerance])
    return res


@needs_cli
def test_nothing_hidden_names_nothing_within_the_tolerance(tmp_path, tolerance):
    # The model-form gap alone (another discretisation and oil-cooling law, ~1.6 C on temp_C) with
    # the tolerance chosen as docs/diagnosis.md says: nothing named, explained.
    res = diagnose(tmp_path, sim.Hidden(), tolerance)
    assert res["missing_effects"] == []
    assert res["verdict"] == "explained"


@needs_cli
def test_bearing_drag_is_named_through_the_model_form_gap(tmp_path, tolerance):
    # A bearing drag mu 0.005 (the rig's own figure, ~3.5 N m at 14.8 kN) on top of the gap:
    # named alone, within 20 % (the target; seen +2 %).
    res = diagnose(tmp_path, sim.Hidden(bearing_mu=0.005), tolerance)
    assert res["missing_effects"] == ["bearing_drag"]
    mu = res["final_effects"][0]["parameters"]["equivalent_mu"]
    assert mu == pytest.approx(0.005, rel=0.2)


@needs_cli
def test_a_thermocouple_offset_is_named_through_the_ir_spot(tmp_path, tolerance):
    # +2 K on the thermocouple: the replay's start temperature (read off the thermocouple) hides
    # it from temp_C; the thermocouple against the IR spot shows it. Named alone within 20 % (seen
    # 2.30 K, +15 %: the oil-flow gap's share).
    res = diagnose(tmp_path, sim.Hidden(tc_offset_K=2.0), tolerance)
    assert res["missing_effects"] == ["thermocouple_offset"]
    assert res["final_effects"][0]["parameters"]["offset_K"] == pytest.approx(2.0, rel=0.2)


@needs_cli
def test_a_half_second_sensor_lag_is_named_alone(tmp_path, tolerance):
    # A 0.5 s thermocouple lag, ~0.9 C RMS inside a 1.5 C temperature tolerance: named alone within
    # 20 % (seen 0.565 s).
    res = diagnose(tmp_path, sim.Hidden(tc_lag_s=0.5), tolerance)
    assert res["missing_effects"] == ["temperature_sensor_lag"]
    assert res["final_effects"][0]["parameters"]["time_constant_s"] == pytest.approx(0.5, rel=0.2)


# --- `shudder characterise` on the independent simulator's ramps, replayed through shudder's model ---

def characterise_and_replay(tmp_path, radius):
    """Paper D cycles at 15 kN from 40, 60, 80 C (seeds 21-23), characterised with `radius` for
    the Case 2 scenario's clutch, replayed through that scenario with the fitted fluid
    (`diagnose --max-effects 0`): torque RMS over noise."""
    runs = []
    for seed, start in ((21, 40.0), (22, 60.0), (23, 80.0)):
        path = str(tmp_path / f"r{int(start)}.csv")
        sig = sim.simulate(sim.Run(force_N=15000.0, start_C=start), sim.Hidden(), FLUID)
        sim.write_csv(path, sim.add_noise(sig, seed), seed, "characterise round trip")
        runs.append(path)
    fluid = str(tmp_path / f"fit_{radius}.toml")
    subprocess.run([CLI, "characterise", *runs, "-o", fluid, "--nu40-cSt", "35", "--nu100-cSt", "6.7",
                    "--radius", radius, "--model", study.MODEL], check=True, capture_output=True)
    with open(study.MODEL) as f:
        text = f.read().replace('fluid = "fluids/lsc_fluid_c.toml"', f'fluid = "{fluid}"')
    model = str(tmp_path / f"model_{radius}.toml")
    with open(model, "w") as f:
        f.write(text)
    out = str(tmp_path / f"replay_{radius}.json")
    subprocess.run([CLI, "diagnose", model, *runs, "--max-effects", "0", "--json", out], check=True,
                   capture_output=True)
    with open(out) as f:
        torque = [c for c in json.load(f)["channels"] if c["signal"] == "torque_Nm"][0]
    return torque["final_rms"] / torque["noise"]


@needs_cli
@pytest.mark.parametrize("radius", ["model", "uniform_wear"])
def test_a_characterised_fluid_replays_its_runs_through_the_model(tmp_path, radius):
    # The true fluid C replays these runs through shudder's model at 1.05 x the noise (the two
    # simulators' thermal model-form gap); the characterised fluid at 1.14 x (measured, either
    # radius: the file records it, the clutch converts it). 1.25 x allows that plus seed scatter; a
    # law read at the wrong radius (46 against 47.84 mm, 4 % in mu) misses by more than 4 x.
    assert characterise_and_replay(tmp_path, radius) <= 1.25
