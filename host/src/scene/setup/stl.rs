//! Closed STL surfaces filled with a lattice (shape `stl`; the method is described in
//! [`super::import`]'s module docs, "STL surfaces").
//!
//! The file is streamed, never read whole: a binary file facet by facet (its header's facet
//! count at most the scene's particle limit, `max_particles`: a surface of more facets
//! than the lattice filling it has sites describes detail the lattice cannot hold), an
//! ASCII file line by line (a line at most
//! [`MAX_LINE`] bytes, so a file without line breaks is refused after that much); what is
//! kept is 36 bytes a facet, less than the file holds for it.

use crate::output::safe::{check_file_name, regular_file, shorten_quotes, MAX_LINE};
use rayon::prelude::*;
use std::collections::HashMap;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

/// A closed triangulated surface, its vertices placed (`scale * vertex + offset`).
#[derive(Debug, Clone)]
pub(super) struct Mesh {
    /// The facets' corners, m.
    pub(super) tris: Vec<[[f64; 3]; 3]>,
    /// Bounding box, m.
    pub lo: [f64; 3],
    /// Bounding box, m.
    pub hi: [f64; 3],
}

/// How [`StlInput`] presents a file to `stl_io`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Ascii,
    Binary,
}

/// A file as `stl_io` reads it, streamed. Binary: the first byte reads as a line break,
/// so that `stl_io`'s probe (which reads the first line and takes a file starting with
/// `solid ` for ASCII) reads one byte and decides binary, also for a binary file whose
/// 80-byte header starts with `solid`, as some exporters write (the header is not data).
/// ASCII: a line longer than [`MAX_LINE`] bytes is an error naming it (else `stl_io`
/// would gather a file without line breaks into one string).
struct StlInput<R> {
    inner: R,
    format: Format,
    pos: u64,
    line: usize,
    run: usize,
}

impl<R: Read> Read for StlInput<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        match self.format {
            Format::Binary if self.pos == 0 && n > 0 => buf[0] = b'\n',
            Format::Binary => {}
            Format::Ascii => {
                for &b in &buf[..n] {
                    if b == b'\n' {
                        self.line += 1;
                        self.run = 0;
                    } else {
                        self.run += 1;
                        if self.run > MAX_LINE {
                            return Err(std::io::Error::new(
                                std::io::ErrorKind::InvalidData,
                                format!(
                                    "line {}: longer than {MAX_LINE} bytes (is this an STL file?)",
                                    self.line
                                ),
                            ));
                        }
                    }
                }
            }
        }
        self.pos += n as u64;
        Ok(n)
    }
}

impl<R: Seek> Seek for StlInput<R> {
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        let p = self.inner.seek(to)?;
        if p != self.pos {
            // stl_io seeks back to the start after its probe, nowhere else
            self.pos = p;
            self.line = 1;
            self.run = 0;
        }
        Ok(p)
    }
}

/// `(x, y, z)` of a vertex for messages.
fn point(v: &[f32; 3]) -> String {
    format!("({}, {}, {})", v[0], v[1], v[2])
}

/// A message of `stl_io` on one line, what it quotes of the file cut to an excerpt.
fn tidy(e: &std::io::Error) -> String {
    let one: Vec<String> = e.to_string().split_whitespace().map(String::from).collect();
    let s = shorten_quotes(&one.join(" "));
    if s.chars().count() > 200 {
        s.chars().take(200).collect::<String>() + "…"
    } else {
        s
    }
}

/// The format of an STL file of `len` bytes starting with `head` (as `stl_io` decides it,
/// a binary file whose header starts with `solid` recognised by its length, 84 + 50 × the
/// facet count in its header), and the facet count of a binary file.
fn format_of(head: &[u8], len: u64) -> (Format, u64) {
    let count = if head.len() >= 84 {
        u64::from(u32::from_le_bytes([head[80], head[81], head[82], head[83]]))
    } else {
        0
    };
    let binary_length = head.len() >= 84 && len == 84 + 50 * count;
    if head.starts_with(b"solid ") && !binary_length {
        (Format::Ascii, 0)
    } else {
        (Format::Binary, count)
    }
}

