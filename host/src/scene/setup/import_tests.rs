//! Unit tests of bodies from files: particle files (CSV) against the lattice bodies they
//! copy, STL surfaces filled against boxes and spheres, and the one-line errors of bad
//! files.

use super::*;
use crate::memory::MAX_PARTICLES;
use crate::scene::{build_particles, load, InitialParticles, Scene};
use std::collections::HashMap;

pub(in crate::scene::setup) type Tri = [[f32; 3]; 3];

/// Writes `tris` as a binary STL file (normals left 0: they are not read).
pub(in crate::scene::setup) fn write_stl(path: &Path, tris: &[Tri]) {
    let mesh: Vec<stl_io::Triangle> = tris
        .iter()
        .map(|t| stl_io::Triangle {
            normal: stl_io::Normal::new([0.0; 3]),
            vertices: t.map(stl_io::Vertex::new),
        })
        .collect();
    let mut f = std::fs::File::create(path).unwrap();
    stl_io::write_stl(&mut f, mesh.iter()).unwrap();
}

/// `tris` as an ASCII STL file.
fn ascii_stl(tris: &[Tri]) -> String {
    let mut s = String::from("solid test\n");
    for t in tris {
        s.push_str("  facet normal 0 0 0\n    outer loop\n");
        for v in t {
            s.push_str(&format!("      vertex {:e} {:e} {:e}\n", v[0], v[1], v[2]));
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid test\n");
    s
}

/// The 12 facets of the box `[lo, hi]`, normals outward (each face split along a
/// diagonal).
pub(in crate::scene::setup) fn cube(lo: [f32; 3], hi: [f32; 3]) -> Vec<Tri> {
    let c = |i: usize| {
        [
            if i & 1 == 0 { lo[0] } else { hi[0] },
            if i & 2 == 0 { lo[1] } else { hi[1] },
            if i & 4 == 0 { lo[2] } else { hi[2] },
        ]
    };
    // faces as corner quads, counter-clockwise seen from outside
    let quads = [
        [0, 4, 6, 2], // x = lo
        [1, 3, 7, 5], // x = hi
        [0, 1, 5, 4], // y = lo
        [2, 6, 7, 3], // y = hi
        [0, 2, 3, 1], // z = lo
        [4, 5, 7, 6], // z = hi
    ];
    quads
        .iter()
        .flat_map(|q| [[c(q[0]), c(q[1]), c(q[2])], [c(q[0]), c(q[2]), c(q[3])]])
        .collect()
}

/// A sphere of radius `r` at `c`: an icosahedron subdivided `levels` times, its vertices
/// pushed onto the sphere (20 × 4^levels facets).
pub(in crate::scene::setup) fn icosphere(c: [f64; 3], r: f64, levels: u32) -> Vec<Tri> {
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<[f64; 3]> = vec![
        [-1.0, g, 0.0],
        [1.0, g, 0.0],
        [-1.0, -g, 0.0],
        [1.0, -g, 0.0],
        [0.0, -1.0, g],
        [0.0, 1.0, g],
        [0.0, -1.0, -g],
        [0.0, 1.0, -g],
        [g, 0.0, -1.0],
        [g, 0.0, 1.0],
        [-g, 0.0, -1.0],
        [-g, 0.0, 1.0],
    ];
    let unit = |p: [f64; 3]| {
        let n = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        p.map(|x| x / n)
    };
    for p in &mut v {
        *p = unit(*p);
    }
    let mut f: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
        let mut next = Vec::new();
        for t in &f {
            let mut m = [0; 3];
            for j in 0..3 {
                let (a, b) = (t[j], t[(j + 1) % 3]);
                m[j] = *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let p = unit([v[a][0] + v[b][0], v[a][1] + v[b][1], v[a][2] + v[b][2]]);
                    v.push(p);
                    v.len() - 1
                });
            }
            next.push([t[0], m[0], m[2]]);
            next.push([t[1], m[1], m[0]]);
            next.push([t[2], m[2], m[1]]);
            next.push(m);
        }
        f = next;
    }
    let place = |p: [f64; 3]| [0, 1, 2].map(|a| (c[a] + r * p[a]) as f32);
    f.iter().map(|t| t.map(|k| place(v[k]))).collect()
}

const AL_3D: &str = r#"dim = 3
scheme = "pm"
t_end = 1e-7
[[materials]]
name = "al"
rho0 = 2700.0
eos = { type = "linear", c0 = 5000.0 }
"#;

