//! The random streams of a run: one scheme for every trial of every study.
//!
//! A trial's numbers come from one generator, a [`TrialRng`] (ChaCha8), seeded by the run's
//! seed (`--seed`) and set to one stream word: the FNV-1a hash of the draws' [`Identity`] (the
//! canonical text of what the draws are for), continued over the trial index's eight
//! little-endian bytes. So a trial's numbers depend on (seed, identity, trial) alone - never on
//! the thread count, the shard, or which study ran before - and two studies draw the same
//! numbers only where they name the same identity.
//!
//! [`Streams`] is the one place a generator is made: [`crate::TrialEngine::stream`] for trials
//! run through the engine, [`Streams::new`] where only the seed is at hand (one trial rebuilt).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The generator of one trial's stream (what [`Streams::stream`] returns).
pub type TrialRng = ChaCha8Rng;

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// 64-bit FNV-1a of `bytes`, continuing from `hash`. Stable across Rust versions and
/// platforms, unlike `std`'s `DefaultHasher`, so stream words and batch keys stay the same.
fn fnv1a_from(mut hash: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        hash ^= u64::from(b);
        hash = hash.wrapping_mul(FNV_PRIME);
    }
    hash
}

/// 64-bit FNV-1a hash of `bytes`: the hash of identities, and of the long texts batch keys and
/// cache keys are shortened to.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    fnv1a_from(FNV_OFFSET, bytes)
}

/// What a stream's draws are for, as a hash of the canonical text that defines them (e.g. a jam
/// cell's `mesh=b2-c1;hypothesis=edmunds-split;...;h=1.1;G=40.0`). Two texts that differ give
/// different streams; the same text gives the same stream in every study that names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Identity(u64);

impl Identity {
    /// The identity named by `canonical`, the text of what the draws are for.
    pub fn of(canonical: &str) -> Identity {
        Identity(fnv1a64(canonical.as_bytes()))
    }

    /// The stream word of trial `trial`: the identity's hash continued over the trial index's
    /// eight little-endian bytes (a hash of the text and the trial together, so that no
    /// identity's trials run into another's, as adjacent stream numbers would).
    fn word(self, trial: u64) -> u64 {
        fnv1a_from(self.0, &trial.to_le_bytes())
    }
}

/// The random streams of one run: the run's seed, and the only way a generator is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Streams {
    seed: u64,
}

impl Streams {
    /// The streams of a run under `seed`.
    pub fn new(seed: u64) -> Streams {
        Streams { seed }
    }

    /// The run's seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The generator of trial `trial` of the draws `identity`: ChaCha8 seeded by the run's seed,
    /// on the stream word of (identity, trial).
    pub fn stream(&self, identity: Identity, trial: u64) -> TrialRng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(identity.word(trial));
        rng
    }
}

#[cfg(test)]
mod tests {
    use rand::Rng;

    use super::*;

    /// The first numbers of a stream.
    fn first(streams: Streams, identity: &str, trial: u64) -> [u64; 4] {
        let mut rng = streams.stream(Identity::of(identity), trial);
        std::array::from_fn(|_| rng.random())
    }

    #[test]
    fn fnv1a64_is_the_published_hash() {
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn the_same_seed_identity_and_trial_give_the_same_numbers() {
        let s = Streams::new(2025);
        assert_eq!(first(s, "cell", 7), first(s, "cell", 7));
        assert_eq!(first(s, "cell", 7), first(Streams::new(2025), "cell", 7));
    }

    #[test]
    fn another_identity_trial_or_seed_gives_other_numbers() {
        let s = Streams::new(2025);
        let base = first(s, "cell", 7);
        assert_ne!(base, first(s, "cell ", 7), "another identity");
        assert_ne!(base, first(s, "cell", 8), "another trial");
        assert_ne!(base, first(Streams::new(2026), "cell", 7), "another seed");
        // Trial t of one identity is no other identity's trial: the words are hashes of both.
        let words: std::collections::BTreeSet<u64> = ["a", "b", "c"]
            .iter()
            .flat_map(|id| (0..1000).map(move |t| Identity::of(id).word(t)))
            .collect();
        assert_eq!(words.len(), 3000);
    }

    /// The stream word is the one jam cells have always drawn from (FNV-1a of the canonical
    /// text, continued over the trial's bytes), so cell-based tables keep their numbers.
    #[test]
    fn the_word_is_fnv1a_of_the_text_then_the_trial() {
        let text = "mesh=b2-c1;hypothesis=ideal;h=1.1;G=40.0";
        let mut bytes = text.as_bytes().to_vec();
        bytes.extend_from_slice(&3_u64.to_le_bytes());
        assert_eq!(Identity::of(text).word(3), fnv1a64(&bytes));
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        rng.set_stream(fnv1a64(&bytes));
        let expected: [u64; 4] = std::array::from_fn(|_| rng.random());
        assert_eq!(first(Streams::new(11), text, 3), expected);
    }

    /// A batch of trials drawing through the engine gives the same numbers on one thread and
    /// on four: each trial's stream is named by (seed, identity, trial), not by who runs it.
    #[test]
    fn the_engines_streams_do_not_depend_on_the_thread_count() {
        let draw = |threads: usize| {
            let engine = crate::TrialEngine::new("streams", 9);
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a thread pool");
            pool.install(|| {
                engine.trials("draws", 200, |t| {
                    let mut rng = engine.stream(Identity::of("draws"), t);
                    Ok(rng.random::<u64>())
                })
            })
            .expect("the batch runs")
        };
        let one = draw(1);
        assert_eq!(one, draw(4));
        assert_eq!(
            one.iter().collect::<std::collections::BTreeSet<_>>().len(),
            200
        );
    }
}
