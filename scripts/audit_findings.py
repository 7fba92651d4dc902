#!/usr/bin/python3
"""The robustness audit's findings re-checked in one place, through the command line only.

    /usr/bin/python3 scripts/audit_findings.py SHUDDER            # one binary: one line per finding
    /usr/bin/python3 scripts/audit_findings.py OLD_SHUDDER NEW_SHUDDER

Each probe runs the given `shudder` binary in a fresh scratch directory on the shipped inputs of
commit 20f3647 (the audited commit; `git archive` of its scenarios/ from this repository, so the
probes do not move when today's scenarios are retuned; docs/formats/measured_run.md keeps them readable) and prints
    finding | PASS/FAIL | what was seen
PASS means today's promised behaviour (docs/audit_findings.md names the unit tests that also
cover each finding). With two binaries the script also prints the table old | new and exits 0
only if every finding FAILs on the old binary and PASSes on the new one. Needs git, h5py and
numpy (Debian's python3-h5py, python3-numpy; scripts/install-deps.sh). Not part of ctest: it
needs a build of the old commit. Takes about two minutes per binary on a quiet machine.
"""

import argparse
import io
import json
import os
import re
import resource
import shutil
import subprocess
import sys
import tarfile
import tempfile
import time

import h5py
import numpy as np

AUDITED_COMMIT = "20f3647"
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class Result:
    def __init__(self, code, out, err, wall_s, timed_out=False):
        self.code, self.out, self.err, self.wall_s, self.timed_out = code, out, err, wall_s, timed_out

    def first_err(self, n=150):
        line = self.err.strip().splitlines()[0] if self.err.strip() else "(stderr empty)"
        return line if len(line) <= n else line[:n] + "..."

    def seen(self):
        if self.timed_out:
            return "still running after %.0f s (killed)" % self.wall_s
        return "exit %d, stderr %d line(s): %s" % (self.code, len(self.err.splitlines()), self.first_err())


class Probe:
    """One binary, one scratch directory per probe."""

    def __init__(self, binary, inputs, scratch):
        self.binary, self.inputs, self.scratch = binary, inputs, scratch
        self.cache = {}

    def dir(self, name):
        d = os.path.join(self.scratch, name)
        shutil.copytree(self.inputs, d)
        return d

    def run(self, args, cwd, timeout=60, env=None, vmem_kb=None):
        cmd = [self.binary] + args
        pre = None
        if vmem_kb is not None:
            def pre():
                resource.setrlimit(resource.RLIMIT_AS, (vmem_kb * 1024, vmem_kb * 1024))

        t0 = time.monotonic()
        p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
                             preexec_fn=pre, start_new_session=True)
        try:
            out, err = p.communicate(timeout=timeout)
            return Result(p.returncode, out.decode(errors="replace"), err.decode(errors="replace"),
                          time.monotonic() - t0)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, 9)
            out, err = p.communicate()
            return Result(-9, out.decode(errors="replace"), err.decode(errors="replace"),
                          time.monotonic() - t0, timed_out=True)


# ---- helpers --------------------------------------------------------------------------------

def slurp(path, mode="r"):
    with open(path, mode) as f:
        return f.read()


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def edit(path, out_path, *pairs):
    """Copies a scenario with exact text replacements; a replacement that does not apply is a
    broken probe, not a finding."""
    s = slurp(path)
    for a, b in pairs:
        if a not in s:
            raise RuntimeError("probe input %s lacks %r" % (path, a))
        s = s.replace(a, b)
    write(out_path, s)


def rejected(r, *fragments):
    """Bad input: exit 2, one stderr line with the prefix, naming every fragment."""
    lines = r.err.splitlines()
    ok = (not r.timed_out and r.code == 2 and len(lines) == 1 and lines[0].startswith("shudder: error: ")
          and all(f in lines[0] for f in fragments))
    return ok, r.seen()


def short_rig(d, name="short.toml", seconds="0.2", rate=None):
    """rig_shudder_negative_slope shortened: a rig run of ~0.1 s CPU."""
    pairs = [("duration_s = 2.0", "duration_s = %s" % seconds),
             ("time_s = [0.0, 2.0]", "time_s = [0.0, %s]" % seconds)]
    if rate:
        pairs.append(("sample_rate_Hz = 20000.0", "sample_rate_Hz = %s" % rate))
    edit(os.path.join(d, "rig_shudder_negative_slope.toml"), os.path.join(d, name), *pairs)
    return name


