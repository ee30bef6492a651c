#!/usr/bin/env python3
"""Communication model of gsph's MPI decomposition for 1e6-1e8 particles (docs/mpi.md).

A 3D run of N particles on a lattice of spacing dx, split into P cubic sub-domains of
n = N/P particles (side a = n^(1/3) spacings). Each sub-domain holds the ghosts within the
lists' reach w = support * (1 + skin) * h_factor spacings (2 * 1.1 * 1.2 = 2.64 for the
cubic spline and the defaults), g = (a + 2w)^3 - a^3 of them for an interior sub-domain.
Per step each ghost receives B bytes (the sum of the scheme's exchanges; ts2 3D: 47 words
= 376 B, host/src/dist and core EXCHANGES) in E exchanges, from up to 26 neighbours.
Ghost rows are also computed (redundant work g/n). Per step one sub-domain costs

    t_step = n * t_pp / threads * (1 + g/n)  +  E * 26 * latency  +  g * B / bandwidth

with t_pp the measured single-thread time per particle-step. The table gives, per N:
the ghost share g/n and the communication share of the step on one 16-core machine
(16 ranks, shared memory) and on 2 and 8 machines (16 ranks each, the network between
machines), and the speed-up of 2 machines over 1; and the memory a gathered output needs
on each rank (the current implementation gathers the whole state on every rank at a
snapshot: N records of ~30 words).

Usage: scripts/mpi_model.py [--t-pp US] [--bytes B] [--exchanges E] [--reach W]
"""
import argparse

p = argparse.ArgumentParser()
p.add_argument("--t-pp", type=float, default=25.0, help="µs per particle-step, 1 thread (ts2 3D, measured: the 3D ball impact)")
p.add_argument("--bytes", type=float, default=378.0, help="halo bytes per ghost per step (ts2 3D, measured)")
p.add_argument("--exchanges", type=int, default=4)
p.add_argument("--reach", type=float, default=2.64, help="halo width in spacings")
p.add_argument("--bytes-per-particle", type=float, default=2400.0, help="state+workspace+lists (3D ts2, measured 2,372)")
a = p.parse_args()

NETS = {  # (latency s, bandwidth B/s)
    "shm": (0.5e-6, 10e9),
    "100G IB": (2e-6, 12e9),
    "10 GbE": (20e-6, 1.1e9),
}
CORES = 16


def step(N, machines, net):
    """Seconds per step of one rank (16 ranks per machine, one thread each)."""
    P = CORES * machines
    n = N / P
    side = n ** (1 / 3)
    g = (side + 2 * a.reach) ** 3 - side ** 3
    g = min(g, N - n)
    lat, bw = NETS[net]
    compute = n * a.t_pp * 1e-6 * (1 + g / n)
    comm = a.exchanges * 26 * lat + g * a.bytes / bw
    return compute, comm, g / n


print("| N | ghosts/owned (16 ranks) | comm share, 1 machine | 2 machines, 100G IB: comm share, speed-up | 2 machines, 10 GbE: comm share, speed-up | 8 machines, 100G IB: speed-up | memory of the state (all particles) | gathered output, per rank |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for N in [1e4, 1e5, 1e6, 1e7, 1e8]:
    c1, m1, g1 = step(N, 1, "shm")
    t1 = c1 + m1
    row = [f"{N:.0e}", f"{g1:.2f}", f"{m1 / t1:.3f}"]
    for net in ["100G IB", "10 GbE"]:
        c2, m2, _ = step(N, 2, net)
        row.append(f"{m2 / (c2 + m2):.3f}, {t1 / (c2 + m2):.2f}x")
    c8, m8, _ = step(N, 8, "100G IB")
    row.append(f"{t1 / (c8 + m8):.2f}x")
    row.append(f"{N * a.bytes_per_particle / 1e9:.1f} GB")
    row.append(f"{N * 30 * 8 * 2 / 1e9:.1f} GB")
    print("| " + " | ".join(row) + " |")
