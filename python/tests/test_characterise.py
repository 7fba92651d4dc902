# shudder.characterise / compare: the CLI's commands on simulated ramp logs; the same fit, fluid
# file and messages as the CLI.
import json

import pytest

import shudder
from conftest import SOURCE, cli

FLUID_ARGS = ["--nu40-cSt", "35", "--nu100-cSt", "6.7", "--radius", "uniform_pressure"]

# Paper D cycle (docs/characterisation.md): hold at 1 rpm, 10 s up to 100 rpm, hold, 10 s down, hold.
RAMP_SCENARIO = """[scenario]
name = "ramps"
type = "prescribed_slip"
duration_s = 26.0

[clutch]
fluid = "{fluids}/lsc_fluid_c.toml"
start_temp_C = {t0}

[drive]
time_s = [0.0, 2.0, 12.0, 14.0, 24.0, 26.0]
speed_rpm = [1.0, 1.0, 100.0, 100.0, 1.0, 1.0]
normal_force_N = {load}

[output]
sample_rate_Hz = 50.0
"""


@pytest.fixture(scope="module")
def ramp_logs(tmp_path_factory):
    """Six noisy ramp logs (CSV): 10 and 20 kN from 40, 60 and 80 degC, written by `shudder run`."""
    d = tmp_path_factory.mktemp("ramps")
    names = []
    seed = 1
    for load in (10000.0, 20000.0):
        for t0 in (40.0, 60.0, 80.0):
            toml = d / f"r{seed}.toml"
            toml.write_text(RAMP_SCENARIO.format(fluids=SOURCE / "scenarios" / "fluids", t0=t0, load=load))
            code, _, err = cli("run", toml, "-o", d / f"r{seed}.h5", "--measurement", d / f"r{seed}.csv",
                               "--noise", "--seed", seed)
            assert code == 0, err
            names.append(str(d / f"r{seed}.csv"))
            seed += 1
    return d, names


def test_characterise_equals_the_cli_fit_and_fluid_file(ramp_logs):
    d, runs = ramp_logs
    fit = shudder.characterise(runs, output=str(d / "py.toml"), nu40_cSt=35, nu100_cSt=6.7, radius="uniform_pressure")
    code, _, err = cli("characterise", *runs, "-o", d / "cli.toml", "--json", d / "cli.json", *FLUID_ARGS)
    assert code == 0, err
    assert fit["format"] == "shudder-characterisation/1"
    # Maki rows: 2 loads x (3 start temperatures + the hot row at the hottest temperature reached)
    assert len(fit["rows"]) == 8
    cli_fit = json.loads((d / "cli.json").read_text())
    # Everything but the output names is the same computation on the same files: equal exactly.
    for key in ("rows", "ramps_used"):
        assert fit[key] == cli_fit[key], key
    py_text = (d / "py.toml").read_text().replace("py.toml", "X")
    cli_text = (d / "cli.toml").read_text().replace("cli.toml", "X")
    assert py_text.replace('"py"', '"X"') == cli_text.replace('"cli"', '"X"')
    # The fitted fluid is one that screen accepts (the loop a user closes in a notebook).
    screened = shudder.screen(str(d / "py.toml"), load_N=15000.0)
    assert screened["format"] == "shudder-screen/1" and screened["verdict_level"] in ("LOW RISK", "CAUTION", "RISK")


def test_characterise_errors_are_the_cli_ones(ramp_logs, tmp_path):
    _, runs = ramp_logs
    missing = str(tmp_path / "none.csv")
    with pytest.raises(shudder.InputError) as e:
        shudder.characterise([missing], output=str(tmp_path / "o.toml"), nu40_cSt=35, nu100_cSt=6.7)
    code, _, err = cli("characterise", missing, "-o", tmp_path / "o.toml", "--nu40-cSt", "35", "--nu100-cSt", "6.7")
    assert code == 2 and err == "shudder: error: " + str(e.value) + "\n"
    with pytest.raises(shudder.InputError, match="--law: 'bogus' is not one of maki, linear, table"):
        shudder.characterise(runs, output=str(tmp_path / "o.toml"), nu40_cSt=35, nu100_cSt=6.7, law="bogus")
    assert not (tmp_path / "o.toml").exists()


def test_compare_equals_the_cli_json(tmp_path):
    fluids = [str(SOURCE / "scenarios" / "fluids" / f) for f in ("paper_e_fluid_a.toml", "paper_e_fluid_e.toml")]
    out = shudder.compare(fluids, temps=[30, 90])
    code, _, err = cli("compare", *fluids, "--temps", "30,90", "--json", tmp_path / "c.json")
    assert code == 0, err
    assert out == json.loads((tmp_path / "c.json").read_text())
    assert [(f["name"], f["rank"]) for f in out["fluids"]] == [("paper-e-fluid-a", 1), ("paper-e-fluid-e", 2)]
