//! Every random number comes from the trial engine's one scheme (`registry::Streams`: a stream
//! per (seed, what the draws are for, trial)): no product code but the engine's own makes or
//! reseeds a generator, so one place says how a trial's numbers are chosen and no two studies
//! share a stream by accident. Tests and benchmarks may make their own.

use crate::source::{crate_dirs, product_files, product_text, rel};

/// What making or reseeding a generator looks like.
const MAKERS: &[&str] = &[
    "trial_rng(",
    "seed_from_u64",
    "set_stream",
    "from_seed",
    "from_entropy",
    "thread_rng",
    "rand::rng()",
];

/// The one file allowed to make generators: the engine's streams.
const ENGINE: &str = "crates/registry/src/streams.rs";

/// Whether a line of code makes or reseeds a generator (a comment naming one does not).
fn makes_a_generator(line: &str) -> bool {
    !line.trim_start().starts_with("//") && MAKERS.iter().any(|m| line.contains(m))
}

#[test]
fn the_generator_reader_sees_one_made() {
    assert!(makes_a_generator(
        "    let mut rng = ChaCha8Rng::seed_from_u64(seed);"
    ));
    assert!(makes_a_generator("let r = rand::rng();"));
    assert!(!makes_a_generator(
        "    /// made by `seed_from_u64` in the engine"
    ));
    assert!(!makes_a_generator(
        "let mut rng = engine.stream(identity, t);"
    ));
}

#[test]
fn only_the_engine_makes_a_random_generator() {
    let mut found = Vec::new();
    let mut scanned = 0;
    for krate in crate_dirs() {
        for file in product_files(&krate) {
            if rel(&file) == ENGINE {
                continue;
            }
            scanned += 1;
            for (i, line) in product_text(&file).lines().enumerate() {
                if makes_a_generator(line) {
                    found.push(format!("{}:{}: {}", rel(&file), i + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        scanned > 100,
        "the scan found the sources ({scanned} files)"
    );
    assert!(
        std::path::Path::new(&crate::source::root().join(ENGINE)).is_file(),
        "{ENGINE} is where the streams are made"
    );
    assert!(
        found.is_empty(),
        "generators made outside the engine (draw through `TrialEngine::stream`, naming what the draws are for in `study::draws`):\n{}",
        found.join("\n")
    );
}
