//! Memory a run will need, estimated before anything large is allocated, against the
//! memory this machine has available: a scene that cannot fit is refused with both
//! figures instead of being killed by the allocator (SIGABRT) minutes later.

use gsph_core::kernel::Kernel;

/// Most particles a scene may have (all bodies together), and so any file of particles
/// it reads: beyond this a spacing or `resolution_scale` is almost surely wrong, and
/// building would exhaust memory.
pub const MAX_PARTICLES: usize = 100_000_000;

/// Bytes of memory available to this process: `MemAvailable` of /proc/meminfo, lowered
/// to the cgroup's limit (less its usage) where one is set. `None` where neither can be
/// read (no refusal is made then).
pub fn available() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok();
    let mem = meminfo.as_deref().and_then(|t| {
        t.lines()
            .find_map(|l| l.strip_prefix("MemAvailable:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    let cgroup = || -> Option<u64> {
        let max = std::fs::read_to_string("/sys/fs/cgroup/memory.max").ok()?;
        let max: u64 = max.trim().parse().ok()?; // "max": no limit
        let used: u64 = std::fs::read_to_string("/sys/fs/cgroup/memory.current")
            .ok()?
            .trim()
            .parse()
            .ok()?;
        Some(max.saturating_sub(used))
    };
    match (mem, cgroup()) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Bytes per particle of a run, an upper estimate: 1 KiB for the particles as built, the
/// state, the workspace and the output tables, and 24 bytes per neighbour within the
/// default capacity of the kernel (list entries each way and the per-pair buffers).
/// Calibrated on the peak resident memory of the bundled scenes (2026-12-02, two steps,
/// ts2): the 3D impact 3.8 kB per particle (estimate 6.1 kB), the 2D impact 1.5 kB
/// (estimate 2.2 kB): about 1.5 times the measured need, room for a denser
/// neighbourhood under compression.
pub fn bytes_per_particle(dim: usize, kernel: Kernel, h_factor: f64) -> f64 {
    let neighbours = crate::neighbors::default_capacity(dim, kernel, h_factor) as f64;
    1024.0 + LIST_BYTES_PER_ENTRY * neighbours
}

/// Bytes of one neighbour-list entry with its share of the per-pair buffers.
pub const LIST_BYTES_PER_ENTRY: f64 = 24.0;

/// Refuses neighbour lists of `particles` × `capacity` entries (the lists hold `capacity`
/// per particle whatever the neighbourhood) when they exceed what is available
/// (`available`, bytes): named `neighbor_capacity`, the key that sets their size.
pub fn check_lists_fit(
    particles: usize,
    capacity: usize,
    available: Option<u64>,
) -> Result<(), String> {
    let Some(avail) = available else {
        return Ok(());
    };
    let need = particles as f64 * capacity as f64 * LIST_BYTES_PER_ENTRY;
    if need > avail as f64 {
        return Err(format!(
            "neighbor_capacity: {particles} particles x {capacity} neighbours need about {} of neighbour lists, more than the {} available on this machine",
            gib(need),
            gib(avail as f64)
        ));
    }
    Ok(())
}

fn gib(b: f64) -> String {
    format!("{:.1} GiB", b / (1u64 << 30) as f64)
}

/// Refuses `particles` particles of `each` bytes (see [`bytes_per_particle`]) when their
/// estimated memory exceeds what is available (`available`, bytes). `key` names what sets
/// the count.
pub fn check_fits(
    each: f64,
    particles: f64,
    available: Option<u64>,
    key: &str,
) -> Result<(), String> {
    let Some(avail) = available else {
        return Ok(());
    };
    let need = particles * each;
    if need > avail as f64 {
        return Err(format!(
            "{key}: about {particles:.3e} particles need about {} of memory ({:.0} bytes each), more than the {} available on this machine; use a coarser spacing or a smaller resolution_scale (or more MPI ranks on more machines)",
            gib(need),
            each,
            gib(avail as f64)
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn this_machine_reports_available_memory() {
        let a = available().expect("Linux has /proc/meminfo");
        assert!(a > 1 << 20, "{a}");
    }

    #[test]
    fn a_run_larger_than_memory_is_refused_with_both_figures() {
        let each = bytes_per_particle(1, Kernel::CubicSpline, 1.2);
        assert!(each > 1024.0 && each < 2048.0, "{each}");
        check_fits(each, 100.0, Some(1 << 30), "bodies[0].spacing").unwrap();
        let e = check_fits(each, 9e7, Some(1 << 30), "bodies[0].spacing").unwrap_err();
        assert!(
            e.starts_with("bodies[0].spacing: about 9.000e7 particles need about ")
                && e.contains("more than the 1.0 GiB available"),
            "{e}"
        );
        check_fits(each, 9e7, None, "k").unwrap();
        check_lists_fit(20_000, 20_000, Some(24 << 30)).unwrap();
        let e = check_lists_fit(20_000, 20_000, Some(1 << 30)).unwrap_err();
        assert!(
            e.starts_with(
                "neighbor_capacity: 20000 particles x 20000 neighbours need about 8.9 GiB"
            ),
            "{e}"
        );
    }
}
