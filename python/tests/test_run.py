# shudder.load / shudder.run: the same numbers as `shudder run`, overrides as `sweep --set`
# sets keys, the CLI's one-line errors as exceptions, the GIL released while a run computes.
import re
import threading
import time

import h5py
import numpy as np
import pytest

import shudder
from conftest import SOURCE, cli, scenario

CASE1 = scenario("paper_g_case1_10kN.toml")


def project_version():
    text = (SOURCE / "CMakeLists.txt").read_text()
    return re.search(r"project\(shudder VERSION ([0-9.]+)", text).group(1)


def test_version_is_the_project_version_and_matches_the_cli():
    assert shudder.__version__.startswith(project_version())
    code, out, _ = cli("--version")
    assert code == 0 and out.strip() == "shudder " + shudder.__version__


# Same code path as the CLI: the signals must be bit-identical to the CLI's HDF5 (no tolerance).
def test_run_equals_the_cli_run_file(tmp_path):
    r = shudder.run(CASE1)
    code, _, err = cli("run", CASE1, "-o", tmp_path / "c.h5")
    assert code == 0, err
    with h5py.File(tmp_path / "c.h5") as f:
        for name in ("time_s", "torque_Nm", "temp_C", "slip_speed_rpm"):
            if name not in f["signals"]:
                continue
            np.testing.assert_array_equal(r.signals[name], f["signals"][name][()])
            assert r.units[name] == f["signals"][name].attrs["units"].decode() \
                if isinstance(f["signals"][name].attrs["units"], bytes) else f["signals"][name].attrs["units"]
    assert r.signals["time_s"][0] == 0.0
    assert r.units["torque_Nm"] == "N m"
    assert r.name == "paper_g_case1_10kN"
    assert r.verdict is not None and r.verdict["verdict"] in ("none", "vibration", "stick_slip", "not_judged")


def test_output_file_is_the_cli_file(tmp_path):
    r = shudder.run(CASE1, output=str(tmp_path / "py.h5"))
    with h5py.File(tmp_path / "py.h5") as f:
        np.testing.assert_array_equal(f["signals/torque_Nm"][()], r.signals["torque_Nm"])
        assert f.attrs["scenario"] == r.scenario_text or f.attrs["scenario"].decode() == r.scenario_text


def test_toml_text_with_source_equals_the_file():
    text = pathlib_text(CASE1)
    a = shudder.run(shudder.load(toml=text, source=CASE1))
    b = shudder.run(CASE1)
    np.testing.assert_array_equal(a.signals["torque_Nm"], b.signals["torque_Nm"])


def pathlib_text(path):
    with open(path) as f:
        return f.read()


# An override is the sweep's key setting: the same numbers as the edited file run by the CLI.
def test_override_equals_editing_the_file(tmp_path):
    text = pathlib_text(CASE1).replace("normal_force_N = 10400.0", "normal_force_N = 20000.0")
    text = text.replace('fluid = "fluids/', 'fluid = "' + str(SOURCE / "scenarios" / "fluids") + "/")
    (tmp_path / "edited.toml").write_text(text)
    code, _, err = cli("run", tmp_path / "edited.toml", "-o", tmp_path / "e.h5")
    assert code == 0, err
    r = shudder.run(CASE1, overrides={"drive.normal_force_N": 2e4})
    with h5py.File(tmp_path / "e.h5") as f:
        np.testing.assert_array_equal(r.signals["torque_Nm"], f["signals/torque_Nm"][()])
    base = shudder.run(CASE1)
    # Torque = n mu F r_m: doubling F must raise the torque clearly (not a no-op override).
    assert r.signals["torque_Nm"][1] > 1.5 * base.signals["torque_Nm"][1]


def test_load_then_override_keeps_earlier_overrides():
    sc = shudder.load(CASE1, overrides={"drive.normal_force_N": 2e4})
    a = shudder.run(sc, overrides={"output.sample_rate_Hz": 50.0})
    b = shudder.run(CASE1, overrides={"drive.normal_force_N": 2e4, "output.sample_rate_Hz": 50.0})
    np.testing.assert_array_equal(a.signals["torque_Nm"], b.signals["torque_Nm"])
    assert a.signals["time_s"][1] == pytest.approx(1 / 50.0)  # 50 S/s: 20 ms steps


# The error texts: the CLI's line is "shudder: error: " + str(exception), exit 2.
def test_missing_file_is_the_cli_input_error(tmp_path):
    missing = str(tmp_path / "nope.toml")
    with pytest.raises(shudder.InputError) as e:
        shudder.run(missing)
    code, _, err = cli("run", missing, "-o", tmp_path / "x.h5")
    assert code == 2
    assert err == "shudder: error: " + str(e.value) + "\n"
    assert isinstance(e.value, shudder.Error) and not isinstance(e.value, shudder.NumericalError)


