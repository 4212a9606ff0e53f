//! Bodies pushed along the fold of a shallow valley or ridge, found by a
//! directed probe in the twenty-third session (R23c). Resting on both
//! faces, the body is pushed into both, and the cone projection keeps the
//! motion along their crease, `n1 x n2`. That cross product of two nearly
//! equal unit normals subtracts products of size 1 and is off by `u`
//! absolute, a direction error of `u / sin theta`: the crease motion
//! then seemed to enter both faces by more than the cone's tolerance,
//! no candidate was admissible, and the body stopped dead (`Blocked`).
//! In `f64` about a third of the pushes along folds below `1e-3` rad
//! froze; in `f32` a valley of `3.7e-3` rad (0.2 degrees) froze a body
//! frame after frame. The crease is now `n1 x (n2 - n1)`, exact but for
//! `u` relative to its length.

use std::sync::Arc;
use sweepslide::Real;
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, StopReason, move_body};
use sweepslide::world::{TriangleMesh, World};

/// Moves a body of `radius` from `start` by `vel` (and `gravity`) for
/// `frames` frames over two folded quads (`vertices`: the fold's two ends,
/// then two corners on each side) and returns its displacement along the
/// unit `fold` and the exact worst penetration.
fn push_along_fold<T: Real>(
    vertices: [[f64; 3]; 6],
    radius: f64,
    start: [f64; 3],
    vel: [f64; 3],
    gravity: Option<[f64; 3]>,
    frames: usize,
) -> (Vec3<T>, f64) {
    let mesh = TriangleMesh::new(vertices.to_vec(), vec![[0, 1, 2], [0, 2, 3], [0, 5, 4], [0, 4, 1]]).unwrap();
    let world = World::<T>::new(Arc::new(mesh)).unwrap();
    let body = Ellipsoid::<T>::sphere(radius).unwrap();
    let v = |x: [f64; 3]| vec3::<T>(x[0], x[1], x[2]);
    let start = v(start);
    let (mut p, mut worst) = (start.clone(), f64::NEG_INFINITY);
    for k in 0..frames {
        let moved = move_body(&world, &body, &p, &v(vel), gravity.map(v).as_ref(), &MoveOptions::new(Response::Robust))
            .unwrap();
        assert!(gravity.is_some() || moved.trace.stop != StopReason::Blocked, "frame {k}: {:?}", moved.trace);
        p = moved.position;
        worst = worst.max(penetration(&world, body.radii(), &p).unwrap_or(f64::NEG_INFINITY));
    }
    (p - start, worst)
}

/// `f64`, a unit sphere in a valley whose faces rise `1e-4` per unit from
/// a fold along `(1, 1, 1)`, pushed along the fold and into both faces:
/// `Blocked`, no displacement, where the fold's component of the push was
/// due.
#[test]
fn sphere_pushed_along_the_fold_of_a_shallow_valley_slides_f64() {
    let s = 57.73502691896258;
    let vertices = [
        [-s, -s, -s],
        [s, s, s],
        [-12.979733682596798, 128.4416225547127, 57.74319188477186],
        [-128.44978752052197, 12.97156871678752, -57.7268619531533],
        [128.4416225547127, -12.979733682596798, 57.74319188477186],
        [12.97156871678752, -128.44978752052197, -57.7268619531533],
    ];
    let start = [-0.40824829250551276, -0.40824829250551276, 0.8164965850110255];
    let vel = [0.5814327520942645, 0.5814327520942645, 0.5691853033803486];
    let (moved, worst) = push_along_fold::<f64>(vertices, 1.0, start, vel, None, 1);
    let fold = 1.0 / 3f64.sqrt();
    let along = (moved.x + moved.y + moved.z) * fold;
    let due = (vel[0] + vel[1] + vel[2]) * fold;
    assert!(along > 0.99 * due, "moved {along} of {due} along the fold");
    assert!(worst <= 0.0, "penetration {worst:e}");
}

/// `f32`, a sphere (radius 0.84) in a valley folded by `3.7e-3` rad,
/// pushed along the fold and into both faces, with gravity: frozen in
/// every frame.
#[test]
fn sphere_pushed_along_the_fold_of_a_shallow_valley_slides_f32() {
    let vertices = [
        [33.39031023611679, 9.928883465025857, -20.890730401058374],
        [-34.039058623043886, -10.595491171233823, 24.2053326458074],
        [-26.417182139125078, 21.340196955044693, 50.13660622479643],
        [41.0121867200356, 41.864571591304376, 5.040543177930662],
        [-41.747920992777054, -42.438635051249385, -1.8138863175772606],
        [25.681447866383625, -21.914260414989702, -46.90994936444303],
    ];
    let start = [-0.01734662428498268, 0.4048895835876465, 0.6604275107383728];
    let vel = [-0.16744080185890198, -0.35427984595298767, 0.48435625433921814];
    let gravity = [0.004718436393886805, -0.005019942298531532, 0.004770482890307903];
    let fold = [-0.8058415985860063, -0.2452847349262206, 0.5389385092944496];
    let (moved, worst) = push_along_fold::<f32>(vertices, 0.8367571117881927, start, vel, Some(gravity), 4);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let along = dot([f64::from(moved.x), f64::from(moved.y), f64::from(moved.z)], fold);
    let due = 4.0 * dot(vel, fold);
    assert!(along > 0.99 * due, "moved {along} of {due} along the fold");
    assert!(worst <= 0.0, "penetration {worst:e}");
}
