# The module's docstring examples run as written (doctest), from a directory that sees the
# repository's scenarios/ as the docstrings' "repository's root" does; a docstring that stops
# matching what the function does fails here. Also: every public function has a docstring, and
# at least load and run carry examples.
import doctest
import os

import shudder
from conftest import SOURCE


def test_docstring_examples_run(tmp_path):
    os.symlink(SOURCE / "scenarios", tmp_path / "scenarios")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        finder = doctest.DocTestFinder(exclude_empty=True)
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
        tests = [t for t in finder.find(shudder, "shudder", globs={"shudder": shudder}) if t.examples]
        for t in tests:
            runner.run(t)
        results = runner.summarize(verbose=False)
    finally:
        os.chdir(cwd)
    names = {t.name for t in tests}
    assert {"shudder.load", "shudder.run"} <= names, names
    assert results.failed == 0, f"{results.failed} of {results.attempted} docstring examples failed (output above)"


def test_public_functions_have_docstrings():
    for name in ("load", "run", "sweep", "screen", "diagnose", "characterise", "compare"):
        assert (getattr(shudder, name).__doc__ or "").strip(), name


def test_toml_text_without_source_says_where_its_fluid_path_is_read_from():
    text = (SOURCE / "scenarios" / "paper_g_case1_10kN.toml").read_text()
    cwd = os.getcwd()
    os.chdir(SOURCE)  # the repository's root: fluids/ is under scenarios/, not here
    try:
        try:
            shudder.load(toml=text)
            raise AssertionError("a relative fluid path outside the current directory was found")
        except shudder.InputError as e:
            message = str(e)
        assert shudder.load(toml=text, source="scenarios/paper_g_case1_10kN.toml").fluid_path == \
            "scenarios/fluids/lsc_fluid_c.toml"
    finally:
        os.chdir(cwd)
    assert "read from the scenario's folder, here the current directory" in message, message
    assert "give source=" in message, message


def test_override_errors_name_the_override():
    path = str(SOURCE / "scenarios" / "paper_g_case1_10kN.toml")
    for overrides, fragments in (
        ({"clutch.normal_force_N": 2e4}, ["overrides['clutch.normal_force_N'] = 20000", "unknown key"]),
        ({"drive.normal_force_N": -5}, ["overrides['drive.normal_force_N'] = -5", "allowed [0, 30000]"]),
    ):
        try:
            shudder.load(path, overrides=overrides)
            raise AssertionError(f"{overrides} accepted")
        except shudder.InputError as e:
            message = str(e)
        for f in fragments:
            assert f in message, message
        assert "paper_g_case1_10kN.toml:" not in message, message  # no line of the file
