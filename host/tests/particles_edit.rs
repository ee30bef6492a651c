//! Removing and inserting particles mid-run (`Sim::retain`, `Sim::append`: the moving
//! window's exit and feed). A body far from the flyer plate never interacts with it, so
//! removing it mid-run, or appending it mid-run, must leave the flyer plate's evolution
//! bitwise identical to a run that never had it (the remaining particles keep their order,
//! hence the order of every pair sum).

use gsph::scene::{build_particles, parse, InitialParticles};
use gsph::sim::Sim;

const FLYER: &str = include_str!("../../cases/flyer_plate.toml");
const FAR: &str = r#"

[[bodies]]
material = "metal"
shape = { type = "segment", min = 0.05, max = 0.06 }
spacing = 1.0e-4
"#;

fn sim(text: &str, scheme: &str) -> (Sim<1>, InitialParticles) {
    let s = parse(text, "edit", &[format!("scheme={scheme}")]).unwrap();
    let parts = build_particles(&s).unwrap();
    (Sim::<1>::new(&s, &parts).unwrap(), parts)
}

/// The particles of body `b` only.
fn body(parts: &InitialParticles, b: u16) -> InitialParticles {
    let mut out = InitialParticles {
        dim: parts.dim,
        ..Default::default()
    };
    for i in (0..parts.len()).filter(|&i| parts.body[i] == b) {
        out.push_from(parts, i);
    }
    out
}

fn steps(sim: &mut Sim<1>, n: usize) {
    for _ in 0..n {
        sim.step(2.0e-9).unwrap();
    }
}

/// Flyer-plate particles (ids below `n`) of two runs are bitwise equal.
fn assert_same(a: &Sim<1>, b: &Sim<1>, n: u32, what: &str) {
    let ta = a.table();
    let tb = b.table();
    let pick = |t: &gsph::output::table::ParticleTable| -> Vec<[u64; 6]> {
        let mut rows: Vec<(u32, [u64; 6])> = (0..t.len())
            .filter(|&i| t.id[i] < n)
            .map(|i| {
                (
                    t.id[i],
                    [t.x[i], t.vx[i], t.rho[i], t.e[i], t.sxx[i], t.p[i]].map(f64::to_bits),
                )
            })
            .collect();
        rows.sort_by_key(|r| r.0);
        rows.into_iter().map(|r| r.1).collect()
    };
    let (pa, pb) = (pick(&ta), pick(&tb));
    assert_eq!(pa.len(), n as usize, "{what}");
    assert!(pa == pb, "{what}: the flyer plate differs");
}

#[test]
fn removing_or_adding_a_distant_body_changes_nothing_else() {
    for scheme in ["av", "pm", "ts2", "tkc"] {
        let with = format!("{FLYER}{FAR}");
        let (mut plain, _) = sim(FLYER, scheme);
        let n = plain.len() as u32;
        steps(&mut plain, 120);

        // removed after 40 steps
        let (mut removed, _) = sim(&with, scheme);
        steps(&mut removed, 40);
        let keep: Vec<bool> = removed.ids.iter().map(|&id| id < n).collect();
        let rebuilds = removed.rebuilds;
        removed.retain(&keep);
        assert_eq!(removed.len(), n as usize);
        steps(&mut removed, 80);
        assert!(
            removed.rebuilds > rebuilds,
            "{scheme}: lists rebuilt after retain"
        );
        assert_same(&plain, &removed, n, &format!("{scheme}, removed"));

        // appended after 40 steps
        let (_, parts_with) = sim(&with, scheme);
        let (mut added, _) = sim(FLYER, scheme);
        steps(&mut added, 40);
        let first = added.append(&body(&parts_with, 2));
        assert_eq!(first, n);
        assert_eq!(added.len(), parts_with.len());
        steps(&mut added, 80);
        assert_same(&plain, &added, n, &format!("{scheme}, appended"));
        // the new body is at rest and unstressed far from everything
        let t = added.table();
        let far: Vec<usize> = (0..t.len()).filter(|&i| t.id[i] >= n).collect();
        assert_eq!(far.len(), 100);
        assert!(
            far.iter().all(|&i| t.vx[i].abs() < 1e-9 && t.x[i] > 0.049),
            "{scheme}"
        );
    }
}
