import matplotlib
matplotlib.use("Agg")            # files only, no display needed
import matplotlib.pyplot as plt
import shudder

case1 = "scenarios/paper_g_case1_10kN.toml"     # Paper G Case 1: slip 1 -> 100 rpm in 10 s
fig, (ax_t, ax_T) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
for force_N in (10.4e3, 20e3):
    # The key is the scenario's own (docs/formats/scenario_file.md), set as `sweep --set` sets it.
    r = shudder.run(case1, overrides={"drive.normal_force_N": force_N})
    t = r.signals["time_s"]
    ax_t.plot(t, r.signals["torque_Nm"], label=f"{force_N / 1e3:.1f} kN")
    ax_T.plot(t, r.signals["temp_C"], label=f"{force_N / 1e3:.1f} kN")
    print(f"{force_N / 1e3:5.1f} kN: torque at 10 s {r.signals['torque_Nm'][-1]:.1f} {r.units['torque_Nm']}, "
          f"verdict {r.verdict['verdict']}")
ax_t.set_ylabel(f"torque [{r.units['torque_Nm']}]")
ax_T.set_ylabel(f"thermocouple [{r.units['temp_C']}]")
ax_T.set_xlabel(f"time [{r.units['time_s']}]")
ax_t.legend()
fig.savefig("case1_torque.png", dpi=100)

# A rig run that shudders, written to HDF5 as `shudder run -o` writes it.
r = shudder.run("scenarios/rig_shudder_negative_slope.toml", output="shudder.h5")
print(r.verdict["verdict"], r.verdict["frequency_Hz"], r.verdict["units"]["frequency_Hz"])
print(sorted(r.scalars)[:3], r.maps["stability_map"]["layers"].keys())
