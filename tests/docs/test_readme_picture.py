# The README's picture (docs/images/shudder_run.png) is what `shudder plot --what torque` draws
# of the shipped shudder scenario today: it is made afresh here and compared pixel by pixel.
# A model change that moves the run (onset, amplitude, frequency) moves the envelope and the
# detail panels by many pixels and fails this test; scripts/readme-picture.sh then remakes it.
# Tolerance: 0.5 % of the pixels may differ, for round-off between builds that shifts a line by
# a pixel here and there (the plot of one build is byte-identical run after run).
import os
import pathlib
import subprocess

import matplotlib.image
import numpy as np

SOURCE = pathlib.Path(os.environ["SHUDDER_SOURCE_DIR"])
CLI = os.environ["SHUDDER_CLI"]
PICTURE = SOURCE / "docs" / "images" / "shudder_run.png"


def make_picture(tmp):
    run = [CLI, "run", str(SOURCE / "scenarios" / "rig_shudder_negative_slope.toml"), "-o", str(tmp / "s.h5")]
    subprocess.run(run, check=True, capture_output=True, timeout=240)
    plot = [CLI, "plot", str(tmp / "s.h5"), "--what", "torque", "-o", str(tmp / "s.png")]
    subprocess.run(plot, check=True, capture_output=True, timeout=120)
    return matplotlib.image.imread(tmp / "s.png")


def differing_fraction(a, b):
    return float(np.mean(np.any(np.abs(a - b) > 1.0 / 255.0, axis=-1)))


def test_readme_shows_the_picture():
    assert "docs/images/shudder_run.png" in (SOURCE / "README.md").read_text()


def test_picture_is_todays_plot(tmp_path):
    today = make_picture(tmp_path)
    shipped = matplotlib.image.imread(PICTURE)
    assert today.shape == shipped.shape, "the plot's size changed: run scripts/readme-picture.sh"
    fraction = differing_fraction(today, shipped)
    assert fraction <= 0.005, f"{fraction:.2%} of the pixels differ: run scripts/readme-picture.sh"


def test_comparison_sees_a_moved_run(tmp_path):
    # The check itself can fail: the same picture shifted by 5 px (a moved onset moves the
    # envelope's edge by more) differs in far more than the tolerance.
    shipped = matplotlib.image.imread(PICTURE)
    assert differing_fraction(np.roll(shipped, 5, axis=1), shipped) > 0.005