/// Reads and checks a closed STL surface (`key` is the shape's key) of at most
/// `max_facets` facets (the scene's particle limit).
pub(super) fn read_stl(
    key: &str,
    file: &str,
    scale: f64,
    offset: [f64; 3],
    max_facets: usize,
) -> Result<Mesh, String> {
    check_file_name(file).map_err(|e| format!("{key}.file: {e}"))?;
    let at = |msg: String| format!("{key}.file: {file}: {msg}");
    let path = Path::new(file);
    let len = regular_file(path).map_err(at)?;
    let open = || std::fs::File::open(path).map_err(|e| at(format!("cannot read: {e}")));
    let mut head = Vec::with_capacity(MAX_LINE + 1);
    open()?
        .take(MAX_LINE as u64 + 1)
        .read_to_end(&mut head)
        .map_err(|e| at(format!("cannot read: {e}")))?;
    let (format, count) = format_of(&head, len);
    if format == Format::Ascii && !head.contains(&b'\n') && head.len() > MAX_LINE {
        return Err(at(format!(
            "line 1: longer than {MAX_LINE} bytes (is this an STL file?)"
        )));
    }
    if count > max_facets as u64 {
        return Err(at(format!(
            "the header declares {count} facets, more than the limit {:.0e} (the scene's particle limit; `max_particles` raises it)",
            max_facets as f64
        )));
    }
    drop(head);
    let mut input = StlInput {
        inner: BufReader::new(open()?),
        format,
        pos: 0,
        line: 1,
        run: 0,
    };
    let reader = stl_io::create_stl_reader(&mut input)
        .map_err(|e| at(format!("not an STL file: {}", tidy(&e))))?;
    let mut raw: Vec<[[f32; 3]; 3]> = Vec::new();
    for (k, t) in reader.enumerate() {
        if k == max_facets {
            return Err(at(format!(
                "more than {:.0e} facets (the scene's particle limit; `max_particles` raises it)",
                max_facets as f64
            )));
        }
        let t = t.map_err(|e| {
            at(if e.kind() == std::io::ErrorKind::UnexpectedEof {
                format!("facet {k}: the file ends before the facet does")
            } else {
                format!("facet {k}: {}", tidy(&e))
            })
        })?;
        let v = t.vertices.map(|p| p.0);
        check_facet(k, &v).map_err(at)?;
        raw.push(v);
    }
    if raw.is_empty() {
        return Err(at("no facets".into()));
    }
    check_closed(&raw).map_err(at)?;
    let place = |v: &[f32; 3]| {
        let mut p = [0.0; 3];
        for a in 0..3 {
            p[a] = scale * f64::from(v[a]) + offset[a];
        }
        p
    };
    let tris: Vec<[[f64; 3]; 3]> = raw.iter().map(|t| t.each_ref().map(place)).collect();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in tris.iter().flatten() {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
    }
    Ok(Mesh { tris, lo, hi })
}

