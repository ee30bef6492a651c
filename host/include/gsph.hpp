// gsph C++ wrapper: RAII ownership of a simulation and exceptions for errors, over the
// whole C ABI of gsph.h (scripts/ffi.sh checks that every function of gsph.h is called
// here, and calls every wrapper). Header-only; link with -lgsph. See docs/embedding.md.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gsph.h"

namespace gsph {

/// A failed gsph call: the status code and gsph's one-line message.
class Error : public std::runtime_error {
  public:
    Error(int code, const std::string &what) : std::runtime_error(what), code_(code) {}
    int code() const noexcept { return code_; }

  private:
    int code_;
};

inline void check(int status, const char *call) {
    if (status != GSPH_OK) throw Error(status, std::string(call) + ": " + gsph_last_error());
}

/// The gsph version.
inline std::string version() { return gsph_version(); }

/// This thread's message for the last failed call ("" after a success).
inline std::string last_error() { return gsph_last_error(); }

/// Worker threads of the process-wide pool (0: one per core; at most 8 per core), before
/// the first simulation is created.
inline void set_threads(std::size_t threads) { check(gsph_set_threads(threads), "gsph_set_threads"); }

/// The caller's particles for Simulation::from_particles: vectors dim values per particle;
/// velocity, density, energy and mass may be left empty (at rest, rho0, 0, density *
/// spacing^dim); spacing one value or one per particle.
struct Particles {
    std::vector<double> position, velocity, density, energy, mass, spacing;
    std::vector<std::uint32_t> material;
};

/// A simulation; destroyed with the object. Movable, not copyable. One call at a time
/// (a call while another thread is inside throws gsph::Error with GSPH_ERR_BUSY).
class Simulation {
  public:
    /// Loads a scene file with overrides `KEY=VALUE` (as `gsph run --set`) and keys to
    /// remove (as `gsph run --unset`).
    explicit Simulation(const std::string &scene, const std::vector<std::string> &overrides = {},
                        const std::vector<std::string> &unset = {}) {
        Strings set(overrides, unset);
        check(gsph_create_from_file(scene.c_str(), set.data(), set.size(), &sim_), "gsph_create_from_file");
    }
    /// A scene file (as the constructor).
    static Simulation from_file(const std::string &path, const std::vector<std::string> &overrides = {},
                                const std::vector<std::string> &unset = {}) {
        return Simulation(path, overrides, unset);
    }
    /// Scene text (TOML) with overrides and keys to remove.
    static Simulation from_text(const std::string &text, const std::vector<std::string> &overrides = {},
                                const std::vector<std::string> &unset = {}) {
        Strings set(overrides, unset);
        gsph_sim *s = nullptr;
        check(gsph_create_from_text(text.c_str(), set.data(), set.size(), &s), "gsph_create_from_text");
        return Simulation(s);
    }
    /// The caller's particles with `settings`, scene text without bodies.
    static Simulation from_particles(const std::string &settings, const Particles &p,
                                     const std::vector<std::string> &overrides = {},
                                     const std::vector<std::string> &unset = {}) {
        Strings set(overrides, unset);
        auto opt = [](const std::vector<double> &v) { return v.empty() ? nullptr : v.data(); };
        gsph_particles c{};
        c.count = p.material.size();
        c.position = p.position.data();
        c.velocity = opt(p.velocity);
        c.density = opt(p.density);
        c.energy = opt(p.energy);
        c.mass = opt(p.mass);
        c.material = p.material.data();
        c.spacing = p.spacing.data();
        c.spacing_count = p.spacing.size();
        gsph_sim *s = nullptr;
        check(gsph_create_from_particles(settings.c_str(), set.data(), set.size(), &c, &s),
              "gsph_create_from_particles");
        return Simulation(s);
    }
    /// Continues from a checkpoint written by write_checkpoint.
    static Simulation from_checkpoint(const std::string &dir) {
        gsph_sim *s = nullptr;
        check(gsph_create_from_checkpoint(dir.c_str(), &s), "gsph_create_from_checkpoint");
        return Simulation(s);
    }

    Simulation(const Simulation &) = delete;
    Simulation &operator=(const Simulation &) = delete;
    Simulation(Simulation &&o) noexcept : sim_(o.sim_) { o.sim_ = nullptr; }
    Simulation &operator=(Simulation &&o) noexcept {
        if (this != &o) {
            gsph_destroy(sim_);
            sim_ = o.sim_;
            o.sim_ = nullptr;
        }
        return *this;
    }
    ~Simulation() { gsph_destroy(sim_); }

    std::size_t dim() const { std::size_t d = 0; check(gsph_dim(sim_, &d), "gsph_dim"); return d; }
    std::size_t size() const { std::size_t n = 0; check(gsph_count(sim_, &n), "gsph_count"); return n; }
    double time() const { double t = 0; check(gsph_time(sim_, &t, nullptr), "gsph_time"); return t; }
    std::uint64_t steps() const { std::uint64_t s = 0; check(gsph_time(sim_, nullptr, &s), "gsph_time"); return s; }
    double stable_dt() { double dt = 0; check(gsph_stable_dt(sim_, &dt), "gsph_stable_dt"); return dt; }
    /// The scene's t_end, s.
    double t_end() const { double t = 0; check(gsph_schedule(sim_, &t, nullptr), "gsph_schedule"); return t; }
    /// The scene's snapshot count (the times t_end k / snapshots that run() lands on).
    std::size_t snapshots() const { std::size_t n = 0; check(gsph_schedule(sim_, nullptr, &n), "gsph_schedule"); return n; }