/// A scene in `dir` (written to `scene.toml`, so relative files resolve there), loaded.
pub(in crate::scene::setup) fn scene_in(
    dir: &Path,
    text: &str,
    set: &[&str],
) -> Result<Scene, String> {
    let p = dir.join("scene.toml");
    std::fs::write(&p, text).unwrap();
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    load(&p, &set).map_err(|e| e.0)
}

fn built(dir: &Path, text: &str) -> InitialParticles {
    let sc = scene_in(dir, text, &[]).unwrap_or_else(|e| panic!("{e}"));
    build_particles(&sc).unwrap()
}

/// The error of loading `text` in `dir`; asserts it is one line.
fn load_err(dir: &Path, text: &str) -> String {
    let e = scene_in(dir, text, &[]).expect_err("the scene should be refused");
    assert!(!e.contains('\n'), "not one line: {e}");
    e
}

fn stl_body(file: &str, extra: &str) -> String {
    format!(
        "{AL_3D}[[bodies]]\nmaterial = \"al\"\nshape = {{ type = \"stl\", file = \"{file}\"{extra} }}\nspacing = 1e-4\n"
    )
}

#[test]
fn an_stl_cube_fills_as_the_box_lattice() {
    let dir = tempfile::tempdir().unwrap();
    // the unit cube scaled to 1 mm: the bounding box is [0, 1e-3]³ to the bit
    write_stl(&dir.path().join("cube.stl"), &cube([0.0; 3], [1.0; 3]));
    let stl = built(dir.path(), &stl_body("cube.stl", ", scale = 1e-3"));
    let boxed = built(
        dir.path(),
        &format!(
            "{AL_3D}[[bodies]]\nmaterial = \"al\"\nshape = {{ type = \"box\", min = [0.0, 0.0, 0.0], max = [1e-3, 1e-3, 1e-3] }}\nspacing = 1e-4\n"
        ),
    );
    assert_eq!(stl.len(), 1000);
    // every lattice ray through a face diagonal (y = z) meets an edge of two facets: still
    // each site is inside exactly once
    assert_eq!(stl.x, boxed.x);
    assert_eq!(stl.m, boxed.m);
    assert_eq!(stl.spacing, boxed.spacing);
    // the same cube as ASCII, translated
    std::fs::write(
        dir.path().join("cube_ascii.stl"),
        ascii_stl(&cube([0.0; 3], [1.0; 3])),
    )
    .unwrap();
    let moved = built(
        dir.path(),
        &stl_body(
            "cube_ascii.stl",
            ", scale = 1e-3, offset = [0.5, 0.0, -0.25]",
        ),
    );
    assert_eq!(moved.len(), 1000);
    for (a, b) in moved.x.iter().zip(&boxed.x) {
        let shifted = [b[0] + 0.5, b[1], b[2] - 0.25];
        for k in 0..3 {
            assert!((a[k] - shifted[k]).abs() < 1e-15, "{a:?} {shifted:?}");
        }
    }
}

#[test]
fn an_stl_sphere_holds_its_volume() {
    let dir = tempfile::tempdir().unwrap();
    let r = 1.0e-3;
    let tris = icosphere([0.2e-3, -0.1e-3, 0.05e-3], r, 4);
    write_stl(&dir.path().join("ball.stl"), &tris);
    let sc = scene_in(
        dir.path(),
        &stl_body("ball.stl", ""),
        &["bodies.0.spacing=4e-5"],
    )
    .unwrap();
    let parts = build_particles(&sc).unwrap();
    let filled: f64 = parts.m.iter().sum::<f64>() / 2700.0;
    let mesh = read_stl(
        "b",
        dir.path().join("ball.stl").to_str().unwrap(),
        1.0,
        [0.0; 3],
        MAX_PARTICLES,
    )
    .unwrap();
    let exact = 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
    let rel = |a: f64, b: f64| (a - b).abs() / b;
    // the polyhedron (5120 facets) lies within 0.3 % of the sphere, the lattice (50
    // sites across) within 1 % of the polyhedron
    assert!(rel(mesh.volume(), exact) < 3e-3, "{}", mesh.volume());
    assert!(
        rel(filled, mesh.volume()) < 1e-2,
        "{filled} {}",
        mesh.volume()
    );
    assert!(rel(filled, exact) < 2e-2, "{filled} {exact}");
    // every site kept is inside the sphere (to the facets' sagitta)
    let c = [0.2e-3, -0.1e-3, 0.05e-3];
    for x in &parts.x {
        let d = ((x[0] - c[0]).powi(2) + (x[1] - c[1]).powi(2) + (x[2] - c[2]).powi(2)).sqrt();
        assert!(d < r, "{x:?} at {d}");
    }
}

