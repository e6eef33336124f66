//! Claims that rest on the pointers and single pairs: ideal teeth against Edmunds' errors
//! (Tables 1 and 2), the two models on the same gears (Table 2, Figure 5), the clearance
//! (Figure IV, Appendix II).

use crate::results::{CasePointers, IdealPointers, SigmaAgainstClearance, SplitPairs};

use super::{Judged, Verdict};

/// The pointers both tables give: Edmunds' Table 2 has the Lunar, Metonic and Saros pointers.
fn shared_pointers<'a>(ideal: &'a IdealPointers, cases: &'a CasePointers) -> Vec<&'a str> {
    ideal
        .pointers
        .iter()
        .map(|p| p.pointer.as_str())
        .filter(|name| {
            cases
                .cases
                .first()
                .is_some_and(|c| c.pointers.iter().any(|p| p.pointer == *name))
        })
        .collect()
}

/// The geometric mean over pointers of Edmunds' σ over ideal teeth's, from (pointer, σ with
/// ideal teeth, σ under Edmunds' model) per pointer; pointers with a σ of 0 are left out.
pub fn ratio_of_sigmas(per_pointer: &[(String, f64, f64)]) -> Option<f64> {
    let logs: Vec<f64> = per_pointer
        .iter()
        .filter(|(_, ideal, edmunds)| *ideal > 0.0 && *edmunds > 0.0)
        .map(|(_, ideal, edmunds)| (edmunds / ideal).ln())
        .collect();
    (!logs.is_empty()).then(|| (logs.iter().sum::<f64>() / logs.len() as f64).exp())
}

