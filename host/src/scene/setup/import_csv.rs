//! The CSV particle files of [`super`]: the header's columns, the rows read with the
//! `csv` crate, and the row count taken before reading (for the memory estimate).

use super::*;
use crate::output::safe::{excerpt, shorten_list, MAX_LINE};

/// Data lines of a CSV file (lines that are neither blank nor comments, less the header),
/// counted without keeping them, in bounded memory: a line longer than [`MAX_LINE`] bytes
/// (a file with no line breaks, or not a CSV file) or more rows than a scene may have
/// particles (`limit`, the scene's `max_particles`) is refused as soon as it is seen.
pub(super) fn count_rows(path: &Path, limit: usize) -> Result<usize, String> {
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read: {e}"))?;
    let mut r = BufReader::with_capacity(1 << 16, file);
    let (mut lines, mut lineno, mut len) = (0usize, 1usize, 0usize);
    // the first byte of the line that is not white space (blank lines and `#` comments
    // are not rows)
    let mut first: Option<u8> = None;
    let too_many = || {
        format!(
            "more than {:.0e} particle rows, the scene's particle limit (`max_particles` raises it)",
            limit as f64
        )
    };
    loop {
        let buf = r
            .fill_buf()
            .map_err(|e| format!("line {lineno}: cannot read: {e}"))?;
        if buf.is_empty() {
            break;
        }
        let used = buf.len();
        for &b in buf {
            if b == b'\n' {
                if first.is_some_and(|c| c != b'#') {
                    lines += 1;
                    if lines > limit.saturating_add(1) {
                        return Err(too_many());
                    }
                }
                lineno += 1;
                len = 0;
                first = None;
            } else {
                len += 1;
                if len > MAX_LINE {
                    return Err(format!(
                        "line {lineno}: longer than {MAX_LINE} bytes (a particle file's row is at most {} numbers; is this a CSV file?)",
                        STATE_COLUMNS.len() + 1 + ignored_columns().len()
                    ));
                }
                if first.is_none() && !b.is_ascii_whitespace() {
                    first = Some(b);
                }
            }
        }
        r.consume(used);
    }
    if first.is_some_and(|c| c != b'#') {
        lines += 1;
    }
    let rows = lines.saturating_sub(1);
    if rows > limit {
        return Err(too_many());
    }
    Ok(rows)
}

/// What a column of a CSV header is.
#[derive(Clone, Copy, PartialEq)]
enum Slot {
    State(usize),
    Material,
    Ignored,
}

/// The header of a CSV particle file: the slot of each field.
fn parse_header(line: &str, lineno: usize, dim: usize) -> Result<Vec<Slot>, String> {
    let mut slots = Vec::new();
    let mut seen: Vec<&str> = Vec::new();
    let ignored = ignored_columns();
    for (k, raw) in line.split(',').enumerate() {
        let name = raw.trim().trim_matches('"').trim();
        let at = format!("line {lineno}, column {}", k + 1);
        if name.is_empty() {
            return Err(format!("{at}: empty column name"));
        }
        let slot = if let Some(c) = STATE_COLUMNS.iter().position(|&s| s == name) {
            Slot::State(c)
        } else if name == "material" {
            Slot::Material
        } else if ignored.contains(&name) {
            Slot::Ignored
        } else {
            // nothing of a file that is not a particle table is quoted (a file named by
            // mistake, or on purpose, never leaks through the message)
            return Err(format!(
                "{at}: not a column name gsph knows (known: {}, material; skipped: {})",
                STATE_COLUMNS.join(", "),
                ignored.join(", ")
            ));
        };
        // a known name, so quoting it quotes nothing of the file
        if seen.contains(&name) {
            return Err(format!("{at}: column `{name}` appears twice"));
        }
        seen.push(name);
        slots.push(slot);
    }
    let has = |c: usize| slots.contains(&Slot::State(c));
    for (a, axis) in ["x", "y", "z"].iter().enumerate().take(dim) {
        if !has(X + a) {
            return Err(format!(
                "line {lineno}: no column `{axis}` (a {dim}D scene needs {}; the header names {})",
                ["x", "y", "z"][..dim].join(", "),
                shorten_list(&seen)
            ));
        }
    }
    let dev: Vec<usize> = (S..S + 6).filter(|&c| has(c)).collect();
    if !dev.is_empty() && dev.len() < 6 {
        let missing: Vec<&str> = (S..S + 6)
            .filter(|c| !dev.contains(c))
            .map(|c| STATE_COLUMNS[c])
            .collect();
        return Err(format!(
            "line {lineno}: the deviator columns sxx, syy, szz, sxy, sxz, syz come all six or none (the deviator is the full symmetric tensor in every dimension); missing {}",
            missing.join(", ")
        ));
    }
    Ok(slots)
}

