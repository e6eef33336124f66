//! One ideal mesh run over a full turn of its larger gear at a given clearance, and the clearance
//! limits of a mesh: below the first it jams, above the second it disengages.

use std::f64::consts::TAU;

use contact::{Mesh, Solve, Start, Trajectory};
use geometry::Gear;
use registry::RunError;

use rules::Rule;

/// A mesh's clearance limits (% of h): (smallest G without a jam, largest G without a
/// disengagement); `None` where 0-100 % does not bracket one.
pub type Limits = (Option<f64>, Option<f64>);

/// An ideal mesh whose clearance can vary.
#[derive(Debug, Clone, Copy)]
pub struct IdealPair {
    /// Driver teeth N1.
    pub n1: usize,
    /// Driven teeth N2.
    pub n2: usize,
    /// Driver tip radius R1 (mm).
    pub r1: f64,
    /// Driven tip radius R2 (mm).
    pub r2: f64,
    /// Tooth height h of both gears (mm).
    pub h: f64,
}

/// The mesh whose ideal pair an experiment studies (`--set mesh=LABEL`).
pub const MESH: registry::Param = registry::Param {
    name: "mesh",
    default: "b2-c1",
    unit: "",
    help: "mesh label in the gearing (radii sized as crates/train sizes them)",
    kind: registry::Kind::Text,
    reading: false,
};

impl IdealPair {
    /// Mesh `label` of gearing `g` with ideal teeth of height `h`, sized as `train` sizes it
    /// (its gears' fitted tip radii); `None` for a label the gearing does not have.
    pub fn of_mesh(g: &train::Gearing, label: &str, h: f64) -> Option<IdealPair> {
        // The clearance does not enter the radii: any value sizes the gears.
        let geo = g.mesh_geometry(label, h, 40.0)?;
        Some(IdealPair {
            n1: geo.driver_teeth as usize,
            n2: geo.driven_teeth as usize,
            r1: geo.driver_tip_radius,
            r2: geo.driven_tip_radius,
            h,
        })
    }

    /// [`IdealPair::of_mesh`] of mesh `label` (the `mesh` parameter's value), refused naming
    /// the parameter.
    pub fn named(label: &str, g: &train::Gearing, h: f64) -> Result<IdealPair, RunError> {
        IdealPair::of_mesh(g, label, h).ok_or_else(|| {
            RunError::bad(
                "--set",
                MESH.name,
                format!("no mesh `{label}` in the gearing"),
            )
        })
    }
    /// The ideal mesh at clearance `g` (% of h), or None when the gears overlap at every tooth.
    ///
    /// The gears' root radii are R - h: a tooth height they cannot take is refused naming
    /// `tooth_height`, the parameter the user set, not the gear's internal field.
    fn mesh(&self, g: f64) -> Result<Option<Mesh>, RunError> {
        let bad = |_: geometry::GeometryError| {
            RunError::bad(
                "--set",
                "tooth_height",
                format!(
                    "must leave each gear a root radius R - h above 0 and below R (R = {} and {}; got h = {})",
                    registry::fmt_number(self.r1),
                    registry::fmt_number(self.r2),
                    registry::fmt_number(self.h)
                ),
            )
        };
        let driver = Gear::ideal(self.n1, self.r1, self.r1 - self.h).map_err(bad)?;
        let driven = Gear::ideal(self.n2, self.r2, self.r2 - self.h).map_err(bad)?;
        Ok(Mesh::new(driver, driven, self.centre_distance(g)).ok())
    }

    /// The centre distance at clearance `g` (% of h): D = R1 + R2 - h + G h.
    pub fn centre_distance(&self, g: f64) -> f64 {
        geometry::centre_distance(self.r1, self.r2, self.h, g)
    }

    /// The pair's ideal gears (driver, driven).
    pub fn ideal_gears(&self) -> Result<(Gear, Gear), RunError> {
        let bad = |e: geometry::GeometryError| RunError::bad("gearing", e.field, e.rule);
        Ok((
            Gear::ideal(self.n1, self.r1, self.r1 - self.h).map_err(bad)?,
            Gear::ideal(self.n2, self.r2, self.r2 - self.h).map_err(bad)?,
        ))
    }