/// C1: "the triangular shape in ideal teeth introduces deviations that are almost negligible
/// compared to those identified by Edmunds, being on average seven times smaller" (conclusions;
/// Table 1 against Table 2). Ours: σ of each pointer with ideal triangular teeth (`ideal`, Table 1)
/// against σ of Edmunds' radial model in Case A, his smallest errors (`cases`, Table 2's model),
/// as the geometric mean of the ratios; the paper's figure `paper` is the same ratio of its own
/// Tables 1 and 2 (pointer, its Table 1 σ, its Table 2 Case A σ). Holds if ours is within a factor
/// of two of the paper's, in part if ideal teeth still give the smaller errors (ratio above 1),
/// differs otherwise.
pub fn ideal_teeth_negligible(
    ideal: &IdealPointers,
    cases: &CasePointers,
    paper: &[(String, f64, f64)],
) -> Judged {
    let Some(case_a) = cases.cases.iter().find(|c| c.case == "A") else {
        return not_run("Table 2 ran no Case A");
    };
    let both: Vec<(String, stats::Estimate, stats::Estimate)> = shared_pointers(ideal, cases)
        .into_iter()
        .filter_map(|name| {
            let i = ideal.pointers.iter().find(|p| p.pointer == name)?;
            let e = case_a.pointers.iter().find(|p| p.pointer == name)?;
            Some((name.to_owned(), i.sigma(), e.edmunds_sigma()))
        })
        .collect();
    let pick =
        |f: fn(&stats::Estimate, &stats::Estimate) -> (f64, f64)| -> Vec<(String, f64, f64)> {
            both.iter()
                .map(|(n, i, e)| {
                    let (a, b) = f(i, e);
                    (n.clone(), a, b)
                })
                .collect()
        };
    let ours = pick(|i, e| (i.mean, e.mean));
    // The ratio's 95 % range from the two t intervals: smallest Edmunds over largest ideal, and
    // the other way round.
    let low = ratio_of_sigmas(&pick(|i, e| (i.hi, e.lo.max(0.0))));
    let high = ratio_of_sigmas(&pick(|i, e| (i.lo.max(0.0), e.hi)));
    let (Some(r), Some(p)) = (ratio_of_sigmas(&ours), ratio_of_sigmas(paper)) else {
        return not_run("no pointer with both sigmas");
    };
    let range = match (low, high) {
        (Some(l), Some(h)) => format!(" [{l:.1} .. {h:.1}]"),
        _ => String::new(),
    };
    let each = |v: &[(String, f64, f64)]| {
        v.iter()
            .map(|(n, i, e)| format!("{n} {:.1}x", e / i))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let verdict = if r >= p / 2.0 && r <= p * 2.0 {
        Verdict::Holds
    } else if r > 1.0 {
        Verdict::HoldsInPart
    } else {
        Verdict::Differs
    };
    Judged {
        verdict,
        ours: format!(
            "Edmunds' Case A sigma {r:.1}{range} times ideal teeth's ({})",
            each(&ours)
        ),
        paper: format!("{p:.1} times ({})", each(paper)),
        reason: match verdict {
            Verdict::Holds => "ideal teeth's errors are smaller by about the paper's factor (within a factor of 2)".into(),
            Verdict::HoldsInPart => "ideal teeth's errors are smaller, but not by about the paper's factor".into(),
            _ => "ideal teeth's errors are not smaller than Edmunds'".into(),
        },
    }
}

fn not_run(why: &str) -> Judged {
    Judged {
        verdict: Verdict::NotTestable,
        ours: "-".into(),
        paper: "-".into(),
        reason: why.into(),
    }
}

/// C3: "when we introduced tooth errors and eccentricity into our model of gears with triangular
/// teeth, the theoretical deviations of the indicators did not differ significantly from those
/// found by Edmunds" (conclusions; Table 2, Figure 5). Ours: for every Case and pointer of Table 2,
/// the paired difference of σ between triangular teeth and Edmunds' radial model on the same
/// gears, with its 95 % interval. Holds if every interval holds 0 or the difference is within 10 %
/// of Edmunds' σ; in part if most do; differs otherwise.
pub fn same_as_edmunds(cases: &CasePointers) -> Judged {
    let mut close = 0;
    let mut all = 0;
    let mut worst: Option<(String, f64)> = None;
    for c in &cases.cases {
        for p in &c.pointers {
            let (d, e) = (p.sigma_difference(), p.edmunds_sigma());
            let relative = d.mean / e.mean.max(f64::MIN_POSITIVE);
            all += 1;
            if (d.lo <= 0.0 && d.hi >= 0.0) || relative.abs() <= 0.10 {
                close += 1;
            }
            if worst.as_ref().is_none_or(|(_, w)| relative.abs() > w.abs()) {
                worst = Some((format!("{} {}", c.case, p.pointer), relative));
            }
        }
    }
    if all == 0 {
        return not_run("Table 2 ran no Case");
    }
    let verdict = if close == all {
        Verdict::Holds
    } else if 2 * close > all {
        Verdict::HoldsInPart
    } else {
        Verdict::Differs
    };
    let worst = worst.map_or(String::new(), |(w, r)| {
        format!("; largest: {w} {:+.0} %", 100.0 * r)
    });
    Judged {
        verdict,
        ours: format!(
            "{close} of {all} Case-pointer sigmas within 10 % or not separated at 95 %{worst}"
        ),
        paper:
            "not significantly different; sometimes slightly greater, sometimes slightly smaller"
                .into(),
        reason: "paired difference of sigma, triangular minus radial, on the same gears".into(),
    }
}

/// C4: "changing the percentage of systematic error applied to one cause or the other does not
/// produce a significant effect on the final behavior of a hypothetical pointer" (section 4,
/// Figure 5). Ours: σ of triangular teeth under the three splits (all eccentricity, 50/50, all
/// sinusoid) of Figure 5's pair. Holds if the largest is within 25 % of the smallest (the spread
/// Figure 5's panels show as "similar"), in part within a factor of 2, differs otherwise.
pub fn split_does_not_matter(fig5: &SplitPairs) -> Judged {
    let Some((lo, hi)) = fig5.triangular_sigma_range() else {
        return not_run("no split drove the gear");
    };
    let spread = hi / lo.max(f64::MIN_POSITIVE);
    let each = fig5
        .splits
        .iter()
        .map(|s| format!("{} {:.3}°", s.name, s.triangular_sigma))
        .collect::<Vec<_>>()
        .join(", ");
    let verdict = if spread <= 1.25 {
        Verdict::Holds
    } else if spread <= 2.0 {
        Verdict::HoldsInPart
    } else {
        Verdict::Differs
    };
    Judged {
        verdict,
        ours: format!("sigma {each}: largest/smallest {spread:.2}"),
        paper: "similar behaviour in all cases (Figure 5 A-C)".into(),
        reason:
            "largest over smallest sigma of the three splits: at most 1.25 holds, at most 2 in part"
                .into(),
    }
}

/// The paper's clearance figures (Appendix II, section 3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperClearance {
    /// Below this G (% of h) the teeth jam.
    pub jam_below: f64,
    /// Above this G the gears disengage.
    pub disengage_above: f64,
    /// The smallest σ lies between these two G.
    pub minimum_from: f64,
    /// See `minimum_from`.
    pub minimum_to: f64,
}

