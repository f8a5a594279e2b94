"""Sweep a wall's stiffness, validate each value, plot the passivity ratio.

A script a notebook can paste (README "Python"). For each stiffness it writes the lab
wall (environments/wall.json) with that stiffness to a temporary file, runs
hapscene.validate on it (the `hapscene validate` scenarios, in simulated time), and
plots each scenario's passivity ratio (energy the loop created / energy dissipated)
against the stiffness, with the passivity bound the report gives for the device.

    PYTHONPATH=build/python/module /usr/bin/python3 docs/python_stiffness_sweep.py [OUT.svg]

Run it from the source tree; it writes docs/python_stiffness_sweep.svg by default.
"""
import json
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt
import numpy as np

import hapscene

stiffnesses_N_per_m = np.geomspace(100.0, 20000.0, 16)
base = json.loads(Path("environments/wall.json").read_text())
scenarios = ["sweep", "press", "release", "hold", "shake"]

ratios = {name: [] for name in scenarios}
verdicts = []
bound_N_per_m = None
with tempfile.TemporaryDirectory() as folder:
    for k in stiffnesses_N_per_m:
        environment = json.loads(json.dumps(base))
        environment["name"] = f"wall {k:.0f} N/m"
        environment["effects"][0]["stiffness"] = float(k)
        path = Path(folder) / "wall.json"
        path.write_text(json.dumps(environment))
        report = hapscene.validate(path, scenarios=scenarios)
        bound_N_per_m = report["scene"]["passivity_bound_N_per_m"]
        verdicts.append(report["pass"])
        for scenario in report["scenarios"]:
            if scenario["name"] in ratios:
                metrics = scenario.get("metrics") or {}
                ratios[scenario["name"]].append(metrics.get("passivity", {}).get("ratio", np.nan))
        print(f"{k:9.1f} N/m  {'pass' if report['pass'] else 'FAIL'}  " +
              "  ".join(f"{name} {ratios[name][-1]:.3f}" for name in scenarios))

figure, axes = plt.subplots(figsize=(7.5, 4.5))
for name in scenarios:
    axes.plot(stiffnesses_N_per_m, ratios[name], marker="o", markersize=3, label=name)
axes.axvline(bound_N_per_m, color="grey", linestyle="--", label=f"passivity bound {bound_N_per_m:.0f} N/m")
failed = [k for k, ok in zip(stiffnesses_N_per_m, verdicts) if not ok]
if failed:
    axes.axvspan(min(failed), max(stiffnesses_N_per_m), color="red", alpha=0.08, label="validate fails")
axes.set_xscale("log")
axes.set_xlabel("wall stiffness (N/m)")
axes.set_ylabel("passivity ratio (created / dissipated)")
axes.set_title("environments/wall.json on the simulated Hapkit, 1 kHz: hapscene.validate per stiffness")
axes.title.set_fontsize(9)
axes.grid(True, which="both", alpha=0.3)
axes.legend(fontsize=8)
figure.tight_layout()
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("docs/python_stiffness_sweep.svg")
figure.savefig(out, metadata={"Date": None})  # no date: the file is the same on every run
print(f"wrote {out}")
