"""Sweep a wall's stiffness, validate each value, plot the passivity ratio.

A script a notebook can paste (docs/tutorials/python.md). For each stiffness it loads the lab
wall (environments/wall.json) with that stiffness from a dict (hapscene.loads: no
temporary files), runs hapscene.validate on it (the `hapscene validate` scenarios, in simulated time), and
plots the passivity ratio (energy the loop created / energy dissipated) of the sweep,
press and release scenarios against the stiffness, with the check's threshold and the
passivity bound the report gives for the device and rate. A red cross marks a
scenario whose passivity check failed.

    PYTHONPATH=build/python/module /usr/bin/python3 docs/python_stiffness_sweep.py [OUT.svg]

Run it from the source tree; it writes docs/python_stiffness_sweep.svg by default.
"""
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display needed
matplotlib.rcParams["svg.hashsalt"] = "hapscene"  # the same SVG on every run
import matplotlib.pyplot as plt
import numpy as np

import hapscene

stiffnesses_N_per_m = np.geomspace(100.0, 20000.0, 16)
scenarios = ["sweep", "press", "release"]
base = json.loads(Path("environments/wall.json").read_text())


def passivity(scenario):
    """(ratio, verdict) of a scenario in a validate report (NaN when not applicable)."""
    if not scenario["applicable"]:
        return np.nan, "not judged"
    check = next(c for c in scenario["checks"] if c["name"] == "passivity")
    return scenario["metrics"]["passivity"]["ratio"], check["verdict"]


ratio = {name: [] for name in scenarios}
verdict = {name: [] for name in scenarios}
environment = base
for k in stiffnesses_N_per_m:
    environment["effects"][0]["stiffness"] = float(k)
    report = hapscene.validate(hapscene.loads(environment, base_dir="environments", name="wall.json"),
                               scenarios=scenarios)
    bound_N_per_m = report["scene"]["passivity_bound_N_per_m"]
    threshold = next(c for c in report["scenarios"][0]["checks"] if c["name"] == "passivity")["threshold"]
    for scenario in report["scenarios"]:
        r, v = passivity(scenario)
        ratio[scenario["name"]].append(r)
        verdict[scenario["name"]].append(v)
        print(f"{k:8.0f} N/m  validate {'pass' if report['pass'] else 'FAIL'}  " +
              "  ".join(f"{n} {ratio[n][-1]:.3f} ({verdict[n][-1]})" for n in scenarios))

figure, axes = plt.subplots(figsize=(7.5, 4.5))
for name in scenarios:
    axes.plot(stiffnesses_N_per_m, ratio[name], marker="o", markersize=3, label=name)
    failed = [i for i, v in enumerate(verdict[name]) if v == "FAIL"]
    axes.plot(stiffnesses_N_per_m[failed], np.array(ratio[name])[failed], "x", color="red", markersize=7)
axes.axhline(threshold, color="black", linewidth=0.8, label=f"passivity check: ratio at most {threshold:g}")
axes.axvline(bound_N_per_m, color="grey", linestyle="--", label=f"passivity bound {bound_N_per_m:.0f} N/m")
axes.set_xscale("log")
axes.set_yscale("log")
axes.set_xlabel("wall stiffness (N/m)")
axes.set_ylabel("passivity ratio (created / dissipated)")
axes.set_title("environments/wall.json, simulated Hapkit at 1 kHz: hapscene.validate per stiffness "
               "(red x: check failed)", fontsize=9)
axes.grid(True, which="both", alpha=0.3)
axes.legend(fontsize=8)
figure.tight_layout()
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("docs/python_stiffness_sweep.svg")
figure.savefig(out, metadata={"Date": None})  # no date: the same file on every run
print(f"wrote {out}")