/// Rays exactly through vertices where four facets meet, and along a plane holding edges:
/// an octahedron `|x - c|₁ <= a` whose tips and equator lie on lattice rays.
#[test]
fn rays_through_vertices_and_edges_count_once() {
    let dir = tempfile::tempdir().unwrap();
    let (c, a) = (0.5f32, 0.375f32);
    let tip = |axis: usize, s: f32| {
        let mut p = [c; 3];
        p[axis] += s * a;
        p
    };
    let mut tris = Vec::new();
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0, 1.0] {
                let t = [tip(0, sx), tip(1, sy), tip(2, sz)];
                // outward: flip where the octant's orientation is negative
                if sx * sy * sz > 0.0 {
                    tris.push(t);
                } else {
                    tris.push([t[0], t[2], t[1]]);
                }
            }
        }
    }
    write_stl(&dir.path().join("octa.stl"), &tris);
    let mesh = read_stl(
        "b",
        dir.path().join("octa.stl").to_str().unwrap(),
        1.0,
        [0.0; 3],
        MAX_PARTICLES,
    )
    .unwrap();
    assert!((mesh.volume() - 4.0 / 3.0 * 0.375f64.powi(3)).abs() < 1e-15);
    // bounding box [0.125, 0.875]³ at spacing 0.25: sites 0.25, 0.5, 0.75 on each axis; the
    // ray y = z = 0.5 runs through both x tips, the rays in the planes y = 0.5 and z = 0.5
    // through edges of the equators
    let (n, d) = mesh.grid(0.25);
    assert_eq!((n, d), ([3; 3], [0.25; 3]));
    let mut pts: Vec<[f64; 3]> = mesh.fill(0.25).into_iter().map(|(x, _)| x).collect();
    pts.sort_by(|p, q| p.partial_cmp(q).unwrap());
    let mut want = vec![[0.5; 3]];
    for axis in 0..3 {
        for v in [0.25, 0.75] {
            let mut p = [0.5; 3];
            p[axis] = v;
            want.push(p);
        }
    }
    want.sort_by(|p, q| p.partial_cmp(q).unwrap());
    assert_eq!(pts, want);
}

#[test]
fn bad_stl_files_are_one_line_naming_the_facet() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut open = cube([0.0; 3], [1.0; 3]);
    open.remove(5);
    write_stl(&d.join("open.stl"), &open);
    let e = load_err(d, &stl_body("open.stl", ""));
    assert!(
        e.contains("bodies[0].shape.file: ")
            && e.contains("open.stl: facet 0: its edge from (0, 0, 0) to (0, 0, 1)")
            && e.contains("belongs to no other facet: the surface is not closed"),
        "{e}"
    );
    let mut flat = cube([0.0; 3], [1.0; 3]);
    flat[7] = [[0.0, 0.0, 0.0], [0.5, 0.5, 0.5], [1.0, 1.0, 1.0]];
    write_stl(&d.join("flat.stl"), &flat);
    let e = load_err(d, &stl_body("flat.stl", ""));
    assert!(e.contains("flat.stl: facet 7: zero area"), "{e}");
    let mut nan = cube([0.0; 3], [1.0; 3]);
    nan[2][1][2] = f32::NAN;
    write_stl(&d.join("nan.stl"), &nan);
    let e = load_err(d, &stl_body("nan.stl", ""));
    assert!(
        e.contains("nan.stl: facet 2: vertex 1 is not finite"),
        "{e}"
    );
    // two cubes sharing an edge: four facets on it
    let mut twice = cube([0.0; 3], [1.0; 3]);
    twice.extend(cube([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]));
    write_stl(&d.join("twice.stl"), &twice);
    let e = load_err(d, &stl_body("twice.stl", ""));
    assert!(e.contains("is shared by 4 facets"), "{e}");
    // cut short inside a facet
    write_stl(&d.join("short.stl"), &cube([0.0; 3], [1.0; 3]));
    let bytes = std::fs::read(d.join("short.stl")).unwrap();
    std::fs::write(d.join("short.stl"), &bytes[..84 + 50 * 3 + 20]).unwrap();
    let e = load_err(d, &stl_body("short.stl", ""));
    assert!(e.contains("short.stl: facet 3: the file ends"), "{e}");
    let e = load_err(d, &stl_body("none.stl", ""));
    assert!(
        e.contains("bodies[0].shape.file: ") && e.contains("none.stl: cannot read"),
        "{e}"
    );
    // not 3D
    let e = load_err(
        d,
        "dim = 2\nscheme = \"pm\"\nt_end = 1e-7\n[[materials]]\nname = \"al\"\nrho0 = 2700.0\neos = { type = \"linear\", c0 = 5000.0 }\n[[bodies]]\nmaterial = \"al\"\nshape = { type = \"stl\", file = \"cube.stl\" }\nspacing = 1e-4\n",
    );
    assert_eq!(
        e,
        "DIR/scene.toml: bodies[0].shape: an `stl` shape is a closed surface in 3D; the scene is 2D"
            .replace("DIR", d.to_str().unwrap())
    );
}

