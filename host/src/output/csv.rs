//! CSV export of a [`ParticleTable`] (`final.csv`) and the matching reader.
//!
//! The header is [`COLUMNS`] followed by [`DERIVED_COLUMNS`] (the Cauchy stress
//! `sigma_xx` .. `sigma_yz` = `-p I + S` and `von_mises`), joined by commas; ids and materials are
//! integers; floats are printed in shortest round-trip scientific notation (`{:e}`), so reading
//! the file back gives the same bits. The file has exactly one header line and no unit row (CSV
//! readers would take one for data): the unit and meaning of every column are in
//! [`quantities`](super::meta::quantities) and docs/output.md. New columns are only ever appended,
//! so readers that look columns up by name (or by position from the left) keep working.

use core::fmt::Write as _;
use std::io::{self, Write};
use std::path::Path;

use super::atomic::AtomicFile;
use super::meta::{derived_row, DERIVED_COLUMNS};
use super::safe::excerpt;
use super::table::{ParticleRow, ParticleTable, BASE_COLUMNS, COLUMNS, NUM_FLOAT_COLUMNS};

/// The CSV header line (without newline): [`COLUMNS`], then [`DERIVED_COLUMNS`].
pub fn csv_header() -> String {
    let all: Vec<&str> = COLUMNS.iter().chain(&DERIVED_COLUMNS).copied().collect();
    all.join(",")
}

/// The float columns a `final.csv` holds (its first `k` of [`COLUMNS`], at least
/// [`BASE_COLUMNS`]: columns are only ever appended, so a file of an earlier gsph has a
/// prefix of them) and whether the derived columns follow (files written before they were
/// added have none); `None` for any other header.
fn header_layout(header: &str) -> Option<(usize, bool)> {
    (BASE_COLUMNS..=COLUMNS.len()).rev().find_map(|k| {
        let base = COLUMNS[..k].join(",");
        let with = format!("{base},{}", DERIVED_COLUMNS.join(","));
        if header == with {
            Some((k, true))
        } else if header == base {
            Some((k, false))
        } else {
            None
        }
    })
}

/// Writes `table` as CSV to `path`, atomically (temp file, fsync, rename).
pub fn write_csv(path: impl AsRef<Path>, table: &ParticleTable) -> io::Result<()> {
    let mut f = AtomicFile::create(path)?;
    writeln!(f, "{}", csv_header())?;
    let mut line = String::with_capacity(512);
    for (i, row) in table.rows().enumerate() {
        line.clear();
        // Writing into a String cannot fail.
        let _ = write!(line, "{},{}", row.id, row.material);
        for v in row.floats().into_iter().chain(derived_row(table, i)) {
            let _ = write!(line, ",{v:e}");
        }
        line.push('\n');
        f.write_all(line.as_bytes())?;
    }
    f.commit()
}

/// Reads a CSV written by [`write_csv`] (or by an earlier gsph, whose header is [`COLUMNS`]
/// alone); the derived columns are checked to be numbers and otherwise ignored.
///
/// Errors name the path and line, in one line.
pub fn read_csv(path: impl AsRef<Path>) -> Result<ParticleTable, String> {
    let path = path.as_ref();
    let at = |e: String| format!("{}: {e}", path.display());
    // a regular file, streamed line by line (a line at most MAX_LINE bytes: a file
    // without line breaks is refused after that much, not read whole)
    super::safe::regular_file(path).map_err(at)?;
    let file = std::fs::File::open(path).map_err(|e| at(format!("cannot read: {e}")))?;
    parse_lines(super::safe::lines(std::io::BufReader::new(file))).map_err(at)
}

/// Parses CSV text in the [`write_csv`] format.
pub fn parse_csv(text: &str) -> Result<ParticleTable, String> {
    parse_lines(text.lines().map(|l| Ok(l.to_string())))
}