/// Parses a CSV particle file (see the module docs) with the `csv` crate: fields may be
/// quoted, lines end in LF or CRLF, `#` starts a comment line, a UTF-8 byte-order mark is
/// skipped; errors name the line.
pub(super) fn parse_csv(
    path: &Path,
    shown: &str,
    dim: usize,
    counted: usize,
) -> Result<FileParticles, String> {
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read: {e}"))?;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(BufReader::new(file));
    let mut slots: Option<(u64, Vec<Slot>)> = None;
    let mut cols: [Option<Vec<f64>>; STATE_COLUMNS.len()] = Default::default();
    let mut material: Option<Vec<u32>> = None;
    let mut lines = Vec::new();
    let mut record = csv::StringRecord::new();
    loop {
        let at = reader.position().line();
        match reader.read_record(&mut record) {
            Ok(false) => break,
            Ok(true) => {}
            Err(e) => {
                let lineno = e.position().map_or(at, |p| p.line());
                return Err(match e.kind() {
                    csv::ErrorKind::Utf8 { .. } => {
                        format!("line {lineno}: not UTF-8 text (is this a CSV file?)")
                    }
                    _ => format!("line {lineno}: {e}"),
                });
            }
        }
        let lineno = record.position().map_or(at, |p| p.line());
        if record.iter().all(str::is_empty) {
            continue; // a blank line (or one of blank fields)
        }
        let Some((header_line, slots)) = &slots else {
            // a byte-order mark (spreadsheets write one) is not part of the first name
            let fields: Vec<&str> = record.iter().collect();
            let first = fields.join(",");
            let s = parse_header(first.trim_start_matches('\u{feff}'), lineno as usize, dim)?;
            for slot in &s {
                match slot {
                    Slot::State(c) => cols[*c] = Some(Vec::new()),
                    Slot::Material => material = Some(Vec::new()),
                    Slot::Ignored => {}
                }
            }
            slots = Some((lineno, s));
            continue;
        };
        if record.len() != slots.len() {
            return Err(format!(
                "line {lineno}: {} field{}, but the header (line {header_line}) names {} columns",
                record.len(),
                if record.len() == 1 { "" } else { "s" },
                slots.len()
            ));
        }
        push_row(&record, slots, lineno, &mut cols, &mut material)?;
        lines.push(lineno as usize);
        if lines.len() > counted {
            return Err(format!(
                "more rows than the {counted} counted before reading (was the file written to meanwhile?)"
            ));
        }
    }
    if slots.is_none() {
        return Err("no header line (an empty file?)".into());
    }
    if lines.is_empty() {
        return Err("no particle rows after the header".into());
    }
    Ok(FileParticles {
        shown: shown.to_string(),
        cols,
        material,
        rows: Rows::Lines(lines),
    })
}

/// Appends the numbers of one row (`record`, at line `lineno`) to the columns its header's
/// `slots` name.
fn push_row(
    record: &csv::StringRecord,
    slots: &[Slot],
    lineno: u64,
    cols: &mut [Option<Vec<f64>>; STATE_COLUMNS.len()],
    material: &mut Option<Vec<u32>>,
) -> Result<(), String> {
    for (field, slot) in record.iter().zip(slots) {
        let name = |s: &Slot| match s {
            Slot::State(c) => STATE_COLUMNS[*c],
            _ => "material",
        };
        let number = || {
            field.parse::<f64>().map_err(|_| {
                format!(
                    "line {lineno}, column `{}`: `{}` is not a number",
                    name(slot),
                    excerpt(field)
                )
            })
        };
        match slot {
            Slot::State(c) => cols[*c].as_mut().expect("column kept").push(number()?),
            Slot::Material => {
                let v = number()?;
                if !(v >= 0.0 && v <= u32::MAX as f64 && v.fract() == 0.0) {
                    return Err(format!(
                        "line {lineno}, column `material`: `{}` is not a material index (0, 1, ...)",
                        excerpt(field)
                    ));
                }
                material.as_mut().expect("column kept").push(v as u32);
            }
            Slot::Ignored => {}
        }
    }
    Ok(())
}
