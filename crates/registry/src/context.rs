//! What the runner hands an experiment: seed, thread count, parameters and config file.

use std::path::PathBuf;
use std::str::FromStr;

use crate::{Experiment, RunError};

/// A config file given with `--config FILE`, already read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConfigFile {
    /// The path as given on the command line; use it in error messages.
    pub path: PathBuf,
    /// The file's contents.
    pub text: String,
}

/// One declared parameter and its value.
#[derive(Debug, Clone)]
struct Value {
    name: &'static str,
    value: String,
    /// Set with `--set` (a parse failure is the user's), rather than the default (a bug).
    overridden: bool,
}

/// What the runner hands an experiment.
#[derive(Debug, Clone)]
pub struct Context {
    id: &'static str,
    seed: u64,
    threads: usize,
    params: Vec<Value>,
    config: Option<ConfigFile>,
}

impl Context {
    /// Builds a context: params start at the experiment's defaults, then `overrides`
    /// (from `--set key=value`, later ones winning) replace them.
    ///
    /// Errors ([`RunError::BadInput`]): an unknown key (naming it and listing the known ones);
    /// `threads == 0`; a config file for an experiment that takes none.
    pub fn new(
        exp: &Experiment,
        seed: u64,
        threads: usize,
        overrides: &[(String, String)],
        config: Option<ConfigFile>,
    ) -> Result<Context, RunError> {
        if threads == 0 {
            return Err(RunError::bad("--threads", "threads", "must be at least 1"));
        }
        let mut params: Vec<Value> = exp
            .params
            .iter()
            .map(|p| Value {
                name: p.name,
                value: p.default.to_owned(),
                overridden: false,
            })
            .collect();
        for (key, value) in overrides {
            match params.iter_mut().find(|p| p.name == key) {
                Some(p) => {
                    p.value.clone_from(value);
                    p.overridden = true;
                }
                None => {
                    let known = if exp.params.is_empty() {
                        format!("experiment `{}` has no parameters", exp.id)
                    } else {
                        let names: Vec<&str> = exp.params.iter().map(|p| p.name).collect();
                        format!(
                            "unknown parameter of experiment `{}`; known: {}",
                            exp.id,
                            names.join(", ")
                        )
                    };
                    return Err(RunError::bad("--set", key.as_str(), known));
                }
            }
        }
        if let (Some(file), None) = (&config, exp.config) {
            return Err(RunError::bad(
                "--config",
                file.path.display().to_string(),
                format!("experiment `{}` takes no --config", exp.id),
            ));
        }
        Ok(Context {
            id: exp.id,
            seed,
            threads,
            params,
            config,
        })
    }

    /// Seed for every random number generator of the run (`--seed`).
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Number of threads of the pool the experiment runs in (`--threads`).
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Raw string value of a declared param (an undeclared name is a bug: [`RunError::Internal`]).
    pub fn param(&self, name: &str) -> Result<&str, RunError> {
        self.value(name).map(|v| v.value.as_str())
    }

    fn value(&self, name: &str) -> Result<&Value, RunError> {
        self.params.iter().find(|p| p.name == name).ok_or_else(|| {
            RunError::Internal(format!(
                "experiment `{}` asked for parameter `{name}`, which it does not declare",
                self.id
            ))
        })
    }

    /// Parses a param; a value set with `--set` that does not parse is
    /// `RunError::BadInput { source: "--set", field: name, rule }`; a default that does not
    /// parse is a bug ([`RunError::Internal`]).
    fn parse<T: FromStr>(&self, name: &str, rule: &str) -> Result<T, RunError> {
        let v = self.value(name)?;
        v.value
            .trim()
            .parse::<T>()
            .map_err(|_| self.reject(v, rule))
    }

    fn reject(&self, v: &Value, rule: &str) -> RunError {
        if v.overridden {
            RunError::bad("--set", v.name, format!("{rule} (got `{}`)", v.value))
        } else {
            RunError::Internal(format!(
                "experiment `{}`: default of parameter `{}` ({:?}) {rule}",
                self.id, v.name, v.value
            ))
        }
    }