#[test]
fn a_binary_stl_whose_header_says_solid_reads() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("solid.stl");
    write_stl(&p, &cube([0.0; 3], [1.0; 3]));
    let mut bytes = std::fs::read(&p).unwrap();
    bytes[..11].copy_from_slice(b"solid cube ");
    std::fs::write(&p, bytes).unwrap();
    let m = read_stl("b", p.to_str().unwrap(), 1.0, [0.0; 3], MAX_PARTICLES).unwrap();
    assert_eq!(m.tris.len(), 12);
    assert!((m.volume() - 1.0).abs() < 1e-12);
}

const AL_2D: &str = r#"dim = 2
scheme = "pm"
t_end = 1e-7
[[materials]]
name = "al"
rho0 = 2700.0
shear_modulus = 26e9
eos = { type = "linear", c0 = 5000.0 }
strength = { type = "von_mises", yield_stress = 3e8 }
"#;

const BOX_2D: &str = "[[bodies]]\nmaterial = \"al\"\nshape = { type = \"box\", min = [0.0, 0.0], max = [1e-3, 5e-4] }\nspacing = 1e-4\nvelocity = { type = \"uniform\", value = [100.0, 0.0] }\n";

fn csv_of(parts: &InitialParticles, cols: &[&str]) -> String {
    let mut s = cols.join(",");
    s.push('\n');
    for i in 0..parts.len() {
        let v: Vec<String> = cols
            .iter()
            .map(|c| match *c {
                "x" => parts.x[i][0],
                "y" => parts.x[i][1],
                "z" => parts.x[i][2],
                "vx" => parts.v[i][0],
                "vy" => parts.v[i][1],
                "m" => parts.m[i],
                "rho" => parts.rho[i],
                "e" => parts.e[i],
                _ => 0.0,
            })
            .map(|v| format!("{v:e}"))
            .collect();
        s.push_str(&v.join(","));
        s.push('\n');
    }
    s
}

fn particles_body(file: &str, extra: &str) -> String {
    format!("[[bodies]]\nmaterial = \"al\"\nshape = {{ type = \"particles\", file = \"{file}\" }}\n{extra}")
}