    /// One step of `dt` (0: the scene's rule); returns the step taken.
    double step(double dt = 0.0) { double taken = 0; check(gsph_step(sim_, dt, &taken), "gsph_step"); return taken; }
    /// Steps to time `t`; returns the steps taken.
    std::uint64_t advance(double t) { std::uint64_t n = 0; check(gsph_advance(sim_, t, &n), "gsph_advance"); return n; }
    /// Runs to t_end as `gsph run` does; returns the steps taken.
    std::uint64_t run() { std::uint64_t n = 0; check(gsph_run(sim_, &n), "gsph_run"); return n; }

    /// Values per particle of the field `name`.
    std::size_t components(const std::string &name) const {
        std::size_t c = 0;
        check(gsph_field_components(sim_, name.c_str(), &c), "gsph_field_components");
        return c;
    }
    /// The field `name`, components per particle, in particle-id order.
    std::vector<double> field(const std::string &name) const {
        std::vector<double> out(size() * components(name));
        check(gsph_read_field(sim_, name.c_str(), out.data(), out.size()), "gsph_read_field");
        return out;
    }
    void set_field(const std::string &name, const std::vector<double> &data) {
        check(gsph_write_field(sim_, name.c_str(), data.data(), data.size()), "gsph_write_field");
    }
    /// Particle ids, in the order of every field.
    std::vector<std::uint32_t> ids() const {
        std::vector<std::uint32_t> out(size());
        check(gsph_read_ids(sim_, out.data(), out.size()), "gsph_read_ids");
        return out;
    }
    /// External accelerations (count x dim, id order); empty removes them.
    void set_acceleration(const std::vector<double> &a) {
        check(gsph_set_acceleration(sim_, a.data(), a.size()), "gsph_set_acceleration");
    }
    /// (kinetic, internal) energy, J.
    std::pair<double, double> energy() const {
        double k = 0, i = 0;
        check(gsph_energy(sim_, &k, &i), "gsph_energy");
        return {k, i};
    }
    /// Total momentum (3 components, unused ones 0).
    std::array<double, 3> momentum() const {
        std::array<double, 3> p{};
        check(gsph_momentum(sim_, p.data(), nullptr), "gsph_momentum");
        return p;
    }
    /// Momentum the external accelerations have added so far.
    std::array<double, 3> external_impulse() const {
        std::array<double, 3> p{}, ext{};
        check(gsph_momentum(sim_, p.data(), ext.data()), "gsph_momentum");
        return ext;
    }
    std::string summary_json() const {
        return text([this](char *b, std::size_t n, std::size_t *need) { return gsph_summary_json(sim_, b, n, need); },
                    "gsph_summary_json");
    }

    /// The series' column names (series.csv's header).
    std::vector<std::string> series_names() const {
        std::string all = text([this](char *b, std::size_t n, std::size_t *need) { return gsph_series_names(sim_, b, n, need); },
                               "gsph_series_names");
        std::vector<std::string> names;
        std::size_t start = 0;
        for (std::size_t k = 0; k <= all.size(); k++) {
            if (k == all.size() || all[k] == ',') {
                names.push_back(all.substr(start, k - start));
                start = k + 1;
            }
        }
        return names;
    }
    /// (rows, columns) of the series.
    std::pair<std::size_t, std::size_t> series_shape() const {
        std::size_t r = 0, c = 0;
        check(gsph_series_shape(sim_, &r, &c), "gsph_series_shape");
        return {r, c};
    }
    /// The series, row after row (series_shape() values).
    std::vector<double> series() const {
        auto shape = series_shape();
        std::vector<double> out(shape.first * shape.second);
        check(gsph_read_series(sim_, out.data(), out.size()), "gsph_read_series");
        return out;
    }
    void write_series(const std::string &path) const { check(gsph_write_series(sim_, path.c_str()), "gsph_write_series"); }

    /// A CSV with the columns of final.csv.
    void write_snapshot(const std::string &path) const { check(gsph_write_snapshot(sim_, path.c_str()), "gsph_write_snapshot"); }
    /// dir/snapshots.h5 + dir/snapshots.xdmf holding the state now.
    void write_snapshots(const std::string &dir) const { check(gsph_write_snapshots(sim_, dir.c_str()), "gsph_write_snapshots"); }
    /// Starts the snapshot pair in dir (run() adds one per snapshot time).
    void open_snapshots(const std::string &dir) { check(gsph_open_snapshots(sim_, dir.c_str()), "gsph_open_snapshots"); }
    void append_snapshot() { check(gsph_append_snapshot(sim_), "gsph_append_snapshot"); }
    void close_snapshots() { check(gsph_close_snapshots(sim_), "gsph_close_snapshots"); }
    void write_checkpoint(const std::string &dir) const { check(gsph_write_checkpoint(sim_, dir.c_str()), "gsph_write_checkpoint"); }

    gsph_sim *raw() const noexcept { return sim_; }

  private:
    explicit Simulation(gsph_sim *s) noexcept : sim_(s) {}

    /// `KEY=VALUE` overrides then `unset:KEY` removals, as C strings kept alive.
    struct Strings {
        std::vector<std::string> all;
        std::vector<const char *> ptrs;
        Strings(const std::vector<std::string> &set, const std::vector<std::string> &unset) : all(set) {
            for (const auto &k : unset) all.push_back("unset:" + k);
            for (const auto &s : all) ptrs.push_back(s.c_str());
        }
        const char *const *data() const { return ptrs.empty() ? nullptr : ptrs.data(); }
        std::size_t size() const { return ptrs.size(); }
    };

    /// A text of the C ABI's two-call pattern (ask the size, then fill).
    template <class F> static std::string text(F call, const char *name) {
        std::size_t need = 0;
        call(nullptr, 0, &need);
        std::string s(need, '\0');
        check(call(s.data(), s.size(), &need), name);
        s.resize(need - 1);
        return s;
    }

    gsph_sim *sim_ = nullptr;
};

}  // namespace gsph
