//! Every command's flags parsed, and bad ones refused with the flag and the rule named.

use super::*;

fn p(s: &str) -> Result<Command, ArgError> {
    let args: Vec<String> = s.split_whitespace().map(str::to_owned).collect();
    parse(&args)
}

fn run(s: &str) -> RunArgs {
    match p(s).unwrap() {
        Command::Run(r) => r,
        other => panic!("not a run: {other:?}"),
    }
}

#[test]
fn commands() {
    assert_eq!(p("").unwrap(), Command::Overview);
    assert_eq!(p("list").unwrap(), Command::List);
    assert_eq!(p("hypotheses").unwrap(), Command::Hypotheses);
    assert_eq!(p("rules").unwrap(), Command::Rules);
    assert!(matches!(p("hypotheses x"), Err(ArgError::Usage(_))));
    assert_eq!(p("help").unwrap(), Command::Help(None));
    assert_eq!(p("help fig2").unwrap(), Command::Help(Some("fig2".into())));
    assert!(matches!(p("frobnicate"), Err(ArgError::Usage(_))));
    assert!(matches!(p("list extra"), Err(ArgError::Usage(_))));
    assert!(matches!(p("run"), Err(ArgError::Usage(_))));
}

#[test]
fn run_defaults_and_flags() {
    let r = run("run fig2");
    assert_eq!(r.ids, ["fig2"]);
    assert_eq!(r.seed, DEFAULT_SEED);
    assert_eq!(r.threads, None);
    assert_eq!(r.out, None);

    let r =
        run("run fig2 --seed 7 fig3 --threads=3 --out /tmp/x --config m.ron --set a=1 --set=b=x=y");
    assert_eq!(r.ids, ["fig2", "fig3"]);
    assert_eq!(r.seed, 7);
    assert_eq!(r.threads, Some(3));
    assert_eq!(r.out, Some(PathBuf::from("/tmp/x")));
    assert_eq!(r.config, Some(PathBuf::from("m.ron")));
    assert_eq!(
        r.sets,
        [("a".into(), "1".into()), ("b".into(), "x=y".into())]
    );
    assert_eq!(run("run x --set k=-1").sets, [("k".into(), "-1".into())]);
}

#[test]
fn new_run_flags() {
    let r = run("run a --trials 7 --format csv --gearing g.ron --hypothesis ideal");
    assert_eq!(r.trials, Some(7));
    assert_eq!(r.format, Format::Csv);
    assert_eq!(r.gearing, Some(PathBuf::from("g.ron")));
    assert_eq!(r.hypothesis.as_deref(), Some("ideal"));
    assert!(r.sets.is_empty(), "shorthands are kept apart from --set");
    assert_eq!(run("run a --format=json").format, Format::Json);
    assert_eq!(run("run a").format, Format::Md);
    assert_eq!(
        run("run a --errors e.ron").errors,
        Some(PathBuf::from("e.ron"))
    );
    match p("run a --trials 18446744073709551615") {
        Err(ArgError::Value(m)) => assert!(m.contains("at most 1000000 "), "{m}"),
        other => panic!("{other:?}"),
    }
    for bad in [
        "run a --trials 3 --set trials=4",
        "run a --gearing g.ron --set gearing=h.ron",
        "run a --hypothesis ideal --set hypothesis=ideal",
        "run a --errors e.ron --hypothesis ideal",
        "run a --errors e.ron --set measured=f.ron",
    ] {
        assert!(matches!(p(bad), Err(ArgError::Usage(_))), "{bad}");
    }
}

fn inv(s: &str) -> Result<(Command, Verbosity), ArgError> {
    let args: Vec<String> = s.split_whitespace().map(str::to_owned).collect();
    parse_invocation(&args)
}

