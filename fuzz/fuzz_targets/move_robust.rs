//! The robust response over a small soup and a sequence of frames: never a
//! NaN, never more collision checks than its bound, never ends a frame
//! penetrating (exact MPFR check), from a start outside the geometry (see
//! `sweepslide_fuzz::oracle` and docs/fuzzing.md).
#![no_main]

use libfuzzer_sys::fuzz_target;
use sweepslide_fuzz::input::{MoveInput, Precision};
use sweepslide_fuzz::oracle::{Skip, check_robust_moves};
use sweepslide_fuzz::stats;

const NAME: &str = "move_robust";

fuzz_target!(|input: MoveInput| {
    let case = input.build();
    stats::count(NAME, "inputs");
    let result = match input.precision {
        Precision::F32 => check_robust_moves::<f32>(&case),
        Precision::F64 => check_robust_moves::<f64>(&case),
    };
    match result {
        Ok(Ok(())) => stats::count(NAME, "checked"),
        Ok(Err(Skip::StartsInside)) => stats::count(NAME, "skip-starts-inside"),
        Ok(Err(Skip::EmptyMesh)) => stats::count(NAME, "skip-empty"),
        Ok(Err(Skip::PaddingCap)) => stats::count(NAME, "skip-padding-cap"),
        Ok(Err(_)) => stats::count(NAME, "skip-range"),
        Err(msg) => panic!("{NAME}: {msg}\ninput: {input:?}"),
    }
});
