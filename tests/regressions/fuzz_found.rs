//! Robust failures the fuzz campaigns found (docs/fuzzing.md), pinned after
//! their fixes. The minimised inputs are in `fuzz/regressions/`, replayed by
//! `cargo run --manifest-path fuzz/Cargo.toml --example replay`; F1 (long
//! sweeps) is pinned by `tests/detect_props.rs`, F2 (the gather box) by its
//! two inputs there.

use std::path::Path;
use std::sync::Arc;
use sweepslide::detect::{DetectOptions, Detection, sweep_world};
use sweepslide::geom::{Ellipsoid, vec3};
use sweepslide::world::{TriangleMesh, World};

/// F7: a vertex the sphere already overlaps (its distance far below the
/// rounding of 7.8e10 coordinates in f32) gave a negative `t`. The vertex
/// branch now requires the body to start outside, like the edge branch.
#[test]
fn huge_coordinates_never_give_a_negative_time() {
    let obj = "o cube\nv -1 -1 -1\nv 1 77777777777 1\nv -11  -5 -1\nv 0 1 -1\nv -1 1 -1\nv -0 -1 1\nv 1 -1 1\nv 1 17777777 6\nf 1 5 5 2\nf  1 3 8\n";
    let mesh = TriangleMesh::from_obj_str(obj, Path::new("huge.obj")).unwrap();
    let world = World::<f32>::new(Arc::new(mesh));
    let body = Ellipsoid::<f32>::sphere(1000.0).unwrap();
    let hit = sweep_world(
        &world,
        &body,
        &vec3(-5.0, 7.78e10, 2.5),
        &vec3(1.2, -7.78e10, 0.7),
        Detection::Robust,
        &DetectOptions::default(),
    )
    .unwrap();
    if let Some(h) = hit {
        assert!((0.0..=1.0).contains(&h.t), "{h:?}");
    }
}
