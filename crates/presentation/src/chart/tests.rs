//! The chart builder's tests: distinct styles, the legend off the data, every figure's axes.

use super::*;

/// Runs `f` on its own thread and fails if it has not returned within a minute (a figure
/// whose axis range `plotters` cannot label never returns).
fn within_a_minute(f: impl FnOnce() + Send + 'static) {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        f();
        let _ = tx.send(());
    });
    match rx.recv_timeout(std::time::Duration::from_secs(60)) {
        Ok(()) => {}
        Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
            panic!("still drawing after a minute")
        }
        Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => panic!("drawing panicked"),
    }
}

#[test]
fn figures_without_a_drawable_range_still_finish() {
    within_a_minute(figures_without_a_drawable_range);
}

fn figures_without_a_drawable_range() {
    let empty = Series {
        label: "none",
        points: Vec::new(),
    };
    let infinite = Series {
        label: "infinite",
        points: vec![(1.0, f64::INFINITY), (f64::NEG_INFINITY, 2.0)],
    };
    let flat_and_large = Series {
        label: "flat",
        points: vec![(1e20, 3e15), (1e20, 3e15)],
    };
    for s in [empty, infinite, flat_and_large] {
        let svg = line_plot("t", "x", "y", std::slice::from_ref(&s)).unwrap();
        assert!(svg.contains("<svg"), "{}", s.label);
        let svg = semilog_plot("t", "x", "y", std::slice::from_ref(&s)).unwrap();
        assert!(svg.contains("<svg"), "{}", s.label);
        // A category chart's x is the category's index.
        let by_category = Series {
            label: s.label,
            points: s.points.iter().map(|p| (0.0, p.1)).collect(),
        };
        let svg = category_plot("t", &["a".into()], "x", "y", &[by_category]).unwrap();
        assert!(svg.contains("<svg"), "{}", s.label);
    }
}

#[test]
fn drawable_ranges_are_kept() {
    assert_eq!(drawable(-1e-9, 1e-9), (-1e-9, 1e-9));
    assert_eq!(drawable(0.0, 102.0), (0.0, 102.0));
    assert_eq!(drawable(f64::INFINITY, f64::NEG_INFINITY), (-0.5, 0.5));
    let (lo, hi) = drawable(1e20, 1e20);
    assert!(lo < 1e20 && hi > 1e20 && hi - lo > 1e16);
}

#[test]
fn long_series_are_thinned_to_their_envelope() {
    let short: Vec<(f64, f64)> = (0..36_001).map(|i| (i as f64, (i % 7) as f64)).collect();
    assert_eq!(
        thinned(&short),
        short,
        "the default runs' curves are drawn whole"
    );
    // 3.6 million points (pair at sample_deg 1e-4 drew them all: a 27 MB SVG).
    let long: Vec<(f64, f64)> = (0..3_600_000)
        .map(|i| {
            (
                i as f64,
                ((i as f64) * 0.001).sin() + if i == 1_234_567 { 5.0 } else { 0.0 },
            )
        })
        .collect();
    let t = thinned(&long);
    assert!(t.len() <= MAX_PLOT_POINTS, "{}", t.len());
    assert_eq!(t.first(), long.first());
    assert_eq!(t.last(), long.last());
    assert!(t.windows(2).all(|w| w[0].0 < w[1].0), "in order");
    let peak = t.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    assert!(peak > 5.0, "a one-point spike survives: {peak}");
}

#[test]
fn log_ticks_read_plainly() {
    assert_eq!(log_tick(0.031_622_776), "0.032");
    assert_eq!(log_tick(0.1), "0.1");
    assert_eq!(log_tick(3.162_277_6), "3.2");
    assert_eq!(log_tick(316.227_76), "316");
    assert_eq!(log_tick(1e-5), "1.0e-5");
    assert_eq!(log_tick(1e6), "1.0e6");
}