    /// Manufactured gears `made` (driver, driven) placed at this pair's centre distance for
    /// clearance `g`, run one full turn of the larger gear from driver angle `phi0`, starting in
    /// contact. Gears that cannot be placed there are bad input naming the field and rule.
    pub fn run_made(
        &self,
        made: (&Gear, &Gear),
        g: f64,
        phi0: f64,
    ) -> Result<Trajectory, RunError> {
        // The centre distance is the clearance's, which is what the user set.
        let mesh =
            Mesh::new(made.0.clone(), made.1.clone(), self.centre_distance(g)).map_err(|e| {
                RunError::bad(
                    "--set",
                    "clearance",
                    format!(
                        "{} % of h places these gears at D = {}, where they cannot mesh: D {}",
                        registry::fmt_number(g),
                        registry::fmt_number(self.centre_distance(g)),
                        e.rule
                    ),
                )
            })?;
        Ok(mesh.solve(
            phi0..=phi0 + self.turn(),
            Start::Touching(0.0),
            Solve::path(),
        ))
    }

    /// Driver rotation for one full turn of the larger gear.
    fn turn(&self) -> f64 {
        TAU * self.n1.max(self.n2) as f64 / self.n1 as f64
    }

    /// One full turn of the larger gear from driver angle 0 at clearance `g` (% of h), or None
    /// when the gears overlap at every tooth.
    pub fn run(&self, g: f64) -> Result<Option<Trajectory>, RunError> {
        Ok(self
            .mesh(g)?
            .map(|mesh| mesh.solve(0.0..=self.turn(), Start::Touching(0.0), Solve::path())))
    }

    /// [`IdealPair::run`] ending at its first jam by `rule` (the trajectory then holds its last
    /// angle): for a caller that uses only runs without a jam, it saves the rest of the turn.
    pub fn run_to_first_jam(&self, g: f64, rule: &Rule) -> Result<Option<Trajectory>, RunError> {
        let stop = |e: &contact::Event| rule.is_jam(e);
        Ok(self.mesh(g)?.map(|mesh| {
            mesh.solve(
                0.0..=self.turn(),
                Start::Touching(0.0),
                Solve::path().stop_at(&stop),
            )
        }))
    }

    /// One full turn of the larger gear from driver angle 0 at clearance `g` with the driven
    /// gear at rest `frac` of the way through the backlash: 0 touching the driver tooth behind
    /// it (as [`IdealPair::run`]), 1 touching the one ahead; it stays put until a driver tooth
    /// takes it up. None when the gears overlap at every tooth.
    pub fn run_in_backlash(&self, g: f64, frac: f64) -> Result<Option<Trajectory>, RunError> {
        let Some(mesh) = self.mesh(g)? else {
            return Ok(None);
        };
        let touching = mesh
            .solve(0.0..=0.0, Start::Touching(0.0), Solve::path())
            .theta_at(0.0);
        // The nearest driver tooth ahead of the driven gear: where the backlash ends.
        let mut obstacles = Vec::new();
        let pitch = TAU / self.n2 as f64;
        mesh.obstacles(0.0, touching, touching + 2.0 * pitch, &mut obstacles);
        let ahead = obstacles
            .iter()
            .map(|o| o.lo)
            .filter(|&lo| lo > touching + 1e-9)
            .fold(f64::INFINITY, f64::min);
        let backlash = if ahead.is_finite() {
            ahead - touching
        } else {
            0.0
        };
        let start = touching + frac.clamp(0.0, 1.0) * backlash;
        Ok(Some(mesh.solve(
            0.0..=self.turn(),
            Start::At(start),
            Solve::path(),
        )))
    }

    /// The events of [`IdealPair::run`] alone (no segments kept: cheaper), or None when the
    /// gears overlap at every tooth.
    fn events(&self, g: f64) -> Result<Option<Vec<contact::Event>>, RunError> {
        Ok(self
            .mesh(g)?
            .map(|mesh| mesh.solve(0.0..=self.turn(), Start::Touching(0.0), Solve::events())))
    }

    /// [`IdealPair::events`] ending at the first event for which `stop` holds: the same events
    /// up to it, so the same answer to whether some event counted by `stop` occurs.
    fn events_until(
        &self,
        g: f64,
        stop: &contact::StopAt<'_>,
    ) -> Result<Option<Vec<contact::Event>>, RunError> {
        Ok(self.mesh(g)?.map(|mesh| {
            mesh.solve(
                0.0..=self.turn(),
                Start::Touching(0.0),
                Solve::events().stop_at(stop),
            )
        }))
    }

