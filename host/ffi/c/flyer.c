/* The flyer plate (cases/flyer_plate.toml) from C: loads the scene, advances it through
 * its snapshot times as `gsph run` does, reads the stress deviator and pressure, and
 * checks the peak compressive sigma_xx = s_xx - p against the value given on the command
 * line (scripts/ffi.sh passes the one `gsph run` wrote to final.csv).
 *
 *   flyer SCENE EXPECTED_PEAK_SIGMA_XX [SNAPSHOT.csv]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gsph.h"

static int fail(const char *what) {
    fprintf(stderr, "flyer: %s: %s\n", what, gsph_last_error());
    return 1;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: %s SCENE EXPECTED_PEAK_SIGMA_XX [SNAPSHOT.csv]\n", argv[0]);
        return 2;
    }
    double expected = strtod(argv[2], NULL);
    gsph_sim *sim = NULL;
    if (gsph_create_from_file(argv[1], NULL, 0, &sim) != GSPH_OK) return fail("create");

    /* the scene's snapshot times: t_end k / snapshots, k = 1..snapshots */
    double t_end = 0.0;
    size_t snapshots = 0;
    if (gsph_schedule(sim, &t_end, &snapshots) != GSPH_OK) return fail("schedule");
    uint64_t steps = 0;
    for (size_t k = 1; k <= snapshots; k++) {
        uint64_t n = 0;
        if (gsph_advance(sim, t_end * (double)k / (double)snapshots, &n) != GSPH_OK) return fail("advance");
        steps += n;
    }

    size_t count = 0, comps = 0;
    if (gsph_count(sim, &count) != GSPH_OK) return fail("count");
    if (gsph_field_components(sim, "deviator", &comps) != GSPH_OK) return fail("components");
    double *s = malloc(count * comps * sizeof *s);
    double *p = malloc(count * sizeof *p);
    if (!s || !p) return 1;
    if (gsph_read_field(sim, "deviator", s, count * comps) != GSPH_OK) return fail("read deviator");
    if (gsph_read_field(sim, "pressure", p, count) != GSPH_OK) return fail("read pressure");
    double peak = 0.0;
    for (size_t i = 0; i < count; i++) {
        double sxx = s[i * comps] - p[i];
        if (sxx < peak) peak = sxx;
    }
    /* a wrong buffer length is refused with a message, not a crash */
    if (gsph_read_field(sim, "pressure", p, count - 1) != GSPH_ERR_ARGUMENT) {
        fprintf(stderr, "flyer: a short buffer was accepted\n");
        return 1;
    }
    /* a time already passed is refused, not 0 steps */
    uint64_t none = 0;
    if (gsph_advance(sim, -1.0, &none) != GSPH_ERR_ARGUMENT || !strstr(gsph_last_error(), "lies before")) {
        fprintf(stderr, "flyer: advancing to t = -1 was accepted\n");
        return 1;
    }
    printf("flyer (C): %zu particles, %llu steps, peak sigma_xx %.17g Pa (gsph run: %.17g)\n",
           count, (unsigned long long)steps, peak, expected);
    if (argc > 3 && gsph_write_snapshot(sim, argv[3]) != GSPH_OK) return fail("snapshot");
    free(s);
    free(p);
    gsph_destroy(sim);
    double rel = fabs(peak - expected) / fabs(expected);
    if (!(rel <= 1e-12)) {
        fprintf(stderr, "flyer: peak sigma_xx differs from gsph run by %.3e (relative)\n", rel);
        return 1;
    }
    return 0;
}