#[test]
fn styles_differ_as_promised() {
    let all: Vec<Style> = (0..DISTINCT_STYLES).map(style).collect();
    let distinct: std::collections::HashSet<&Style> = all.iter().collect();
    assert_eq!(
        distinct.len(),
        DISTINCT_STYLES,
        "every series its own style"
    );
    assert_eq!(style(DISTINCT_STYLES), style(0), "and no more than that");
    for i in 0..28 {
        for j in 0..i {
            let (a, b) = (style(i), style(j));
            assert!((a.dash, a.marker) != (b.dash, b.marker), "{i}, {j}: grey");
            if i < 10 {
                assert_ne!(a.colour, b.colour, "{i}, {j}: colour");
            }
        }
    }
}

/// The value of attribute `name` in the first tag of `svg` holding `marker`.
fn attr(svg: &str, marker: &str, name: &str) -> f64 {
    let start = svg.find(marker).unwrap();
    let tag_start = svg[..=start].rfind('<').unwrap();
    let tag = &svg[tag_start..start + svg[start..].find('>').unwrap()];
    let at = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
    tag[at..at + tag[at..].find('"').unwrap()].parse().unwrap()
}

fn rect(svg: &str, class: &str) -> Rect {
    let m = format!("class=\"{class}\"");
    Rect {
        x: attr(svg, &m, "x"),
        y: attr(svg, &m, "y"),
        w: attr(svg, &m, "width"),
        h: attr(svg, &m, "height"),
    }
}

/// The `data-style` of every `<g class="series">` of `svg`, in order.
fn series_styles(svg: &str) -> Vec<String> {
    svg.match_indices("<g class=\"series\"")
        .map(|(i, _)| {
            let tag = &svg[i..i + svg[i..].find('>').unwrap()];
            let at = tag.find("data-style=\"").unwrap() + 12;
            tag[at..at + tag[at..].find('"').unwrap()].to_owned()
        })
        .collect()
}

fn many(n: usize, label_len: usize) -> Vec<(String, Vec<(f64, f64)>)> {
    (0..n)
        .map(|k| {
            // Words, and one word longer than any canvas (a file's path).
            let mut label = format!("{k}");
            while label.len() < label_len {
                label.push_str(if label.len() % 7 == 0 { " /a/very/long/path/of/a/measured/table/that/no/legend/column/can/hold/on/one/line.ron" } else { " word" });
            }
            let points = (0..50)
                .map(|i| (f64::from(i), 1.0 + (k as f64 + f64::from(i)).sin().abs()))
                .collect();
            (label, points)
        })
        .collect()
}

#[test]
fn n_series_get_n_distinct_styles_and_the_legend_stays_off_the_plot() {
    for (n, label_len) in [
        (1, 3),
        (2, 40),
        (5, 10),
        (15, 5),
        (30, 60),
        (140, 4),
        (3, 300),
    ] {
        let data = many(n, label_len);
        let series: Vec<Series<'_>> = data
            .iter()
            .map(|(l, p)| Series {
                label: l,
                points: p.clone(),
            })
            .collect();
        let categories: Vec<String> = (0..50).map(|i| format!("c{i}")).collect();
        let limits = [
            Limit {
                series: 0,
                x: -3.0,
                kind: LimitKind::Lower,
            },
            Limit {
                series: n - 1,
                x: 55.0,
                kind: LimitKind::Upper,
            },
        ];
        let charts = [
            line_plot("t", "x", "y", &series).unwrap(),
            semilog_plot("t", "x", "y", &series).unwrap(),
            Plot::new("t", "x", "y", &series)
                .limits(&limits, "jam", "disengagement")
                .svg()
                .unwrap(),
            category_plot("t", &categories, "x", "y", &series).unwrap(),
        ];
        for svg in &charts {
            let styles = series_styles(svg);
            assert_eq!(styles.len(), n, "{n} series drawn");
            let distinct: std::collections::HashSet<&String> = styles.iter().collect();
            assert_eq!(distinct.len(), n, "{n} series, {} styles", distinct.len());
            let plot = rect(svg, "plot-area");
            let legend = rect(svg, "legend-box");
            assert!(
                !plot.intersects(&legend),
                "{n} series: legend {legend:?} on the plot {plot:?}"
            );
            let canvas_h = attr(svg, "<svg", "height");
            let canvas_w = attr(svg, "<svg", "width");
            assert!(
                legend.y + legend.h <= canvas_h && legend.x >= 0.0,
                "{n}: the legend is on the canvas: {legend:?} in {canvas_w} x {canvas_h}"
            );
            assert!(
                legend.x + legend.w <= canvas_w,
                "{n}: {legend:?} wider than {canvas_w}"
            );
            // Every series named in the legend, in its own style.
            assert_eq!(
                svg.matches("<g class=\"legend-entry\" data-series=")
                    .count(),
                n
            );
        }
        let with_limits = &charts[2];
        assert_eq!(with_limits.matches("<g class=\"legend-entry\">").count(), 2);
    }
}

