//! The Theoretical Difference of one run against the driver's angle (`pair.svg`), its events
//! numbered as the event table numbers them and drawn by kind, readable with many events.

use contact::Trajectory;
use registry::RunError;

use crate::chart::{Mark, Plot, Series};

/// The kinds of the events of `traj` as a legend names them (`lock, counted as a jam: 25`),
/// and each event's index into them, in event order.
fn kinds_of(
    traj: &Trajectory,
    counted: &dyn Fn(&contact::Event) -> &'static str,
) -> (Vec<String>, Vec<usize>) {
    let mut keys: Vec<(&'static str, &'static str)> = Vec::new();
    let mut counts: Vec<usize> = Vec::new();
    let groups = traj
        .events()
        .iter()
        .map(|e| {
            let key = (e.label(), counted(e));
            let g = keys.iter().position(|k| *k == key).unwrap_or_else(|| {
                keys.push(key);
                counts.push(0);
                keys.len() - 1
            });
            counts[g] += 1;
            g
        })
        .collect();
    let names = keys
        .iter()
        .zip(&counts)
        .map(|((kind, counted), n)| match *counted {
            "-" => format!("{kind}, not a failure under the rule: {n}"),
            c => format!("{kind}, counted as a {c}: {n}"),
        })
        .collect();
    (names, groups)
}

/// The value of the polyline `points` (sorted by x) at `x`, by straight interpolation.
fn value_at(points: &[(f64, f64)], x: f64) -> Option<f64> {
    let i = points.partition_point(|p| p.0 < x);
    match (points.get(i.wrapping_sub(1)), points.get(i)) {
        (Some(a), Some(b)) if b.0 > a.0 => Some(a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)),
        (_, Some(b)) => Some(b.1),
        (Some(a), None) => Some(a.1),
        (None, None) => None,
    }
}

/// The title of the plot of run `name` with `events` events, all of them numbered or (`every`
/// false) as many as there is room for.
fn title(name: &str, events: usize, every: bool) -> String {
    let numbered = if every {
        "numbered as in the event table"
    } else {
        "numbered as in the event table where there is room (event-log.csv lists every one)"
    };
    match events {
        0 => format!(
            "Theoretical Difference of {name} (sections 2-3): no event, the driven gear driven throughout"
        ),
        1 => format!("Theoretical Difference of {name} (sections 2-3): its one event, {numbered}"),
        n => format!("Theoretical Difference of {name} (sections 2-3): its {n} events, {numbered}"),
    }
}

/// `pair.svg`: the Theoretical Difference `td` (points of φ − φ0 and TD, in degrees) of run
/// `traj` of `name`, drawn as a line without markers; each event a marker on the curve in the
/// style of its kind (what `counted` counts it as), and a numbered tick in a band above the
/// data, every number inside the frame and apart from the others (in as many rows as they
/// need, on a leader where one had to move; the title says so if some had to be left out); the
/// stretch after the first lock greyed as the paper's protocol.
pub fn td_plot(
    name: &str,
    traj: &Trajectory,
    counted: &dyn Fn(&contact::Event) -> &'static str,
    td: &[(f64, f64)],
) -> Result<String, RunError> {
    let (kinds, groups) = kinds_of(traj, counted);
    let phi0 = traj.phi_start();
    let marks: Vec<Mark> = traj
        .events()
        .iter()
        .zip(groups)
        .enumerate()
        .map(|(i, (e, group))| {
            let x = (e.phi - phi0).to_degrees();
            Mark {
                x,
                y: value_at(td, x),
                number: i + 1,
                group,
            }
        })
        .collect();
    let series = [Series {
        label: "Theoretical Difference of the run (line; sampled)",
        points: td.to_vec(),
    }];
    let first = crate::pair_html::first_lock(traj.events());
    let protocol = first.map(|f| {
        format!(
            "grey: after the first lock (event {}), the paper's protocol - the driven gear let go to the next free position and driven on - not a physical motion",
            f + 1
        )
    });
    let drawn = |title: &str| {
        let plot = Plot::new(
            title,
            "driver angle from the start phi - phi0 [deg]",
            "Theoretical Difference [deg]",
            &series,
        )
        .plain_lines()
        .marks(&marks, &kinds);
        match (first, &protocol) {
            (Some(f), Some(label)) => plot.shaded_from(marks[f].x, label).svg(),
            _ => plot.svg(),
        }
    };
    let svg = drawn(&title(name, marks.len(), true))?;
    if crate::chart::every_mark_numbered(&svg, marks.len()) {
        Ok(svg)
    } else {
        drawn(&title(name, marks.len(), false))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    use super::*;
    use contact::{Solve, Start};

    fn td_of(traj: &Trajectory, n: usize) -> Vec<(f64, f64)> {
        let (phi0, phi1) = (traj.phi_start(), traj.phi_end());
        let theta0 = traj.theta_at(phi0);
        let ratio = traj.mesh().driver().teeth() as f64 / traj.mesh().driven().teeth() as f64;
        (0..=n)
            .map(|i| {
                let phi = phi0 + (phi1 - phi0) * i as f64 / n as f64;
                (
                    (phi - phi0).to_degrees(),
                    ((traj.theta_at(phi) - theta0) - ratio * (phi - phi0)).to_degrees(),
                )
            })
            .collect()
    }

    #[test]
    fn a_run_without_events_promises_no_marks() {
        let mesh = crate::test_pair::ideal_20_30(0.3);
        let traj = mesh.solve(0.0..=1.0, Start::Touching(0.0), Solve::path());
        assert!(traj.events().is_empty());
        let svg = td_plot("a test pair", &traj, &|_| "-", &td_of(&traj, 50)).unwrap();
        assert!(svg.contains("no event"), "{svg}");
        assert!(!svg.contains("mark-tick"), "{svg}");
    }

    #[test]
    fn every_event_gets_a_tick_and_the_legend_names_its_kind() {
        // Gears so far apart that the tips slip past each other again and again.
        let mesh = crate::test_pair::ideal_20_30(1.09);
        let traj = mesh.solve(
            0.0..=std::f64::consts::TAU * 3.0,
            Start::Touching(0.0),
            Solve::path(),
        );
        let n = traj.events().len();
        assert!(n >= 1, "the loose mesh must have an event");
        let svg = td_plot(
            "a test pair",
            &traj,
            &|_| "disengagement",
            &td_of(&traj, 400),
        )
        .unwrap();
        assert_eq!(svg.matches("class=\"mark-tick\"").count(), n);
        let said = if n == 1 {
            "its one event".to_string()
        } else {
            format!("its {n} events")
        };
        assert!(svg.contains(&said), "{svg}");
        assert!(svg.contains("counted as a disengagement"), "{svg}");
    }
}
