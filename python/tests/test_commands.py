# shudder.sweep / screen / diagnose: the CLI's commands, their files and messages.
import json

import h5py
import numpy as np
import pytest

import shudder
from conftest import SOURCE, cli, scenario

KEY = "rig.torsion_bar.natural_frequency_Hz"


def short_sweep_scenario(tmp_path):
    """The torsion-bar sweep scenario shortened to 0.5 s (cases of ~10 ms)."""
    text = (SOURCE / "scenarios" / "sweep_torsion_bar.toml").read_text()
    text = text.replace("duration_s = 20.0", "duration_s = 0.5").replace("time_s = [0.0, 20.0]", "time_s = [0.0, 0.5]")
    text = text.replace('fluid = "fluids/', 'fluid = "' + str(SOURCE / "scenarios" / "fluids") + "/")
    path = tmp_path / "s.toml"
    path.write_text(text)
    return str(path)


# The /cases table equals the CLI's sweep of the same grid, column by column, exactly.
def test_sweep_returns_the_cli_cases_table(tmp_path):
    s = short_sweep_scenario(tmp_path)
    out = shudder.sweep(s, {KEY: [150.0, 250.0, 450.0]}, output=str(tmp_path / "py.h5"), jobs=2)
    code, _, err = cli("sweep", s, "--set", KEY + "=150,250,450", "--jobs", "2", "-o", tmp_path / "cli.h5")
    assert code == 0, err
    cases = out["cases"]
    assert list(cases[KEY]) == [150.0, 250.0, 450.0]
    assert out["units"]["amplitude_Nm"] == "N m"
    with h5py.File(tmp_path / "cli.h5") as f:
        for name, values in cases.items():
            col = f["cases"][name][()]
            if col.dtype.kind in "SO":
                col = [c.decode() if isinstance(c, bytes) else c for c in col]
                assert list(values) == list(col), name
            else:
                np.testing.assert_array_equal(values, col, err_msg=name)
    # The scenario predicts shudder below 355 Hz and none above (its header): 150/250 vs 450.
    assert list(cases["predicted_stable"]) == [0.0, 0.0, 1.0]


def test_sweep_range_string_and_its_errors_are_the_cli_ones(tmp_path):
    s = short_sweep_scenario(tmp_path)
    out = shudder.sweep(s, {KEY: "200:400:100"}, output=str(tmp_path / "r.h5"), jobs=1)
    assert list(out["cases"][KEY]) == [200.0, 300.0, 400.0]
    with pytest.raises(shudder.InputError) as e:
        shudder.sweep(s, [KEY + "=200,300", KEY + "=400"], output=str(tmp_path / "d.h5"))
    code, _, err = cli("sweep", s, "--set", KEY + "=200,300", "--set", KEY + "=400", "-o", tmp_path / "d.h5")
    assert code == 2 and err == "shudder: error: " + str(e.value) + "\n"


# screen: the dict is the CLI's --json file.
def test_screen_returns_the_cli_json(tmp_path):
    fluid = scenario("fluids/lsc_fluid_c.toml")
    d = shudder.screen(fluid, temps=[40, 80])
    code, _, err = cli("screen", fluid, "--temps", "40,80", "--json", tmp_path / "s.json")
    assert code == 0, err
    assert d == json.loads((tmp_path / "s.json").read_text())


def test_screen_missing_fluid_is_the_cli_input_error(tmp_path):
    missing = str(tmp_path / "none.toml")
    with pytest.raises(shudder.InputError) as e:
        shudder.screen(missing)
    code, _, err = cli("screen", missing)
    assert code == 2 and err == "shudder: error: " + str(e.value) + "\n"


def test_diagnose_missing_run_is_the_cli_input_error(tmp_path):
    missing = str(tmp_path / "run.csv")
    with pytest.raises(shudder.InputError) as e:
        shudder.diagnose(scenario("paper_g_case2_15kN.toml"), [missing])
    code, _, err = cli("diagnose", scenario("paper_g_case2_15kN.toml"), missing)
    assert code == 2 and err == "shudder: error: " + str(e.value) + "\n"


# diagnose: a run measured with bearing drag hidden; the dict is the JSON and names the effect.
def test_diagnose_finds_the_hidden_effect(tmp_path):
    probe = (SOURCE / "scenarios" / "diagnosis_probe.toml").read_text()
    probe = probe.replace('fluid = "fluids/', 'fluid = "' + str(SOURCE / "scenarios" / "fluids") + "/")
    (tmp_path / "hidden.toml").write_text(probe + "\n[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.005\n")
    # One run at one constant force cannot tell a bearing drag from a torque-cell offset (the same
    # constant torque, no heat in the clutch): the model declares its cell zeroed, as the CLI test does.
    (tmp_path / "model.toml").write_text(probe + "\n[effects.torque_sensor_offset]\nenabled = true\noffset_Nm = 0.0\n")
    code, _, err = cli("run", "hidden.toml", "-o", "hidden.h5", "--measurement", "a.csv", "--sample-rate", "100",
                       "--noise", "--seed", "1", cwd=tmp_path)
    assert code == 0, err
    d = shudder.diagnose(str(tmp_path / "model.toml"), [str(tmp_path / "a.csv")], jobs=2)
    assert d["format"] == "shudder-diagnosis/1"
    assert d["missing_effects"] == ["bearing_drag"]


def test_screen_without_an_index_is_not_judged_not_an_exception(tmp_path):
    # A table law measured at 20-30 degC: none of the default 40/80/120 degC is inside its data.
    fluid = tmp_path / "cold.toml"
    fluid.write_text('[fluid]\nname = "cold"\nnu40_cSt = 35.0\nnu100_cSt = 6.7\n'
                     '[static_friction]\nbreakaway_ratio = 1.0\n'
                     '[table]\nspeeds_mm_s = [5.0, 50.0, 500.0]\nloads_N = [20000.0]\n'
                     '[[table.row]]\ntemp_C = 20.0\nmu = [[0.10, 0.11, 0.12]]\n'
                     '[[table.row]]\ntemp_C = 30.0\nmu = [[0.09, 0.10, 0.11]]\n')
    result = shudder.screen(str(fluid))
    assert result["verdict_level"] == "NOT JUDGED", result["verdict"]
    assert shudder.screen(str(fluid), temps=[25])["verdict_level"] == "LOW RISK"
