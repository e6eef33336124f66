use super::*;
use polycheck::{Mesh, push_theta_bruteforce};

fn paper() -> Pair {
    Pair::new(8, 8, 200.0, 100.0, 200.0, 100.0, 310.0).expect("paper example is valid")
}

/// Gears with R proportional to N (`k` per tooth), tooth height `h`, clearance `G` as a
/// fraction of `h`.
fn sized(n1: u32, n2: u32, k: f64, h: f64, g_frac: f64) -> Pair {
    let r1 = k * f64::from(n1);
    let r2 = k * f64::from(n2);
    let d = r1 + r2 - h + g_frac * h;
    Pair::new(n1, n2, r1, r1 - h, r2, r2 - h, d).expect("valid test geometry")
}

fn geometries() -> Vec<Pair> {
    vec![
        paper(),
        sized(15, 38, 0.5, 1.1, 0.4),
        sized(38, 15, 0.5, 1.1, 0.4),
        sized(223, 38, 0.29, 1.1, 0.4),
        sized(38, 223, 0.29, 1.1, 0.6),
        sized(7, 12, 1.5, 2.5, 0.22),
        sized(20, 20, 1.0, 3.0, 0.5),
        sized(48, 24, 0.3, 1.1, 0.1),
        Pair::new(20, 9, 30.0, 26.0, 14.0, 11.5, 42.5).expect("valid mixed heights"),
    ]
}

fn mesh(g: &Pair) -> Mesh {
    Mesh::ideal(
        g.n1() as usize,
        g.r_tip1(),
        g.r_root1(),
        g.n2() as usize,
        g.r_tip2(),
        g.r_root2(),
        g.centre_distance(),
    )
}

/// Deterministic spread of `count` points over `[lo, hi)`, not aligned with the pitch.
fn spread(lo: f64, hi: f64, count: usize) -> impl Iterator<Item = f64> {
    (0..count).map(move |i| lo + (hi - lo) * ((i as f64 * 0.618_033_988_749_894_9) % 1.0))
}

#[test]
fn paper_theta_prime_at_zero() {
    let g = paper();
    let t0 = theta_prime(&g, 0.0).to_degrees();
    assert!((t0 - 17.96).abs() < 0.005, "{t0}");
    // Exact value of [I] at phi' = 0: q = 110, theta' = asin(200 sin(alpha2) / 110) - alpha2.
    let a2 = (100.0 * (PI / 8.0).sin()).atan2(200.0 - 100.0 * (PI / 8.0).cos());
    let exact = (200.0 * a2.sin() / 110.0).asin() - a2;
    assert!((theta_prime(&g, 0.0) - exact).abs() < 1e-15);
    assert!((t0 - 17.955_387_657_7).abs() < 1e-9, "{t0}");
    assert_eq!(
        contact(&g, 0.0),
        Contact {
            pair: 0,
            phase: Phase::Two,
            theta_prime: exact
        }
    );
}

#[test]
fn switch_is_intersection_of_i_and_ii() {
    for g in geometries() {
        let s = phase_switch(&g);
        let i = expr_i(&g, s);
        let ii = expr_ii(&g, s);
        assert!((i - ii).abs() < 1e-13, "{g:?}: {i} vs {ii}");
        assert!(phase1_theta(&g, s).is_some() && phase2_theta(&g, s).is_some());
        // [II] above before, [I] above after.
        assert_eq!(
            tooth_pair_theta(&g, s - 1e-9).map(|t| t.1),
            Some(Phase::One)
        );
        assert_eq!(
            tooth_pair_theta(&g, s + 1e-9).map(|t| t.1),
            Some(Phase::Two)
        );
        // The switch is inside the stretch where pair 0 is binding, for these geometries.
        let h = handoff(&g);
        assert!(
            h - g.pitch1() < s && s < h,
            "{g:?}: switch {s}, handoff {h}"
        );
        assert_eq!(contact(&g, s - 1e-9).phase, Phase::One);
        assert_eq!(contact(&g, s + 1e-9).phase, Phase::Two);
    }
}

