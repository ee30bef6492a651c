// gsph C++ wrapper: RAII ownership of a simulation and exceptions for errors, over the
// C ABI of gsph.h. Header-only; link with -lgsph. See docs/embedding.md.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
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

/// A simulation; destroyed with the object. Movable, not copyable. Not for use by two
/// threads at once.
class Simulation {
  public:
    /// Loads a scene file with overrides `KEY=VALUE`.
    explicit Simulation(const std::string &scene, const std::vector<std::string> &overrides = {}) {
        std::vector<const char *> set;
        for (const auto &o : overrides) set.push_back(o.c_str());
        check(gsph_create_from_file(scene.c_str(), set.data(), set.size(), &sim_), "gsph_create_from_file");
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

    /// One step of `dt` (0: the scene's rule); returns the step taken.
    double step(double dt = 0.0) { double taken = 0; check(gsph_step(sim_, dt, &taken), "gsph_step"); return taken; }
    /// Steps to time `t`; returns the steps taken.
    std::uint64_t advance(double t) { std::uint64_t n = 0; check(gsph_advance(sim_, t, &n), "gsph_advance"); return n; }
    /// Runs to t_end as `gsph run` does; returns the steps taken.
    std::uint64_t run() { std::uint64_t n = 0; check(gsph_run(sim_, &n), "gsph_run"); return n; }

    /// The field `name`, components per particle, in particle-id order.
    std::vector<double> field(const std::string &name) const {
        std::size_t c = 0;
        check(gsph_field_components(sim_, name.c_str(), &c), "gsph_field_components");
        std::vector<double> out(size() * c);
        check(gsph_read_field(sim_, name.c_str(), out.data(), out.size()), "gsph_read_field");
        return out;
    }
    void set_field(const std::string &name, const std::vector<double> &data) {
        check(gsph_write_field(sim_, name.c_str(), data.data(), data.size()), "gsph_write_field");
    }
    void set_acceleration(const std::vector<double> &a) {
        check(gsph_set_acceleration(sim_, a.data(), a.size()), "gsph_set_acceleration");
    }
    std::string summary_json() const {
        std::size_t need = 0;
        gsph_summary_json(sim_, nullptr, 0, &need);
        std::string s(need, '\0');
        check(gsph_summary_json(sim_, s.data(), s.size(), &need), "gsph_summary_json");
        s.resize(need - 1);
        return s;
    }
    gsph_sim *raw() const noexcept { return sim_; }

  private:
    gsph_sim *sim_ = nullptr;
};

}  // namespace gsph