/// [`parse_csv`] of lines given one by one (`Err`: a line could not be read).
fn parse_lines(
    lines: impl Iterator<Item = Result<String, String>>,
) -> Result<ParticleTable, String> {
    let mut lines = lines.enumerate();
    let header = match lines.next() {
        Some((_, l)) => l?,
        None => String::new(),
    };
    let header = header.trim_end();
    let Some((columns, derived)) = header_layout(header) else {
        return Err(format!("line 1: header is not `{}`", csv_header()));
    };
    let derived = if derived { DERIVED_COLUMNS.len() } else { 0 };
    let mut table = ParticleTable::default();
    for (i, line) in lines {
        let line = line?;
        let line = line.trim_end();
        if line.is_empty() {
            continue;
        }
        let lineno = i + 1;
        let mut fields = line.split(',');
        let mut next = |name: &str| {
            fields
                .next()
                .map(str::trim)
                .ok_or_else(|| format!("line {lineno}: missing column `{name}`"))
        };
        let parse_u32 = |name: &str, s: &str| {
            s.parse::<u32>()
                .map_err(|e| format!("line {lineno}: column `{name}`: `{}`: {e}", excerpt(s)))
        };
        let id = parse_u32("id", next("id")?)?;
        let material = parse_u32("material", next("material")?)?;
        // a column the file predates reads as NaN
        let mut floats = [f64::NAN; NUM_FLOAT_COLUMNS];
        for (v, name) in floats.iter_mut().zip(&COLUMNS[2..columns]) {
            let s = next(name)?;
            *v = s
                .parse::<f64>()
                .map_err(|e| format!("line {lineno}: column `{name}`: `{}`: {e}", excerpt(s)))?;
        }
        for name in &DERIVED_COLUMNS[..derived] {
            let s = next(name)?;
            s.parse::<f64>()
                .map_err(|e| format!("line {lineno}: column `{name}`: `{}`: {e}", excerpt(s)))?;
        }
        if fields.next().is_some() {
            return Err(format!(
                "line {lineno}: more than {} columns",
                columns + derived
            ));
        }
        table.push(&ParticleRow::from_parts(id, material, floats));
    }
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::super::table::tests::sample_table;
    use super::*;

    #[test]
    fn csv_round_trip_exact() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("final.csv");
        let mut t = sample_table(7, 0.3);
        t.x[0] = 0.1 + 0.2; // not representable in short decimal
        t.p[1] = -1.234_567_890_123_456_7e-300;
        t.e[2] = f64::MAX;
        t.h[3] = f64::MIN_POSITIVE;
        t.vz[4] = -0.0;
        write_csv(&p, &t).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        let header = text.lines().next().unwrap();
        assert_eq!(header, csv_header());
        // columns are only ever appended; the stress columns come last
        assert!(header.starts_with(
            "id,material,x,y,z,vx,vy,vz,m,rho,p,e,sxx,syy,szz,sxy,sxz,syz,eps_p,damage,temperature,h,"
        ));
        assert!(
            header.ends_with(",sigma_xx,sigma_yy,sigma_zz,sigma_xy,sigma_xz,sigma_yz,von_mises")
        );
        assert_eq!(text.lines().count(), 8);
        let back = read_csv(&p).unwrap();
        assert_eq!(back, t);
        for (a, b) in back.float_columns().iter().zip(t.float_columns()) {
            let bits = |v: &Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(a), bits(b));
        }
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "no temp file left");
    }

    #[test]
    fn derived_columns_are_the_cauchy_stress_and_von_mises() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("final.csv");
        let t = sample_table(5, 0.7);
        write_csv(&p, &t).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
        for (i, line) in lines.enumerate() {
            let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
            assert_eq!(v.len(), header.len());
            assert_eq!(v[col("sigma_xx")], t.sxx[i] - t.p[i]);
            assert_eq!(v[col("sigma_yy")], t.syy[i] - t.p[i]);
            assert_eq!(v[col("sigma_zz")], t.szz[i] - t.p[i]);
            assert_eq!(v[col("sigma_xy")], t.sxy[i]);
            assert_eq!(v[col("sigma_xz")], t.sxz[i]);
            assert_eq!(v[col("sigma_yz")], t.syz[i]);
            let ss = t.sxx[i].powi(2)
                + t.syy[i].powi(2)
                + t.szz[i].powi(2)
                + 2.0 * (t.sxy[i].powi(2) + t.sxz[i].powi(2) + t.syz[i].powi(2));
            let vm = v[col("von_mises")];
            assert!((vm - (1.5 * ss).sqrt()).abs() <= 1e-15 * vm, "{vm}");
        }
    }

    #[test]
    fn files_without_derived_columns_still_read() {
        let t = sample_table(3, 0.2);
        let mut text = format!("{}\n", COLUMNS.join(","));
        for r in t.rows() {
            let f: Vec<String> = r.floats().iter().map(|v| format!("{v:e}")).collect();
            text.push_str(&format!("{},{},{}\n", r.id, r.material, f.join(",")));
        }
        assert_eq!(parse_csv(&text).unwrap(), t);
    }

    #[test]
    fn files_of_an_earlier_column_set_read_with_nan_in_the_later_columns() {
        let t = sample_table(2, 0.7);
        let k = BASE_COLUMNS;
        let mut text = format!("{},{}\n", COLUMNS[..k].join(","), DERIVED_COLUMNS.join(","));
        for (i, r) in t.rows().enumerate() {
            let f: Vec<String> = r.floats()[..k - 2]
                .iter()
                .map(|v| format!("{v:e}"))
                .collect();
            let d: Vec<String> = derived_row(&t, i)
                .iter()
                .map(|v| format!("{v:e}"))
                .collect();
            text.push_str(&format!(
                "{},{},{},{}\n",
                r.id,
                r.material,
                f.join(","),
                d.join(",")
            ));
        }
        let back = parse_csv(&text).unwrap();
        for (c, (a, b)) in back
            .float_columns()
            .iter()
            .zip(t.float_columns())
            .enumerate()
        {
            if c + 2 < k {
                assert_eq!(*a, b);
            } else {
                assert!(a.iter().all(|v| v.is_nan()), "column {}", COLUMNS[c + 2]);
            }
        }
        let short = COLUMNS[..k - 1].join(",");
        assert!(parse_csv(&format!("{short}\n"))
            .unwrap_err()
            .contains("header"));
    }

    #[test]
    fn empty_table_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("final.csv");
        write_csv(&p, &ParticleTable::default()).unwrap();
        assert_eq!(read_csv(&p).unwrap().len(), 0);
    }

    #[test]
    fn bad_input_is_rejected() {
        assert!(parse_csv("id,x\n1,2\n").unwrap_err().contains("header"));
        let h = csv_header();
        let e = parse_csv(&format!("{h}\n1,0,1.0\n")).unwrap_err();
        assert!(e.contains("line 2") && e.contains("missing"), "{e}");
        let width = COLUMNS.len() + DERIVED_COLUMNS.len();
        let row: Vec<String> = (0..width).map(|k| k.to_string()).collect();
        let e = parse_csv(&format!("{h}\n{},9\n", row.join(","))).unwrap_err();
        assert!(e.contains(&format!("more than {width}")), "{e}");
        let e = parse_csv(&format!("{h}\n-1,{}\n", row[1..].join(","))).unwrap_err();
        assert!(e.contains("`id`"), "{e}");
        let e = parse_csv(&format!("{h}\n{}\n", row[..width - 1].join(","))).unwrap_err();
        assert!(e.contains("`von_mises`"), "{e}");
        let legacy = COLUMNS.join(",");
        let n = COLUMNS.len();
        let e = parse_csv(&format!("{legacy}\n{},9\n", row[..n].join(","))).unwrap_err();
        assert!(e.contains(&format!("more than {n}")), "{e}");
        assert!(read_csv("/nonexistent/final.csv").is_err());
    }
}