#[test]
fn paper_switch_and_handoff_values() {
    let g = paper();
    // Phase 1 -> Phase 2 about 6 degrees before the line of centres; next pair takes over
    // about 11.6 degrees after it.
    assert!((phase_switch(&g).to_degrees() + 6.0396).abs() < 1e-3);
    assert!((handoff(&g).to_degrees() - 11.5558).abs() < 1e-3);
}

#[test]
fn handoff_matches_next_pair() {
    for g in geometries() {
        let h = handoff(&g);
        let f = |a: f64| tooth_pair_theta(&g, a).map(|t| t.0);
        let (Some(a), Some(b)) = (f(h), f(h - g.pitch1())) else {
            panic!("{g:?}: both pairs valid at the handoff");
        };
        assert!((a - (b + g.pitch2())).abs() < 1e-13, "{g:?}");
        assert_eq!(contact(&g, h - 1e-9).pair, 0);
        assert_eq!(contact(&g, h + 1e-9).pair, 1);
    }
}

#[test]
fn continuity_at_switch_and_handoff() {
    for g in geometries() {
        for x in [phase_switch(&g), handoff(&g), handoff(&g) - g.pitch1()] {
            let eps = 4.0 * f64::EPSILON * x.abs().max(1.0);
            let jump = theta_prime(&g, x + eps) - theta_prime(&g, x - eps);
            assert!(jump.abs() < 1e-12, "{g:?} at {x}: jump {jump}");
        }
        // And no jumps anywhere on a fine grid: a step that looks steep is refined, and a
        // jump would keep its size while a steep but continuous stretch shrinks. (theta' may
        // also decrease briefly, where a driver tip slides back along the driven flank near
        // the end of a contact, and is steep just after a Phase 1 tangency.)
        let p1 = g.pitch1();
        let n = 4000;
        let dx = 2.0 * p1 / f64::from(n);
        for i in 0..n {
            let x = -p1 + dx * f64::from(i);
            let dt = theta_prime(&g, x + dx) - theta_prime(&g, x);
            if dt.abs() < 10.0 * g.ratio() * dx {
                continue;
            }
            let sub = 10_000;
            let h = dx / f64::from(sub);
            let worst = (0..sub)
                .map(|j| {
                    let y = x + h * f64::from(j);
                    (theta_prime(&g, y + h) - theta_prime(&g, y)).abs()
                })
                .fold(0.0, f64::max);
            assert!(
                worst < 0.1 * dt.abs(),
                "{g:?} at {x}: step {dt}, refined {worst}"
            );
        }
    }
}

#[test]
fn periodicity() {
    for g in geometries() {
        let (p1, p2) = (g.pitch1(), g.pitch2());
        for x in spread(-3.0 * p1, 3.0 * p1, 50) {
            for k in [-3_i32, -1, 1, 2, 7] {
                let k = f64::from(k);
                let lhs = theta_prime(&g, x + k * p1);
                let rhs = theta_prime(&g, x) + k * p2;
                assert!((lhs - rhs).abs() < 1e-12, "{g:?} at {x}, k {k}");
            }
        }
    }
}

#[test]
fn whole_teeth_follow_the_ratio() {
    for g in geometries() {
        let p1 = g.pitch1();
        for phi_o in [0.0, 0.1 * p1, 0.77 * p1] {
            for k in 0..=g.n1() {
                let phi = f64::from(k) * p1;
                let th = theta_from(&g, phi_o, phi);
                assert!((th - g.ratio() * phi).abs() < 1e-12, "{g:?}, k {k}");
                assert!(td_from(&g, phi_o, phi).abs() < 1e-12);
            }
        }
        assert_eq!(theta(&g, 0.0), 0.0);
        assert_eq!(td(&g, 0.0), 0.0);
    }
}

