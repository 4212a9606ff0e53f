//! The lab: scenes, exact metrics and the experiment runner.
//!
//! A run is a scene (geometry, body, motion), a response, a detection and a
//! precision; [`runner::run`] plays it frame by frame and measures it with
//! [`metrics`], independently of the code under test.

pub mod json_float;
pub mod metrics;
pub mod rng;
pub mod runner;
pub mod scenes;
pub mod search;

pub use runner::{FrameRecord, Precision, RunConfig, RunOutput, RunResult, run, run_all};
pub use scenes::{Motion, Scene};
