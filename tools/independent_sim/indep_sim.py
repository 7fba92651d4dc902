#!/usr/bin/python3
"""An independently written simulator of the LSC test rig in prescribed slip (Paper G Case 2).

Written from docs/physics.md (thesis digest), the thesis (Paper G eqs. 2-13, Table 1)
and the file contracts of docs/formats/ only -- not from shudder's C++ (clutch/, rig_models/,
analysis/). Its purpose: "measured" runs from a different author's discretisation and oil-flow
calibration, to test `shudder diagnose` outside its own model family.

Physics (SI units inside; names carry units):
* friction  mu = C1 tanh(C2 v) + C3 v^0.1 + C4, v local sliding speed in mm/s (Paper G eq. 13),
  parameters from the fluid file's Maki matrix; mu interpolated linearly between the load sets
  and temperature rows (docs/physics.md section 1), v clamped to the file's range, load to its loads,
  temperature held beyond the end rows.
* contact   one sliding interface (Paper G's simulation), uniform pressure p = F / A over the
  annulus R_in..R_out; torque M = sum_i r_i p mu_i A_i; heat flux q_i = r_i dw p mu_i (W/m^2).
* heat      rho c dT/dt = k (1/r d/dr(r dT/dr) + d2T/dz2) in half separator (steel), lining
  (sintered bronze) and half core disc (steel); z = 0 (separator back face) and the core's back
  face adiabatic; T(R_in) = oil inlet = sump temperature, T(R_out) = sump temperature (Paper G).
* cooling   (this simulator's own calibration, not Paper G eq. 12): the oil in the grooves cools
  the interface with a heat-transfer coefficient to the sump temperature that grows with slip
  speed, h(dw) = h0 (0.5 + 0.5 sqrt(dw / 10.47 rad/s)) -- a convective coefficient rises roughly
  with the square root of the flow velocity, and the groove flow is pumped by the slip. h0 is
  calibrated to Paper G Case 1 (10.4 kN from 77 C: thermocouple about 90 C after the 10 s ramp;
  `indep_sim.py calibrate` reproduces it).
* sump      held at its start temperature (Paper D: "the oil sump temperature is constant").
* sensors   thermocouple at r = 48 mm, z = 0.5 mm from the separator's back face (Paper G);
  IR spot: chord-weighted mean interface temperature over a 4 mm spot at r = 48 mm with its
  30 ms response (docs/physics.md section 4); noise sigma = half the stated accuracy (torque 0.625 N m,
  force 37.5 N, thermocouples 0.335 C, IR 0.75 C; speed 0.005 rpm, an estimate).

Discretisation (deliberately unlike a cell-centred backward-Euler 2-D solve):
* z: vertex-centred nodes, 5 intervals in the half separator, 4 in the lining, 3 in the half
  core (13 nodes; the interface is a node shared by separator and lining, no film capacity);
* r: 12 cell-centred rings, Dirichlet ends through half-cell conductances;
* time: 25 ms steps, Lie splitting -- radial conduction explicit (stable: alpha dt / dr^2 < 0.2),
  then each ring's z column implicit (Thomas algorithm) with the friction heat of the step's
  start temperatures and the oil cooling implicit; samples are interpolated linearly in time.

Hidden effects (each its own way; all off by default):
* thermocouple first-order lag tau (exact update of a first-order hold at the sample rate);
* rig heat capacity: a lumped mass C linked by conductance G to the separator's back face,
  spread over the rings by area (implicit in the column solve, mass temperature updated after);
* bearing drag: the torque cell also sees mu_b F r_b, r_b = 47.25 mm; it heats no disc;
* torque-cell gain and offset (reads g M + M0), thermocouple offset (reads T + dT),
  load-cell gain (reads g_F F while the clutch is pressed with F).
"""
import argparse
import math
import sys
import tomllib
from dataclasses import dataclass, field

import numpy as np

RPM = 2.0 * math.pi / 60.0  # rad/s per rpm

# Paper G Table 1 (lining c_p: 500 J/kgK, not the printed 5000 -- docs/physics.md section 3).
R_IN_M, R_OUT_M = 38.1e-3, 56.4e-3
LAYERS = (  # (thickness m, intervals, k W/mK, rho kg/m3, c J/kgK)
    (0.75e-3, 5, 46.0, 7600.0, 449.0),   # half separator
    (0.56e-3, 4, 15.7, 5000.0, 500.0),   # friction lining
    (0.55e-3, 3, 46.0, 7600.0, 449.0),   # half core disc
)
N_RINGS = 12
STEP_S = 0.025
# Calibrated (see `calibrate`): Case 1, 10.4 kN, 77 C start -> thermocouple 90.0 C at 10 s.
H0_W_PER_M2K = 5608.0
BEARING_RADIUS_M = 47.25e-3
TC_R_M, TC_Z_M = 48e-3, 0.5e-3
IR_R_M, IR_SPOT_M, IR_TAU_S = 48e-3, 4e-3, 0.030
NOISE = {"speed_rpm": 0.005, "normal_force_N": 37.5, "torque_Nm": 0.625,
         "temp_C": 0.335, "sump_temp_C": 0.335, "ir_temp_C": 0.75}


