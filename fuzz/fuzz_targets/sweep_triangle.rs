//! The robust sweep of the unit sphere against one triangle: never panics,
//! `t` in `[0, 1]`, touches exactly where it says, enters nothing before,
//! agrees with `Mpfr<256>` on the same input within the bound (see
//! `sweepslide_fuzz::oracle` and docs/fuzzing.md). Fauerby's detection runs
//! on the same input for "never panics" only.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sweepslide::Real;
use sweepslide::detect::sweep_fauerby;
use sweepslide::geom::{Triangle, vec3};
use sweepslide_fuzz::input::{Precision, SweepCase, SweepInput};
use sweepslide_fuzz::oracle::{Skip, check_sweep};
use sweepslide_fuzz::stats;

const NAME: &str = "sweep_triangle";

fn run<T: Real>(case: &SweepCase) -> Result<Result<sweepslide_fuzz::oracle::SweepStats, Skip>, String> {
    let p = |a: &[f64; 3]| vec3::<T>(a[0], a[1], a[2]);
    let tri = Triangle::new(p(&case.tri[0]), p(&case.tri[1]), p(&case.tri[2]));
    let _ = sweep_fauerby(&tri, &p(&case.base), &p(&case.vel), 0);
    check_sweep::<T>(case.base, case.vel, case.tri)
}

fuzz_target!(|input: SweepInput| {
    let case = input.build();
    stats::count(NAME, "inputs");
    let (result, key) = match input.precision {
        Precision::F32 => (run::<f32>(&case), "f32"),
        Precision::F64 => (run::<f64>(&case), "f64"),
    };
    match result {
        Ok(Ok(s)) => {
            stats::count(NAME, if s.hit { "hit" } else { "miss" });
            stats::worst(key, s.worst);
        }
        Ok(Err(Skip::OutOfRange)) => stats::count(NAME, "skip-range"),
        Ok(Err(Skip::Excluded)) => stats::count(NAME, "skip-excluded"),
        Ok(Err(_)) => stats::count(NAME, "skip-degenerate"),
        Err(msg) => panic!("{NAME}: {msg}\ninput: {input:?}\ncase: {case:?}"),
    }
});