#[test]
fn a_csv_body_equals_the_box_it_copies() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let boxed = built(d, &format!("{AL_2D}{BOX_2D}"));
    assert_eq!(boxed.len(), 50);
    std::fs::write(
        d.join("box.csv"),
        csv_of(&boxed, &["x", "y", "vx", "vy", "m", "rho"]),
    )
    .unwrap();
    let csv = built(d, &format!("{AL_2D}{}", particles_body("box.csv", "")));
    assert_eq!(csv.x, boxed.x);
    assert_eq!(csv.v, boxed.v);
    assert_eq!(csv.m, boxed.m);
    assert_eq!(csv.rho, boxed.rho);
    assert_eq!(csv.e, boxed.e);
    assert_eq!(csv.s, boxed.s);
    assert_eq!(csv.eps_p, boxed.eps_p);
    assert_eq!(csv.temp, boxed.temp);
    for (a, b) in csv.spacing.iter().zip(&boxed.spacing) {
        assert!((a - b).abs() < 1e-15, "{a} {b}");
    }
    // with a byte-order mark and Windows line ends
    let text = csv_of(&boxed, &["x", "y", "vx", "vy", "m", "rho"]).replace('\n', "\r\n");
    std::fs::write(d.join("bom.csv"), format!("\u{feff}{text}")).unwrap();
    let bom = built(d, &format!("{AL_2D}{}", particles_body("bom.csv", "")));
    assert_eq!(bom.x, boxed.x);
    assert_eq!(bom.m, boxed.m);
    // quoted names and values, comment lines and blank lines, as spreadsheets and other
    // codes export them (read with the csv crate)
    let quoted: String = csv_of(&boxed, &["x", "y", "vx", "vy", "m", "rho"])
        .lines()
        .map(|l| {
            let q: Vec<String> = l.split(',').map(|f| format!("\"{f}\"")).collect();
            format!("# a comment\n{}\n\n", q.join(","))
        })
        .collect();
    std::fs::write(d.join("quoted.csv"), quoted).unwrap();
    let q = built(d, &format!("{AL_2D}{}", particles_body("quoted.csv", "")));
    assert_eq!(q.x, boxed.x);
    assert_eq!(q.v, boxed.v);
    assert_eq!(q.m, boxed.m);
    // positions only: mass rho0 spacing², the body's velocity
    std::fs::write(d.join("xy.csv"), csv_of(&boxed, &["x", "y"])).unwrap();
    let xy = built(
        d,
        &format!(
            "{AL_2D}{}",
            particles_body(
                "xy.csv",
                "spacing = 1e-4\nvelocity = { type = \"uniform\", value = [100.0, 0.0] }\n"
            )
        ),
    );
    assert_eq!(xy.x, boxed.x);
    assert_eq!(xy.v, boxed.v);
    assert_eq!(xy.spacing, vec![1e-4; 50]);
    for (a, b) in xy.m.iter().zip(&boxed.m) {
        assert!((a - b).abs() < 1e-12 * b, "{a} {b}");
    }
}

#[test]
fn file_columns_give_the_state_and_body_keys_win() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("s.csv"),
        "# a comment\n\nid,material,x,y,z,vx,vy,m,rho,p,e,sxx,syy,szz,sxy,sxz,syz,eps_p,damage,temperature,von_mises\n\
         7,0,0.0,0.0,0.0,1.5,-2.5,0.027,2750.0,9.9,120.0,1e6,-5e5,-5e5,2e5,0.0,0.0,0.01,0.0,0.0,1.0\n\
         3,0,1e-4,0.0,0.0,0.0,0.0,0.027,2700.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0\n",
    )
    .unwrap();
    let p = built(d, &format!("{AL_2D}{}", particles_body("s.csv", "")));
    assert_eq!(p.len(), 2);
    assert_eq!(p.x[0], [0.0; 3]);
    assert_eq!(p.v[0], [1.5, -2.5, 0.0]);
    assert_eq!((p.m[0], p.rho[0], p.e[0]), (0.027, 2750.0, 120.0));
    assert_eq!(
        p.s[0],
        gsph_core::math::Sym3::new(1e6, -5e5, -5e5, 2e5, 0.0, 0.0)
    );
    assert_eq!(p.eps_p[0], 0.01);
    assert!((p.spacing[0] - (0.027f64 / 2750.0).sqrt()).abs() < 1e-18);
    // `velocity` and `initial` replace the file's columns
    let p = built(
        d,
        &format!(
            "{AL_2D}{}",
            particles_body(
                "s.csv",
                "velocity = { type = \"uniform\", value = [10.0, 0.0] }\ninitial = { type = \"density\", rho = 2800.0, e = 5.0 }\n"
            )
        ),
    );
    assert_eq!(p.v[0], [10.0, 0.0, 0.0]);
    assert_eq!((p.m[0], p.rho[0], p.e[0]), (0.027, 2800.0, 5.0));
    assert_eq!(p.s[0], gsph_core::math::Sym3::ZERO);
    assert_eq!(p.eps_p[0], 0.01, "plastic strain stays the file's");
}

