#!/usr/bin/env python3
"""How far apart in memory a particle's neighbours lie, for a 1D order of a 2D lattice.

docs/performance.md "Size and threads" (measured in docs/notes/performance_history_28_continued.md,
issue 28 "continued (6)"): a pass over the particles in index order
finds a neighbour's data in L2 only when it was touched recently, i.e. when the neighbour
lies few places away in the order. This script lays out two rings of lattice particles
like cases/rings.toml (about 4,416 / 17,592 / 70,320 particles), orders them in Morton
order (as gsph does, `host/src/neighbors.rs::morton_order`, cells of three spacings) and
in Hilbert order, and prints the share of neighbour pairs (within 3.2 spacings, about 32
per particle) that lie more than W places apart.

    .venv/bin/python scripts/order_locality.py      (numpy; `make setup` makes .venv)
"""
import numpy as np


def spread(v):
    v = v.astype(np.uint64)
    r = np.zeros_like(v)
    for b in range(21):
        r |= ((v >> np.uint64(b)) & np.uint64(1)) << np.uint64(2 * b)
    return r


def morton(cx, cy):
    return spread(cx) | (spread(cy) << np.uint64(1))


def hilbert(cx, cy, order=16):
    x, y = cx.astype(np.int64).copy(), cy.astype(np.int64).copy()
    d = np.zeros_like(x)
    s = 1 << (order - 1)
    while s > 0:
        rx = ((x & s) > 0).astype(np.int64)
        ry = ((y & s) > 0).astype(np.int64)
        d += s * s * ((3 * rx) ^ ry)
        low = ry == 0
        flip = low & (rx == 1)
        x = np.where(flip, s - 1 - x, x)
        y = np.where(flip, s - 1 - y, y)
        x, y = np.where(low, y, x), np.where(low, x, y)
        s //= 2
    return d


def rings(n):
    """Two annuli (inner radius 0.6 of the outer) of about n lattice points, side by side."""
    outer = np.sqrt(n / (2 * np.pi * (1 - 0.36)))
    m = int(outer) + 5
    xs, ys = np.meshgrid(np.arange(-m, m + 1), np.arange(-m, m + 1))
    r = np.hypot(xs, ys)
    keep = (r < outer) & (r > 0.6 * outer)
    x, y = xs[keep].ravel(), ys[keep].ravel()
    return np.concatenate([x, x + int(2.2 * outer)]), np.concatenate([y, y])


def distances(x, y, key):
    order = np.argsort(key, kind="stable")
    place = np.empty(len(x), int)
    place[order] = np.arange(len(x))
    lut = np.full((x.max() - x.min() + 9, y.max() - y.min() + 9), -1)
    lut[x - x.min() + 4, y - y.min() + 4] = np.arange(len(x))
    out = []
    for a in range(-3, 4):
        for b in range(-3, 4):
            if (a or b) and a * a + b * b <= 10.5:
                j = lut[x - x.min() + 4 + a, y - y.min() + 4 + b]
                ok = j >= 0
                out.append(np.abs(place[ok] - place[j[ok]]))
    return np.concatenate(out)


def main():
    widths = (100, 300, 1000, 3000, 10000)
    print("| particles | order | " + " | ".join(f"> {w}" for w in widths) + " |")
    print("| ---: | --- |" + " ---: |" * len(widths))
    for n in (4416, 17592, 70320):
        x, y = rings(n)
        cx, cy = (x - x.min()) // 3, (y - y.min()) // 3
        for name, key in (("Morton", morton(cx, cy)), ("Hilbert", hilbert(cx, cy))):
            d = distances(x, y, key)
            shares = " | ".join(f"{100 * (d > w).mean():.2f} %" for w in widths)
            print(f"| {len(x):,} | {name} | {shares} |")


if __name__ == "__main__":
    main()