@dataclass
class Hidden:
    """Effects hidden in the data; defaults = nothing hidden."""
    tc_lag_s: float = 0.0
    rig_C_J_per_K: float = 0.0
    rig_G_W_per_K: float = 0.0
    bearing_mu: float = 0.0
    torque_gain: float = 1.0
    torque_offset_Nm: float = 0.0
    tc_offset_K: float = 0.0
    load_gain: float = 1.0


@dataclass
class Run:
    force_N: float
    start_C: float
    time_s: list = field(default_factory=lambda: [0.0, 5.0, 15.0, 17.0, 27.0, 30.0])
    speed_rpm: list = field(default_factory=lambda: [1.0, 1.0, 100.0, 100.0, 1.0, 1.0])
    rate_Hz: float = 100.0


class Friction:
    """Paper G eq. 13 over the fluid file's matrix; mu interpolated, not the C's."""

    def __init__(self, fluid_path):
        with open(fluid_path, "rb") as f:
            m = tomllib.load(f)["maki"]
        rows = sorted(m["row"], key=lambda r: r["temp_C"])
        self.temps = np.array([r["temp_C"] for r in rows])
        self.loads = np.array(m["loads_N"], dtype=float)
        self.C = np.array([r["sets"] for r in rows], dtype=float)  # (rows, loads, 4)
        self.vmin, self.vmax = m["min_speed_mm_s"], m["max_speed_mm_s"]

    def mu(self, v_mm_s, temp_C, force_N):
        v = np.clip(v_mm_s, self.vmin, self.vmax)
        F = min(max(force_N, self.loads[0]), self.loads[-1])
        j = min(int(np.searchsorted(self.loads, F, side="right")) - 1, len(self.loads) - 2)
        wl = (F - self.loads[j]) / (self.loads[j + 1] - self.loads[j])
        T = np.clip(temp_C, self.temps[0], self.temps[-1])
        k = np.minimum(np.searchsorted(self.temps, T, side="right") - 1, len(self.temps) - 2)
        wt = (T - self.temps[k]) / (self.temps[k + 1] - self.temps[k])

        def law(c):  # c: (..., 4)
            return c[..., 0] * np.tanh(c[..., 1] * v) + c[..., 2] * v ** 0.1 + c[..., 3]
        m00, m01 = law(self.C[k, j]), law(self.C[k, j + 1])
        m10, m11 = law(self.C[k + 1, j]), law(self.C[k + 1, j + 1])
        lo = (1 - wl) * m00 + wl * m01
        hi = (1 - wl) * m10 + wl * m11
        return (1 - wt) * lo + wt * hi


