#!/usr/bin/env python3
"""Linear stability of a uniform 1D chain under the contact family's pair force, with the
seeds' specific volumes 1/(rho_i rho_j) and with Sugiura & Inutsuka's interpolated ones
(options.specific_volume = "interpolated"; core/src/schemes/pm/volume.rs), issue 27 part 6.

The chain: N particles of unit mass at unit spacing, periodic; the pair force of
core/src/schemes/pm/pairs.rs without dissipation (the Riemann pressure of a pair at rest
is the pair's mean pressure), a_i = -sum_j 2 P*_ij F_ij dW/dx_i, with F_ij = V_i V_j or
V_ij^2 (linear where the pair is compressed, cubic through the plain kernel-sum slopes
where it is stretched); p = P0 + c^2 (rho - rho_0). The density is the kernel sum, which
to first order is what the continuity equation of a pair at rest accumulates
(d/dt sum_j m W_ij = sum_j m (v_i - v_j) . grad W_ij). The Jacobian of a over the
positions is circulant; omega^2(k) < 0 is a growing mode (the tensile instability).

    python3 scripts/tensile_modes.py            (needs numpy; prints a Markdown table)
    python3 scripts/tensile_modes.py --plot FILE (also omega^2(k) in tension at h = dx and 2 dx
        into FILE; needs matplotlib)
    python3 scripts/tensile_modes.py --inutsuka (Inutsuka's own setting: Gaussian
        W(x, h) = exp(-x^2/h^2)/(sqrt(pi) h), summation density with W(h), the force with
        W(sqrt(2) h), <s^2> = h^2/4)
"""
import sys
import numpy as np

N = 48
L = float(N)
C2 = 1.0  # rho c^2 with rho ~ 1


def shape(q):  # gsph's cubic spline, 1D: sigma = 2/3 (core/src/kernel.rs)
    q = np.abs(q)
    return np.where(q < 1, 1 - 1.5 * q**2 + 0.75 * q**3, np.where(q < 2, 0.25 * (2 - q) ** 3, 0.0)) * 2 / 3


def dshape(q):
    s, q = np.sign(q), np.abs(q)
    return s * np.where(q < 1, -3 * q + 2.25 * q**2, np.where(q < 2, -0.75 * (2 - q) ** 2, 0.0)) * 2 / 3


def pair_v2(vi, vj, vpi, vpj, ds, mu, cubic):  # core/src/schemes/pm/volume.rs::pair_v2
    dv, sp, dp = vi - vj, vpi + vpj, vpi - vpj
    lin = (0.5 * (vi + vj)) ** 2 + (dv / ds) ** 2 * mu
    a = (sp - 2 * dv / ds) / ds**2
    b = dp / (2 * ds)
    c = 1.5 * dv / ds - 0.25 * sp
    d = 0.5 * (vi + vj) - dp * ds / 8
    cub = ((15 * a * a * mu + 3 * (2 * a * c + b * b)) * mu + (2 * b * d + c * c)) * mu + d * d
    return np.where(cubic, cub, lin)


INUTSUKA = "--inutsuka" in sys.argv


def gauss(x, h):
    return np.exp(-(x**2) / h**2) / (np.sqrt(np.pi) * h)


def density_kernel(d, h):
    if INUTSUKA:
        return gauss(d, h), -2 * d / h**2 * gauss(d, h)
    return shape(d / h) / h, dshape(d / h) / h**2


def accel(x, h, p0, rho0, mode):
    d = x[:, None] - x[None, :]
    d -= L * np.round(d / L)
    w, dw = density_kernel(d, h)
    rho = w.sum(1)
    v = 1 / rho
    p = p0 + C2 * (rho - rho0)
    ps = 0.5 * (p[:, None] + p[None, :])
    if mode == "product":
        f = v[:, None] * v[None, :]
    else:
        # 1D cubic spline: <r^2> = h^2/3, mu = <r^2>/(4 D); Inutsuka's Gaussian: h^2/4
        mu = h * h / 4 if INUTSUKA else h * h / 3 / 4
        vp = -(v**2) * dw.sum(1)  # grad V from the plain kernel sum
        e = np.sign(d)  # (x_i - x_j)/r
        ds = np.where(d == 0, 1.0, np.abs(d))
        f = pair_v2(v[:, None], v[None, :], vp[:, None] * e, vp[None, :] * e, ds, mu, ps < 0)
    np.fill_diagonal(f, 0)
    if INUTSUKA:  # the force's kernel is W(sqrt(2) h)
        hf = np.sqrt(2) * h
        dw = -2 * d / hf**2 * gauss(d, hf)
    return -(2 * ps * f * dw).sum(1)


def omega2(h, p0, mode):
    x0 = np.arange(N, dtype=float)
    d = x0[:, None] - x0[None, :]
    d -= L * np.round(d / L)
    rho0 = density_kernel(d, h)[0].sum(1)[0]
    jac = np.zeros((N, N))
    eps = 1e-6
    for k in range(N):
        xp, xm = x0.copy(), x0.copy()
        xp[k] += eps
        xm[k] -= eps
        jac[:, k] = (accel(xp, h, p0, rho0, mode) - accel(xm, h, p0, rho0, mode)) / (2 * eps)
    ks = np.arange(1, N // 2 + 1)
    return np.array([((-jac @ np.exp(2j * np.pi * n * x0 / L)) / np.exp(2j * np.pi * n * x0 / L)).real.mean() for n in ks])


def main():
    print("| h/dx | P0/(rho c^2) | product: min omega^2 | interpolated: min omega^2 | at k dx/pi (product, interpolated) |")
    print("| ---: | ---: | ---: | ---: | --- |")
    for h in (0.8, 1.0, 1.2, 1.5) if INUTSUKA else (1.0, 1.2, 1.5, 2.0):
        for p0 in (-0.05, -0.01, 0.05):
            a, b = omega2(h, p0, "product"), omega2(h, p0, "interpolated")
            ka, kb = (np.argmin(a) + 1) * 2 / N, (np.argmin(b) + 1) * 2 / N
            print(f"| {h} | {p0:+.2f} | {a.min():+.5f} | {b.min():+.5f} | {ka:.2f}, {kb:.2f} |")


def plot(path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    k = np.arange(1, N // 2 + 1) * 2 / N
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.4))
    p0 = -0.05
    for ax, h in zip(axes, (1.0, 2.0)):
        for mode, style in (("product", "-"), ("interpolated", "--")):
            ax.plot(k, omega2(h, p0, mode), style, label=mode)
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xlabel("k dx / pi")
        ax.set_title(f"h = {h} dx, P0 = {p0:+.2f} rho c^2")
    axes[0].set_ylabel("omega^2 (< 0: grows)")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
    if "--plot" in sys.argv:
        plot(sys.argv[sys.argv.index("--plot") + 1])