    /// Whether a full turn at clearance `g` jams by `rule` (or the gears overlap at every tooth):
    /// the run ends at its first jam.
    pub fn jams(&self, g: f64, rule: &Rule) -> Result<bool, RunError> {
        Ok(self
            .events_until(g, &|e| rule.is_jam(e))?
            .is_none_or(|e| rule.tally(&e).0))
    }

    /// Whether a full turn at clearance `g` disengages by `rule`.
    pub fn disengages(&self, g: f64, rule: &Rule) -> Result<bool, RunError> {
        Ok(self.events(g)?.is_some_and(|e| rule.tally(&e).1))
    }

    /// Standard deviation of the driven gear's Theoretical Difference (degrees) over a run.
    pub fn td_sigma(&self, t: &Trajectory, samples: usize) -> stats::PointerStats {
        let th0 = t.theta_at(t.phi_start());
        let end = t.phi_end();
        let ratio = self.n1 as f64 / self.n2 as f64;
        let n = samples.max(2);
        (0..n)
            .map(|k| {
                let phi = end * k as f64 / (n - 1) as f64;
                (t.theta_at(phi) - th0 - ratio * phi).to_degrees()
            })
            .collect::<stats::Accumulator>()
            .stats()
    }

    /// The clearance limits (% of h), located by bisection to `tol` between grid points 0 and 100:
    /// (smallest G without a jam, largest G without a disengagement). None where the grid does not
    /// bracket a limit.
    pub fn limits(&self, tol: f64, rule: &Rule) -> Result<Limits, RunError> {
        Ok(self.limits_under(tol, std::slice::from_ref(rule))?[0])
    }

    /// [`IdealPair::limits`] under each of `rules`, in their order. A run at a given G is made
    /// once and counted under every rule (the searches of rules that agree visit the same G).
    pub fn limits_under(&self, tol: f64, rules: &[Rule]) -> Result<Vec<Limits>, RunError> {
        type Events = Option<std::rc::Rc<Vec<contact::Event>>>;
        // Runs by G: (whether the run ended at an event every rule counts as a jam, events).
        // A run ended there answers every rule's jam question (yes) but no disengagement one.
        let memo: std::cell::RefCell<std::collections::HashMap<u64, (bool, Events)>> =
            std::cell::RefCell::default();
        let jam_for_all = |e: &contact::Event| rules.iter().all(|r| r.is_jam(e));
        let at = |g: f64, whole: bool| -> Result<Events, RunError> {
            if let Some((cut, e)) = memo.borrow().get(&g.to_bits())
                && !(whole && *cut)
            {
                return Ok(e.clone());
            }
            let (cut, e) = if whole {
                (false, self.events(g)?)
            } else {
                let e = self.events_until(g, &jam_for_all)?;
                let cut = e.as_ref().is_some_and(|e| e.iter().any(jam_for_all));
                (cut, e)
            };
            let e = e.map(std::rc::Rc::new);
            memo.borrow_mut().insert(g.to_bits(), (cut, e.clone()));
            Ok(e)
        };
        rules
            .iter()
            .map(|rule| {
                // Overlapping at every tooth counts as a jam.
                let jams = |g: f64| Ok(at(g, false)?.is_none_or(|e| rule.tally(&e).0));
                let disengages = |g: f64| Ok(at(g, true)?.is_some_and(|e| rule.tally(&e).1));
                let mid = 50.0;
                let jam = if jams(mid)? || !jams(0.0)? {
                    None
                } else {
                    Some(boundary(0.0, mid, tol, jams)?)
                };
                let dis = if disengages(mid)? || !disengages(100.0)? {
                    None
                } else {
                    Some(boundary(100.0, mid, tol, disengages)?)
                };
                Ok((jam, dis))
            })
            .collect()
    }
}

/// The boundary between `yes_at` and `no_at` of a monotone predicate, to `tol`; returns the
/// side where the predicate is false.
pub fn boundary(
    mut yes_at: f64,
    mut no_at: f64,
    tol: f64,
    pred: impl Fn(f64) -> Result<bool, RunError>,
) -> Result<f64, RunError> {
    while (yes_at - no_at).abs() > tol {
        let m = 0.5 * (yes_at + no_at);
        if pred(m)? { yes_at = m } else { no_at = m }
    }
    Ok(no_at)
}