def fmt(x):
    return "%.4g" % x


# ---- verdicts (one shipped shudder run, shared by four probes) -------------------------------

def shudder_run(p):
    """rig_shudder_negative_slope as shipped, with --report: the audit's 378 Hz example."""
    if "neg" not in p.cache:
        d = p.dir("verdict")
        r = p.run(["run", "rig_shudder_negative_slope.toml", "-o", "neg.h5", "--report", "rep"], d, timeout=120)
        p.cache["neg"] = (d, r)
    return p.cache["neg"]


def verdict_summary(p):
    d, r = shudder_run(p)
    m = re.search(r"^Shudder: (\S+) at ([0-9.]+) Hz, amplitude ([0-9.e+]+) N m, onset ([0-9.]+) s", r.out, re.M)
    if r.code != 0 or not m:
        return False, "exit %d; no 'Shudder:' verdict line in the summary" % r.code
    ok = m.group(1) == "vibration" and abs(float(m.group(2)) / 378.0 - 1) < 0.01
    return ok, m.group(0)


def verdict_block(path):
    with h5py.File(path, "r") as f:
        if "analysis/verdict" not in f:
            return None, "groups under /analysis: %s" % sorted(f["analysis"].keys()) if "analysis" in f else "no /analysis"
        g = f["analysis/verdict"]
        block = {k: float(g[k][()]) for k in g.keys()}
        block.update({k: str(g.attrs[k]) for k in g.attrs.keys()})
        block["_mode_Hz"] = float(f["analysis/summary/clutch_side_frequency_Hz"][()])
        return block, ""


def verdict_hdf5(p):
    d, r = shudder_run(p)
    if r.code != 0:
        return False, r.seen()
    b, why = verdict_block(os.path.join(d, "neg.h5"))
    if b is None:
        return False, "no /analysis/verdict; " + why
    ok = (b.get("verdict") == "vibration" and abs(b["frequency_Hz"] / b["_mode_Hz"] - 1) < 0.005
          and 0 < b["onset_time_s"] < 2 and b["amplitude_Nm"] > b["threshold_Nm"])
    return ok, "/analysis/verdict: %s at %s Hz (mode %s Hz), amplitude %s N m, onset %s s, predicted margin %s 1/s" % (
        b.get("verdict"), fmt(b["frequency_Hz"]), fmt(b["_mode_Hz"]), fmt(b["amplitude_Nm"]),
        fmt(b["onset_time_s"]), fmt(b.get("predicted_margin_per_s", float("nan"))))