class Clutch:
    """The r-z temperature field of one interface and its sensors."""

    def __init__(self, friction, h0=H0_W_PER_M2K):
        self.fr = friction
        self.h0 = h0
        z, cap, kz, kthick = [0.0], [0.0], [], [0.0]
        for thick, n, k, rho, c in LAYERS:
            dz = thick / n
            for _ in range(n):
                cap[-1] += rho * c * dz / 2
                kthick[-1] += k * dz / 2
                kz.append(k / dz)
                z.append(z[-1] + dz)
                cap.append(rho * c * dz / 2)
                kthick.append(k * dz / 2)
        self.z = np.array(z)
        self.cap = np.array(cap)[:, None]        # J/m^2K per node (per unit area)
        self.kz = np.array(kz)                    # W/m^2K between nodes
        self.kthick = np.array(kthick)[:, None]   # W/K: k times thickness, for radial flow
        self.i_if = LAYERS[0][1]                  # interface node
        dr = (R_OUT_M - R_IN_M) / N_RINGS
        self.dr = dr
        self.r = R_IN_M + dr * (np.arange(N_RINGS) + 0.5)
        self.area = 2 * math.pi * self.r * dr
        self.area_total = math.pi * (R_OUT_M ** 2 - R_IN_M ** 2)
        faces = R_IN_M + dr * np.arange(1, N_RINGS)
        self.g_face = 2 * math.pi * faces / dr               # x kthick -> W/K between rings
        self.g_in = 2 * math.pi * R_IN_M / (dr / 2)
        self.g_out = 2 * math.pi * R_OUT_M / (dr / 2)
        iz = np.searchsorted(self.z, TC_Z_M) - 1
        self.tc_iz, self.tc_wz = iz, (TC_Z_M - self.z[iz]) / (self.z[iz + 1] - self.z[iz])
        offs = np.linspace(-IR_SPOT_M / 2, IR_SPOT_M / 2, 41)
        w = np.sqrt(np.maximum((IR_SPOT_M / 2) ** 2 - offs ** 2, 0.0))
        self.ir_r, self.ir_w = IR_R_M + offs, w / w.sum()

    def start(self, temp_C, hidden):
        self.T = np.full((len(self.z), N_RINGS), float(temp_C))
        self.T_rig = float(temp_C)
        self.T_sump = float(temp_C)
        self.hid = hidden

    def torque_and_flux(self, T_if, dw, force_N):
        p = force_N / self.area_total
        mu = self.fr.mu(self.r * abs(dw) * 1e3, T_if, force_N)
        return float(np.sum(self.r * p * mu * self.area)), self.r * abs(dw) * p * mu

    def step(self, dw_mid, force_N, dt):
        T = self.T
        _, q = self.torque_and_flux(T[self.i_if], dw_mid, force_N)
        # radial conduction, explicit
        flow = np.zeros_like(T)
        between = self.kthick * self.g_face * (T[:, 1:] - T[:, :-1])
        flow[:, :-1] += between
        flow[:, 1:] -= between
        flow[:, 0] += self.kthick[:, 0] * self.g_in * (self.T_sump - T[:, 0])
        flow[:, -1] += self.kthick[:, 0] * self.g_out * (self.T_sump - T[:, -1])
        Ts = T + dt * flow / (self.cap * self.area)
        # z columns, implicit (Thomas) -- per unit area
        n = len(self.z)
        a = np.zeros((n, N_RINGS)); b = np.tile(self.cap / dt, (1, N_RINGS)); c = np.zeros((n, N_RINGS))
        d = Ts * self.cap / dt
        for j in range(n - 1):
            b[j] += self.kz[j]; b[j + 1] += self.kz[j]
            c[j] -= self.kz[j]; a[j + 1] -= self.kz[j]
        h = self.h0 * (0.5 + 0.5 * math.sqrt(abs(dw_mid) / (100 * RPM)))
        b[self.i_if] += h
        d[self.i_if] += q + h * self.T_sump
        G_area = self.hid.rig_G_W_per_K / self.area_total
        if self.hid.rig_C_J_per_K > 0:
            b[0] += G_area
            d[0] += G_area * self.T_rig
        for j in range(1, n):
            w = a[j] / b[j - 1]
            b[j] -= w * c[j - 1]
            d[j] -= w * d[j - 1]
        x = np.empty_like(d)
        x[-1] = d[-1] / b[-1]
        for j in range(n - 2, -1, -1):
            x[j] = (d[j] - c[j] * x[j + 1]) / b[j]
        self.T = x
        if self.hid.rig_C_J_per_K > 0:
            G_i = G_area * self.area
            C = self.hid.rig_C_J_per_K
            self.T_rig = (C / dt * self.T_rig + np.sum(G_i * x[0])) / (C / dt + np.sum(G_i))

    def _radial(self, row, r):
        return np.interp(r, self.r, row)  # held flat beyond the outer ring centres

    def thermocouple(self):
        iz, w = self.tc_iz, self.tc_wz
        return (1 - w) * self._radial(self.T[iz], TC_R_M) + w * self._radial(self.T[iz + 1], TC_R_M)

    def ir_spot(self):
        return float(np.sum(self.ir_w * self._radial(self.T[self.i_if], self.ir_r)))


def simulate(run, hidden, fluid_path, h0=H0_W_PER_M2K):
    """Noise-free signals at run.rate_Hz: dict of numpy arrays (sensor readings incl. faults)."""
    cl = Clutch(Friction(fluid_path), h0)
    cl.start(run.start_C, hidden)
    dur = run.time_s[-1]
    t_out = np.arange(0.0, dur + 1e-9, 1.0 / run.rate_Hz)
    speed = np.interp(t_out, run.time_s, run.speed_rpm)
    n_steps = int(round(dur / STEP_S))
    hist_t, hist_if, hist_tc, hist_ir = [0.0], [cl.T[cl.i_if].copy()], [cl.thermocouple()], [cl.ir_spot()]
    for s in range(n_steps):
        t0 = s * STEP_S
        dw = float(np.interp(t0 + STEP_S / 2, run.time_s, run.speed_rpm)) * RPM
        cl.step(dw, run.force_N, STEP_S)
        hist_t.append(t0 + STEP_S)
        hist_if.append(cl.T[cl.i_if].copy())
        hist_tc.append(cl.thermocouple())
        hist_ir.append(cl.ir_spot())
    hist_t = np.array(hist_t); hist_if = np.array(hist_if)
    tc = np.interp(t_out, hist_t, hist_tc)
    ir_raw = np.interp(t_out, hist_t, hist_ir)
    T_if = np.stack([np.interp(t_out, hist_t, hist_if[:, k]) for k in range(N_RINGS)], axis=1)
    p = run.force_N / cl.area_total
    mu = cl.fr.mu(cl.r * np.abs(speed[:, None]) * RPM * 1e3, T_if, run.force_N)
    torque = np.sum(cl.r * p * mu * cl.area, axis=1)
    torque += hidden.bearing_mu * run.force_N * BEARING_RADIUS_M
    dt = 1.0 / run.rate_Hz
    tc = first_order_lag(tc, hidden.tc_lag_s, dt)
    ir = first_order_lag(ir_raw, IR_TAU_S, dt)
    return {
        "time_s": t_out,
        "speed_rpm": speed,
        "normal_force_N": np.full_like(t_out, hidden.load_gain * run.force_N),
        "torque_Nm": hidden.torque_gain * torque + hidden.torque_offset_Nm,
        "temp_C": tc + hidden.tc_offset_K,
        "sump_temp_C": np.full_like(t_out, cl.T_sump),
        "ir_temp_C": ir,
    }