#[test]
fn quiet_and_verbose_stand_anywhere() {
    assert_eq!(inv("").unwrap(), (Command::Overview, Verbosity::Normal));
    assert_eq!(inv("-q list").unwrap(), (Command::List, Verbosity::Quiet));
    assert_eq!(inv("list --verbose").unwrap().1, Verbosity::Verbose);
    let (cmd, v) = inv("run fig2 -v --seed 3").unwrap();
    assert_eq!(v, Verbosity::Verbose);
    assert!(matches!(cmd, Command::Run(r) if r.seed == 3));
    assert_eq!(inv("-q -q list").unwrap().1, Verbosity::Quiet);
    assert!(matches!(inv("-q run x -v"), Err(ArgError::Usage(_))));
}

#[test]
fn run_all_takes_no_other_ids() {
    assert!(run("run all --seed 3").is_all());
    assert!(!run("run fig2").is_all());
    for bad in ["run all fig2", "run fig2 all", "run all all"] {
        match p(bad) {
            Err(ArgError::Usage(m)) => assert!(m.contains("`run all`"), "{m}"),
            other => panic!("{bad}: {other:?}"),
        }
    }
}

fn bench(s: &str) -> BenchArgs {
    match p(s).unwrap() {
        Command::Bench(b) => b,
        other => panic!("not a bench: {other:?}"),
    }
}

#[test]
fn bench_defaults_and_flags() {
    let b = bench("bench");
    assert_eq!(b.targets, [BenchTarget::Table5, BenchTarget::All]);
    assert_eq!(b.threads, [1, 2]);
    let b = bench("bench --only all --threads 2,1,4");
    assert_eq!(b.targets, [BenchTarget::All]);
    assert_eq!(b.threads, [2, 1, 4]);
    let b = bench("bench --threads=1 --only=table5");
    assert_eq!(b.targets, [BenchTarget::Table5]);
    assert_eq!(b.threads, [1]);
    assert_eq!(BenchTarget::Table5.name(), "table5");
}

#[test]
fn bench_refuses_bad_flags() {
    for bad in [
        "bench --only table6",
        "bench --threads 0",
        "bench --threads 1,,2",
        "bench --threads x",
        "bench --threads 100000",
        "bench --threads 2,1025",
    ] {
        assert!(matches!(p(bad), Err(ArgError::Value(_))), "{bad}");
    }
    for bad in [
        "bench table5",
        "bench --seed 1",
        "bench --only",
        "bench --threads",
    ] {
        assert!(matches!(p(bad), Err(ArgError::Usage(_))), "{bad}");
    }
}