/// Figure IV's sweep: for each pair, σ of the driven gear's Theoretical Difference (`samples`
/// samples) at each of `clearances`, `None` where the run jams or disengages under `rule` or
/// the gears overlap at every tooth. The pairs run in parallel, collected in order.
pub fn sigma_sweep(
    pairs: &[IdealPair],
    clearances: &[f64],
    rule: &Rule,
    samples: usize,
) -> Result<Vec<Vec<Option<f64>>>, RunError> {
    use rayon::prelude::*;
    let cells: Vec<Result<Vec<Option<f64>>, RunError>> = pairs
        .par_iter()
        .map(|pair| {
            clearances
                .iter()
                .map(|&c| {
                    // A run that jams shows no σ: it may end at its first jam.
                    Ok(pair.run_to_first_jam(c, rule)?.and_then(|t| {
                        (crate::events::counts(rule, &t) == (0, 0))
                            .then(|| pair.td_sigma(&t, samples).sigma)
                    }))
                })
                .collect()
        })
        .collect();
    cells.into_iter().collect()
}

/// Each pair's limits under `rule` ([`IdealPair::limits`], to `tol` % of h), in parallel,
/// collected in order; each pair's result on its own.
pub fn all_limits(pairs: &[IdealPair], tol: f64, rule: &Rule) -> Vec<Result<Limits, RunError>> {
    use rayon::prelude::*;
    pairs
        .par_iter()
        .map(|pair| pair.limits(tol, rule))
        .collect()
}

/// Each pair's limits under every rule of `rules` ([`IdealPair::limits_under`], to `tol` % of
/// h): `[pair][rule]`. The pairs' searches are independent and deterministic; collected in
/// order, so the thread count changes nothing.
pub fn limits_under_rules(
    pairs: &[IdealPair],
    tol: f64,
    rules: &[Rule],
) -> Result<Vec<Vec<Limits>>, RunError> {
    use rayon::prelude::*;
    pairs
        .par_iter()
        .map(|p| p.limits_under(tol, rules))
        .collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    /// A run cut at its first jam has the whole run's events up to that jam (where and what; a
    /// jam's release is sized only by the rest of the run), so every rule's jam answer is the
    /// whole run's: blocked, jamming at every tooth, jamming once and running
    /// meshes of small and unequal gears, every registered rule.
    #[test]
    fn a_run_cut_at_its_first_jam_answers_as_the_whole_turn() {
        rules::link();
        let g = train::Gearing::freeth2006();
        let all: Vec<Rule> = rules::rules()
            .unwrap()
            .keys()
            .map(|name| Rule::parse(name).unwrap())
            .collect();
        let mut cut_short = 0;
        for label in ["b2-c1", "m2-n1", "e1-b3", "h2-i1", "c2-d1"] {
            let pair = IdealPair::of_mesh(&g, label, 1.1).unwrap();
            for gp in [0.5, 2.0, 5.0, 8.0, 11.0, 14.0, 17.0, 40.0, 92.0] {
                let whole = pair.events(gp).unwrap();
                for rule in &all {
                    let cut = pair.events_until(gp, &|e| rule.is_jam(e)).unwrap();
                    let (Some(whole), Some(cut)) = (&whole, &cut) else {
                        assert_eq!(whole.is_none(), cut.is_none(), "{label} at {gp}");
                        continue;
                    };
                    // The same events up to the cut, where they happened and what they are
                    // (the whole run sizes a jam's release later: lost motion, lag).
                    let seen = |e: &[contact::Event]| -> Vec<_> {
                        e.iter()
                            .map(|e| (e.phi, e.theta, e.kind, e.driver_tooth, e.driven_tooth))
                            .collect()
                    };
                    assert_eq!(seen(&whole[..cut.len()]), seen(cut), "{label} at {gp}");
                    assert_eq!(
                        rule.tally(whole).0,
                        rule.tally(cut).0,
                        "{label} at {gp} under {rule:?}"
                    );
                    cut_short += usize::from(cut.len() < whole.len());
                }
                assert_eq!(
                    pair.jams(gp, &all[0]).unwrap(),
                    whole.as_ref().is_none_or(|e| all[0].tally(e).0)
                );
            }
        }
        // The test means something only if some runs were cut short.
        assert!(cut_short > 0);
    }
}
