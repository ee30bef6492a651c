"""Colliding elastic rings in PySPH 1.0b2, after pysph/examples/solid_mech/rings.py.

Same physics as the example (ElasticSolidsScheme: Monaghan artificial viscosity alpha = beta
= 1, Monaghan/Gray artificial stress eps = 0.3, n = 4 with W(dx) as reference, XSPH eps =
0.5, continuity density, EPEC integrator with SolidMechStep, cubic spline, h = 1.5 dx, fixed
dt = 1e-8 s) and the geometry of gsph's cases/rings.toml (scripts/peers/case.py): left ring
centred at (0, 0), right ring at (0.082, 0), the example's particles too (it builds x - 0.041
and x + 0.041 and then adds 0.041). Differences from the example: the left ring is tagged
by an integer property `body` (0 left, 1 right) that is saved, the stress deviator
s00..s22 is saved, output is written only at t = 0, 1e-5 and 5e-5 s (not every 500 steps),
and --dx sets the resolution.

    python pysph_rings.py --dx 5e-4 -d OUT                 # full run to 5e-5 s
    python pysph_rings.py --dx 5e-4 -d OUT --max-steps 1000 --disable-output   # timing
"""

import os
import sys

import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import case  # noqa: E402

from pysph.base.kernels import CubicSpline  # noqa: E402
from pysph.solver.application import Application  # noqa: E402
from pysph.sph.solid_mech.basic import (  # noqa: E402
    ElasticSolidsScheme, get_particle_array_elastic_dynamics)


class Rings(Application):
    def add_user_options(self, group):
        group.add_argument("--dx", action="store", type=float, dest="dx",
                           default=5e-4, help="lattice spacing (m)")

    def consume_user_options(self):
        self.dx = self.options.dx
        self.hdx = case.HDX
        self.h = self.hdx * self.dx

    def create_particles(self):
        dx = self.dx
        x, y, vx, vy, m, body = case.particles(dx)
        h = numpy.ones_like(x) * self.h
        rho = numpy.ones_like(x) * case.RHO0
        kernel = CubicSpline(dim=2)
        self.wdeltap = kernel.kernel(rij=dx, h=self.h)
        pa = get_particle_array_elastic_dynamics(
            name="solid", x=x, y=y, m=m, rho=rho, h=h,
            constants=dict(wdeltap=self.wdeltap, n=case.AS_N,
                           rho_ref=case.RHO0, E=case.E, nu=case.NU))
        # pa.cs = sqrt(E / (3 (1 - 2 nu) rho0)) = c0, as in the example
        pa.u[:] = pa.cs * 0.059 * numpy.where(body == 0, 1.0, -1.0)
        pa.v[:] = vy
        pa.add_property("body", type="int", data=body)
        pa.add_output_arrays(["s00", "s01", "s02", "s11", "s12", "s22", "body"])
        print("rings: %d particles, dx = %g, h = %g, G = %g, c0 = %.10g, u0 = %.10g"
              % (x.size, dx, self.h, pa.G[0], pa.cs[0], abs(pa.u[0])))
        return [pa]

    def create_scheme(self):
        s = ElasticSolidsScheme(elastic_solids=["solid"], solids=[], dim=2,
                                artificial_stress_eps=case.AS_EPS,
                                alpha=case.AV_ALPHA, beta=case.AV_BETA)
        s.configure_solver(dt=case.DT, tf=case.T_END, pfreq=1 << 30,
                           output_at_times=list(case.T_OUT))
        return s


if __name__ == "__main__":
    app = Rings(fname="rings")
    app.run()
