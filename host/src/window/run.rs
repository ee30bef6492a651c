//! `gsph hugoniot` as a library call: the Hugoniot points of a window scene with their
//! tables (and plots with the feature `plot`) written as they finish.

use std::path::Path;

/// The Hugoniot points of a window scene, written into `out` (the tables;
/// the plots only with the feature `plot`).
pub fn run_hugoniot(
    scene: &crate::scene::Scene,
    opts: &crate::window::hugoniot::HugoniotOptions,
    out: &Path,
) -> Result<Vec<crate::window::hugoniot::HugoniotPoint>, String> {
    use crate::window::hugoniot::{hugoniot, seed_fit, to_csv};
    use crate::window::plot::{write_outputs, write_point};
    // each point's profiles are written as it finishes, and the rows finished so far go
    // into hugoniot.partial.csv (a run of hours that is stopped keeps its points under a
    // name that does not pass for the whole table); hugoniot.csv and the plot when all
    // points are done, and the partial table is then removed
    // refused before any computation: an --out that is a file, or a folder another
    // process writes
    let _lock = crate::outdir::OutLock::acquire_for(out, &crate::window::plot::files(opts))?;
    let partial = out.join("hugoniot.partial.csv");
    let mut rows = String::new();
    #[cfg(not(feature = "plot"))]
    eprintln!("hugoniot: plots left out: {}", crate::NO_PLOT);
    let points = hugoniot(scene, opts, |p| {
        write_point(out, p)?;
        let one = to_csv(std::slice::from_ref(p));
        match (rows.is_empty(), one.split_once('\n')) {
            (false, Some((_, row))) => rows.push_str(row),
            _ => rows.push_str(&one),
        }
        crate::output::write_atomic(&partial, rows.as_bytes())
            .map_err(|e| format!("{}: {e}", partial.display()))
    })?;
    write_outputs(out, &points)?;
    match std::fs::remove_file(&partial) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            return Err(format!("{}: {e}", partial.display()));
        }
        _ => {}
    }
    println!(
        "   u_p     u_s    fit    diff  bulk -sxx behind  precursor  u_prec  mass/RH  mom/RH  pores behind   wall"
    );
    for p in &points {
        let fit = seed_fit(p.up);
        println!(
            "{:6.1} {:7.1} {:6.1} {:+6.1}%  {:12.3} GPa  {:5.3} GPa {:5.1}   {:6.3}   {:6.3}  {:12.4} {:5.0} s",
            p.up,
            p.us,
            fit,
            100.0 * (p.us - fit) / fit,
            p.stress_behind * 1e-9,
            p.stress_precursor * 1e-9,
            p.precursor_velocity,
            p.mass_jump_ratio(),
            p.momentum_jump_ratio(),
            p.pores_behind,
            p.wall_s
        );
    }
    Ok(points)
}
