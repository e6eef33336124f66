//! libFuzzer target: `study::pair_file::prepare` on arbitrary bytes, then every promise of
//! `xtask/src/fuzz_targets.rs` (shared with `cargo xtask fuzz`).

#![no_main]

use libfuzzer_sys::fuzz_target;

#[allow(dead_code)] // Reason: only this target's function of the shared file is used here.
#[path = "../../xtask/src/fuzz_targets.rs"]
mod fuzz_targets;

fuzz_target!(|data: &[u8]| {
    // The loader takes text; a file that is not UTF-8 is refused before it.
    if let Ok(text) = std::str::from_utf8(data)
        && let Err(broken) = fuzz_targets::pair(text)
    {
        panic!("{broken}");
    }
});
