//! Claims that rest on whole mechanisms run with Edmunds' errors (section 5's 30-run study and
//! the conclusions).

use crate::results::failure::{FailureInput, FailureStudy, TrainSummary};
use crate::whole_mechanism::MECHANISM;

use super::{Judged, Verdict};

/// What the paper reports of its 30 runs with Edmunds' measured errors (section 5), from the
/// reference file: the share of mechanisms that jammed, % of runs, and each train's mean day of
/// its first jam.
#[derive(Debug, Clone, PartialEq)]
pub struct PaperRuns {
    /// Mechanisms that jammed, % of the runs.
    pub jammed_percent: f64,
    /// Runs the share is of.
    pub runs: u64,
    /// (train as the study names it, the paper's mean day of its first jam).
    pub mean_days: Vec<(String, f64)>,
}

fn mechanism(input: &FailureInput) -> Option<&TrainSummary> {
    input.trains.iter().find(|t| t.train == MECHANISM)
}

fn share_words(t: &TrainSummary) -> String {
    let s = t.within_year;
    format!(
        "{}/{} ({:.0} % [{:.0} .. {:.0}])",
        s.k,
        s.n,
        100.0 * s.k as f64 / s.n.max(1) as f64,
        100.0 * s.lo,
        100.0 * s.hi
    )
}

/// Each Case's share of mechanisms jammed within a year, for orientation where the paper's own
/// input (Edmunds' measured errors) is not there.
fn cases_words(study: &FailureStudy) -> String {
    study
        .inputs
        .iter()
        .filter(|i| !i.measured)
        .filter_map(|i| mechanism(i).map(|t| format!("Case {} {}", i.label, share_words(t))))
        .collect::<Vec<_>>()
        .join("; ")
}

