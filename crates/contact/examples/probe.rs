#![allow(clippy::unwrap_used, missing_docs, reason = "example")]
use contact::{Mesh, Start};
use geometry::Gear;
use std::f64::consts::TAU;
fn main() {
    let k = 64.0 / 38.0;
    let r2 = (k * 15.30 + 9.85) / (k * k + 1.0);
    let r1 = k * r2;
    let g: f64 = std::env::args().nth(1).unwrap().parse().unwrap();
    let phi_j: f64 = std::env::args().nth(2).unwrap().parse::<f64>().unwrap().to_radians();
    let d = geometry::centre_distance(r1, r2, 1.1, g);
    let m = Mesh::new(Gear::ideal(64, r1, r1 - 1.1).unwrap(), Gear::ideal(38, r2, r2 - 1.1).unwrap(), d).unwrap();
    for i in -10..=2 {
        let p = phi_j + i as f64 * 1e-3_f64.to_radians();
        let show = |j, kk| m.obstacle(p, j, kk).map(|o| (o.lo.to_degrees(), o.hi.to_degrees()));
        println!("{:.6} (0,1)={:?} (0,0)={:?} (-1,0)={:?} (-1,1)={:?}", p.to_degrees(), show(0, 1), show(0, 0), show(-1, 0), show(-1,1));
    }
    let t = m.run(0.0, phi_j - 1e-4, Start::Touching(0.0));
    for e in t.events() { println!("{:?} phi={} th={}", e.kind, e.phi.to_degrees(), e.theta.to_degrees()); }
    let _ = TAU;
}