    /// A param as a finite number (`NaN` and infinities are refused).
    pub fn f64(&self, name: &str) -> Result<f64, RunError> {
        let rule = "must be a finite number";
        let x: f64 = self.parse(name, rule)?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.reject(self.value(name)?, rule))
        }
    }

    /// A param as a non-negative integer.
    pub fn usize(&self, name: &str) -> Result<usize, RunError> {
        self.parse(name, "must be a non-negative integer")
    }

    /// A param as a non-negative 64-bit integer.
    pub fn u64(&self, name: &str) -> Result<u64, RunError> {
        self.parse(name, "must be a non-negative integer")
    }

    /// The config file given with `--config`, if any.
    pub fn config(&self) -> Option<&ConfigFile> {
        self.config.as_ref()
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;
    use crate::{Param, Report};

    fn nothing(_: &Context) -> Result<Report, RunError> {
        Ok(Report::default())
    }

    const PARAMS: &[Param] = &[
        Param {
            name: "teeth",
            default: "24",
            unit: "",
            help: "number of teeth",
        },
        Param {
            name: "module",
            default: "0.5",
            unit: "mm",
            help: "tooth size",
        },
        Param {
            name: "broken",
            default: "lots",
            unit: "",
            help: "a default that does not parse",
        },
    ];

    static EXP: Experiment = Experiment {
        id: "t",
        title: "test",
        paper_item: "Figure 0",
        params: PARAMS,
        config: Some("a mesh"),
        run: nothing,
    };

    static BARE: Experiment = Experiment {
        id: "bare",
        title: "no params, no config",
        paper_item: "Table 0",
        params: &[],
        config: None,
        run: nothing,
    };

    fn set(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
        pairs
            .iter()
            .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
            .collect()
    }

    fn field_of(e: &RunError) -> (&str, &str, &str) {
        match e {
            RunError::BadInput {
                source,
                field,
                rule,
            } => (source, field, rule),
            RunError::Internal(m) => panic!("expected BadInput, got Internal({m})"),
        }
    }

    #[test]
    fn defaults_then_overrides() {
        let ctx = Context::new(&EXP, 7, 3, &[], None).unwrap();
        assert_eq!(ctx.seed(), 7);
        assert_eq!(ctx.threads(), 3);
        assert_eq!(ctx.param("teeth").unwrap(), "24");
        assert_eq!(ctx.usize("teeth").unwrap(), 24);
        assert_eq!(ctx.u64("teeth").unwrap(), 24);
        assert!((ctx.f64("module").unwrap() - 0.5).abs() < 1e-15);
        assert!(ctx.config().is_none());

        let ctx =
            Context::new(&EXP, 7, 1, &set(&[("teeth", "30"), ("teeth", "31")]), None).unwrap();
        assert_eq!(ctx.usize("teeth").unwrap(), 31, "later --set wins");
        assert!((ctx.f64("module").unwrap() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn unknown_key_is_named_with_known_ones() {
        let e = Context::new(&EXP, 0, 1, &set(&[("nonsense", "1")]), None).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        let (source, field, rule) = field_of(&e);
        assert_eq!(source, "--set");
        assert_eq!(field, "nonsense");
        assert!(rule.contains("teeth, module, broken"), "{rule}");

        let e = Context::new(&BARE, 0, 1, &set(&[("x", "1")]), None).unwrap_err();
        assert!(e.to_string().contains("has no parameters"), "{e}");
    }

    #[test]
    fn parse_errors_are_bad_input() {
        let ctx = Context::new(
            &EXP,
            0,
            1,
            &set(&[("teeth", "-3"), ("module", "NaN")]),
            None,
        )
        .unwrap();
        let e = ctx.usize("teeth").unwrap_err();
        assert_eq!(field_of(&e).0, "--set");
        assert_eq!(field_of(&e).1, "teeth");
        assert!(!e.to_string().contains('\n'));
        assert!(ctx.u64("teeth").is_err());
        let e = ctx.f64("module").unwrap_err();
        assert_eq!(field_of(&e).1, "module");
        assert!(field_of(&e).2.contains("finite"));

        let ctx = Context::new(&EXP, 0, 1, &set(&[("module", "inf")]), None).unwrap();
        assert!(ctx.f64("module").is_err());
        let ctx = Context::new(&EXP, 0, 1, &set(&[("module", "abc")]), None).unwrap();
        assert_eq!(ctx.f64("module").unwrap_err().exit_code(), 2);
    }

    #[test]
    fn bad_default_and_undeclared_name_are_internal() {
        let ctx = Context::new(&EXP, 0, 1, &[], None).unwrap();
        assert!(matches!(ctx.usize("broken"), Err(RunError::Internal(_))));
        assert!(matches!(ctx.param("nope"), Err(RunError::Internal(_))));
        assert!(matches!(ctx.f64("nope"), Err(RunError::Internal(_))));
    }

    #[test]
    fn zero_threads_and_unwanted_config_are_refused() {
        assert_eq!(
            Context::new(&EXP, 0, 0, &[], None).unwrap_err().exit_code(),
            2
        );
        let file = ConfigFile {
            path: "mesh.ron".into(),
            text: "()".into(),
        };
        let e = Context::new(&BARE, 0, 1, &[], Some(file.clone())).unwrap_err();
        assert!(e.to_string().contains("takes no --config"), "{e}");
        let ctx = Context::new(&EXP, 0, 1, &[], Some(file.clone())).unwrap();
        assert_eq!(ctx.config(), Some(&file));
    }
}