#[test]
fn file_material_selects_rows() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("two.csv"),
        "material,x,y,m\n0,0.0,0.0,0.027\n1,1e-4,0.0,0.05\n1,2e-4,0.0,0.05\n",
    )
    .unwrap();
    let e = load_err(d, &format!("{AL_2D}{}", particles_body("two.csv", "")));
    assert!(
        e.ends_with("two.csv holds particles of materials 0, 1 (column `material`); a body is of one material: choose its rows with `file_material`"),
        "{e}"
    );
    let one = |k: u32| {
        format!(
            "{AL_2D}[[bodies]]\nmaterial = \"al\"\nshape = {{ type = \"particles\", file = \"two.csv\", file_material = {k} }}\n"
        )
    };
    let p = built(d, &one(1));
    assert_eq!(p.len(), 2);
    assert_eq!(p.x[0][0], 1e-4);
    let e = load_err(d, &one(4));
    assert!(
        e.contains("bodies[0].shape.file_material: no row of ")
            && e.ends_with("two.csv is of material 4 (it has 0, 1)"),
        "{e}"
    );
}

#[test]
fn bad_particle_files_are_one_line_naming_the_row() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = |body: &str| format!("{AL_2D}{body}");
    let cases: &[(&str, &str, &str)] = &[
        ("x,y,m\n0,0,1\n1e-4,0\n", "", "bad.csv: line 3: 2 fields, but the header (line 1) names 3 columns"),
        ("x,y,m\n0,0,1\n1e-4,zero,1\n", "", "bad.csv: line 3, column `y`: `zero` is not a number"),
        ("y,m\n0,1\n", "", "bad.csv: line 1: no column `x` (a 2D scene needs x, y; the header names y, m)"),
        ("x,y,m\n0,0,1\nNaN,0,1\n", "", "bad.csv: line 3, column `x`: NaN not finite"),
        ("x,y,m\n0,0,-1\n", "", "bad.csv: line 2, column `m`: -1 must be positive"),
        ("x,y,z,m\n0,0,1e-3,1\n", "", "bad.csv: line 2, column `z`: 0.001 must be 0 in a 2D scene"),
        ("x,y,Vx,m\n0,0,1,1\n", "", "bad.csv: line 1, column 3: not a column name gsph knows (known: x, y, z, vx,"),
        ("x,y,x\n0,0,0\n", "", "bad.csv: line 1, column 3: column `x` appears twice"),
        ("x,y,sxx,syy,m\n0,0,0,0,1\n", "", "bad.csv: line 1: the deviator columns sxx, syy, szz, sxy, sxz, syz come all six or none"),
        ("x,y,damage,m\n0,0,2,1\n", "", "bad.csv: line 2, column `damage`: 2 must lie in [0, 1]"),
        ("# only a comment\n", "", "bad.csv: no header line"),
        ("x,y,m\n", "", "bad.csv: no particle rows after the header"),
        ("x,y\n0,0\n", "", "bodies[0].spacing: missing: "),
        ("x,y,m\n0,0,1\n", "step = 3\n", "bodies[0].shape.step: selects a snapshot of an HDF5 file; "),
    ];
    for (text, extra, want) in cases {
        std::fs::write(d.join("bad.csv"), text).unwrap();
        let body = if extra.starts_with("step") {
            "[[bodies]]\nmaterial = \"al\"\nshape = { type = \"particles\", file = \"bad.csv\", step = 3 }\n".to_string()
        } else {
            particles_body("bad.csv", extra)
        };
        let e = load_err(d, &scene(&body));
        assert!(e.contains(want), "got `{e}`, want `{want}`");
        assert!(e.contains("scene.toml: bodies[0]."), "{e}");
    }
    let e = load_err(d, &scene(&particles_body("absent.csv", "")));
    assert!(
        e.contains("bodies[0].shape.file: ") && e.contains("absent.csv: cannot read"),
        "{e}"
    );
    std::fs::write(d.join("ok.csv"), "x,y,m\n0,0,1\n").unwrap();
    let e = scene_in(
        d,
        &scene(&particles_body("ok.csv", "")),
        &["resolution_scale=2"],
    )
    .unwrap_err();
    assert!(
        e.contains("resolution_scale: bodies[0] is read from a file"),
        "{e}"
    );
    let e = load_err(d, &scene(&particles_body("ok.csv", "jitter = 0.1\n")));
    assert!(
        e.contains("bodies[0].jitter: not for a `particles` body"),
        "{e}"
    );
    let e = load_err(d, &scene(BOX_2D).replace("spacing = 1e-4\n", ""));
    assert!(
        e.contains("bodies[0].spacing: missing (this key is required"),
        "{e}"
    );
}

