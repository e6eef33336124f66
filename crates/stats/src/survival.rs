//! Times to an event (a mechanism's first jam): the median, and the Kaplan-Meier survival curve
//! with its exact 95 % band.

use crate::clopper_pearson95;

/// The median of `values` (`None` for none): the middle value, or the mean of the two middle
/// values of an even count.
#[must_use]
pub fn median(values: &[f64]) -> Option<f64> {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(v[n / 2]),
        _ => Some(0.5 * (v[n / 2 - 1] + v[n / 2])),
    }
}

/// One step of a Kaplan-Meier curve: from `day` on, `survival` [%] of the runs have not had the
/// event, with the 95 % band `lo..hi` [%].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The day the step starts.
    pub day: f64,
    /// Surviving share [%].
    pub survival: f64,
    /// Lower end of the 95 % band [%].
    pub lo: f64,
    /// Upper end of the 95 % band [%].
    pub hi: f64,
}

/// Kaplan-Meier survival from day 0 to `horizon`: `times` holds each run's event day, `None`
/// for a run still going at the horizon (events after the horizon count as none). The first
/// step is day 0 at 100 %; then one step per distinct event day.
///
/// S(t) = Π over event days d ≤ t of (1 − k_d / n_d), with k_d events among the n_d runs still
/// at risk. Every run is observed to the same horizon (no run leaves the study early), so S(t)
/// is the share of runs without an event by t, a binomial proportion, and its band is the exact
/// Clopper-Pearson interval of that count ([`clopper_pearson95`]) - which, unlike Greenwood's
/// variance, is not empty at 100 % or 0 %.
#[must_use]
pub fn kaplan_meier(times: &[Option<f64>], horizon: f64) -> Vec<Step> {
    let mut events: Vec<f64> = times
        .iter()
        .flatten()
        .copied()
        .filter(|&d| d <= horizon)
        .collect();
    events.sort_by(f64::total_cmp);
    let n = times.len() as u64;
    let step = |day: f64, surviving: u64| {
        let band = clopper_pearson95(surviving, n);
        Step {
            day,
            survival: if n == 0 {
                100.0
            } else {
                100.0 * surviving as f64 / n as f64
            },
            lo: if n == 0 { 100.0 } else { 100.0 * band.lo },
            hi: if n == 0 { 100.0 } else { 100.0 * band.hi },
        }
    };
    let mut surviving = n;
    let mut steps = vec![step(0.0, n)];
    let mut i = 0;
    while i < events.len() {
        let d = events[i];
        while i < events.len() && events[i] == d {
            surviving -= 1;
            i += 1;
        }
        steps.push(step(d, surviving));
    }
    steps
}

/// The surviving share [%] at `day` (after any event on that very day).
#[must_use]
pub fn survival_at(steps: &[Step], day: f64) -> f64 {
    steps
        .iter()
        .take_while(|p| p.day <= day)
        .last()
        .map_or(100.0, |p| p.survival)
}

/// The curve as (day, survival) points for drawing: pairs at each event day (before, after), so
/// straight lines between them draw the steps, ending at `horizon`.
#[must_use]
pub fn step_points(steps: &[Step], horizon: f64) -> Vec<(f64, f64)> {
    let mut points = Vec::with_capacity(2 * steps.len() + 1);
    let mut last = 100.0;
    for (i, st) in steps.iter().enumerate() {
        if i == 0 {
            points.push((st.day, st.survival));
        } else {
            points.push((st.day, last));
            points.push((st.day, st.survival));
        }
        last = st.survival;
    }
    points.push((horizon, last));
    points
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), Some(2.5));
    }

    #[test]
    fn kaplan_meier_steps_and_points() {
        // 4 runs: events on days 10 and 10 and 30, one censored at 100.
        let steps = kaplan_meier(&[Some(30.0), None, Some(10.0), Some(10.0)], 100.0);
        let at: Vec<(f64, f64)> = steps.iter().map(|s| (s.day, s.survival)).collect();
        assert_eq!(at, [(0.0, 100.0), (10.0, 50.0), (30.0, 25.0)]);
        assert_eq!(
            step_points(&steps, 100.0),
            [
                (0.0, 100.0),
                (10.0, 100.0),
                (10.0, 50.0),
                (30.0, 50.0),
                (30.0, 25.0),
                (100.0, 25.0)
            ]
        );
        assert_eq!(survival_at(&steps, 5.0), 100.0);
        assert_eq!(survival_at(&steps, 10.0), 50.0);
        assert_eq!(survival_at(&steps, 99.0), 25.0);
        assert_eq!(
            step_points(&kaplan_meier(&[None, None], 5.0), 5.0),
            [(0.0, 100.0), (5.0, 100.0)]
        );
    }

    #[test]
    fn the_band_is_the_exact_binomial_interval() {
        // 10 runs, 3 events on day 5: 7 of 10 survive, Clopper-Pearson 34.75 .. 93.33 %.
        let times: Vec<Option<f64>> = (0..10).map(|i| (i < 3).then_some(5.0)).collect();
        let steps = kaplan_meier(&times, 10.0);
        let s = steps[1];
        assert!((s.survival - 70.0).abs() < 1e-12);
        assert!((s.lo - 34.75).abs() < 0.01, "{s:?}");
        assert!((s.hi - 93.33).abs() < 0.01, "{s:?}");
        // Nobody yet: 10 of 10, whose interval still reaches down to 69.2 %.
        assert!((steps[0].lo - 69.15).abs() < 0.01, "{:?}", steps[0]);
        assert_eq!(steps[0].hi, 100.0);
    }
}
