//! Regression tests, one module per topic, each test named after the case
//! it pins: inputs found by the lab, by fuzzing or in the literature where
//! a variant once gave (or still gives, for the faithful baselines) a wrong
//! answer.

mod detect_long_edges;
mod detect_long_slivers;
mod fauerby_detection;
mod fuzz_found;
mod lab_found;
mod respond_back_face;
mod respond_ellipsoid_reach;
mod respond_embedded;
mod respond_far_origin;
mod respond_hard_pushes;
mod respond_huge_wall_slots;
mod respond_messy_levels;
mod respond_parallel_planes;
mod respond_seam_hits;
mod respond_shallow_climbs;
mod respond_shallow_folds;
mod world_reach;
