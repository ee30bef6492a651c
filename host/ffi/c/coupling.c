/* Coupling from C: a host code builds a 2D aluminium block from its own particle arrays
 * (gsph_create_from_particles), and every step computes an external force field on it
 * from the current positions (a body force that grows with height, as a host code's
 * field would) and hands gsph the accelerations. The momentum budget must close: the
 * momentum gsph ends with minus the momentum it started with equals the impulse the
 * host applied, sum m a dt, to round-off.
 *
 *   coupling [STEPS]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "gsph.h"

static const char *SETTINGS =
    "dim = 2\n"
    "scheme = \"ts2\"\n"
    "t_end = 1.0\n"
    "[[materials]]\n"
    "name = \"al\"\n"
    "rho0 = 2785.0\n"
    "shear_modulus = 27.6e9\n"
    "eos = { type = \"mie_gruneisen\", c0 = 5328.0, s1 = 1.338, gamma0 = 2.0 }\n"
    "strength = { type = \"von_mises\", yield_stress = 0.3e9 }\n";

static int fail(const char *what) {
    fprintf(stderr, "coupling: %s: %s\n", what, gsph_last_error());
    return 1;
}

int main(int argc, char **argv) {
    int steps = argc > 1 ? atoi(argv[1]) : 100;
    enum { NX = 40, NY = 20 };
    const double dx = 1.0e-3;
    size_t n = NX * NY;
    double *x = malloc(2 * n * sizeof *x), *v = malloc(2 * n * sizeof *v);
    uint32_t *mat = calloc(n, sizeof *mat);
    for (size_t j = 0; j < NY; j++)
        for (size_t i = 0; i < NX; i++) {
            size_t k = j * NX + i;
            x[2 * k] = (i + 0.5) * dx;
            x[2 * k + 1] = (j + 0.5) * dx;
            v[2 * k] = 50.0; /* moving right, spinning a little */
            v[2 * k + 1] = 20.0 * (x[2 * k] - 0.02) / 0.02;
        }
    gsph_particles parts = {0};
    parts.count = n;
    parts.position = x;
    parts.velocity = v;
    parts.material = mat;
    parts.spacing = &dx;
    parts.spacing_count = 1;
    gsph_sim *sim = NULL;
    if (gsph_create_from_particles(SETTINGS, NULL, 0, &parts, &sim) != GSPH_OK) return fail("create");

    double *m = malloc(n * sizeof *m), *a = malloc(2 * n * sizeof *a);
    if (gsph_read_field(sim, "mass", m, n) != GSPH_OK) return fail("mass");
    double p0[3], p1[3], ext[3], applied[2] = {0.0, 0.0};
    if (gsph_momentum(sim, p0, NULL) != GSPH_OK) return fail("momentum");
    for (int s = 0; s < steps; s++) {
        if (gsph_read_field(sim, "position", x, 2 * n) != GSPH_OK) return fail("position");
        for (size_t k = 0; k < n; k++) {
            double h = x[2 * k + 1] / (NY * dx); /* 0 at the bottom, 1 at the top */
            a[2 * k] = 2.0e5 * h;                /* m/s^2 */
            a[2 * k + 1] = -9.81e4 * (1.0 + h * h);
        }
        if (gsph_set_acceleration(sim, a, 2 * n) != GSPH_OK) return fail("acceleration");
        double dt = 0.0;
        if (gsph_step(sim, 0.0, &dt) != GSPH_OK) return fail("step");
        for (size_t k = 0; k < n; k++) {
            applied[0] += m[k] * a[2 * k] * dt;
            applied[1] += m[k] * a[2 * k + 1] * dt;
        }
    }
    if (gsph_momentum(sim, p1, ext) != GSPH_OK) return fail("momentum");
    gsph_destroy(sim);
    int ok = 1;
    for (int c = 0; c < 2; c++) {
        double change = p1[c] - p0[c];
        double err = fabs(change - applied[c]) / fabs(applied[c]);
        printf("coupling (C): %d steps, momentum_%c change %.12e, impulse applied %.12e, "
               "relative difference %.2e (gsph's own count %.12e)\n",
               steps, "xy"[c], change, applied[c], err, ext[c]);
        ok &= err < 1e-9;
    }
    free(x), free(v), free(mat), free(m), free(a);
    if (!ok) {
        fprintf(stderr, "coupling: the momentum budget does not close\n");
        return 1;
    }
    return 0;
}
