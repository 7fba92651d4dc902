# docs/python.md's example is python/examples/plot_case1.py (the README's command runs it): the
# block and the file are the same text, the file runs as a script from a directory that sees
# the repository's scenarios/ and writes its plot; then the doc's other blocks (sweep, screen,
# h5py readers) run there in order, on the files the example wrote.
import os
import re
import subprocess
import sys

from conftest import SOURCE


def test_docs_python_md_example_and_blocks_run(tmp_path):
    text = (SOURCE / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 4
    example = SOURCE / "python" / "examples" / "plot_case1.py"
    assert blocks[0] == example.read_text()
    os.symlink(SOURCE / "scenarios", tmp_path / "scenarios")
    p = subprocess.run([sys.executable, str(example)], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    png = tmp_path / "case1_torque.png"
    assert png.exists() and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "10.4 kN: torque at 10 s" in p.stdout and "20.0 kN: torque at 10 s" in p.stdout
    assert "vibration" in p.stdout  # the negative-slope rig shudders (docs/validation.md)
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        scope = {}
        for block in blocks[1:]:
            exec(compile(block, "docs/python.md", "exec"), scope)
    finally:
        os.chdir(cwd)
    assert (tmp_path / "sweep.h5").exists()