#[test]
fn shard_and_merge() {
    let r = run("run table5 --shard 2/4");
    assert_eq!(r.shard, Some(Shard::new(2, 4).unwrap()));
    assert_eq!(run("run table5").shard, None);
    assert_eq!(
        run("run table5 --shard=0/1").shard,
        Some(Shard::new(0, 1).unwrap())
    );
    for bad in ["4/4", "0/0", "x", "1-4", "-1/4"] {
        match p(&format!("run table5 --shard {bad}")) {
            Err(ArgError::Value(m)) => assert!(m.starts_with("--shard: "), "{m}"),
            other => panic!("{bad}: {other:?}"),
        }
    }
    for bad in ["run all --shard 0/2", "run a b --shard 0/2"] {
        match p(bad) {
            Err(ArgError::Usage(m)) => assert!(m.contains("exactly one experiment id"), "{m}"),
            other => panic!("{bad}: {other:?}"),
        }
    }
    match p("merge a b/c --out o --threads=2 --format csv").unwrap() {
        Command::Merge(m) => {
            assert_eq!(m.inputs, [PathBuf::from("a"), PathBuf::from("b/c")]);
            assert_eq!(m.out, Some(PathBuf::from("o")));
            assert_eq!(m.threads, Some(2));
            assert_eq!(m.format, Format::Csv);
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(p("merge"), Err(ArgError::Usage(_))));
    assert!(matches!(p("merge --out o"), Err(ArgError::Usage(_))));
    assert!(matches!(p("merge a --seed 1"), Err(ArgError::Usage(_))));
    assert!(matches!(p("merge a --threads 0"), Err(ArgError::Value(_))));
}

#[test]
fn run_refuses_bad_flags() {
    assert!(matches!(p("run x --threads 0"), Err(ArgError::Value(_))));
    assert!(matches!(p("run x --threads -1"), Err(ArgError::Value(_))));
    assert!(matches!(p("run x --seed abc"), Err(ArgError::Value(_))));
    assert!(matches!(p("run x --seed"), Err(ArgError::Usage(_))));
    assert!(matches!(p("run x --out --seed 1"), Err(ArgError::Usage(_))));
    assert!(matches!(p("run x --bogus"), Err(ArgError::Usage(_))));
    assert!(
        matches!(p("run x -v"), Err(ArgError::Usage(_))),
        "-v is not run's"
    );
    assert!(matches!(p("run x --threads 1025"), Err(ArgError::Value(_))));
    assert!(matches!(p("run x --format xml"), Err(ArgError::Value(_))));
    assert!(matches!(p("run x --trials 0"), Err(ArgError::Value(_))));
    assert!(matches!(p("run x --trials 2.5"), Err(ArgError::Value(_))));
    assert!(matches!(p("run x --errors="), Err(ArgError::Value(_))));
    assert!(matches!(p("run x --set novalue"), Err(ArgError::Usage(_))));
    assert!(matches!(p("run x --set =1"), Err(ArgError::Usage(_))));
}

#[test]
fn fuzz_arguments() {
    let p = |s: &str| {
        parse_fuzz(
            &s.split_whitespace()
                .map(str::to_owned)
                .collect::<Vec<String>>(),
        )
    };
    let o = p("").unwrap();
    assert_eq!(o.budget, Budget::Seconds(DEFAULT_FUZZ_SECONDS));
    let o = p("--seconds 2.5 --seed=9 --findings /tmp/f").unwrap();
    assert_eq!((o.budget, o.seed), (Budget::Seconds(2.5), 9));
    assert_eq!(o.findings, PathBuf::from("/tmp/f"));
    assert_eq!(p("--execs 10").unwrap().budget, Budget::Execs(10));
    for bad in [
        "--seconds 0",
        "--seconds x",
        "--seconds NaN",
        "--seed -1",
        "--execs 0",
        "--execs 1.5",
    ] {
        assert!(matches!(p(bad), Err(ArgError::Value(_))), "{bad}");
    }
    assert!(matches!(p("--bogus 1"), Err(ArgError::Usage(_))));
    assert!(matches!(p("--seconds"), Err(ArgError::Usage(_))));
}

#[test]
fn report_arguments() {
    assert!(parse_report(&[]).is_ok());
    assert_eq!(
        parse_report(&["--out=x".into()]).unwrap(),
        ReportArgs {
            out: Some(PathBuf::from("x")),
            quiet: false,
            bundle: None,
        }
    );
    assert_eq!(
        parse_report(&["-q".into(), "--out".into(), "y".into()]).unwrap(),
        ReportArgs {
            out: Some(PathBuf::from("y")),
            quiet: true,
            bundle: None,
        }
    );
    assert_eq!(
        parse_report(&["--bundle".into(), "s.tar.gz".into()]).unwrap(),
        ReportArgs {
            out: None,
            quiet: false,
            bundle: Some(PathBuf::from("s.tar.gz")),
        }
    );
    assert_eq!(
        parse_report(&["--bundle=a".into(), "--bundle=b".into()]).unwrap_err(),
        ArgError::Usage("--bundle given twice".into())
    );
    assert_eq!(
        parse_report(&["--out=x".into(), "--out=y".into()]).unwrap_err(),
        ArgError::Usage("--out given twice".into())
    );
    assert!(parse_report(&["--out".into()]).is_err());
    assert!(matches!(
        parse_report(&["--out=".into()]),
        Err(ArgError::Value(_))
    ));
    assert!(matches!(
        parse_report(&["fig2".into()]),
        Err(ArgError::Usage(_))
    ));
}