def test_bad_value_in_toml_text_names_the_source_and_line():
    text = pathlib_text(CASE1).replace("normal_force_N = 10400.0", "normal_force_N = -5.0")
    with pytest.raises(shudder.InputError) as e:
        shudder.load(toml=text, source=CASE1)
    assert str(e.value).startswith(CASE1 + ":")
    assert "normal_force_N" in str(e.value)
    assert "\n" not in str(e.value)


def test_override_of_a_text_key_is_the_sweep_set_error(tmp_path):
    # The sweep's reason, said of the override (not of a line of the file the user did not write).
    with pytest.raises(shudder.InputError) as e:
        shudder.run(CASE1, overrides={"scenario.name": 3.0})
    code, _, err = cli("sweep", CASE1, "--set", "scenario.name=3", "-o", tmp_path / "s.h5")
    assert code == 2
    reason = err.split("key 'scenario.name': ", 1)[1].rstrip("\n")
    assert str(e.value) == "overrides['scenario.name'] = 3: " + reason


def test_non_numeric_override_value_is_an_input_error():
    with pytest.raises(shudder.InputError, match=r"key 'drive.normal_force_N': override 'lots' is not a number"):
        shudder.run(CASE1, overrides={"drive.normal_force_N": "lots"})


# A run that fails while it computes is exit 1 in the CLI and NumericalError here, same text:
# the stick-slip rig with the loosest tolerances the reader accepts loses ~4 % of the motor's
# work, beyond the energy guard's 1e-3 (tests/app/test_cli_guards.cpp). The file is still written.
def test_failure_while_computing_is_a_numerical_error_with_the_cli_text(tmp_path):
    text = pathlib_text(scenario("rig_stick_slip.toml"))
    text = text.replace('fluid = "fluids/', 'fluid = "' + str(SOURCE / "scenarios" / "fluids") + "/")
    text += "\n[solver]\nabs_tol = 1e-2\nrel_tol = 1e-2\nmax_step_ms = 1000\n"
    (tmp_path / "loose.toml").write_text(text)
    out = str(tmp_path / "x.h5")
    code, _, err = cli("run", tmp_path / "loose.toml", "-o", out)
    assert code == 1, err
    with pytest.raises(shudder.NumericalError) as e:
        shudder.run(str(tmp_path / "loose.toml"), output=out)
    assert err == "shudder: " + str(e.value) + "\n"
    assert str(e.value).startswith("simulation failed: numerical failure: mechanical energy balance error")
    assert isinstance(e.value, shudder.Error) and not isinstance(e.value, shudder.InputError)


# While a run computes in one thread, another Python thread keeps running: the GIL is released.
# (Held, the main thread could not take a single step until the run returned.)
def test_the_gil_is_released_during_a_run():
    state = {"started": False, "finished": False}

    def work():
        state["started"] = True
        shudder.run(scenario("rig_case2_15kN_175Hz.toml"))
        state["finished"] = True

    t = threading.Thread(target=work)
    t.start()
    steps = 0
    while not state["finished"]:
        if state["started"]:
            steps += 1
        time.sleep(0.001)
    t.join()
    assert steps >= 20


# A network scenario (docs/formats/network_file.md) runs from Python as from the CLI: same signals,
# overrides by `network.COMPONENT.KEY`, the clutches' verdict blocks.
def test_network_run_equals_the_cli_and_takes_overrides(tmp_path):
    net = scenario("networks/four_inertia_chain.toml")
    r = shudder.run(net)
    code, _, err = cli("run", net, "-o", tmp_path / "n.h5")
    assert code == 0, err
    with h5py.File(tmp_path / "n.h5") as f:
        np.testing.assert_array_equal(r.signals["c1.torque_Nm"], f["signals"]["c1.torque_Nm"][()])
    assert r.blocks["verdict"]["clutch"] in ("c1", "c2", "c3")
    assert "verdict.c2" in r.blocks
    # A twice as strong first clutch locks sooner: its heat is the same (1/2 J_eff dw^2), its time shorter.
    faster = shudder.run(net, overrides={"network.c1.max_force_N": 6000})
    lock = lambda res: res.signals["time_s"][np.argmax(res.signals["c1.stuck"] > 0.5)]
    assert lock(faster) < lock(r)
    assert faster.scalars["c1.friction_work_J"] == pytest.approx(r.scalars["c1.friction_work_J"], rel=1e-6)
