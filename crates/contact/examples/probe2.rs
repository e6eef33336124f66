#![allow(clippy::unwrap_used, missing_docs, reason = "example")]
use contact::{Mesh, Start, Motion};
use geometry::Gear;
use std::f64::consts::TAU;
fn main() {
    let k = 64.0 / 38.0;
    let r2 = (k * 15.30 + 9.85) / (k * k + 1.0);
    let r1 = k * r2;
    let g: f64 = std::env::args().nth(1).unwrap().parse().unwrap();
    let d = geometry::centre_distance(r1, r2, 1.1, g);
    let m = Mesh::new(Gear::ideal(64, r1, r1 - 1.1).unwrap(), Gear::ideal(38, r2, r2 - 1.1).unwrap(), d).unwrap();
    let t = m.run(0.0, TAU / 64.0 * 3.0, Start::Touching(0.0));
    for e in t.events() { println!("{:?} phi={} th={} teeth=({},{})", e.kind, e.phi.to_degrees(), e.theta.to_degrees(), e.driver_tooth, e.driven_tooth); }
    for s in t.segments() { let kind = match &s.motion { Motion::Rest => "rest".to_string(), Motion::Held => "held".into(), Motion::Push(p) => format!("push{:?}", p) }; println!("{:.5}..{:.5} th {:.5}..{:.5} {}", s.phi_start.to_degrees(), s.phi_end.to_degrees(), s.theta_start.to_degrees(), s.theta_end.to_degrees(), kind); }
}