/// C10: "We simulated a model 30 times using Edmunds' error values and an optimal separation (G)
/// of 40%, which resulted in jamming in 90% of instances. On average, the Lunar train jammed
/// after 129 days, the Metonic and Games train ... 234 days ..., the Saros and Exeligmos train
/// ... 121 days" (section 5). Testable only with Edmunds' per-gear measured errors (a
/// `measured` input): then the paper's share is compared with ours by Fisher's exact two-sample
/// test and each mean day by whether it lies in our 95 % interval. Without them: not testable,
/// with each Case's share shown for orientation.
pub fn thirty_runs(study: &FailureStudy, paper: &PaperRuns) -> Judged {
    let paper_words = format!(
        "{:.0} % of {} jammed; mean days {}",
        paper.jammed_percent,
        paper.runs,
        paper
            .mean_days
            .iter()
            .map(|(t, d)| format!("{t} {d:.0}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let Some(measured) = study.inputs.iter().find(|i| i.measured) else {
        return Judged {
            verdict: Verdict::NotTestable,
            ours: format!("with Edmunds' Cases instead: {}", cases_words(study)),
            paper: paper_words,
            reason: "the paper ran Edmunds' per-gear measured errors, which are not published openly; give them with --set measured=FILE".into(),
        };
    };
    let Some(m) = mechanism(measured) else {
        return Judged {
            verdict: Verdict::NotTestable,
            ours: "no mechanism row".into(),
            paper: paper_words,
            reason: "the study has no mechanism row".into(),
        };
    };
    let paper_k = (paper.jammed_percent / 100.0 * paper.runs as f64).round() as u64;
    let share_ok = stats::consistent(m.within_year.k, m.within_year.n, paper_k, paper.runs);
    let mut parts = vec![Verdict::from_bool(share_ok)];
    let mut days = Vec::new();
    for (train, day) in &paper.mean_days {
        let ours = measured.trains.iter().find(|t| &t.train == train);
        match ours.and_then(|t| t.mean_day) {
            Some(md) => {
                parts.push(Verdict::from_bool(md.lo <= *day && *day <= md.hi));
                days.push(format!(
                    "{train} {:.0} [{:.0} .. {:.0}]",
                    md.mean, md.lo, md.hi
                ));
            }
            None => {
                parts.push(Verdict::Differs);
                days.push(format!("{train} never jammed"));
            }
        }
    }
    Judged {
        verdict: Verdict::of_parts(&parts),
        ours: format!("{} jammed; mean days {}", share_words(m), days.join(", ")),
        paper: paper_words,
        reason: "share by Fisher's exact two-sample test, each mean day inside our 95 % interval"
            .into(),
    }
}

/// The share of `t`'s runs not yet jammed on `day` (Kaplan-Meier), %.
fn surviving_on(t: &TrainSummary, day: f64) -> f64 {
    t.survival
        .iter()
        .take_while(|s| s.day <= day)
        .last()
        .map_or(100.0, |s| s.survival)
}

/// C11: "A mechanism with the errors found by Edmunds would generally stop after the solar
/// pointer completed one-third (120°) of its full rotation" (conclusions). "Generally": more than
/// half of the mechanisms have jammed by the day the solar pointer has turned `stop_deg`
/// (Kaplan-Meier: fewer than half still running). Testable only with the measured errors, as
/// C10; the Cases are shown for orientation.
pub fn stops_within_a_third(study: &FailureStudy, stop_deg: f64) -> Judged {
    let day = stop_deg / 360.0 * train::DAYS_PER_TURN;
    let running = |i: &FailureInput| mechanism(i).map(|t| surviving_on(t, day));
    let paper = format!("more than half stop by day {day:.0} ({stop_deg:.0}° of the Sun)");
    let cases: Vec<String> = study
        .inputs
        .iter()
        .filter_map(|i| running(i).map(|r| format!("Case {} {:.0} % still running", i.label, r)))
        .collect();
    match study.inputs.iter().find(|i| i.measured).and_then(running) {
        Some(r) => Judged {
            verdict: Verdict::from_bool(r < 50.0),
            ours: format!("{r:.0} % still running on day {day:.0}"),
            paper,
            reason: "Kaplan-Meier share still running on that day below 50 %".into(),
        },
        None => Judged {
            verdict: Verdict::NotTestable,
            ours: format!("on day {day:.0}: {}", cases.join("; ")),
            paper,
            reason: "rests on Edmunds' per-gear measured errors, which are not here (--set measured=FILE)".into(),
        },
    }
}

/// C12: "either the mechanism never functioned, or its errors were smaller than those found by
/// Edmunds" (abstract, conclusions). Judged on the failure study at Edmunds' own summary of the
/// errors - he concluded the mechanism "could have functioned better than Case C and probably as
/// well as Case B" (section 4) - and on the verdicts of the claims the conclusion rests on
/// (`supporting`: claim id and its verdict under the same reading). The failure study's part holds
/// if a mechanism with Case B's errors jams within a year in most runs (the 95 % interval of the
/// share above one half), in part if only Case C's do, and differs if neither; the conclusion holds
/// where that part and every supporting claim hold.
pub fn the_conclusion(study: &FailureStudy, supporting: &[(&str, Verdict)]) -> Judged {
    let most = |label: &str| {
        study
            .inputs
            .iter()
            .find(|i| !i.measured && i.label == label)
            .and_then(mechanism)
            .map(|t| (t.within_year.lo > 0.5, share_words(t)))
    };
    let (b, c) = (most("B"), most("C"));
    let jams = match (&b, &c) {
        (Some((true, _)), _) => Verdict::Holds,
        (Some((false, _)), Some((true, _))) => Verdict::HoldsInPart,
        (Some(_), Some(_)) => Verdict::Differs,
        _ => Verdict::NotTestable,
    };
    let mut parts = vec![jams];
    parts.extend(supporting.iter().map(|(_, v)| *v));
    let verdict = Verdict::of_parts(&parts);
    let words =
        |x: &Option<(bool, String)>| x.as_ref().map_or("not run".into(), |(_, w)| w.clone());
    let resting = supporting
        .iter()
        .map(|(id, v)| format!("{id} {}", v.words()))
        .collect::<Vec<_>>()
        .join(", ");
    Judged {
        verdict,
        ours: format!(
            "mechanisms jammed within a year: Case B {}; Case C {}; resting on {resting}",
            words(&b),
            words(&c)
        ),
        paper: "with Edmunds' errors the mechanism would jam (90 % of 30 runs)".into(),
        reason: format!(
            "{}; and the claims it rests on: {resting}",
            match jams {
                Verdict::Holds =>
                    "with Case B's errors, Edmunds' own estimate, most mechanisms jam within a year",
                Verdict::HoldsInPart =>
                    "most mechanisms jam within a year with Case C's errors, but not with Case B's, Edmunds' own estimate",
                Verdict::Differs => "with Case B's and Case C's errors most mechanisms run a year",
                Verdict::NotTestable => "the failure study ran no Case B or C",
            }
        ),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use crate::results::{MeanDay, Share, SurvivalStep};

    /// An input whose mechanism row jammed `k` of `n` runs within a year, the runs still going
    /// falling to `left` % on day 100, with the Lunar train's mean day `lunar`.
    fn input(label: &str, measured: bool, k: u64, left: f64, lunar: Option<f64>) -> FailureInput {
        let share = stats::clopper_pearson95(k, 30);
        let train = |name: &str, mean_day: Option<MeanDay>| TrainSummary {
            train: name.into(),
            within_year: Share::from(share),
            mean_day,
            survival: vec![
                SurvivalStep {
                    day: 0.0,
                    survival: 100.0,
                    lo: 100.0,
                    hi: 100.0,
                },
                SurvivalStep {
                    day: 100.0,
                    survival: left,
                    lo: left,
                    hi: left,
                },
            ],
            ..TrainSummary::default()
        };
        let day = |d: f64| MeanDay {
            mean: d,
            lo: d - 20.0,
            hi: d + 20.0,
            n: k as usize,
        };
        FailureInput {
            label: label.into(),
            measured,
            trains: vec![
                train("Lunar", lunar.map(day)),
                train(MECHANISM, lunar.map(day)),
            ],
            ..FailureInput::default()
        }
    }

    fn study(inputs: Vec<FailureInput>) -> FailureStudy {
        FailureStudy {
            horizon: 365.25,
            runs_per_input: 30,
            inputs,
        }
    }

    fn paper() -> PaperRuns {
        PaperRuns {
            jammed_percent: 90.0,
            runs: 30,
            mean_days: vec![("Lunar".into(), 129.0)],
        }
    }

    #[test]
    fn thirty_runs_need_the_measured_errors_and_then_move_with_them() {
        let cases = study(vec![input("B", false, 27, 10.0, Some(120.0))]);
        assert_eq!(thirty_runs(&cases, &paper()).verdict, Verdict::NotTestable);
        let like = study(vec![input("measured", true, 27, 10.0, Some(130.0))]);
        assert_eq!(thirty_runs(&like, &paper()).verdict, Verdict::Holds);
        let fine = study(vec![input("measured", true, 1, 97.0, None)]);
        assert_eq!(thirty_runs(&fine, &paper()).verdict, Verdict::Differs);
    }

    #[test]
    fn stopping_within_a_third_is_read_off_the_survival_curve() {
        // 120° of the Sun is day 121.75: the curve's step at day 100 counts.
        let stops = study(vec![input("measured", true, 27, 10.0, Some(80.0))]);
        assert_eq!(stops_within_a_third(&stops, 120.0).verdict, Verdict::Holds);
        let runs = study(vec![input("measured", true, 5, 80.0, Some(80.0))]);
        assert_eq!(stops_within_a_third(&runs, 120.0).verdict, Verdict::Differs);
        // Before day 100 nothing has stopped yet.
        assert_eq!(stops_within_a_third(&stops, 90.0).verdict, Verdict::Differs);
        let cases = study(vec![input("B", false, 27, 10.0, Some(80.0))]);
        assert_eq!(
            stops_within_a_third(&cases, 120.0).verdict,
            Verdict::NotTestable
        );
    }

    #[test]
    fn the_conclusion_follows_case_b_and_the_claims_it_rests_on() {
        let jams = study(vec![
            input("B", false, 28, 5.0, Some(90.0)),
            input("C", false, 30, 0.0, Some(40.0)),
        ]);
        let held = [("C5", Verdict::Holds)];
        assert_eq!(the_conclusion(&jams, &held).verdict, Verdict::Holds);
        let j = the_conclusion(&jams, &[("C5", Verdict::Differs)]);
        assert_eq!(j.verdict, Verdict::HoldsInPart, "{j:?}");
        assert!(j.reason.contains("C5 differs"), "{}", j.reason);
        let runs = study(vec![
            input("B", false, 2, 95.0, Some(300.0)),
            input("C", false, 3, 90.0, Some(300.0)),
        ]);
        assert_eq!(the_conclusion(&runs, &[]).verdict, Verdict::Differs);
    }
}
