//! `table3`: trials with at least one jam / at least one disengagement, each of the 15 meshes on
//! its own, Edmunds' Cases A-D at G = 40 %, 200 trials per cell, with 95 % Wilson intervals.

use rayon::prelude::*;
use registry::{Context, Experiment, OutputFile, Param, Report, RunError, Table};
use stats::wilson95;

use crate::errors;
use crate::gearing;
use crate::pair_jams::{Cell, trial};
use crate::table2::CASES;

const PARAMS: &[Param] = &[
    Param {
        name: "trials",
        default: "200",
        unit: "",
        help: "trials per cell (the paper: 200)",
    },
    gearing::CLEARANCE,
    gearing::TOOTH_HEIGHT,
    errors::SPLIT,
    errors::PARAM,
    errors::PARAMS_PARAM,
    gearing::PARAM,
];

registry::inventory::submit! {
    Experiment {
        id: "table3",
        title: "Jams and disengagements of each mesh on its own, Cases A-D at G = 40 %, 200 trials per cell",
        paper_item: "Table 3 (section 5)",
        params: PARAMS,
        config: None,
        run,
    }
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    let g = gearing::load(ctx)?;
    let hyp = errors::chosen(ctx)?;
    let trials = ctx.u64("trials")?;
    if trials == 0 {
        return Err(RunError::bad("--set", "trials", "must be at least 1"));
    }
    let (h, clearance, split) = (
        ctx.f64("tooth_height")?,
        ctx.f64("clearance")?,
        ctx.f64("split")?,
    );
    let meshes: Vec<&str> = g.meshes().iter().map(|m| m.label.as_str()).collect();
    let mut params = Vec::new();
    for &(_, systematic, random) in &CASES {
        params.push(errors::params(
            ctx,
            hyp,
            &[
                ("random", random),
                ("systematic", systematic),
                ("split", split),
            ],
        )?);
    }
    // Every (case, mesh, trial) is independent: run them all in parallel, collected in order.
    let jobs: Vec<(usize, usize, u64)> = (0..CASES.len())
        .flat_map(|c| (0..meshes.len()).flat_map(move |m| (0..trials).map(move |t| (c, m, t))))
        .collect();
    let seed = ctx.seed();
    let outcomes: Result<Vec<(bool, bool)>, RunError> = jobs
        .par_iter()
        .map(|&(c, m, t)| {
            let cell = Cell {
                mesh: meshes[m],
                hypothesis: hyp,
                params: &params[c],
                tooth_height: h,
                clearance,
                index: (c * meshes.len() + m) as u64,
            };
            trial(&g, &cell, seed, t)
        })
        .collect();
    let outcomes = outcomes?;

    let mut header = vec!["case".to_string()];
    header.extend(meshes.iter().map(|m| (*m).to_string()));
    let mut ours = Table::new(
        format!(
            "Table 3: trials (of {trials}) with at least one jam / disengagement, G = {clearance} %: ours (paper); * where the paper's count is outside our 95 % interval"
        ),
        header,
    );
    let mut csv = String::from(
        "case,mesh,jams,jam_lo,jam_hi,paper_jams,disengagements,dis_lo,dis_hi,paper_disengagements\n",
    );
    let (mut inside, mut outside) = (0, 0);
    for (c, &(case, _, _)) in CASES.iter().enumerate() {
        let mut row = vec![case.to_string()];
        for (m, mesh) in meshes.iter().enumerate() {
            let start = (c * meshes.len() + m) * trials as usize;
            let cell = &outcomes[start..start + trials as usize];
            let jams = cell.iter().filter(|o| o.0).count() as u64;
            let dis = cell.iter().filter(|o| o.1).count() as u64;
            let (wj, wd) = (wilson95(jams, trials), wilson95(dis, trials));
            let paper = |q: &str| {
                crate::paper::get("table3", &format!("{case}.{mesh}.{q}")).map(|r| r.value as u64)
            };
            let (pj, pd) = (paper("jam"), paper("dis"));
            // The paper's counts are out of 200: compare as rates when our trial count differs.
            let agrees = |w: &stats::Proportion, p: Option<u64>| {
                p.is_none_or(|p| {
                    let rate = p as f64 / 200.0;
                    rate >= w.lo - 1e-12 && rate <= w.hi + 1e-12
                })
            };
            let ok = agrees(&wj, pj) && agrees(&wd, pd);
            if pj.is_some() {
                if ok { inside += 1 } else { outside += 1 }
            }
            let show = |p: Option<u64>| p.map_or_else(|| "-".to_string(), |v| v.to_string());
            row.push(format!(
                "{jams}/{dis} ({}/{}){}",
                show(pj),
                show(pd),
                if ok { "" } else { "*" }
            ));
            csv.push_str(&format!(
                "{case},{mesh},{jams},{},{},{},{dis},{},{},{}\n",
                wj.lo * trials as f64,
                wj.hi * trials as f64,
                show(pj),
                wd.lo * trials as f64,
                wd.hi * trials as f64,
                show(pd)
            ));
        }
        ours.row(row);
    }
    ours.note(format!(
        "Cells where the paper's counts lie inside our 95 % Wilson intervals: {inside}; outside: {outside}."
    ));
    ours.note("Each trial: both gears manufactured afresh (hypothesis and Case), a random initial angle, one full turn of the gear with more teeth.");
    Ok(Report {
        tables: vec![ours],
        files: vec![OutputFile::new("table3-data.csv", csv)],
        trials: outcomes.len() as u64,
        agreement: Some(registry::Agreement { inside, outside }),
        ..Default::default()
    })
}
