//! Differential check: the same random meshes run with different step lengths must give the
//! same events. `cargo run --release -p contact --example differential -- 300 4` (hard meshes:
//! cases, steps a pitch, the reference's steps, a fixed clearance if given), or
//! `-- wide 3000 [LO HI] [curved]` (the wider class with clearances drawn from LO-HI % of h, 5-95
//! by default, straight flanks unless `curved`: how many meshes differ from a 64-times-finer run
//! in any event, and in jammed at all or disengaged at all, by band of clearance).
#![allow(missing_docs, clippy::unwrap_used, reason = "harness")]

use contact::{Solve, Start};

#[path = "../tests/support/hard_meshes.rs"]
mod hard_meshes;
use hard_meshes::hard_mesh;
#[path = "../tests/support/wide_meshes.rs"]
mod wide_meshes;

/// The wider class by clearance, in bands of 10 %: meshes, how many differ from a
/// 64-times-finer run in any event, and how many in jammed at all or disengaged at all.
fn wide(cases: u64, clearances: (f64, f64), curved: bool) {
    let mut bands = [(0u32, 0u32, 0u32, 0usize); 10];
    for wide_meshes::WideMesh {
        mesh: m,
        phi0,
        end,
        clearance,
        what,
    } in wide_meshes::wide_meshes(cases, clearances, curved)
    {
        let band = &mut bands[((clearance / 10.0) as usize).min(9)];
        let a = m.solve(
            phi0..=end,
            Start::Touching(0.0),
            Solve::path().steps_per_pitch(4.0),
        );
        let b = m.solve(
            phi0..=end,
            Start::Touching(0.0),
            Solve::path().steps_per_pitch(64.0).exact_core(),
        );
        let same = same_events(a.events(), b.events());
        let answer = |t: &contact::Trajectory| (t.jams() > 0, t.disengagements() > 0);
        band.0 += 1;
        band.3 += a.events().len();
        if !same {
            band.1 += 1;
            println!(
                "{what}: {} vs {} events",
                a.events().len(),
                b.events().len()
            );
        }
        band.2 += u32::from(answer(&a) != answer(&b));
    }
    for (i, (n, differ, answers, events)) in bands.iter().enumerate() {
        if *n > 0 {
            println!(
                "G {}-{} %: {n} meshes ({events} events), {differ} differ in some event, {answers} in jammed or disengaged at all",
                10 * i,
                10 * i + 10
            );
        }
    }
}

/// Two runs found the same events: as many, of the same kinds, at the same driver and driven
/// angles to 1e-9 rad.
fn same_events(a: &[contact::Event], b: &[contact::Event]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same_event(x, y))
}

fn same_event(x: &contact::Event, y: &contact::Event) -> bool {
    x.kind == y.kind && (x.phi - y.phi).abs() < 1e-9 && (x.theta - y.theta).abs() < 1e-9
}

fn main() {
    let mut args = std::env::args().skip(1).peekable();
    if args.peek().is_some_and(|a| a == "wide") {
        let rest: Vec<String> = args.skip(1).collect();
        let cases = rest.first().map_or(1000, |s| s.parse().unwrap());
        let curved = rest.iter().any(|a| a == "curved");
        let bounds: Vec<f64> = rest.iter().skip(1).filter_map(|s| s.parse().ok()).collect();
        let clearances = match bounds[..] {
            [lo, hi] => (lo, hi),
            _ => (5.0, 95.0),
        };
        wide(cases, clearances, curved);
        return;
    }
    let cases: u64 = args.next().map_or(200, |s| s.parse().unwrap());
    let steps: f64 = args.next().map_or(4.0, |s| s.parse().unwrap());
    let reference: f64 = args.next().map_or(16.0, |s| s.parse().unwrap());
    let g_fixed: Option<f64> = args.next().and_then(|s| s.parse().ok());
    let certify = std::env::var("BRACKET_ONLY").is_err();
    let (mut diffs, mut events, mut first_diffs) = (0, 0, 0);
    let (mut b_evals, mut b_time) = (0, 0.0);
    for s in 0..cases {
        let Some(h) = hard_mesh(s, g_fixed) else {
            continue;
        };
        let (m, phi0, end, what) = (h.mesh, h.phi0, h.end, h.what);
        let a = m.solve(
            phi0..=end,
            Start::Touching(0.0),
            Solve::path().steps_per_pitch(reference).exact_core(),
        );
        let e0 = contact::tooth_pair_evaluations();
        let t0 = std::time::Instant::now();
        let how = Solve::path().steps_per_pitch(steps);
        let how = if certify { how } else { how.exact_core() };
        let b = m.solve(phi0..=end, Start::Touching(0.0), how);
        b_evals += contact::tooth_pair_evaluations() - e0;
        b_time += t0.elapsed().as_secs_f64();
        events += a.events().len();
        let same = same_events(a.events(), b.events());
        if !same {
            diffs += 1;
            if (a.jams() > 0) != (b.jams() > 0)
                || (a.disengagements() > 0) != (b.disengagements() > 0)
            {
                first_diffs += 1;
            }
            let first = a
                .events()
                .iter()
                .zip(b.events())
                .position(|(x, y)| !same_event(x, y));
            if let Some(i) = first {
                println!(
                    "  first diff at event {i}: ref: {:?}\n   other: {:?}",
                    a.events()[i],
                    b.events()[i]
                );
            }
            println!(
                "{what}: {reference} steps {} jams {} dis; {steps} steps {} jams {} dis",
                a.jams(),
                a.disengagements(),
                b.jams(),
                b.disengagements()
            );
        }
    }
    println!("tooth-pair evaluations {b_evals}, {b_time:.3} s (the run checked)");
    println!(
        "{diffs} of {cases} cases differ ({first_diffs} in the first event or in jammed/disengaged at all); {events} events at 16 steps"
    );
}
