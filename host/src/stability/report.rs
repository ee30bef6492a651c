//! The stability table as CSV and Markdown.

use super::{energy_bound, Row, Verdict, MOMENTUM_BOUND};
use gsph_core::schemes::Scheme;
use std::fmt::Write as _;

/// A number for the CSV (empty where NaN).
fn csv_num(v: f64) -> String {
    if v.is_nan() {
        String::new()
    } else {
        format!("{v:e}")
    }
}

/// Quotes a CSV field.
fn csv_text(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\""))
}

/// The table as CSV, one row per run.
pub fn to_csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "case,scheme,particles,steps,t,t_end,reached_t_end,nan,density_min,energy_rel_error,momentum_rel_error,wall_s,result,note\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{:.4},{},{}",
            r.case,
            r.scheme,
            r.particles,
            r.steps,
            csv_num(r.t),
            csv_num(r.t_end),
            r.reached,
            r.nan,
            csv_num(r.rho_min),
            csv_num(r.energy_error),
            csv_num(r.momentum_error),
            r.wall_s,
            r.verdict.label(),
            csv_text(&r.note)
        );
    }
    s
}

fn md_num(v: f64, prec: usize) -> String {
    if v.is_nan() {
        "–".into()
    } else {
        format!("{v:.prec$e}")
    }
}

/// The table as Markdown, with the criteria and a count of the verdicts.
pub fn to_markdown(rows: &[Row], quick: bool, threads: usize) -> String {
    let count = |v: Verdict| rows.iter().filter(|r| r.verdict == v).count();
    let mut s = format!(
        "# gsph stability{}\n\n{} runs: {} PASS, {} FAIL, {} n/a. Wall time is the stepping loop on {threads} threads.\n\n\
         PASS: reached t_end, no NaN/Inf, density_min > 0, momentum error <= {MOMENTUM_BOUND:.0e}, \
         |energy error| <= the scheme's bound ({}).\n\n\
         | case | scheme | particles | steps | reached t_end | NaN/Inf | density_min | energy error | momentum error | wall s | result | note |\n\
         | --- | --- | ---: | ---: | --- | --- | ---: | ---: | ---: | ---: | --- | --- |\n",
        if quick { " --quick" } else { "" },
        rows.len(),
        count(Verdict::Pass),
        count(Verdict::Fail),
        count(Verdict::NotApplicable),
        Scheme::ALL
            .iter()
            .map(|&sc| format!("{} {:.0e}", sc.name(), energy_bound(sc)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2} | {} | {} |",
            r.case,
            r.scheme,
            r.particles,
            r.steps,
            if r.reached { "yes" } else { "no" },
            if r.nan { "yes" } else { "no" },
            if r.rho_min.is_nan() {
                "–".to_string()
            } else {
                format!("{:.0}", r.rho_min)
            },
            md_num(r.energy_error, 2),
            md_num(r.momentum_error, 1),
            r.wall_s,
            r.verdict.label(),
            r.note.replace('|', "\\|")
        );
    }
    s
}
