// The collapsing beryllium ring (cases/ring_collapse.toml) from C++: loads the scene with
// overrides, takes STEPS steps of the scene's CFL rule, reads the positions and checks the
// inner radius (the smallest distance of a particle from the centre) against the value
// given on the command line (scripts/ffi.sh passes the one from `gsph run`'s final.csv
// after the same steps). A bad field name must come back as a gsph::Error.
//
//   ring SCENE STEPS EXPECTED_INNER_RADIUS [KEY=VALUE ...]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gsph.hpp"

int main(int argc, char **argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s SCENE STEPS EXPECTED_INNER_RADIUS [KEY=VALUE ...]\n", argv[0]);
        return 2;
    }
    const long steps = std::atol(argv[2]);
    const double expected = std::strtod(argv[3], nullptr);
    std::vector<std::string> overrides(argv + 4, argv + argc);
    try {
        gsph::Simulation sim(argv[1], overrides);
        for (long k = 0; k < steps; ++k) sim.step();
        const auto x = sim.field("position");
        double inner = INFINITY;
        for (std::size_t i = 0; i < sim.size(); ++i)
            inner = std::fmin(inner, std::sqrt(x[2 * i] * x[2 * i] + x[2 * i + 1] * x[2 * i + 1]));
        bool refused = false;
        try {
            sim.field("no_such_field");
        } catch (const gsph::Error &e) {
            refused = e.code() == GSPH_ERR_ARGUMENT;
            std::printf("ring (C++): a bad field name is refused: %s\n", e.what());
        }
        std::printf("ring (C++): %zu particles, %llu steps, t = %.6e s, inner radius %.17g m (gsph run: %.17g)\n",
                    sim.size(), static_cast<unsigned long long>(sim.steps()), sim.time(), inner, expected);
        const double rel = std::fabs(inner - expected) / expected;
        if (!(rel <= 1e-12) || !refused) {
            std::fprintf(stderr, "ring: inner radius differs from gsph run by %.3e (relative)\n", rel);
            return 1;
        }
    } catch (const gsph::Error &e) {
        std::fprintf(stderr, "ring: %s\n", e.what());
        return 1;
    }
    return 0;
}
