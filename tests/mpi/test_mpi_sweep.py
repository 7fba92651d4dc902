# `mpirun -np 2 shudder sweep ... --mpi` (app/mpi_sweep.hpp) on one machine (shared memory and
# loopback): the file equals the threaded sweep's, an interrupted MPI sweep resumes from the
# threaded sweep's part files, and an input error on rank 0 ends every rank with the one line.
import os
import pathlib
import subprocess

import h5py
import numpy as np

SOURCE = pathlib.Path(os.environ["SHUDDER_SOURCE_DIR"])
CLI = os.environ["SHUDDER_CLI"]
KEY = "rig.torsion_bar.natural_frequency_Hz"
GRID = KEY + "=150:450:50"  # 7 cases, both sides of the 355 Hz boundary
# CI runs as root; containers forbid the single-copy (CMA) transport, so shared memory copies.
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_btl_vader_single_copy_mechanism="none", OMPI_MCA_rmaps_base_oversubscribe="1")


def run(args, cwd, mpi_ranks=None):
    cmd = [CLI, *args]
    if mpi_ranks:
        cmd = ["mpirun", "-np", str(mpi_ranks), "--oversubscribe", *cmd, "--mpi"]
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, env=ENV, timeout=240)
    return p.returncode, p.stdout, p.stderr


def scenario(tmp):
    text = (SOURCE / "scenarios" / "sweep_torsion_bar.toml").read_text()
    text = text.replace("duration_s = 20.0", "duration_s = 0.5").replace("time_s = [0.0, 20.0]", "time_s = [0.0, 0.5]")
    text = text.replace('fluid = "fluids/', 'fluid = "' + str(SOURCE / "scenarios" / "fluids") + "/")
    (tmp / "s.toml").write_text(text)


def assert_same_sweep(a, b):
    """Every dataset and attribute equal (bit for bit; NaN == NaN) but the creation time."""
    def attrs(obj):
        return {k: (list(v) if hasattr(v, "__len__") and not isinstance(v, (str, bytes)) else v)
                for k, v in obj.attrs.items() if k != "created_utc"}

    with h5py.File(a) as fa, h5py.File(b) as fb:
        names, other = [], []
        fa.visit(names.append)
        fb.visit(other.append)
        assert sorted(names) == sorted(other)
        assert attrs(fa) == attrs(fb)
        for n in names:
            assert attrs(fa[n]).keys() == attrs(fb[n]).keys(), n
            for k in attrs(fa[n]):
                np.testing.assert_array_equal(fa[n].attrs[k], fb[n].attrs[k], err_msg=n + "@" + k)
            if isinstance(fa[n], h5py.Dataset):
                x, y = fa[n][()], fb[n][()]
                if x.dtype.kind == "f":
                    np.testing.assert_array_equal(x, y, err_msg=n)
                else:
                    assert list(x) == list(y), n


def test_mpi_sweep_equals_the_threaded_sweep(tmp_path):
    scenario(tmp_path)
    code, out, err = run(["sweep", "s.toml", "--set", GRID, "--jobs", "2", "-o", "threads.h5"], tmp_path)
    assert code == 0, err
    code, out, err = run(["sweep", "s.toml", "--set", GRID, "-o", "mpi.h5"], tmp_path, mpi_ranks=2)
    assert code == 0, err
    assert "7 cases (7 run now, 2 jobs)" in out  # one summary: rank 0's
    assert out.count("Sweep of") == 1
    # Both ranks ran cases (rank 0 on its second thread, rank 1 sent its parts back).
    counts = [int(n) for n in out.split("Cases per MPI rank:")[1].split("\n")[0].split()]
    assert len(counts) == 2 and sum(counts) == 7 and min(counts) >= 1, out
    assert not (tmp_path / "mpi.h5.parts").exists()
    assert_same_sweep(tmp_path / "threads.h5", tmp_path / "mpi.h5")
    with h5py.File(tmp_path / "mpi.h5") as f:
        v = [s.decode() if isinstance(s, bytes) else s for s in f["cases/simulated_verdict"][()]]
        stable = list(f["cases/predicted_stable"][()])
    assert stable == [0, 0, 0, 0, 0, 1, 1]  # 150-350 Hz unstable, 400-450 stable: boundary 355 Hz (its header)
    assert len(v) == 7