/// Facet `k`: finite corners, not of zero area (|e1 x e2| within the single-precision
/// round-off of the corners).
fn check_facet(k: usize, t: &[[f32; 3]; 3]) -> Result<(), String> {
    for (j, p) in t.iter().enumerate() {
        if p.iter().any(|c| !c.is_finite()) {
            return Err(format!("facet {k}: vertex {j} is not finite {}", point(p)));
        }
    }
    let p = t.map(|v| v.map(f64::from));
    let d = |a: usize, b: usize| [p[b][0] - p[a][0], p[b][1] - p[a][1], p[b][2] - p[a][2]];
    let (e1, e2, e3) = (d(0, 1), d(0, 2), d(1, 2));
    let norm = |u: [f64; 3]| (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    let cross = norm([
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ]);
    let l = norm(e1).max(norm(e2)).max(norm(e3));
    let c = p.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    if cross <= 8.0 * f32::EPSILON as f64 * l * l.max(c) {
        return Err(format!(
            "facet {k}: zero area (its corners {}, {}, {} are collinear or coincide, to the file's single precision)",
            point(&t[0]),
            point(&t[1]),
            point(&t[2])
        ));
    }
    Ok(())
}

/// An edge between two vertices: the facets on it (the first two) and how many, and the
/// sum of its directions in them (+1 from the lower vertex id to the higher, -1 back).
#[derive(Clone, Copy)]
struct Edge {
    count: u32,
    facets: [usize; 2],
    direction: i32,
}

/// Closed and consistently oriented: every edge, between vertices identified by their exact
/// coordinates, shared by exactly two facets that run it in opposite directions (the
/// winding-number inside test counts each crossing by the facet's orientation).
fn check_closed(raw: &[[[f32; 3]; 3]]) -> Result<(), String> {
    let mut ids: HashMap<[u32; 3], u32> = HashMap::new();
    let mut id_of = |v: &[f32; 3]| {
        let bits = v.map(|c| (c + 0.0).to_bits()); // -0 and 0 are one vertex
        let n = ids.len() as u32;
        *ids.entry(bits).or_insert(n)
    };
    let mut edges: HashMap<(u32, u32), Edge> = HashMap::new();
    for (k, t) in raw.iter().enumerate() {
        let v = [id_of(&t[0]), id_of(&t[1]), id_of(&t[2])];
        for j in 0..3 {
            let (a, b) = (v[j], v[(j + 1) % 3]);
            let e = edges.entry((a.min(b), a.max(b))).or_insert(Edge {
                count: 0,
                facets: [k, k],
                direction: 0,
            });
            if e.count == 1 {
                e.facets[1] = k;
            }
            e.count += 1;
            e.direction += if a < b { 1 } else { -1 };
        }
    }
    // the edge whose first facet comes first in the file
    let mut ends = |first: usize, bad: &dyn Fn(&Edge) -> bool| {
        let t = &raw[first];
        (0..3)
            .map(|j| (t[j], t[(j + 1) % 3]))
            .find(|(a, b)| {
                let (a, b) = (id_of(a), id_of(b));
                edges.get(&(a.min(b), a.max(b))).is_some_and(bad)
            })
            .expect("the facet has the edge")
    };
    let open = |e: &Edge| e.count != 2;
    if let Some(e) = edges
        .values()
        .filter(|e| open(e))
        .min_by_key(|e| e.facets[0])
    {
        let (a, b) = ends(e.facets[0], &open);
        let how = if e.count == 1 {
            "belongs to no other facet: the surface is not closed".to_string()
        } else {
            format!(
                "is shared by {} facets: the surface is not a simple closed one",
                e.count
            )
        };
        return Err(format!(
            "facet {}: its edge from {} to {} {how} (every edge must be shared by exactly two facets)",
            e.facets[0],
            point(&a),
            point(&b)
        ));
    }
    let flipped = |e: &Edge| e.direction != 0;
    if let Some(e) = edges
        .values()
        .filter(|e| flipped(e))
        .min_by_key(|e| e.facets[0])
    {
        let (a, b) = ends(e.facets[0], &flipped);
        return Err(format!(
            "facets {} and {} both run their shared edge from {} to {}: one of them is flipped (a surface's facets run counter-clockwise seen from outside, the STL rule the inside test relies on)",
            e.facets[0],
            e.facets[1],
            point(&a),
            point(&b)
        ));
    }
    Ok(())
}

/// Sign of a value: -1, 0 or 1.
fn sign(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// Orientation of `(a, b, p)` in the plane: twice the signed area (its sign exact), and
/// the sign of the orientation with `p` moved to `p + (ε, ε²)` (which breaks exact ties
/// the same way for `(a, b)` and `(b, a)`; 0 only where `a == b`).
fn side(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> (f64, i8) {
    let c = |q: [f64; 2]| robust::Coord { x: q[0], y: q[1] };
    let o = robust::orient2d(c(a), c(b), c(p));
    if o != 0.0 {
        return (o, sign(o));
    }
    // (b - a) x (p + (ε, ε²) - a) = (b_u - a_u) ε² - (b_v - a_v) ε
    let dv = b[1] - a[1];
    let du = b[0] - a[0];
    (0.0, if dv != 0.0 { -sign(dv) } else { sign(du) })
}

/// Where the ray `(y, z) = p` along x crosses facet `t`, if it does, and the sign of the
/// facet's normal along x there (+1: the ray leaves the facet's solid through it).
fn crossing(t: &[[f64; 3]; 3], p: [f64; 2]) -> Option<(f64, i8)> {
    let q = |k: usize| [t[k][1], t[k][2]];
    let (wa, sa) = side(q(1), q(2), p);
    let (wb, sb) = side(q(2), q(0), p);
    let (wc, sc) = side(q(0), q(1), p);
    if sa == 0 || sa != sb || sb != sc {
        return None;
    }
    let w = wa + wb + wc;
    let (lo, hi) = (
        t[0][0].min(t[1][0]).min(t[2][0]),
        t[0][0].max(t[1][0]).max(t[2][0]),
    );
    let x = if w != 0.0 {
        (wa * t[0][0] + wb * t[1][0] + wc * t[2][0]) / w
    } else {
        (t[0][0] + t[1][0] + t[2][0]) / 3.0
    };
    Some((x.clamp(lo, hi), sa))
}

impl Mesh {
    /// Sites per axis and their spacing: the `box` lattice over the bounding box,
    /// `round(extent / dx)` sites of `extent / n` each.
    pub(super) fn grid(&self, dx: f64) -> ([usize; 3], [f64; 3]) {
        let mut n = [0usize; 3];
        let mut d = [0.0; 3];
        for a in 0..3 {
            n[a] = ((self.hi[a] - self.lo[a]) / dx).round() as usize;
            d[a] = (self.hi[a] - self.lo[a]) / n[a] as f64;
        }
        (n, d)
    }

    /// Number of sites of the lattice over the bounding box (the `box` estimate).
    pub fn sites(&self, dx: f64) -> f64 {
        (0..3)
            .map(|a| (self.hi[a] - self.lo[a]) / dx + 1.0)
            .product()
    }

    /// The sites of the `box` lattice over the bounding box at spacing `dx` that lie
    /// inside the surface, each with its volume, in the order a `box` lists them (z, then
    /// y, then x slowest to fastest).
    pub fn fill(&self, dx: f64) -> Vec<([f64; 3], f64)> {
        let (n, d) = self.grid(dx);
        if n.contains(&0) {
            return Vec::new();
        }
        let vol: f64 = d.iter().product();
        let (lo, ny, nz) = (self.lo, n[1], n[2]);
        let at = |a: usize, k: usize| lo[a] + (k as f64 + 0.5) * d[a];
        // facets binned by the lattice columns (ky, kz) their projection's box covers
        // (one column more each side: the exact test decides)
        let index = |a: usize, v: f64, nmax: usize| -> (usize, usize) {
            let f = (v - lo[a]) / d[a] - 0.5;
            let first = (f.floor() as i64 - 1).clamp(0, nmax as i64 - 1) as usize;
            let last = (f.ceil() as i64 + 1).clamp(0, nmax as i64 - 1) as usize;
            (first, last)
        };
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (k, t) in self.tris.iter().enumerate() {
            let (ymin, ymax) = (
                t[0][1].min(t[1][1]).min(t[2][1]),
                t[0][1].max(t[1][1]).max(t[2][1]),
            );
            let (zmin, zmax) = (
                t[0][2].min(t[1][2]).min(t[2][2]),
                t[0][2].max(t[1][2]).max(t[2][2]),
            );
            let (y0, _) = index(1, ymin, ny);
            let (_, y1) = index(1, ymax, ny);
            let (z0, _) = index(2, zmin, nz);
            let (_, z1) = index(2, zmax, nz);
            for kz in z0..=z1 {
                for ky in y0..=y1 {
                    pairs.push(((kz * ny + ky) as u32, k as u32));
                }
            }
        }
        pairs.sort_unstable();
        let mut start = vec![0usize; ny * nz + 1];
        for &(c, _) in &pairs {
            start[c as usize + 1] += 1;
        }
        for c in 0..ny * nz {
            start[c + 1] += start[c];
        }
        let columns: Vec<Vec<([f64; 3], f64)>> = (0..ny * nz)
            .into_par_iter()
            .map(|c| {
                let (ky, kz) = (c % ny, c / ny);
                let p = [at(1, ky), at(2, kz)];
                let mut xs: Vec<(f64, i8)> = pairs[start[c]..start[c + 1]]
                    .iter()
                    .filter_map(|&(_, t)| crossing(&self.tris[t as usize], p))
                    .collect();
                xs.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
                let mut out = Vec::new();
                // the winding number of the surface about the site: +1 past a facet facing
                // -x (into the solid), -1 past one facing +x; inside where it is not 0, so
                // that overlapping solids fill their union and a cavity (facets facing into
                // it) stays empty
                let (mut passed, mut winding) = (0, 0i64);
                for kx in 0..n[0] {
                    let x = at(0, kx);
                    while passed < xs.len() && xs[passed].0 < x {
                        winding -= i64::from(xs[passed].1);
                        passed += 1;
                    }
                    if winding != 0 {
                        out.push(([x, p[0], p[1]], vol));
                    }
                }
                out
            })
            .collect();
        columns.into_iter().flatten().collect()
    }

    /// The volume the surface encloses (divergence theorem; its sign is the facets'
    /// orientation: positive for outward normals).
    #[cfg(test)]
    pub fn volume(&self) -> f64 {
        self.tris
            .iter()
            .map(|[a, b, c]| {
                (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0
            })
            .sum()
    }
}