#[test]
fn limits_widen_the_axis_and_sit_on_their_series() {
    let series = [Series {
        label: "a",
        points: vec![(10.0, 1.0), (20.0, 2.0)],
    }];
    let limits = [
        Limit {
            series: 0,
            x: 5.0,
            kind: LimitKind::Lower,
        },
        Limit {
            series: 0,
            x: 25.0,
            kind: LimitKind::Upper,
        },
    ];
    let svg = Plot::new("t", "x", "y", &series)
        .limits(&limits, "jam limit", "disengagement limit")
        .svg()
        .unwrap();
    assert!(svg.contains(">jam limit</text>"));
    assert!(svg.contains(">disengagement limit</text>"));
    let plot = rect(&svg, "plot-area");
    // Both brackets drawn inside the plot area, in the series' colour.
    let brackets: Vec<&str> = svg
        .match_indices("stroke-width=\"2.5\"")
        .map(|(i, _)| &svg[svg[..i].rfind('<').unwrap()..i])
        .collect();
    assert_eq!(brackets.len(), 4, "two on the plot, two in the legend");
    for b in &brackets[..2] {
        assert!(b.contains(style(0).colour), "{b}");
        let d = &b[b.find("d=\"M").unwrap() + 4..];
        let x: f64 = d[..d.find(' ').unwrap()].parse().unwrap();
        assert!(x >= plot.x - 6.0 && x <= plot.x + plot.w + 6.0, "{b}");
    }
}

/// The numbers of an SVG's axis labels (plotters writes each tick label as its own `<text>`).
fn tick_numbers(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = t[t.find('>')? + 1..t.find("</text>")?].trim();
            body.parse::<f64>().is_ok().then(|| body.to_owned())
        })
        .collect()
}

#[test]
fn ticks_are_round_numbers_written_plainly() {
    let points: Vec<(f64, f64)> = (0..=36)
        .map(|i| (10.0 * f64::from(i), 0.01 * f64::from(i)))
        .collect();
    let series = [Series {
        label: "s",
        points: points.clone(),
    }];
    for svg in [
        Plot::new("t", "x", "y", &series).svg().unwrap(),
        Plot::new("t", "x", "y", &series)
            .ranges((0.0, 360.0), (-0.1, 0.4))
            .svg()
            .unwrap(),
    ] {
        let ticks = tick_numbers(&svg);
        assert!(ticks.len() >= 8, "{ticks:?}");
        for t in &ticks {
            assert!(
                !t.ends_with(".0"),
                "tick {t} written with a needless decimal"
            );
            // A round number: at most two significant digits after its leading zeros.
            let digits: String = t.chars().filter(char::is_ascii_digit).collect();
            let significant = digits.trim_start_matches('0').trim_end_matches('0');
            assert!(significant.len() <= 2, "tick {t} is not a round number");
        }
    }
}