# Resume: parts left by an interrupted sweep (here: a threaded one kept its parts, two removed
# as if their cases had not finished) are reused; only the missing cases run on the ranks.
def test_mpi_sweep_resumes_from_part_files(tmp_path):
    scenario(tmp_path)
    code, _, err = run(["sweep", "s.toml", "--set", GRID, "--jobs", "2", "--keep-parts", "-o", "ref.h5"], tmp_path)
    assert code == 0, err
    (tmp_path / "ref.h5.parts").rename(tmp_path / "out.h5.parts")
    (tmp_path / "out.h5.parts" / "case_00002.h5").unlink()
    (tmp_path / "out.h5.parts" / "case_00005.h5").unlink()
    code, out, err = run(["sweep", "s.toml", "--set", GRID, "-o", "out.h5"], tmp_path, mpi_ranks=2)
    assert code == 0, err
    assert "shudder: resuming: 5 of 7 cases already finished" in err
    assert "7 cases (2 run now, 2 jobs)" in out
    assert_same_sweep(tmp_path / "ref.h5", tmp_path / "out.h5")


# An input error on rank 0 stops the worker too (no hang): exit 2, the CLI's one line, no file.
def test_input_error_ends_every_rank(tmp_path):
    scenario(tmp_path)
    code, _, err = run(["sweep", "s.toml", "--set", "no.such.key=1,2", "-o", "bad.h5"], tmp_path, mpi_ranks=2)
    assert code != 0
    lines = [l for l in err.splitlines() if l.startswith("shudder:")]
    assert len(lines) == 1 and lines[0].startswith("shudder: error: s.toml"), err
    assert not (tmp_path / "bad.h5").exists()
    code, _, err = run(["sweep", "s.toml", "--set", GRID, "--jobs", "2", "-o", "j.h5"], tmp_path, mpi_ranks=2)
    assert code != 0 and "shudder: error: --jobs: not with --mpi" in err


# `shudder` itself does not load libmpi (start-up of every other command; docs/performance.md):
# `sweep --mpi` hands the process to the shudder-mpi beside it (the tests above go through that).
# A shudder copied without its shudder-mpi refuses --mpi with the CLI's one line, exit 2.
def test_shudder_without_mpi_hands_over_or_refuses(tmp_path):
    maps = subprocess.run(["ldd", CLI], capture_output=True, text=True).stdout
    assert "libmpi" not in maps, maps
    lone = tmp_path / "bin" / "shudder"
    lone.parent.mkdir()
    lone.write_bytes(pathlib.Path(CLI).read_bytes())
    lone.chmod(0o755)
    scenario(tmp_path)
    p = subprocess.run([str(lone), "sweep", "s.toml", "--set", GRID, "-o", "m.h5", "--mpi"], cwd=tmp_path,
                       capture_output=True, text=True, env=ENV, timeout=60)
    assert p.returncode == 2, p.stderr
    assert p.stderr.startswith("shudder: error: --mpi: this shudder has no MPI and found no shudder-mpi beside it"), p.stderr
    assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert not (tmp_path / "m.h5").exists()
    # A shudder-mpi that is itself a shudder without MPI refuses too (hands over once, no loop).
    (lone.parent / "shudder-mpi").write_bytes(lone.read_bytes())
    (lone.parent / "shudder-mpi").chmod(0o755)
    p = subprocess.run([str(lone), "sweep", "s.toml", "--set", GRID, "-o", "m.h5", "--mpi"], cwd=tmp_path,
                       capture_output=True, text=True, env=ENV, timeout=60)
    assert p.returncode == 2 and "--mpi: this shudder has no MPI" in p.stderr, p.stderr