/// C2: "When G is less than 10% of h, jamming occurs, and when it exceeds 90% of h, disengagement
/// happens. Acceptable values for G are around 40%" (section 3); "a minimum occurs around 40% to
/// 50% separation" (Appendix II, Figure IV). Ours, over Figure IV's meshes: the largest jam limit
/// (the G below which some mesh jams), the smallest disengagement limit, and where each mesh's σ
/// is smallest. Three parts: the jam limit within 5 points of h of the paper's, the
/// disengagement limit within 5 points, and G = 40 % no farther from the mesh's best G than the
/// paper's band is wide (40-50 %: within 10 points) for most meshes.
pub fn clearance_limits(sweep: &SigmaAgainstClearance, paper: PaperClearance) -> Judged {
    let jam = sweep
        .meshes
        .iter()
        .filter_map(|m| m.jam_limit)
        .reduce(f64::max);
    let dis = sweep
        .meshes
        .iter()
        .filter_map(|m| m.disengagement_limit)
        .reduce(f64::min);
    let best: Vec<f64> = sweep
        .meshes
        .iter()
        .filter_map(|m| m.smallest_sigma_at)
        .collect();
    let band = paper.minimum_to - paper.minimum_from;
    let near_40 = best
        .iter()
        .filter(|&&g| g >= paper.minimum_from - band && g <= paper.minimum_to + band)
        .count();
    let within = |ours: Option<f64>, theirs: f64| {
        Verdict::from_bool(ours.is_some_and(|x| (x - theirs).abs() <= 5.0))
    };
    let parts = [
        within(jam, paper.jam_below),
        within(dis, paper.disengage_above),
        Verdict::from_bool(2 * near_40 > best.len()),
    ];
    let g = |x: Option<f64>| x.map_or("none".into(), |v| format!("{v:.0} %"));
    Judged {
        verdict: Verdict::of_parts(&parts),
        ours: format!(
            "jams below {} of h, disengages above {}; smallest sigma within {:.0}-{:.0} % for {near_40} of {} meshes",
            g(jam),
            g(dis),
            paper.minimum_from - band,
            paper.minimum_to + band,
            best.len()
        ),
        paper: format!(
            "jams below {:.0} %, disengages above {:.0} %; smallest sigma at {:.0}-{:.0} %",
            paper.jam_below, paper.disengage_above, paper.minimum_from, paper.minimum_to
        ),
        reason:
            "limits within 5 points of h of the paper's; the best G near 40-50 % for most meshes"
                .into(),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use crate::pointers::{BothModels, PointerTrial};
    use crate::results::{CasePointer, CaseRun, IdealPointer, MeshSweep, SplitRun};

    fn ideal(sigmas: &[(&str, [f64; 3])]) -> IdealPointers {
        IdealPointers {
            clearance: 40.0,
            tooth_height: 1.0,
            trials: 3,
            pointers: sigmas
                .iter()
                .map(|(name, s)| IdealPointer {
                    pointer: (*name).into(),
                    turns: 1.0,
                    samples: 10,
                    meshes: 3,
                    ratio: None,
                    days_per_degree: None,
                    trials: s
                        .iter()
                        .map(|&sigma| PointerTrial {
                            sigma,
                            dm: 2.0 * sigma,
                            mean: 0.0,
                            stopped: false,
                        })
                        .collect(),
                })
                .collect(),
        }
    }

    /// Case A with (pointer, [(Edmunds' σ, triangular σ); trials]).
    fn case_a(pointers: &[(&str, [(f64, f64); 3])]) -> CasePointers {
        CasePointers {
            clearance: 40.0,
            trials: 3,
            pin_and_slot: false,
            pointers: pointers.iter().map(|(n, _)| ((*n).into(), None)).collect(),
            cases: vec![CaseRun {
                case: "A".into(),
                systematic: 0.5,
                random: 0.04,
                pointers: pointers
                    .iter()
                    .map(|(n, t)| CasePointer {
                        pointer: (*n).into(),
                        trials: t
                            .iter()
                            .map(|&(e, tri)| BothModels {
                                edmunds_sigma: e,
                                edmunds_dm: 2.0 * e,
                                triangular_sigma: tri,
                                triangular_dm: 2.0 * tri,
                                jammed: false,
                            })
                            .collect(),
                    })
                    .collect(),
            }],
        }
    }

    #[test]
    fn ideal_teeth_seven_times_smaller_hold_and_equal_ones_differ() {
        let paper = vec![("Lunar".to_owned(), 0.6, 4.4)];
        let i = ideal(&[("Lunar", [0.59, 0.6, 0.61]), ("Games", [0.1; 3])]);
        let seven = case_a(&[("Lunar", [(4.3, 4.3), (4.4, 4.4), (4.5, 4.5)])]);
        let j = ideal_teeth_negligible(&i, &seven, &paper);
        assert_eq!(j.verdict, Verdict::Holds, "{j:?}");
        assert!(j.ours.contains("7.3 ["), "{}", j.ours);
        let twice = case_a(&[("Lunar", [(1.2, 1.2); 3])]);
        assert_eq!(
            ideal_teeth_negligible(&i, &twice, &paper).verdict,
            Verdict::HoldsInPart
        );
        let same = case_a(&[("Lunar", [(0.6, 0.6); 3])]);
        assert_eq!(
            ideal_teeth_negligible(&i, &same, &paper).verdict,
            Verdict::Differs
        );
    }

    #[test]
    fn triangular_teeth_like_edmunds_hold_and_far_off_differ() {
        let like = case_a(&[("Lunar", [(4.0, 4.1), (4.4, 4.2), (4.5, 4.6)])]);
        assert_eq!(same_as_edmunds(&like).verdict, Verdict::Holds);
        let far = case_a(&[("Lunar", [(4.0, 8.1), (4.4, 8.3), (4.5, 8.6)])]);
        let j = same_as_edmunds(&far);
        assert_eq!(j.verdict, Verdict::Differs, "{j:?}");
    }

    fn splits(sigmas: [f64; 3]) -> SplitPairs {
        SplitPairs {
            teeth: 30,
            tip_radius: 20.0,
            root_radius: 18.0,
            hypothesis: "edmunds-split".into(),
            values: vec![],
            driver_angles: vec![],
            splits: sigmas
                .iter()
                .map(|&s| SplitRun {
                    name: "x".into(),
                    sinusoid_share: 0.5,
                    edmunds_td: vec![],
                    triangular_td: vec![],
                    edmunds_sigma: s,
                    triangular_sigma: s,
                    never_driven: false,
                    jams: 0,
                    disengagements: 0,
                })
                .collect(),
        }
    }

    #[test]
    fn the_split_matters_only_when_the_sigmas_spread() {
        assert_eq!(
            split_does_not_matter(&splits([0.30, 0.32, 0.33])).verdict,
            Verdict::Holds
        );
        assert_eq!(
            split_does_not_matter(&splits([0.30, 0.45, 0.5])).verdict,
            Verdict::HoldsInPart
        );
        assert_eq!(
            split_does_not_matter(&splits([0.1, 0.3, 0.5])).verdict,
            Verdict::Differs
        );
    }

    fn sweep(meshes: &[(Option<f64>, Option<f64>, Option<f64>)]) -> SigmaAgainstClearance {
        SigmaAgainstClearance {
            tooth_height: 1.0,
            clearances: vec![10.0, 40.0, 90.0],
            meshes: meshes
                .iter()
                .map(|&(jam, dis, best)| MeshSweep {
                    mesh: "m".into(),
                    sigma: vec![],
                    jam_limit: jam,
                    disengagement_limit: dis,
                    smallest_sigma_at: best,
                })
                .collect(),
        }
    }

    #[test]
    fn the_clearance_limits_hold_near_the_papers_and_differ_far_from_them() {
        let paper = PaperClearance {
            jam_below: 10.0,
            disengage_above: 87.0,
            minimum_from: 40.0,
            minimum_to: 50.0,
        };
        let near = sweep(&[
            (Some(9.0), Some(88.0), Some(45.0)),
            (Some(7.0), Some(90.0), Some(40.0)),
        ]);
        assert_eq!(clearance_limits(&near, paper).verdict, Verdict::Holds);
        let jam_late = sweep(&[(Some(30.0), Some(88.0), Some(45.0))]);
        assert_eq!(
            clearance_limits(&jam_late, paper).verdict,
            Verdict::HoldsInPart
        );
        let far = sweep(&[(Some(30.0), Some(60.0), Some(20.0))]);
        assert_eq!(clearance_limits(&far, paper).verdict, Verdict::Differs);
    }
}
