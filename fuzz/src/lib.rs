//! Shared code of the sweepslide fuzz targets (see `docs/fuzzing.md`):
//! the inputs ([`input`], decoded with `arbitrary`), their encoding for the
//! seed corpus ([`encode`]), the invariants and their exact oracles
//! ([`oracle`], shared with the root crate's `tests/fuzz_props.rs`) and
//! the findings log of `compare_responses` ([`findings`]).

pub mod encode;
pub mod findings;
pub mod input;
#[path = "oracle.rs"]
pub mod oracle;
pub mod stats;
