//! A displacement that approaches a surface by less than the cone's
//! tolerance but more than the sweep's graze share, found by a directed
//! probe in the twenty-third session (R23d): the cone projection left it
//! unchanged, the next sweep met the same surface again, and the body
//! spent every sweep of the pass on it without moving (`IterationCap`).
//! In `f32` a push along a floor tilted into it by between `16 u` and
//! `64 u` (`1e-6` to `3.8e-6` of its length) froze the body; shallow bowls
//! alike. The displacement now keeps none of its approach to the plane
//! just hit.

use std::sync::Arc;
use sweepslide::geom::{Ellipsoid, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, StopReason, move_body};
use sweepslide::world::{TriangleMesh, World};

/// A unit sphere settled on an `f32` floor, pushed 100 radii along it and
/// `3.5e-4` into it (`3.5e-6` of the push, between the two tolerances):
/// it stayed put at the iteration cap; it slides the whole way now.
#[test]
fn sphere_pushed_along_a_floor_and_slightly_into_it_slides_f32() {
    let floor = TriangleMesh::new(
        vec![[-30.0, -30.0, 0.0], [200.0, -30.0, 0.0], [200.0, 30.0, 0.0], [-30.0, 30.0, 0.0]],
        vec![[0, 1, 2], [0, 2, 3]],
    )
    .unwrap();
    let world = World::<f32>::new(Arc::new(floor)).unwrap();
    let body = Ellipsoid::<f32>::sphere(1.0).unwrap();
    let options = MoveOptions::new(Response::Robust);
    let mut p = vec3::<f32>(0.0, 0.0, 1.0001);
    for _ in 0..3 {
        p = move_body(&world, &body, &p, &vec3(0.0, 0.0, -0.02), None, &options).unwrap().position;
    }
    let moved = move_body(&world, &body, &p, &vec3(100.0, 0.0, -3.5e-4), None, &options).unwrap();
    assert_ne!(moved.trace.stop, StopReason::IterationCap, "{:?}", moved.trace);
    assert!(moved.position.x > 99.99, "moved to {:?} from {p:?}", moved.position);
    let depth = penetration(&world, body.radii(), &moved.position).unwrap_or(f64::NEG_INFINITY);
    assert!(depth <= 0.0, "penetration {depth:e}");
}
