// Every wrapper of gsph.hpp, called once at least on the flyer plate (scripts/ffi.sh
// checks with nm that this program reaches every function of gsph.h, and runs it): each
// call's result is checked against another call or against what the scene says.
//
//   every_cpp SCENE(flyer_plate.toml) WORK_DIR
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gsph.hpp"

static int failures = 0;

static void expect(bool ok, const std::string &what) {
    if (!ok) {
        std::fprintf(stderr, "every (C++): FAILED: %s\n", what.c_str());
        failures++;
    }
}

/// Runs `f`, which must throw gsph::Error with `code`; returns the message.
template <class F> static std::string refused(F f, int code, const std::string &what) {
    try {
        f();
    } catch (const gsph::Error &e) {
        expect(e.code() == code, what + ": code " + std::to_string(e.code()));
        return e.what();
    }
    expect(false, what + ": accepted");
    return "";
}

static std::string read_file(const std::string &path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

int main(int argc, char **argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s FLYER_SCENE WORK_DIR\n", argv[0]);
        return 2;
    }
    const std::string scene = argv[1], dir = argv[2];
    try {
        expect(!gsph::version().empty(), "version");
        std::string m = refused([] { gsph::set_threads(100000); }, GSPH_ERR_ARGUMENT, "set_threads(100000)");
        expect(m.find("threads per core") != std::string::npos, "set_threads message: " + m);
        expect(gsph::last_error() == m.substr(m.find(": ") + 2), "last_error");

        // a run with its snapshots and series, as `gsph run`
        gsph::Simulation sim = gsph::Simulation::from_file(scene, {"output.snapshots=2"});
        expect(sim.dim() == 1 && sim.size() == 100, "dim and size");
        expect(sim.t_end() == 0.5e-6 && sim.snapshots() == 2, "schedule");
        expect(sim.time() == 0.0 && sim.steps() == 0 && sim.stable_dt() > 0.0, "time, steps, stable_dt");
        sim.open_snapshots(dir + "/run");
        const auto steps = sim.run();
        sim.close_snapshots();
        expect(steps == sim.steps() && std::fabs(sim.time() - 0.5e-6) < 1e-18, "run");
        const auto names = sim.series_names();
        const auto shape = sim.series_shape();
        const auto series = sim.series();
        expect(names.size() == shape.second && names[0] == "t" && names[1] == "step", "series names");
        expect(series.size() == shape.first * shape.second && shape.first > 2, "series shape");
        expect(series[(shape.first - 1) * shape.second + 1] == double(steps), "series: last step");
        sim.write_series(dir + "/series.csv");
        expect(read_file(dir + "/series.csv").rfind("t,step,dt,", 0) == 0, "write_series");
        expect(read_file(dir + "/run/snapshots.xdmf").find("complete") != std::string::npos, "snapshots.xdmf");

        // stepping, fields, ids, external accelerations, budgets
        expect(sim.step() > 0.0 && sim.steps() == steps + 1, "step");
        expect(sim.advance(sim.time() + 1e-8) > 0, "advance");
        expect(sim.components("deviator") == 6, "components");
        auto rho = sim.field("density");
        rho[0] *= 1.001;
        sim.set_field("density", rho);
        expect(sim.field("rho")[0] == rho[0], "set_field");
        const auto ids = sim.ids();
        expect(ids.size() == 100 && ids[99] == 99, "ids");
        const auto e = sim.energy();
        expect(e.first > 0.0 && e.second > 0.0, "energy");
        const auto p0 = sim.momentum();
        sim.set_acceleration(std::vector<double>(100, 1.0e6));
        sim.step();
        sim.set_acceleration({});
        const auto ext = sim.external_impulse();
        expect(ext[0] > 0.0 && ext[1] == 0.0, "external_impulse");
        expect(std::fabs(sim.momentum()[0] - p0[0] - ext[0]) < 1e-9 * std::fabs(p0[0]) + 1e-12, "momentum budget");
        expect(sim.summary_json().find("\"external_work\"") != std::string::npos, "summary_json");
        sim.write_snapshot(dir + "/now.csv");
        expect(read_file(dir + "/now.csv").rfind("id,", 0) == 0, "write_snapshot");
        refused([&] { sim.write_snapshot(dir + "/now.h5"); }, GSPH_ERR_ARGUMENT, "write_snapshot(.h5)");
        sim.write_snapshots(dir + "/one");
        sim.open_snapshots(dir + "/two");
        refused([&] { sim.append_snapshot(); }, GSPH_ERR_ARGUMENT, "append_snapshot at the same step");
        sim.step();
        sim.append_snapshot();
        sim.close_snapshots();
        refused([&] { sim.close_snapshots(); }, GSPH_ERR_ARGUMENT, "close_snapshots twice");
        refused([&] { sim.write_checkpoint(dir + "/ck"); }, GSPH_ERR_ARGUMENT, "checkpoint after external forces");

        // checkpoints continue bit for bit
        gsph::Simulation a(scene);
        a.advance(0.1e-6);
        a.write_checkpoint(dir + "/ck");
        gsph::Simulation b = gsph::Simulation::from_checkpoint(dir + "/ck");
        a.advance(0.2e-6);
        b.advance(0.2e-6);
        expect(a.field("position") == b.field("position") && a.series() == b.series(), "from_checkpoint");

        // scene text, overrides that unset a key, the caller's particles
        gsph::Simulation t = gsph::Simulation::from_text(read_file(scene), {"scheme=ts1"});
        expect(t.summary_json().find("\"ts1\"") != std::string::npos, "from_text with an override");
        gsph::Simulation u(scene, {}, {"reference"});
        expect(t.summary_json().find("l1_error") != std::string::npos &&
                   u.summary_json().find("l1_error") == std::string::npos,
               "unset reference");
        m = refused([&] { gsph::Simulation(scene, {}, {"nope"}); }, GSPH_ERR_SCENE, "unset of a missing key");
        expect(m.find("--unset nope") != std::string::npos, "unset message: " + m);
        gsph::Particles parts;
        parts.position = {0.0, 1e-4, 2e-4, 3e-4};
        parts.material = {0, 0, 0, 0};
        parts.spacing = {1e-4};
        parts.velocity = {10.0, 10.0, 0.0, 0.0};
        gsph::Simulation q = gsph::Simulation::from_particles(
            "dim = 1\nscheme = \"ts1\"\nt_end = 1e-7\n[[materials]]\nname = \"m\"\nrho0 = 1000.0\n"
            "eos = { type = \"linear\", c0 = 1000.0 }\n",
            parts);
        expect(q.size() == 4 && q.field("mass")[0] == 1000.0 * 1e-4, "from_particles");
        gsph::Simulation moved = std::move(q);
        expect(moved.raw() != nullptr && q.raw() == nullptr, "move");
    } catch (const gsph::Error &e) {
        std::fprintf(stderr, "every (C++): unexpected error %d: %s\n", e.code(), e.what());
        return 1;
    }
    if (failures) return 1;
    std::printf("every (C++): every wrapper of gsph.hpp called and checked\n");
    return 0;
}