def first_order_lag(x, tau_s, dt):
    """y' = (x - y)/tau with x linear between samples (exact first-order-hold update)."""
    if tau_s <= 0:
        return x.copy()
    e = math.exp(-dt / tau_s)
    g = 1.0 - tau_s / dt * (1.0 - e)  # weight of the new sample's slope term
    y = np.empty_like(x)
    y[0] = x[0]
    for i in range(1, len(x)):
        y[i] = e * y[i - 1] + (1 - e) * x[i - 1] + g * (x[i] - x[i - 1])
    return y


def add_noise(sig, seed):
    rng = np.random.default_rng(seed)
    out = dict(sig)
    for name, sigma in NOISE.items():
        out[name] = sig[name] + rng.normal(0.0, sigma, len(sig[name]))
    out["normal_force_N"] = np.maximum(out["normal_force_N"], 0.0)
    return out


def write_csv(path, sig, seed, note):
    cols = ["time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C", "sump_temp_C", "ir_temp_C"]
    with open(path, "w") as f:
        f.write("# format: shudder-measurement/1\n# rig: lsctr\n# fluid: lsc-fluid-c\n")
        f.write("# temp_sensor: separator_thermocouple r_mm=48 z_mm=0.5\n# oil_flow_ml_min: 200\n")
        f.write(f"# sample_rate_Hz: 100\n# noise: on\n# seed: {seed}\n")
        f.write(f"# generator: tools/independent_sim/indep_sim.py ({note})\n")
        f.write(",".join(cols) + "\n")
        for i in range(len(sig["time_s"])):
            f.write(f"{sig['time_s'][i]:.3f}," + ",".join(f"{sig[c][i]:.6g}" for c in cols[1:]) + "\n")


def calibrate(fluid_path):
    """Bisect h0 so that Paper G Case 1 (10.4 kN, 77 C, 1 -> 100 rpm in 10 s) reads 90 C at 10 s."""
    case1 = Run(force_N=10400.0, start_C=77.0, time_s=[0.0, 10.0], speed_rpm=[1.0, 100.0])
    lo, hi = 500.0, 20000.0
    for _ in range(30):
        mid = math.sqrt(lo * hi)
        tc = simulate(case1, Hidden(), fluid_path, mid)["temp_C"][-1]
        lo, hi = (lo, mid) if tc < 90.0 else (mid, hi)
    return math.sqrt(lo * hi)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    g = sub.add_parser("run", help="write one noisy measured-run CSV")
    g.add_argument("out")
    g.add_argument("--fluid", required=True)
    g.add_argument("--force-N", type=float, required=True)
    g.add_argument("--start-C", type=float, default=80.0)
    g.add_argument("--seed", type=int, default=1)
    for f_ in Hidden.__dataclass_fields__:
        g.add_argument("--" + f_.replace("_", "-"), type=float, default=getattr(Hidden(), f_))
    c = sub.add_parser("calibrate", help="recompute h0 from Paper G Case 1 at 10.4 kN")
    c.add_argument("--fluid", required=True)
    a = ap.parse_args(argv)
    if a.cmd == "calibrate":
        print(f"h0 = {calibrate(a.fluid):.1f} W/m2K")
        return 0
    hidden = Hidden(**{f_: getattr(a, f_) for f_ in Hidden.__dataclass_fields__})
    sig = simulate(Run(force_N=a.force_N, start_C=a.start_C), hidden, a.fluid)
    write_csv(a.out, add_noise(sig, a.seed), a.seed, repr(hidden))
    return 0


if __name__ == "__main__":
    sys.exit(main())
