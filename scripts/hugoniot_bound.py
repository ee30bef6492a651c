#!/usr/bin/env python3
"""The full-compaction bound of a steady compaction wave, from a gsph Hugoniot table.

In a steady window the mass flux into the wave equals the flux out of it, whatever the
precursor does: rho_a (u_s - u_a) = rho_1 (u_s - u_p), with the measured state ahead
(rho_ahead, precursor_velocity). The slowest wave that leaves solid material behind
(rho_1 = rho_solid) moves at

    u_s,bound = (rho_solid u_p - rho_a u_a) / (rho_solid - rho_a).

A slower wave would have to compress the solid. For each row this prints the bound, how
far gsph's u_s and the paper's fit (us_fit) lie above it, and the porosity
m = u_s / (u_s - u_p) that a single wave into the undisturbed sample at the fit's speed
would imply with full compaction (the sample's is 1.35).

usage: scripts/hugoniot_bound.py docs/hugoniot/hugoniot_05um_pm.csv [rho_solid]
"""
import csv
import sys


def main():
    path = sys.argv[1]
    rho_s = float(sys.argv[2]) if len(sys.argv) > 2 else 8960.0
    print(f"{path}: rho_solid = {rho_s} kg/m3")
    print("| u_p | u_s gsph | u_s fit | bound | gsph / bound − 1 | fit / bound − 1 | m implied by the fit |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in csv.DictReader(open(path)):
        up, us, fit = float(r["up"]), float(r["us"]), float(r["us_fit"])
        rho_a, ua = float(r["rho_ahead"]), float(r["precursor_velocity"])
        bound = (rho_s * up - rho_a * ua) / (rho_s - rho_a)
        m_fit = fit / (fit - up)
        print(
            f"| {up:g} | {us:.1f} | {fit:.1f} | {bound:.1f} | {100 * (us / bound - 1):+.1f} % "
            f"| {100 * (fit / bound - 1):+.1f} % | {m_fit:.3f} |"
        )


if __name__ == "__main__":
    main()
