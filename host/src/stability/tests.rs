use super::*;

fn row() -> Row {
    Row {
        case: "c".into(),
        scheme: "ts2".into(),
        particles: 10,
        steps: 5,
        t: 1e-6,
        t_end: 1e-6,
        reached: true,
        nan: false,
        rho_min: 1000.0,
        energy_error: 1e-14,
        momentum_error: 1e-15,
        wall_s: 0.1,
        verdict: Verdict::Fail,
        note: String::new(),
    }
}

#[test]
fn momentum_error_is_relative_to_the_larger_scale() {
    // zero total momentum (bodies closing): relative to sum m|v|
    assert_eq!(momentum_error(&[0.0, 0.0], &[1e-3, 0.0], 10.0, 5.0), 1e-4);
    // net momentum larger than sum m|v| cannot happen, but |p| is a scale too
    assert_eq!(momentum_error(&[3.0, 4.0], &[3.0, 4.0], 1.0, 1.0), 0.0);
    // the larger of |p0| = 5 and |p1| = sqrt(29.25)
    let e = momentum_error(&[3.0, 4.0], &[3.0, 4.5], 1.0, 1.0);
    assert!((e - 0.5 / 29.25f64.sqrt()).abs() < 1e-15, "{e}");
    // nothing moves: no division by zero
    assert_eq!(momentum_error(&[0.0], &[0.0], 0.0, 0.0), 0.0);
}

#[test]
fn judge_passes_a_clean_run_and_names_each_failed_criterion() {
    let mut r = row();
    judge(&mut r, Scheme::Ts2);
    assert_eq!(r.verdict, Verdict::Pass, "{}", r.note);
    assert!(r.note.is_empty());
    type Spoil = (fn(&mut Row), &'static str);
    let cases: [Spoil; 6] = [
        (|r| r.reached = false, "stopped at"),
        (|r| r.nan = true, "NaN"),
        (|r| r.rho_min = 0.0, "density_min"),
        (|r| r.rho_min = f64::NAN, "density_min"),
        (|r| r.momentum_error = 1e-8, "momentum error"),
        (|r| r.energy_error = -1e-6, "energy error"),
    ];
    for (spoil, word) in cases {
        let mut r = row();
        spoil(&mut r);
        judge(&mut r, Scheme::Ts2);
        assert_eq!(r.verdict, Verdict::Fail, "{word}");
        assert!(r.note.contains(word), "{word}: {}", r.note);
    }
    // the energy bound is the scheme's
    let mut r = row();
    r.energy_error = 1e-3;
    judge(&mut r, Scheme::Av);
    assert_eq!(r.verdict, Verdict::Pass);
    judge(&mut r, Scheme::Ts1);
    assert_eq!(r.verdict, Verdict::Fail);
}

#[test]
fn every_quick_override_names_a_hard_case() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/hard");
    let files = case_files(&dir).unwrap();
    let stems: Vec<String> = files.iter().map(|f| stem(f)).collect();
    assert!(stems.len() >= 8, "{stems:?}");
    for s in &stems {
        assert!(!quick_overrides(s).is_empty(), "{s} has no quick overrides");
        // every hard case parses with its quick overrides and every scheme
        for sc in Scheme::ALL {
            let set: Vec<String> = quick_overrides(s).iter().map(|x| x.to_string()).collect();
            match scene::load_for_scheme(&dir.join(format!("{s}.toml")), &set, sc.name()) {
                Ok(_) => {}
                // tl's one refusal of a scene shape: periodic boundaries, by key and scheme
                Err(e)
                    if sc == Scheme::Tl
                        && e.to_string().contains("periodic: not yet with scheme tl") => {}
                Err(e) => panic!("{s} {}: {e}", sc.name()),
            }
        }
    }
}

#[test]
fn tables_carry_every_row() {
    let mut a = row();
    judge(&mut a, Scheme::Ts2);
    let mut b = row();
    b.case = "d".into();
    b.nan = true;
    b.note = "step 3 (t = 1e-9 s): x of particle 2 is not finite, \"quoted\"".into();
    b.verdict = Verdict::Fail;
    let csv = to_csv(&[a.clone(), b.clone()]);
    assert_eq!(csv.lines().count(), 3);
    assert!(csv.contains("c,ts2,10,5,"));
    assert!(
        csv.contains("FAIL,\"step 3 (t = 1e-9 s): x of particle 2 is not finite, \"\"quoted\"\"\"")
    );
    let md = to_markdown(&[a, b], true, 2);
    assert!(md.contains("2 runs: 1 PASS, 1 FAIL, 0 n/a"));
    assert!(md.contains("| c | ts2 | 10 | 5 | yes | no | 1000 |"));
    assert!(md.contains("| d | ts2 |") && md.contains("| FAIL | step 3"));
}