#[test]
fn paper_td_has_zero_mean_scale() {
    // The Theoretical Difference of the paper example oscillates by a few degrees.
    let g = paper();
    let p1 = g.pitch1();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in spread(0.0, p1, 500) {
        let v = td(&g, x).to_degrees();
        lo = lo.min(v);
        hi = hi.max(v);
    }
    assert!(lo < 0.0 && hi > 0.0 && hi - lo < 20.0, "{lo} {hi}");
}

#[test]
fn bruteforce_matches_closed_form() {
    for g in geometries() {
        let m = mesh(&g);
        let (p1, p2) = (g.pitch1(), g.pitch2());
        // Length scale for the touch tolerance.
        let scale = g.r_tip1().max(g.r_tip2());
        for phi in spread(-1.5 * p1, 1.5 * p1, 200) {
            let t = theta_prime(&g, phi);
            let bf = push_theta_bruteforce(&m, phi, t - p2 / 8.0, t + p2 / 64.0);
            let Some(bf) = bf else {
                panic!("{g:?} at phi' {phi}: no brute-force push angle near {t}");
            };
            assert!(
                (bf - t).abs() < 1e-9,
                "{g:?} at phi' {phi}: closed form {t}, brute force {bf}"
            );
            assert!(m.is_touching(phi, t, 1e-9 * scale), "{g:?} at {phi}");
            assert!(m.penetration_at(phi, t - 1e-7) > 0.0, "{g:?} at {phi}");
        }
    }
}

#[test]
fn validation_names_the_field() {
    let e = Pair::new(2, 8, 200.0, 100.0, 200.0, 100.0, 310.0);
    assert!(matches!(e, Err(PairError::TooFewTeeth { field: "n1", .. })));
    let e = Pair::new(8, 8, 200.0, f64::NAN, 200.0, 100.0, 310.0);
    assert!(matches!(
        e,
        Err(PairError::NotPositive {
            field: "r_root1",
            ..
        })
    ));
    let e = Pair::new(8, 8, 200.0, 100.0, 200.0, 200.0, 310.0);
    assert!(matches!(
        e,
        Err(PairError::RootNotBelowTip {
            field: "r_root2",
            ..
        })
    ));
    let e = Pair::new(8, 8, 200.0, 100.0, 200.0, 100.0, f64::INFINITY);
    assert!(matches!(
        e,
        Err(PairError::NotPositive {
            field: "centre_distance",
            ..
        })
    ));
    let e = Pair::new(8, 8, 200.0, 100.0, 200.0, 100.0, 300.0);
    assert!(matches!(
        e,
        Err(PairError::TooClose {
            field: "centre_distance",
            ..
        })
    ));
    let e = Pair::new(8, 8, 200.0, 100.0, 200.0, 100.0, 400.0);
    assert!(matches!(
        e,
        Err(PairError::TooFar {
            field: "centre_distance",
            ..
        })
    ));
    // G = 95 % of h: the teeth let go before the next pair engages.
    let e = Pair::new(8, 8, 200.0, 100.0, 200.0, 100.0, 395.0);
    assert!(
        matches!(
            e,
            Err(PairError::ContactInterrupted {
                field: "centre_distance",
                ..
            })
        ),
        "{e:?}"
    );
    // Teeth too tall for their pitch: the next pair strikes the driven.
    let e = Pair::new(7, 12, 10.5, 8.0, 18.0, 15.5, 26.75);
    assert!(
        matches!(e, Err(PairError::ContactInterrupted { reason, .. }) if reason.contains("jumps")),
        "{e:?}"
    );
    let msg = Pair::new(8, 3, 200.0, 100.0, 200.0, 100.0, -1.0)
        .err()
        .map(|e| e.to_string());
    assert_eq!(
        msg.as_deref(),
        Some("centre_distance: must be finite and positive, got -1")
    );
}
