//! Scratch: jam/disengagement counts against clearance for b2-c1.
#![allow(clippy::unwrap_used, missing_docs, reason = "example")]
use contact::{Mesh, Start};
use geometry::Gear;
use std::f64::consts::TAU;
fn main() {
    let k = 64.0 / 38.0;
    let r2 = (k * 15.30 + 9.85) / (k * k + 1.0);
    let r1 = k * r2;
    for gi in std::env::args().skip(1).map(|a| a.parse::<i32>().unwrap()) {
        let g = gi as f64;
        let d = geometry::centre_distance(r1, r2, 1.1, g);
        let m = match Mesh::new(Gear::ideal(64, r1, r1 - 1.1).unwrap(), Gear::ideal(38, r2, r2 - 1.1).unwrap(), d) { Ok(m) => m, Err(e) => { println!("G={g}: {e}"); continue; } };
        let t0 = std::time::Instant::now();
        let t = m.run(0.0, TAU, Start::Touching(0.0));
        println!("G={g:5} jams={} dis={} segs={} {:?}", t.jams(), t.disengagements(), t.segments().len(), t0.elapsed());
    }
}
#[allow(dead_code)]
fn debug() {}
