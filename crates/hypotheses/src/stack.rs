//! Hypotheses applied one after another, named `a+b`: `edmunds-split+asymmetric-teeth` cuts
//! Edmunds' errors first and then displaces the valleys of the gear that came out.
//!
//! A stack declares the parameters of all its layers and passes the same [`Params`] to each, so
//! `--set valley_shift=0.1` reaches `asymmetric-teeth` and `--set random=0.08` reaches
//! `edmunds-split`. Two layers declaring the same parameter name would make that ambiguous, so
//! such a stack is refused. Each layer draws from the one random stream in turn, so a stack is
//! as deterministic as its layers.

use std::collections::BTreeMap;
use std::sync::{Mutex, OnceLock};

use geometry::Gear;

use crate::{About, Describe, Hypothesis, HypothesisError, Param, Params};

/// The separator of layer names in a stack's name.
pub const SEPARATOR: char = '+';

struct Stack {
    about: About,
    layers: Vec<&'static dyn Hypothesis>,
    params: &'static [Param],
}

impl Describe for Stack {
    fn about(&self) -> &About {
        &self.about
    }
}

impl Hypothesis for Stack {
    fn params(&self) -> &'static [Param] {
        self.params
    }

    fn check(&self, params: &Params) -> Result<(), HypothesisError> {
        self.layers.iter().try_for_each(|layer| layer.check(params))
    }

    fn apply(
        &self,
        gear: &Gear,
        gear_name: &str,
        params: &Params,
        rng: &mut dyn rand::RngCore,
    ) -> Result<Gear, HypothesisError> {
        let mut made = gear.clone();
        for layer in &self.layers {
            made = layer.apply(&made, gear_name, params, rng)?;
        }
        Ok(made)
    }
}

/// Stacks built so far, by name: each is built once and lives for the whole process (a name
/// and parameter list must be `'static` to be a [`Hypothesis`]), so looking one up again does
/// not leak again.
fn built() -> &'static Mutex<BTreeMap<String, &'static Stack>> {
    static BUILT: OnceLock<Mutex<BTreeMap<String, &'static Stack>>> = OnceLock::new();
    BUILT.get_or_init(|| Mutex::new(BTreeMap::new()))
}

/// The layer names of the hypothesis `name`, each trimmed: `name` split at [`SEPARATOR`],
/// except where the separator belongs to the path of a `measured:FILE` layer. Such a layer is
/// read as the longest run of parts that names an existing file (`measured:my+errors.ron` is
/// one layer when that file exists; `measured:a.ron+edmunds-split` is two when `a.ron` exists
/// and `a.ron+edmunds-split` does not), and as its first part alone when none does (the file's
/// own check then names it). The file is looked up as [`crate::measured_file`] reads it.
pub fn stack_layers(name: &str) -> Vec<String> {
    let parts: Vec<&str> = name.split(SEPARATOR).collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < parts.len() {
        let mut end = i + 1;
        if parts[i].trim_start().starts_with("measured:") {
            let sep = SEPARATOR.to_string();
            end = (i + 2..=parts.len())
                .rev()
                .find(|&j| {
                    let joined = parts[i..j].join(&sep);
                    joined
                        .trim()
                        .strip_prefix("measured:")
                        .is_some_and(|path| std::path::Path::new(path).is_file())
                })
                .unwrap_or(i + 1);
        }
        out.push(parts[i..end].join(&SEPARATOR.to_string()).trim().to_owned());
        i = end;
    }
    out
}

/// The stack named `name` (layer names joined by [`SEPARATOR`], split by [`stack_layers`]),
/// each layer found by `find`.
///
/// Refused: an empty layer name, a layer named twice, and two layers that declare the same
/// parameter.
pub(crate) fn lookup_stack(
    name: &str,
    find: impl Fn(&str) -> Result<&'static dyn Hypothesis, HypothesisError>,
) -> Result<&'static dyn Hypothesis, HypothesisError> {
    let what = || format!("error hypothesis `{name}`");
    if let Some(s) = built().lock().map_err(|_| poisoned())?.get(name) {
        return Ok(*s);
    }
    let parts = stack_layers(name);
    // One `measured:FILE` layer whose path holds the separator: not a stack.
    if let [one] = parts.as_slice() {
        return find(one);
    }
    let mut layers: Vec<&'static dyn Hypothesis> = Vec::new();
    for part in parts.iter().map(String::as_str) {
        if part.is_empty() {
            return Err(HypothesisError::new(
                what(),
                format!("a stack names its layers joined by `{SEPARATOR}`, none of them empty"),
            ));
        }
        let h = find(part)?;
        if layers.iter().any(|l| l.name() == h.name()) {
            return Err(HypothesisError::new(
                what(),
                format!("names `{part}` twice (apply it once, with larger parameters)"),
            ));
        }
        layers.push(h);
    }
    let mut params: Vec<Param> = Vec::new();
    for l in &layers {
        for p in l.params() {
            if let Some(owner) = layers
                .iter()
                .take_while(|o| o.name() != l.name())
                .find(|o| o.params().iter().any(|q| q.name == p.name))
            {
                return Err(HypothesisError::new(
                    what(),
                    format!(
                        "parameter `{}` is declared by both `{}` and `{}`, so a value could not say which it is for",
                        p.name,
                        owner.name(),
                        l.name()
                    ),
                ));
            }
            params.push(*p);
        }
    }
    let names: Vec<&str> = layers.iter().map(|l| l.name()).collect();
    let about = About {
        name: Box::leak(names.join("+").into_boxed_str()),
        summary: Box::leak(
            format!(
                "{}, applied in this order to each gear",
                names
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(" then ")
            )
            .into_boxed_str(),
        ),
        details: "",
    };
    let stack: &'static Stack = Box::leak(Box::new(Stack {
        about,
        layers,
        params: Box::leak(params.into_boxed_slice()),
    }));
    built()
        .lock()
        .map_err(|_| poisoned())?
        .insert(name.to_string(), stack);
    Ok(stack)
}

fn poisoned() -> HypothesisError {
    HypothesisError::new(
        "error hypothesis stacks",
        "a thread panicked while building one",
    )
}