/// Files are found relative to the scene file, wherever gsph runs.
#[test]
fn files_are_relative_to_the_scene() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("sub");
    std::fs::create_dir(&sub).unwrap();
    std::fs::write(sub.join("p.csv"), "x,y,m\n0,0,1\n").unwrap();
    let sc = scene_in(
        &sub,
        &format!("{AL_2D}{}", particles_body("p.csv", "")),
        &[],
    )
    .unwrap();
    let ShapeSpec::Particles { file, .. } = &sc.bodies[0].shape else {
        panic!()
    };
    assert_eq!(Path::new(file), sub.join("p.csv"));
    assert_eq!(resolve_path(None, "p.csv"), PathBuf::from("p.csv"));
    assert_eq!(
        resolve_path(Some(Path::new("/a")), "/b/p.csv"),
        PathBuf::from("/b/p.csv")
    );
}

/// On a convex polyhedron a site is inside exactly when it is behind every facet's plane:
/// the ray test agrees site by site (sites within round-off of a plane excepted), for
/// several placements of the lattice against the facets.
#[test]
fn fill_agrees_with_the_plane_test_of_a_convex_polyhedron() {
    let dir = tempfile::tempdir().unwrap();
    let tris = icosphere([0.0; 3], 1.0, 2);
    write_stl(&dir.path().join("p.stl"), &tris);
    let file = dir.path().join("p.stl");
    for (k, dx) in [0.1, 0.0731, 0.05, 0.125].into_iter().enumerate() {
        let offset = [0.013 * k as f64, -0.007 * k as f64, 0.0];
        let mesh = read_stl("b", file.to_str().unwrap(), 1.0, offset, MAX_PARTICLES).unwrap();
        let planes: Vec<([f64; 3], f64)> = mesh
            .tris
            .iter()
            .map(|[a, b, c]| {
                let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
                let n = [
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                ];
                let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                let n = n.map(|x| x / l);
                (n, n[0] * a[0] + n[1] * a[1] + n[2] * a[2])
            })
            .collect();
        let (n, d) = mesh.grid(dx);
        let pts: std::collections::HashSet<[u64; 3]> = mesh
            .fill(dx)
            .into_iter()
            .map(|(x, _)| x.map(f64::to_bits))
            .collect();
        let mut inside = 0;
        for kz in 0..n[2] {
            for ky in 0..n[1] {
                for kx in 0..n[0] {
                    let p = [kx, ky, kz];
                    let p: [f64; 3] = [0, 1, 2].map(|a| mesh.lo[a] + (p[a] as f64 + 0.5) * d[a]);
                    let depth = planes
                        .iter()
                        .map(|(nn, off)| nn[0] * p[0] + nn[1] * p[1] + nn[2] * p[2] - off)
                        .fold(f64::NEG_INFINITY, f64::max);
                    if depth.abs() < 1e-9 {
                        continue;
                    }
                    assert_eq!(
                        pts.contains(&p.map(f64::to_bits)),
                        depth < 0.0,
                        "{p:?} dx {dx}"
                    );
                    inside += usize::from(depth < 0.0);
                }
            }
        }
        assert!(inside > 1000, "{inside}");
    }
}

/// The particle limit of a scene is its key `max_particles` (default 1e8): a particle file
/// or an STL surface beyond it is refused naming the key, counted before it is read, and
/// the key raised lets it through.
#[test]
fn max_particles_bounds_particle_files_and_stl_facets() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let boxed = built(d, &format!("{AL_2D}{BOX_2D}"));
    std::fs::write(d.join("box.csv"), csv_of(&boxed, &["x", "y", "m", "rho"])).unwrap();
    let body = particles_body("box.csv", "");
    let e = load_err(d, &format!("max_particles = 20\n{AL_2D}{body}"));
    assert!(
        e.contains("box.csv: more than 2e1 particle rows, the scene's particle limit (`max_particles` raises it)"),
        "{e}"
    );
    assert_eq!(
        built(d, &format!("max_particles = 50\n{AL_2D}{body}")).len(),
        50
    );
    // an STL surface of 12 facets (a cube) under a limit of 4
    std::fs::write(d.join("cube.stl"), ascii_stl(&cube([0.0; 3], [1e-3; 3]))).unwrap();
    let e = load_err(
        d,
        &format!("max_particles = 4\n{}", stl_body("cube.stl", "")),
    );
    assert!(
        e.contains("more than 4e0 facets (the scene's particle limit; `max_particles` raises it)"),
        "{e}"
    );
    let e = load_err(d, &format!("max_particles = 0\n{AL_2D}{body}"));
    assert!(e.contains("max_particles: must be at least 1"), "{e}");
}
