//! Where the driven gear is free at a driver angle: the obstacles near it swept in order of
//! their lower ends, up to where they first leave a gap - the next free position - or, where
//! they close up over a whole turn, the chain of them that holds the gear.

use std::f64::consts::TAU;

use super::SIDE_TOL;
use crate::mesh::{Mesh, Obstacle, PairMemo};

impl Mesh {
    /// The nearest driven angle ≥ θ that overlaps no driver tooth at φ, or None if the obstacles
    /// close up over more than a turn of the driven gear. An obstacle that only touches θ from
    /// behind does not move it; one that touches it from ahead does when `through` is set (the
    /// release after a jam: the driven gear is let go to the next position where it is free).
    pub fn next_free(&self, phi: f64, theta: f64, through: bool) -> Option<f64> {
        self.free_or_cover(phi, theta, through).ok()
    }

    /// [`Mesh::next_free`], but where there is no free position, the tooth pairs whose
    /// obstacles, one after another, close up over the turn: the proof of being blocked.
    fn free_or_cover(&self, phi: f64, theta: f64, through: bool) -> Result<f64, Vec<(i64, i64)>> {
        self.free_or_cover_with(phi, theta, through, None)
    }

    /// [`Mesh::free_or_cover`], and where there is no free position, the obstacles of the
    /// returned cover at φ into `links` (in the order the sweep took them), if given.
    pub(super) fn free_or_cover_with(
        &self,
        phi: f64,
        theta: f64,
        through: bool,
        links: Option<&mut Vec<Obstacle>>,
    ) -> Result<f64, Vec<(i64, i64)>> {
        self.free_or_cover_in(phi, theta, through, links, &mut PairMemo::new(self, phi))
    }

    /// [`Mesh::free_or_cover_with`], taking the pairs already evaluated at φ from `memo` (a memo
    /// at φ) and leaving there those it evaluates.
    pub(super) fn free_or_cover_in(
        &self,
        phi: f64,
        theta: f64,
        through: bool,
        links: Option<&mut Vec<Obstacle>>,
        memo: &mut PairMemo,
    ) -> Result<f64, Vec<(i64, i64)>> {
        let gap = self.driven.max_gap;
        let (mut obs, mut more) = (Vec::new(), Vec::new());
        let mut reach = 3.0 * gap;
        // The widening windows pass the same teeth again a turn on: each pair is evaluated once.
        self.obstacles_with(phi, theta - gap, theta + reach, &mut obs, Some(&mut *memo));
        loop {
            let (top, chain) = cover_from(theta, &mut obs, through);
            if top < theta + reach - gap {
                // A driven angle is one a whole turn on: a free position found past a turn (a
                // gap just opening, on the side tolerance's edge at one turn and not the other)
                // is taken within the turn, so that θ never jumps by a turn.
                return Ok(top - TAU * ((top - theta) / TAU).floor());
            }
            if reach > TAU + 3.0 * gap {
                if let Some(links) = links {
                    chain_links(theta, &obs, through, links);
                }
                return Err(chain);
            }
            // Widen the search by what lies beyond its reach: those that straddle it come twice,
            // which changes nothing in the sweep (a copy never reaches past the top its first
            // left).
            self.obstacles_with(
                phi,
                theta + reach,
                theta + 2.0 * reach,
                &mut more,
                Some(&mut *memo),
            );
            obs.append(&mut more);
            reach *= 2.0;
        }
    }

    /// How far above θ the obstacles must close up for the driven gear at θ to have no free
    /// position: the top of the widest search of [`Mesh::free_or_cover`] (which gives up there),
    /// less a driven gap.
    pub(super) fn held_threshold(&self, theta: f64) -> f64 {
        let gap = self.driven.max_gap;
        let mut reach = 3.0 * gap;
        while reach <= TAU + 3.0 * gap {
            reach *= 2.0;
        }
        theta + reach - gap
    }
}

/// How far above θ the obstacles close up, swept in order of their lower ends (those that
/// extend the cover are kept, in order): an obstacle that only touches θ from behind does not
/// start it; one that touches it from ahead does when `through` is set.
fn cover_from(theta: f64, obs: &mut [Obstacle], through: bool) -> (f64, Vec<(i64, i64)>) {
    obs.sort_by(|a, b| a.lo.total_cmp(&b.lo));
    let mut chain = Vec::new();
    let top = sweep(theta, obs, through, |o| {
        chain.push((o.driver_tooth, o.driven_tooth));
    });
    (top, chain)
}

/// The obstacles [`cover_from`] took into its cover (those that lifted the top), in order, into
/// `links`, from `obs` as it left them (sorted).
fn chain_links(theta: f64, obs: &[Obstacle], through: bool, links: &mut Vec<Obstacle>) {
    links.clear();
    sweep(theta, obs, through, |o| links.push(*o));
}

/// [`cover_from`]'s sweep over obstacles sorted by their lower ends: the top reached, each
/// obstacle that lifted it passed to `take`.
fn sweep(theta: f64, obs: &[Obstacle], through: bool, mut take: impl FnMut(&Obstacle)) -> f64 {
    let mut top = theta;
    for o in obs {
        let carried = through || top > theta;
        let reaches = if carried {
            o.lo <= top + SIDE_TOL
        } else {
            o.lo < top - SIDE_TOL
        };
        if reaches && o.hi > top {
            top = o.hi;
            take(o);
        }
    }
    top
}
