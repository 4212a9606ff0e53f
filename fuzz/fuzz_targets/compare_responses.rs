//! The same soup, start and frames through Fauerby's, Linahan's and the
//! robust response. Failures of the faithful two (a NaN position, a frame
//! ending inside the geometry) are recorded, not asserted (see
//! `sweepslide_fuzz::findings`); only the robust response's are.
#![no_main]

use arbitrary::{Arbitrary, Unstructured};
use libfuzzer_sys::fuzz_target;
use sweepslide::Real;
use sweepslide::respond::Response;
use sweepslide_fuzz::input::{MoveInput, Precision};
use sweepslide_fuzz::oracle::{MoveCase, play, prepare};
use sweepslide_fuzz::{findings, stats};

const NAME: &str = "compare_responses";

fn compare<T: Real>(input: &MoveInput, case: &MoveCase, data: &[u8]) {
    let Ok(prepared) = prepare::<T>(case) else {
        stats::count(NAME, "skipped");
        return;
    };
    stats::count(NAME, "checked");
    for response in [Response::Fauerby, Response::Linahan] {
        if let Some(f) = play(case, &prepared, response) {
            stats::count(NAME, if response == Response::Fauerby { "fauerby-fails" } else { "linahan-fails" });
            findings::record(NAME, response.name(), input.precision, case, data, &f);
        }
    }
    if let Some(f) = play(case, &prepared, Response::Robust) {
        panic!("{NAME}: robust response failed ({}): {f:?}\ninput: {input:?}\ncase: {case:?}", T::name());
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(input) = MoveInput::arbitrary_take_rest(Unstructured::new(data)) else {
        return;
    };
    stats::count(NAME, "inputs");
    let case = input.build();
    match input.precision {
        Precision::F32 => compare::<f32>(&input, &case, data),
        Precision::F64 => compare::<f64>(&input, &case, data),
    }
});
