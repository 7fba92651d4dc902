# Shared helpers of the Python module's tests: the source tree, the CLI next to the module, and
# running the CLI to compare its messages and files with the module's.
import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ["SHUDDER_SOURCE_DIR"])
CLI = os.environ["SHUDDER_CLI"]


def scenario(name):
    return str(SOURCE / "scenarios" / name)


def cli(*args, cwd=None):
    """Runs the shudder CLI; returns (exit code, stdout, stderr)."""
    p = subprocess.run([CLI, *map(str, args)], cwd=cwd, capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


@pytest.fixture
def source():
    return SOURCE