def verdict_json(p):
    d, r = shudder_run(p)
    path = os.path.join(d, "rep", "verdict.json")
    if r.code != 0 or not os.path.exists(path):
        return False, "exit %d; report directory holds %s" % (
            r.code, sorted(os.listdir(os.path.join(d, "rep"))) if os.path.isdir(os.path.join(d, "rep")) else "nothing")
    j = json.loads(slurp(path), parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
    b, _ = verdict_block(os.path.join(d, "neg.h5"))
    ok = (b is not None and j.get("verdict") == "vibration"
          and all(abs(j[k] - b[k]) <= 1e-9 * abs(b[k]) for k in ("frequency_Hz", "amplitude_Nm", "onset_time_s")))
    return ok, "rep/verdict.json: verdict %s, frequency %s Hz, amplitude %s N m (same as /analysis/verdict: %s)" % (
        j.get("verdict"), fmt(j.get("frequency_Hz", float("nan"))), fmt(j.get("amplitude_Nm", float("nan"))), ok)


def driveline_verdict(p):
    """The driveline's run stores the same block, with its own linear prediction."""
    d = p.dir("driveline_verdict")
    r = p.run(["run", "driveline_tight_turn.toml", "-o", "d.h5"], d)
    if r.code != 0:
        return False, r.seen()
    with h5py.File(os.path.join(d, "d.h5"), "r") as f:
        if "analysis/verdict" not in f:
            return False, "summary line %r; no /analysis/verdict (groups: %s)" % (
                next((l for l in r.out.splitlines() if "judder" in l), ""), sorted(f["analysis"].keys()))
        g = f["analysis/verdict"]
        verdict, prediction = str(g.attrs.get("verdict")), str(g.attrs.get("prediction", ""))
        margin = float(g["predicted_margin_per_s"][()]) if "predicted_margin_per_s" in g else float("nan")
    ok = verdict in ("none", "vibration", "stick_slip") and "driveline linear stability" in prediction and (
        "Predicted there:" in r.out)
    return ok, "/analysis/verdict: %s; prediction '%s', margin %s 1/s" % (verdict, prediction[:60], fmt(margin))


def summary_min_max(p):
    """The last fifth's row must show the torque's true min and max over 1.6-2.0 s, not a sample."""
    d, r = shudder_run(p)
    if r.code != 0:
        return False, r.seen()
    with h5py.File(os.path.join(d, "neg.h5"), "r") as f:
        t, q = f["signals/time_s"][()], f["signals/torque_Nm"][()]
    row = next((l for l in r.out.splitlines() if l.split() and l.split()[0].startswith("1.60")), None)
    if row is None:
        return False, "no row starting 1.60 in the summary"
    nums = [float(x) for x in re.findall(r"-?\d+\.\d+", row)[1:]]
    want = []
    for sel in ((t >= 1.6) & (t <= 2.0), (t >= 1.6) & (t < 2.0)):  # closed or half-open interval
        want.append((q[sel].min(), q[sel].max()))
    # 0.006 N m: the summary prints two decimals.
    ok = any(any(abs(x - lo) < 0.006 for x in nums) and any(abs(x - hi) < 0.006 for x in nums) for lo, hi in want)
    return ok, "row '%s'; torque_Nm over 1.6-2.0 s: min %.2f, max %.2f" % (" ".join(row.split()), want[0][0], want[0][1])


# ---- physical guards -------------------------------------------------------------------------

def negative_beta(p):
    d = p.dir("beta")
    edit(os.path.join(d, "fluids/paper_e_fluid_a.toml"), os.path.join(d, "neg.toml"),
         ("beta = [0.1018, 0.1164]", "beta = [-0.1018, -0.1164]"))
    ok1, seen1 = rejected(p.run(["screen", "neg.toml"], d), "neg.toml", "linear.beta")
    edit(os.path.join(d, "rig_shudder_negative_slope.toml"), os.path.join(d, "s.toml"),
         ('fluid = "fluids/schematic_negative_slope.toml"', 'fluid = "neg.toml"'),
         ("duration_s = 2.0", "duration_s = 0.2"), ("time_s = [0.0, 2.0]", "time_s = [0.0, 0.2]"))
    r = p.run(["run", "s.toml", "-o", "out.h5"], d)
    ok2, seen2 = rejected(r, "neg.toml", "linear.beta")
    ok2 = ok2 and not os.path.exists(os.path.join(d, "out.h5"))
    energy = re.search(r"^Energy: generated (\S+) J", r.out, re.M)
    return ok1 and ok2, "screen: %s; run: %s%s" % (seen1, seen2, "; heat generated %s J" % energy.group(1) if energy else "")


def final_thermocouple(r):
    m = re.search(r"^Final temperatures: thermocouple (\S+) C", r.out, re.M)
    return "; thermocouple %s C" % fmt(float(m.group(1))) if m else ""


def tiny_value_rejected(p, d, scenario, appended, key):
    """`scenario` in d with `appended` (a 1e-300 for `key`): refused by name and allowed range."""
    write(os.path.join(d, "s.toml"), slurp(os.path.join(d, scenario)) + appended)
    r = p.run(["run", "s.toml", "-o", "out.h5"], d)
    ok, seen = rejected(r, key, "allowed [")
    return ok, seen + final_thermocouple(r)


def tiny_film(p):
    d = p.dir("film")
    return tiny_value_rejected(p, d, short_rig(d), "\n[clutch.oil]\nfilm_thickness_um = 1e-300\n",
                               "clutch.oil.film_thickness_um")


def tiny_gap(p):
    d = p.dir("gap")
    return tiny_value_rejected(p, d, "paper_g_case1_10kN.toml",
                               "\n[effects.viscous_shear]\nenabled = true\ngap_um = 1e-300\n",
                               "effects.viscous_shear.gap_um")


def energy_error(p):
    """The stick-slip rig at the loosest tolerances the reader takes loses ~4 % of the work."""
    d = p.dir("energy")
    write(os.path.join(d, "s.toml"), slurp(os.path.join(d, "rig_stick_slip.toml")) +
          "\n[solver]\nabs_tol = 1e-2\nrel_tol = 1e-2\nmax_step_ms = 1000\n")
    r = p.run(["run", "s.toml", "-o", "out.h5"], d)
    lines = r.err.splitlines()
    ok = (r.code == 1 and len(lines) == 1 and "mechanical energy balance error" in lines[0]
          and "exceeds the bound" in lines[0] and os.path.exists(os.path.join(d, "out.h5")))
    m = re.search(r"mechanical energy error (\S+)", r.out)
    return ok, r.seen() + ("; summary printed 'mechanical energy error %s'" % m.group(1) if m else "")


# ---- file safety -----------------------------------------------------------------------------

def output_is_input(p):
    d = p.dir("over_input")
    s = short_rig(d, "s.toml")
    before = slurp(os.path.join(d, s), "rb")
    r = p.run(["run", s, "-o", "./s.toml"], d)
    ok, seen = rejected(r, "s.toml")
    kept = slurp(os.path.join(d, s), "rb") == before
    return ok and kept, seen + ("; scenario kept" if kept else "; scenario REPLACED (now starts %r)" % slurp(os.path.join(d, s), "rb")[:8])


def measurement_is_output(p):
    d = p.dir("same_outputs")
    s = short_rig(d)
    r = p.run(["run", s, "--measurement", "same.h5", "-o", "same.h5"], d)
    ok, seen = rejected(r, "same.h5")
    path = os.path.join(d, "same.h5")
    if os.path.exists(path):
        ok = False
        try:
            with h5py.File(path, "r") as f:
                seen += "; same.h5 holds only %s" % sorted(f.keys())
        except OSError:
            seen += "; same.h5 is not HDF5 (%d bytes)" % os.path.getsize(path)
    return ok, seen


def sweep_missing_dir(p):
    d = p.dir("sweep_dir")
    s = short_rig(d)
    r = p.run(["sweep", s, "--set", "rig.torsion_bar.natural_frequency_Hz=300", "--quiet", "-o", "nonexistent/s.h5"], d)
    ok, seen = rejected(r, "nonexistent", "does not exist")
    made = os.path.exists(os.path.join(d, "nonexistent"))
    return ok and not made, seen + ("; nonexistent/ was CREATED" if made else "; nothing created")


def stale_tmp(p):
    """Temporaries of a killed writer (the old fixed name and today's name with a dead pid)."""
    d = p.dir("stale_tmp")
    s = short_rig(d)
    pid_max = int(slurp("/proc/sys/kernel/pid_max").strip())
    stale = ["run.h5.tmp", "run.h5.tmp.%d.0" % (pid_max + 1)]
    for name in stale:
        write(os.path.join(d, name), "x")
    r = p.run(["run", s, "-o", "run.h5"], d)
    left = [n for n in stale if os.path.exists(os.path.join(d, n))]
    return r.code == 0 and not left, "exit %d; stale temporaries left: %s" % (r.code, left or "none")


def huge_output(p):
    """1 MS/s over a 30 s run: 3.6 GB. Refused at once; the old binary is stopped after 8 s."""
    d = p.dir("huge")
    edit(os.path.join(d, "rig_case2_15kN_175Hz.toml"), os.path.join(d, "s.toml"),
         ("sample_rate_Hz = 1000.0", "sample_rate_Hz = 1e6"))
    r = p.run(["run", "s.toml", "-o", "out.h5"], d, timeout=8, vmem_kb=4000000)
    ok, seen = rejected(r, "estimated output size", "--force")
    ok = ok and r.wall_s < 8 and not os.path.exists(os.path.join(d, "out.h5"))
    s = short_rig(d)
    f = p.run(["run", s, "-o", "forced.h5", "--force"], d)
    return ok and f.code == 0, "1 MS/s: %s; --force on a small run: exit %d%s" % (
        seen, f.code, "" if f.code == 0 else " (" + f.first_err(80) + ")")


def compressed(p):
    """A run signal of 80,001 samples (datasets from 65,536 values up are chunked and deflated)."""
    d = p.dir("compressed")
    s = short_rig(d, rate="400000.0")
    r = p.run(["run", s, "-o", "c.h5"], d)
    if r.code != 0:
        return False, r.seen()
    with h5py.File(os.path.join(d, "c.h5"), "r") as f:
        ds = f["signals/torque_Nm"]
        raw = sum(f["signals"][k].size * 8 for k in f["signals"].keys())
        chunks, comp = ds.chunks, ds.compression
    size = os.path.getsize(os.path.join(d, "c.h5"))
    # The sweep file's case signals too (the audit's 41-case sweep wrote 164 MB plain).
    w = p.run(["sweep", s, "--set", "drive.normal_force_N=15000", "--quiet", "-o", "sw.h5"], d)
    if w.code != 0:
        return False, "sweep: " + w.seen()
    with h5py.File(os.path.join(d, "sw.h5"), "r") as f:
        sw = f["case_00000/signals/torque_Nm"]
        sw_chunks, sw_comp = sw.chunks, sw.compression
    ok = chunks is not None and comp == "gzip" and size < raw and sw_chunks is not None and sw_comp == "gzip"
    return ok, "run /signals/torque_Nm chunks %s, filter %s, file %.2f MB for %.2f MB of signals; sweep case signal chunks %s, filter %s" % (
        chunks, comp, size / 1e6, raw / 1e6, sw_chunks, sw_comp)


def rerun_from_file(p):
    d = p.dir("repro_first")
    s = short_rig(d)
    r = p.run(["run", s, "-o", "a.h5"], d)
    if r.code != 0:
        return False, r.seen()
    with h5py.File(os.path.join(d, "a.h5"), "r") as f:
        attrs = {k: f.attrs[k] for k in f.attrs.keys()}
    if "fluid" not in attrs:
        return False, "root attributes %s: no fluid text" % sorted(attrs)
    fluid_text, scenario_text = str(attrs["fluid"]), str(attrs["scenario"])
    if fluid_text != slurp(os.path.join(d, "fluids/schematic_negative_slope.toml")):
        return False, "stored fluid text differs from the fluid file"
    # A fresh directory holding only what the file holds.
    e = os.path.join(p.scratch, "repro_second")
    os.makedirs(os.path.join(e, "fluids"))
    write(os.path.join(e, "s.toml"), scenario_text)
    write(os.path.join(e, "fluids/schematic_negative_slope.toml"), fluid_text)
    r2 = p.run(["run", "s.toml", "-o", "b.h5"], e)
    if r2.code != 0:
        return False, "re-run: " + r2.seen()
    with h5py.File(os.path.join(d, "a.h5"), "r") as a, h5py.File(os.path.join(e, "b.h5"), "r") as b:
        names = sorted(a["signals"].keys())
        same = names == sorted(b["signals"].keys()) and all(
            a["signals"][n][()].tobytes() == b["signals"][n][()].tobytes() for n in names)
    return same, "fluid text stored (%d bytes); re-run from the file alone: %d signals bit-identical: %s" % (
        len(fluid_text), len(names), same)


# ---- sweeps ------------------------------------------------------------------------------------

KEY = "rig.torsion_bar.natural_frequency_Hz"


def one_second(d):
    return short_rig(d, "s.toml", seconds="1.0", rate="10000.0")


def cases(path):
    with h5py.File(path, "r") as f:
        c = f["cases"]
        cols = {k: c[k][()] for k in c.keys()}
    return cols


def bitwise_equal(x, y):
    """Numbers bit for bit (NaN included); strings (object arrays hold pointers) by value."""
    x, y = np.asarray(x), np.asarray(y)
    if x.dtype == object or y.dtype == object:
        return x.tolist() == y.tolist()
    return x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()


def failing_case(p):
    """At 50 S/s the 1 s case has 51 samples, fewer than the detector's 64: it fails when judged."""
    d = p.dir("sweep_fail")
    s = one_second(d)
    r = p.run(["sweep", s, "--set", "output.sample_rate_Hz=10000,50,5000", "--jobs", "2", "-o", "sw.h5"], d)
    if r.code != 0 or not os.path.exists(os.path.join(d, "sw.h5")):
        return False, r.seen() + "; sw.h5 %s" % ("exists" if os.path.exists(os.path.join(d, "sw.h5")) else "missing")
    c = cases(os.path.join(d, "sw.h5"))
    verdicts = [v.decode() if isinstance(v, bytes) else str(v) for v in c["simulated_verdict"]]
    msgs = [m.decode() if isinstance(m, bytes) else str(m) for m in c.get("simulated_message", [])]
    ok = verdicts == ["vibration", "failed", "vibration"] and len(msgs) == 3 and "64 samples" in msgs[1]
    return ok, "exit 0; /cases verdicts %s; case 1 message: %s" % (verdicts, msgs[1] if len(msgs) == 3 else "none")


def resume_with_failure(p):
    d = p.dir("sweep_resume")
    s = one_second(d)
    args = ["sweep", s, "--set", "output.sample_rate_Hz=10000,50", "--set", KEY + "=200,300", "--jobs", "2",
            "--quiet", "-o"]
    r = p.run(args + ["whole.h5"], d)
    if r.code != 0:
        return False, "uninterrupted sweep: " + r.seen()
    r = p.run(args + ["part.h5", "--keep-parts"], d)
    if r.code != 0:
        return False, "second sweep: " + r.seen()
    os.remove(os.path.join(d, "part.h5"))
    for k in (0, 3):  # a case that ran and a failed one
        os.remove(os.path.join(d, "part.h5.parts", "case_%05d.h5" % k))
    r = p.run(args + ["part.h5"], d)
    if r.code != 0:
        return False, "resumed sweep: " + r.seen()
    a, b = cases(os.path.join(d, "whole.h5")), cases(os.path.join(d, "part.h5"))
    same = sorted(a) == sorted(b) and all(bitwise_equal(a[k], b[k]) for k in a)
    resumed = "resuming: 2 of 4 cases already finished" in r.err
    return same and resumed, "resumed after removing 2 of 4 parts (%s); /cases bit-identical to the uninterrupted sweep: %s" % (
        "said so" if resumed else "no resume message", same)


def repeated_key(p):
    d = p.dir("sweep_repeat")
    s = one_second(d)
    r = p.run(["sweep", s, "--set", KEY + "=200,300", "--set", KEY + "=400", "--quiet", "-o", "sw.h5"], d)
    ok, seen = rejected(r, KEY, "given twice")
    left = [n for n in ("sw.h5", "sw.h5.parts") if os.path.exists(os.path.join(d, n))]
    return ok and not left, seen + "; %.1f s; left behind: %s" % (r.wall_s, left or "nothing")


# ---- messages --------------------------------------------------------------------------------

def cli11_errors(p):
    d = p.dir("cli11")
    s = short_rig(d)
    results = [p.run(["run", s, "--bogus"], d), p.run(["sweep", s, "-o", "x.h5"], d), p.run([], d)]
    oks = [rejected(results[0], "--bogus")[0], rejected(results[1], "--set")[0], rejected(results[2])[0]]
    return all(oks), "; ".join("%s: %s" % (a, r.seen()) for a, r in zip(("--bogus", "no --set", "no subcommand"), results))


def unknown_key(p):
    d = p.dir("unknown_key")
    edit(os.path.join(d, "rig_shudder_negative_slope.toml"), os.path.join(d, "s.toml"),
         ("duration_s = 2.0", "durration_s = 2.0"))
    return rejected(p.run(["run", "s.toml", "-o", "out.h5"], d), "durration_s", "unknown key", "did you mean 'duration_s'")


def out_of_memory(p):
    """A 1e15-case grid under a 600 MB address-space limit (the old binary grows it until then)."""
    d = p.dir("oom")
    axis = "=1:100000:1"
    r = p.run(["sweep", "rig_shudder_negative_slope.toml", "--set", KEY + axis, "--set", "drive.normal_force_N" + axis,
               "--set", "clutch.start_temp_C" + axis, "-o", "sw.h5"], d, timeout=60, vmem_kb=600000)
    return rejected(r, "1e+15 cases", "ran out of memory")


def gnuplot_failure(p):
    """A stand-in gnuplot that prints what gnuplot 5 prints for a script error and exits 1."""
    d = p.dir("gnuplot")
    s = short_rig(d)
    r = p.run(["run", s, "-o", "r.h5"], d)
    if r.code != 0:
        return False, "run: " + r.seen()
    fake = os.path.join(d, "fakebin")
    os.makedirs(fake)
    write(os.path.join(fake, "gnuplot"), "#!/bin/sh\necho ''\necho \"plot 'data.txt' using 1:2 with lines\"\n"
          "echo '                       ^'\necho \"\\\"$1\\\" line 14: undefined variable: foo\"\nexit 1\n")
    os.chmod(os.path.join(fake, "gnuplot"), 0o755)
    env = dict(os.environ, PATH=fake + ":" + os.environ.get("PATH", ""))
    r = p.run(["plot", "r.h5", "--what", "torque", "-o", "t.png"], d, env=env)
    lines = r.err.splitlines()
    ok = (r.code != 0 and len(lines) == 1 and lines[0].startswith("shudder: ") and "undefined variable: foo" in lines[0]
          and "data.txt" not in r.err and "shudder-plot" not in r.err and not os.path.exists(os.path.join(d, "t.png")))
    return ok, "exit %d, stderr %d line(s): %s" % (r.code, len(lines), " / ".join(l.strip() for l in lines if l.strip()))


def driveline_modes(p):
    d = p.dir("modes")
    r = p.run(["modes", "driveline_tight_turn.toml"], d)
    ok = r.code == 0 and "frequency [Hz]" in r.out and "Coupling" in r.out
    return ok, r.seen() if not ok else "exit 0: " + " / ".join(l.strip() for l in r.out.splitlines()[:1])


def seed_without_noise(p):
    d = p.dir("seed")
    s = short_rig(d)
    r = p.run(["run", s, "--seed", "7", "-o", "out.h5"], d)
    ok, seen = rejected(r, "--seed", "--noise")
    return ok and not os.path.exists(os.path.join(d, "out.h5")), seen


def os_refused_path(p):
    """Found by fuzz_scenario (part 7): a fluid path the OS refuses (a 300-byte name) escaped
    the scenario loader as a filesystem_error."""
    d = p.dir("long_path")
    edit(os.path.join(d, "rig_shudder_negative_slope.toml"), os.path.join(d, "s.toml"),
         ("fluids/schematic_negative_slope.toml", "fluids/" + "a" * 300 + ".toml"))
    return rejected(p.run(["run", "s.toml", "-o", "out.h5"], d), "clutch.fluid", "File name too long")


# ---- onset and the thermal step ----------------------------------------------------------------

def onset_thermal_step(p):
    """rig_ramp_peak10 (300 Hz bar): onset at thermal steps 10 and 5 ms must agree to 5 %."""
    d = p.dir("onset")
    r = p.run(["sweep", "rig_ramp_peak10.toml", "--set", "solver.thermal_step_ms=10,5", "--jobs", "2", "--quiet",
               "-o", "th.h5"], d, timeout=120)
    if r.code != 0:
        return False, r.seen()
    c = cases(os.path.join(d, "th.h5"))
    v = [x.decode() if isinstance(x, bytes) else str(x) for x in c["simulated_verdict"]]
    a, b = c["onset_time_s"]
    change = b / a - 1 if a > 0 else float("inf")
    return v == ["vibration", "vibration"] and abs(change) < 0.05, "verdicts %s, onset %.4f s (10 ms) / %.4f s (5 ms): %+.1f %%" % (
        v, a, b, 100 * change)


def isothermal_seed(p):
    """rig_shudder_negative_slope with one thermal step longer than the run (isothermal): the
    unstable sliding state must still start to oscillate, seeded by physics."""
    d = p.dir("isothermal")
    r = p.run(["sweep", "rig_shudder_negative_slope.toml", "--set", "solver.thermal_step_ms=10000", "--jobs", "1",
               "--quiet", "-o", "iso.h5"], d, timeout=120)
    if r.code != 0:
        return False, r.seen()
    c = cases(os.path.join(d, "iso.h5"))
    with h5py.File(os.path.join(d, "iso.h5"), "r") as f:
        q = f["case_00000/signals/torque_Nm"][()]
    v = c["simulated_verdict"][0]
    v = v.decode() if isinstance(v, bytes) else str(v)
    return v == "vibration" and q.max() - q.min() > 10, "verdict %s, onset %s s, torque %.2f..%.2f N m" % (
        v, fmt(c["onset_time_s"][0]), q.min(), q.max())


PROBES = [
    ("verdict in the run summary", verdict_summary),
    ("verdict in HDF5 /analysis/verdict", verdict_hdf5),
    ("verdict in --report verdict.json", verdict_json),
    ("driveline verdict stored with its prediction", driveline_verdict),
    ("summary min/max/RMS, not aliased samples", summary_min_max),
    ("fluid with beta < 0 rejected when loaded", negative_beta),
    ("film_thickness_um = 1e-300 bounded", tiny_film),
    ("gap_um = 1e-300 bounded", tiny_gap),
    ("energy-balance error is a failure", energy_error),
    ("-o equal to an input refused", output_is_input),
    ("--measurement equal to -o refused", measurement_is_output),
    ("sweep -o into a missing directory refused", sweep_missing_dir),
    ("stale .tmp removed", stale_tmp),
    ("sweep with a failing case finishes, case recorded", failing_case),
    ("resume with a failed case bit-identical", resume_with_failure),
    ("repeated --set key refused before running", repeated_key),
    ("CLI11 errors one line with the prefix", cli11_errors),
    ("unknown key named with the nearest key", unknown_key),
    ("out of memory is an input error with the size", out_of_memory),
    ("gnuplot failure in our words", gnuplot_failure),
    ("modes on a driveline", driveline_modes),
    ("--seed without --noise refused", seed_without_noise),
    ("size estimate, refusal, --force", huge_output),
    ("fuzz: fluid path the OS refuses is bad input", os_refused_path),
    ("datasets chunked and compressed", compressed),
    ("fluid text stored, re-run from the file alone", rerun_from_file),
    ("onset vs thermal step (10 -> 5 ms) < 5 %", onset_thermal_step),
    ("isothermal unstable sliding starts oscillating", isothermal_seed),
]


def check(binary, inputs, keep):
    scratch = tempfile.mkdtemp(prefix="shudder_i14_")
    p = Probe(binary, inputs, scratch)
    results = []
    t0 = time.monotonic()
    for name, fn in PROBES:
        try:
            ok, seen = fn(p)
        except Exception as e:  # a probe that cannot judge is a FAIL with its reason
            ok, seen = False, "probe error: %s: %s" % (type(e).__name__, e)
        seen = " ".join(seen.split())
        print("%s | %s | %s" % (name, "PASS" if ok else "FAIL", seen), flush=True)
        results.append((name, ok, seen))
    print("# %s: %d of %d PASS in %.0f s (scratch %s%s)" % (binary, sum(r[1] for r in results), len(results),
                                                           time.monotonic() - t0, scratch, ", kept" if keep else ""))
    if not keep:
        shutil.rmtree(scratch, ignore_errors=True)
    return results


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binaries", nargs="+", help="SHUDDER, or OLD_SHUDDER NEW_SHUDDER")
    ap.add_argument("--inputs-commit", default=AUDITED_COMMIT, help="commit whose scenarios/ the probes use")
    ap.add_argument("--keep", action="store_true", help="keep the scratch directories")
    a = ap.parse_args()
    if len(a.binaries) > 2:
        ap.error("give one or two binaries")
    for b in a.binaries:
        if not os.access(b, os.X_OK):
            ap.error("%s is not an executable" % b)
    inputs_root = tempfile.mkdtemp(prefix="shudder_i14_inputs_")
    tar = subprocess.run(["git", "-C", REPO, "archive", a.inputs_commit, "scenarios"], check=True,
                         stdout=subprocess.PIPE).stdout
    tarfile.open(fileobj=io.BytesIO(tar)).extractall(inputs_root)
    inputs = os.path.join(inputs_root, "scenarios")
    try:
        runs = []
        for b in a.binaries:
            print("## %s" % b, flush=True)
            runs.append(check(os.path.abspath(b), inputs, a.keep))
    finally:
        shutil.rmtree(inputs_root, ignore_errors=True)
    if len(runs) == 1:
        return 0 if all(r[1] for r in runs[0]) else 1
    print("## finding | old | new")
    good = True
    for (name, old_ok, _), (_, new_ok, _) in zip(*runs):
        good &= (not old_ok) and new_ok
        print("%s | %s | %s" % (name, "PASS" if old_ok else "FAIL", "PASS" if new_ok else "FAIL"))
    print("# every finding FAILs on the old binary and PASSes on the new one: %s" % ("yes" if good else "NO"))
    return 0 if good else 1


if __name__ == "__main__":
    sys.exit(main())
