"""The clamped oscillating plate's measures from one run's series.csv, as rows of
scripts/elastic.sh's rows.csv (case,dx,scheme,variant,metric,value,wall_s):

- mechanical_energy_ratio_3T: (KE+SE)/E0 at three periods (the last sample at or before
  3 T, T from the run itself);
- mechanical_energy_ratio_max: the largest (KE+SE)/E0 (above 1: energy created);
- ke_peak_ratio_3T: the kinetic energy's last peak before 3 T over KE0 (what SPHinXsys
  monitors: its UL plate keeps 0.979 at 0.857 s, its TL plate 0.993);
- period, period_vs_eb: the period from the kinetic energy's minima (the largest
  deflections, two per period) and its excess over Euler-Bernoulli's T_EB = 0.25406 s
  (E/(1 - nu^2), plane strain; SPHinXsys TL +8.1 %, UL +12.5 %);
- min_distance_min: the nearest pair over the run, in spacings.

    python3 scripts/plate_measures.py RUN_DIR DX SCHEME VARIANT
"""
import csv
import json
import math
import sys
from pathlib import Path

T_EB = 0.25406


def measures(run):
    rows = list(csv.DictReader(open(Path(run) / "series.csv")))
    t = [float(r["t"]) for r in rows]
    ke = [float(r["kinetic"]) for r in rows]
    mech = [float(r["mechanical_energy_ratio"]) for r in rows]
    dmin = [float(r["min_distance"]) for r in rows]
    ke0 = ke[0]
    # the largest deflections: minima of the kinetic energy below 10 % of KE0, one per
    # half period (minima closer than a fifth of T_EB are the same one)
    mins = []
    for k in range(1, len(t) - 1):
        if ke[k] < 0.1 * ke0 and ke[k] <= ke[k - 1] and ke[k] < ke[k + 1]:
            if mins and t[k] - mins[-1][0] < 0.2 * T_EB:
                if ke[k] < mins[-1][1]:
                    mins[-1] = (t[k], ke[k])
            else:
                mins.append((t[k], ke[k]))
    out = {}
    if len(mins) >= 2:
        period = 2.0 * (mins[-1][0] - mins[0][0]) / (len(mins) - 1)
        out["period"] = period
        out["period_vs_eb"] = period / T_EB - 1.0
        three = 3.0 * period
        last = max((k for k in range(len(t)) if t[k] <= three), default=len(t) - 1)
        if t[-1] >= three * 0.99:
            out["mechanical_energy_ratio_3T"] = mech[last]
            # a peak at the last sample before 3 T counts (it has a later sample)
            peaks = [k for k in range(1, min(last + 1, len(t) - 1))
                     if ke[k] >= ke[k - 1] and ke[k] > ke[k + 1]]
            late = [ke[k] for k in peaks if t[k] > three - period / 2]
            if late:
                out["ke_peak_ratio_3T"] = max(late) / ke0
    out["mechanical_energy_ratio_max"] = max(mech)
    out["min_distance_min"] = min(dmin)
    return out


def main():
    run, dx, scheme, variant = sys.argv[1:5]
    try:
        wall = json.load(open(Path(run) / "summary.json")).get("wall_s", math.nan)
        m = measures(run)
    except (OSError, KeyError, ValueError):
        wall, m = math.nan, {}
    for k in ["mechanical_energy_ratio_3T", "ke_peak_ratio_3T", "mechanical_energy_ratio_max",
              "period", "period_vs_eb", "min_distance_min"]:
        print(f"plate,{dx},{scheme},{variant},{k},{m.get(k, math.nan)},{wall}")


if __name__ == "__main__":
    main()
