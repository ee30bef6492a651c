/* A handle used by two threads at once (docs/embedding.md, "Thread safety"): gsph must
 * refuse, never crash or free memory under a call.
 *
 * 1. TRIES times: a thread steps the flyer plate in a loop while the main thread destroys
 *    the handle after a few milliseconds. The stepping thread must end with a refusal
 *    (GSPH_ERR_POINTER: not a live handle, or GSPH_ERR_BUSY: in use) and the program must
 *    not crash (before gsph 0.1's handle table it crashed in 4 of 8 tries).
 * 2. A thread runs a long gsph_run; a call from the main thread meanwhile fails with
 *    GSPH_ERR_BUSY; destroying the handle stops the run after its step (gsph_run returns
 *    GSPH_ERR_BUSY) long before its end.
 * 3. gsph_set_threads(100000) is refused (the cap of `gsph run --threads`).
 *
 *   threads SCENE(flyer_plate.toml) [TRIES]
 */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "gsph.h"

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void sleep_ms(long ms) {
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

struct stepper {
    gsph_sim *sim;
    long steps;
    int status;
    char message[512];
};

/* steps until a call fails; keeps the failing status and its message */
static void *step_loop(void *arg) {
    struct stepper *s = arg;
    for (;;) {
        int rc = gsph_step(s->sim, 0.0, NULL);
        if (rc != GSPH_OK) {
            s->status = rc;
            snprintf(s->message, sizeof s->message, "%s", gsph_last_error());
            return NULL;
        }
        s->steps++;
    }
}

/* gsph_run, tried again while the main thread's gsph_count holds the handle */
static void *run_all(void *arg) {
    struct stepper *s = arg;
    while ((s->status = gsph_run(s->sim, NULL)) == GSPH_ERR_BUSY && strstr(gsph_last_error(), "in use"))
        sleep_ms(1);
    snprintf(s->message, sizeof s->message, "%s", gsph_last_error());
    return NULL;
}

static int fail(const char *what) {
    fprintf(stderr, "threads: %s: %s\n", what, gsph_last_error());
    return 1;
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: %s FLYER_SCENE [TRIES]\n", argv[0]);
        return 2;
    }
    int tries = argc > 2 ? atoi(argv[2]) : 8;

    if (gsph_set_threads(100000) != GSPH_ERR_ARGUMENT || !strstr(gsph_last_error(), "threads per core")) {
        fprintf(stderr, "threads: gsph_set_threads(100000) was not refused: %s\n", gsph_last_error());
        return 1;
    }
    printf("threads: gsph_set_threads(100000) refused: %s\n", gsph_last_error());

    /* 1. destroy racing a stepping thread */
    for (int k = 0; k < tries; k++) {
        struct stepper s = {0};
        if (gsph_create_from_file(argv[1], NULL, 0, &s.sim) != GSPH_OK) return fail("create");
        pthread_t th;
        pthread_create(&th, NULL, step_loop, &s);
        sleep_ms(2 + 3 * k);
        gsph_destroy(s.sim);
        pthread_join(th, NULL);
        if (s.status != GSPH_ERR_POINTER && s.status != GSPH_ERR_BUSY) {
            fprintf(stderr, "threads: try %d: the stepping thread ended with %d: %s\n", k, s.status, s.message);
            return 1;
        }
        size_t n = 0;
        if (gsph_count(s.sim, &n) != GSPH_ERR_POINTER) {
            fprintf(stderr, "threads: try %d: a destroyed handle was accepted\n", k);
            return 1;
        }
        gsph_destroy(s.sim); /* twice: ignored */
        printf("threads: try %d: destroyed after %ld steps; the stepping thread got %d (%s)\n", k, s.steps,
               s.status, s.message);
    }

    /* 2. a busy handle refuses; destroy stops a long run */
    const char *set[] = {"t_end=1e-2", "output.snapshots=1"};
    struct stepper r = {0};
    if (gsph_create_from_file(argv[1], set, 2, &r.sim) != GSPH_OK) return fail("create long run");
    pthread_t th;
    double t0 = now();
    pthread_create(&th, NULL, run_all, &r);
    size_t n = 0;
    int rc = GSPH_OK;
    while ((rc = gsph_count(r.sim, &n)) == GSPH_OK && now() - t0 < 10.0) sleep_ms(1);
    if (rc != GSPH_ERR_BUSY) {
        fprintf(stderr, "threads: gsph_count during gsph_run on another thread gave %d, not GSPH_ERR_BUSY: %s\n",
                rc, gsph_last_error());
        return 1;
    }
    printf("threads: gsph_count during a run: %s\n", gsph_last_error());
    sleep_ms(50);
    double t1 = now();
    gsph_destroy(r.sim);
    double waited = now() - t1;
    pthread_join(th, NULL);
    if (r.status != GSPH_ERR_BUSY || !strstr(r.message, "destroyed")) {
        fprintf(stderr, "threads: gsph_run whose handle was destroyed returned %d: %s\n", r.status, r.message);
        return 1;
    }
    if (waited > 1.0) {
        fprintf(stderr, "threads: gsph_destroy waited %.3f s for the run to stop\n", waited);
        return 1;
    }
    printf("threads: destroy stopped gsph_run after %.3f s (destroy waited %.4f s): %s\n", now() - t0, waited,
           r.message);
    return 0;
}
