//! What a query gathers: every triangle within reach, however far from the
//! origin and however small the body (a review, twenty-second session).
//!
//! * `Reach::of_sweep` centred its ball on the sweep's midpoint rounded in
//!   world coordinates; a million radii from the origin in `f32` that
//!   rounding (half an ulp, 0.0625) exceeds the ball's margin beyond the
//!   radius (0.05 radii of 0.51), and `sweep_world` missed the wall the
//!   sweep ends on. The ball now grows by that rounding, and every reach's
//!   box by the rounding of its corners.
//! * A body of radius `1e-160` at the exact origin of an `f64` world: the
//!   ball query widened its radius by `0 * |scale|`, where `|scale|`
//!   overflowed (`1 / r` squared), so the radius became NaN and nothing was
//!   ever gathered: the body fell through the floor.

use std::sync::Arc;
use sweepslide::Real;
use sweepslide::detect::{DetectOptions, Detection, sweep_world};
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

/// A wall at `x = wall`, a sphere of radius 0.51 at `x = 2^20` swept
/// 0.124 towards it: touches at `t = (wall - 2^20 - 0.51) / 0.124`.
fn hits_the_far_wall<T: Real>() -> Option<f64> {
    let wall = 1048576.625;
    let mesh =
        TriangleMesh::new(vec![[wall, -100.0, -100.0], [wall, 0.0, 100.0], [wall, 100.0, -100.0]], vec![[0, 1, 2]])
            .unwrap();
    let world = World::<T>::new(Arc::new(mesh)).unwrap();
    let body = Ellipsoid::<T>::sphere(0.51).unwrap();
    let (position, velocity): (Vec3<T>, Vec3<T>) = (vec3(1048576.0, 0.0, 0.0), vec3(0.124, 0.0, 0.0));
    let hit = sweep_world(&world, &body, &position, &velocity, Detection::Robust, &DetectOptions::default()).unwrap();
    hit.map(|h| h.t.to_f64())
}

#[test]
fn a_sweep_a_million_radii_from_the_origin_finds_the_wall_it_ends_on() {
    // The velocity 0.124 is rounded to f32 (0.12399999797).
    let exact = 0.115 / f64::from(0.124f32);
    let t = hits_the_far_wall::<f32>().expect("the wall is hit");
    assert!((t - exact).abs() < 1e-5, "t = {t}, exact {exact}");
    #[cfg(feature = "mpfr")]
    assert_eq!(hits_the_far_wall::<sweepslide::Mpfr<24>>(), Some(t), "Mpfr<24> reproduces f32");
}

#[test]
fn a_tiny_body_at_the_origin_lands_on_the_floor() {
    for r in [1e-150, 1e-160, 1e-200] {
        // A floor 2 radii below the centre; the body moves 3 radii down.
        let corners = vec![[-4.0 * r, -4.0 * r, -2.0 * r], [4.0 * r, -4.0 * r, -2.0 * r], [0.0, 4.0 * r, -2.0 * r]];
        let world = World::<f64>::new(Arc::new(TriangleMesh::new(corners, vec![[0, 1, 2]]).unwrap())).unwrap();
        let body = Ellipsoid::<f64>::sphere(r).unwrap();
        let mut candidates = Vec::new();
        let zero = vec3(0.0, 0.0, 0.0);
        world.each_candidate(&zero, &zero, Some((&zero, body.radii(), &1.05)), |t| candidates.push(t));
        assert_eq!(candidates, [0], "r = {r:e}: the floor is within 1.05 radii");
        let m = move_body(&world, &body, &zero, &vec3(0.0, 0.0, -3.0 * r), None, &MoveOptions::new(Response::Robust))
            .unwrap();
        let z = m.position.z / r;
        assert!(z > -1.0 - 1e-9 && z < -0.99, "r = {r:e}: ends at z = {z} radii (the floor is at -2)");
    }
}
