//! How far ahead a tooth pair near the mesh could be proved to stay off the driven gear's path by
//! a second-order bound along the exact path, at best (a design question of the contact core;
//! BENCHMARKS.md has the figures): `cargo run --release -p contact --example horizons -- 4` (seeds per mesh).
//!
//! From starts every quarter pitch of full turns (m3-e3 and m2-n1, random tip errors σ = 0.04
//! pitch, G = 40 and 10 %, starts within a pitch of an event left out), each pair whose obstacle
//! lies within a driven gap of θ - ahead of the driven gear or behind it, not pushing - has its
//! margin along the solver's path sampled over the next driver pitch (to where the pair vanishes,
//! if it does): lo − θ ahead, θ − hi behind. Its *true horizon* is where the margin first reaches
//! zero (else the window's end). Its *best second-order horizon* is the largest Δ with
//! m0 + m0′Δ − MΔ²/2 > 0, M the largest second difference of the sampled margin up to Δ: any
//! rigorous bound on the second derivative is at least that, so no second-order certificate on
//! these margins along the exact path reaches farther (one on the signed distances of
//! `speed/certify.rs` has its own second derivatives). Kinks (a pair's end switching from one contact to
//! another, a hand-over) are where such a bound must stop and start again; the third figure
//! leaves them out (second differences above twenty times the median's).
#![allow(missing_docs, clippy::unwrap_used, reason = "measurement harness")]

use std::f64::consts::TAU;

use contact::{Mesh, Solve, Start};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

mod support;

use support::{MESHES, gear};

#[derive(Default)]
struct Tally {
    n: usize,
    truth: f64,
    oracle: f64,
    truth_full: usize,
    oracle_full: usize,
    oracle_quarter: usize,
    smooth: f64,
    smooth_full: usize,
}

fn main() {
    let seeds: u64 = std::env::args().nth(1).map_or(3, |s| s.parse().unwrap());
    const N: usize = 512;
    for (name, n1, n2, r1, r2) in MESHES {
        for g in [40.0, 10.0] {
            let (mut ahead, mut behind) = (Tally::default(), Tally::default());
            for s in 0..seeds {
                let mut rng = ChaCha8Rng::seed_from_u64(s);
                let d = geometry::centre_distance(r1, r2, 1.1, g);
                let m = Mesh::new(
                    gear(n1, r1, 0.04, &mut rng),
                    gear(n2, r2, 0.04, &mut rng),
                    d,
                )
                .unwrap();
                let pitch = TAU / n1 as f64;
                let end = TAU * n2 as f64 / n1 as f64;
                let t = m.solve(0.0..=end, Start::Touching(0.0), Solve::path());
                let gap = TAU / n2 as f64;
                let h = pitch / N as f64;
                let mut obs = Vec::new();
                let mut i = 0;
                loop {
                    let phi0 = 0.01 + i as f64 * pitch / 4.0;
                    i += 1;
                    if phi0 + pitch >= end {
                        break;
                    }
                    // Skip starts near an event (a jam moves θ discontinuously).
                    if t.events()
                        .iter()
                        .any(|e| e.phi >= phi0 - pitch && e.phi <= phi0 + pitch)
                    {
                        continue;
                    }
                    let theta0 = t.theta_at(phi0);
                    m.obstacles(phi0, theta0 - gap, theta0 + gap, &mut obs);
                    for o in &obs {
                        let is_ahead = o.lo > theta0 + 1e-9;
                        let is_behind = o.hi < theta0 - 1e-9;
                        if !is_ahead && !is_behind {
                            continue;
                        }
                        let (j, k) = (o.driver_tooth, o.driven_tooth);
                        // The margin along the path, to the pair's death or a pitch.
                        let mut gs = Vec::with_capacity(N + 1);
                        for q in 0..=N {
                            let phi = phi0 + q as f64 * h;
                            let Some(ob) = m.obstacle(phi, j, k) else {
                                break;
                            };
                            let th = t.theta_at(phi);
                            gs.push(if is_ahead { ob.lo - th } else { th - ob.hi });
                        }
                        let last = gs.len() - 1;
                        let truth = gs.iter().position(|&x| x <= 0.0).unwrap_or(last);
                        // Best second-order horizon: m0 + d0 Δ − M(Δ) Δ²/2 > 0, M the largest
                        // second difference seen up to Δ (the true bound is no smaller).
                        let d0 = if gs.len() > 1 {
                            (gs[1] - gs[0]) / h
                        } else {
                            0.0
                        };
                        let mut mx: f64 = 0.0;
                        let mut oracle = 0;
                        for q in 1..last {
                            let dd = (gs[q + 1] - 2.0 * gs[q] + gs[q - 1]).abs() / (h * h);
                            mx = mx.max(dd);
                            let dl = (q + 1) as f64 * h;
                            if gs[0] + d0 * dl - 0.5 * mx * dl * dl > 0.0 {
                                oracle = q + 1;
                            } else {
                                break;
                            }
                        }
                        // The same, with kinks (a second difference above 20 times the median's)
                        // left out: what a bound that splits at kinks could reach.
                        let mut dds: Vec<f64> = (1..last)
                            .map(|q| (gs[q + 1] - 2.0 * gs[q] + gs[q - 1]).abs() / (h * h))
                            .collect();
                        let mut sorted = dds.clone();
                        sorted.sort_by(f64::total_cmp);
                        let median = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
                        for x in &mut dds {
                            if *x > 20.0 * median {
                                *x = 0.0;
                            }
                        }
                        let mut mx2: f64 = 0.0;
                        let mut smooth = 0;
                        for (q, dd) in dds.iter().enumerate() {
                            mx2 = mx2.max(*dd);
                            let dl = (q + 2) as f64 * h;
                            if gs[0] + d0 * dl - 0.5 * mx2 * dl * dl > 0.0 {
                                smooth = q + 2;
                            } else {
                                break;
                            }
                        }
                        let tally = if is_ahead { &mut ahead } else { &mut behind };
                        tally.n += 1;
                        tally.truth += truth as f64 / N as f64;
                        tally.oracle += oracle as f64 / N as f64;
                        tally.truth_full += usize::from(truth == N);
                        tally.oracle_full += usize::from(oracle == N);
                        tally.oracle_quarter += usize::from(oracle >= N / 4);
                        tally.smooth += smooth as f64 / N as f64;
                        tally.smooth_full += usize::from(smooth >= last);
                    }
                }
            }
            for (side, t) in [("ahead", &ahead), ("behind", &behind)] {
                let n = t.n.max(1) as f64;
                println!(
                    "{name} G {g}: {side:6} pairs {:6}: mean true horizon {:.2} pitch ({:.0} % a whole pitch); best second-order {:.2} pitch ({:.0} % a whole pitch, {:.0} % at least a quarter); kinks left out {:.2} pitch ({:.0} % to the window's end)",
                    t.n,
                    t.truth / n,
                    100.0 * t.truth_full as f64 / n,
                    t.oracle / n,
                    100.0 * t.oracle_full as f64 / n,
                    100.0 * t.oracle_quarter as f64 / n,
                    t.smooth / n,
                    100.0 * t.smooth_full as f64 / n,
                );
            }
        }
    }
}
