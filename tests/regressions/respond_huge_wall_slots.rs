//! Slots between one huge wall (a single triangle whose vertices lie
//! `5e5` to `9e5` radii away) and a tessellated wall, narrower than the
//! huge wall's padding, in `f32`: the regime where the robust response
//! caps its padding (`max_padding`) because the huge triangle's distance,
//! computed from vertices that far, is off by more than the cap (`u s`
//! with `s = 5e5`: `0.03` radii).
//!
//! A push that restores the skin between two walls at once
//! (`skin_in_crease`, the fix of fuzz finding F34) must not move the body
//! there. Two of its drafts did, found by a random probe of 300 such slots
//! (the code before left a body inside in one, the first draft in 20, up
//! to `3.3e-3` deep, the second in 3; the final code in the same one as
//! the code before). The first trusted the huge wall's direction, off by
//! `0.03` radians (its closest point is off by `u s`, `0.03` radii at
//! `s = 5e5` in `f32`): a push along the tessellated wall seemed to gain
//! on the huge one, and the draft shortened such pushes, longer than its
//! limits' reach, instead of refusing them; the body ended `4.7e-4`
//! inside. The second set no limit for the huge wall where its distance,
//! off by more than `0.01`, put it beyond reach, and a push towards it
//! ended `6.5e-4` inside. Where a triangle whose padding is capped could
//! be within reach, the push is now refused, and so is any push longer
//! than the reach; the first scene fails only without both, the second
//! without the first (or with the reach not widened by the capped
//! triangle's error).

use std::sync::Arc;
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

/// A slot: the huge wall's three vertices, the tessellated wall in the
/// plane `x = wall_x` (a grid of `cells` x `cells` squares of side `cell`
/// over `y, z` in `[-cells cell / 2, cells cell / 2]`, square `(i, j)`
/// split along the diagonal from corner `(i, j)` where bit `i cells + j`
/// of `diagonals` is 0, along the other where it is 1), the body and its
/// motion, and the offset added to every coordinate.
struct Slot {
    huge: [[f64; 3]; 3],
    wall_x: f64,
    cells: u32,
    cell: f64,
    diagonals: u128,
    radii: [f64; 3],
    velocity: [f64; 3],
    gravity: [f64; 3],
    offset: [f64; 3],
}

impl Slot {
    /// The largest exact penetration (radii-relative, positive inside)
    /// over 60 frames of the robust response in `f32`, from the slot's
    /// centre.
    fn worst_penetration(&self) -> f64 {
        let o = self.offset;
        let at = |p: [f64; 3]| [p[0] + o[0], p[1] + o[1], p[2] + o[2]];
        let mut vertices: Vec<[f64; 3]> = self.huge.iter().map(|&p| at(p)).collect();
        let mut indices = vec![[0, 1, 2]];
        let n = self.cells;
        let half = self.cell * f64::from(n) / 2.0;
        for i in 0..=n {
            for j in 0..=n {
                let (y, z) = (-half + self.cell * f64::from(i), -half + self.cell * f64::from(j));
                vertices.push(at([self.wall_x, y, z]));
            }
        }
        let id = |i: u32, j: u32| 3 + i * (n + 1) + j;
        for i in 0..n {
            for j in 0..n {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                if self.diagonals >> (i * n + j) & 1 == 0 {
                    indices.extend([[a, d, c], [a, c, b]]);
                } else {
                    indices.extend([[a, d, b], [b, d, c]]);
                }
            }
        }
        let world = World::<f32>::new(Arc::new(TriangleMesh::new(vertices, indices).unwrap())).unwrap();
        let body = Ellipsoid::<f32>::new(self.radii).unwrap();
        let v = |p: [f64; 3]| -> Vec3<f32> { vec3(p[0], p[1], p[2]) };
        let radii = v(self.radii);
        let mut p = v(o);
        assert!(penetration(&world, &radii, &p).unwrap_or(-1.0) <= 0.0, "the body must start outside");
        let options = MoveOptions::new(Response::Robust);
        (0..60).fold(f64::NEG_INFINITY, |worst, frame| {
            let step = move_body(&world, &body, &p, &v(self.velocity), Some(&v(self.gravity)), &options);
            p = step.unwrap_or_else(|e| panic!("frame {frame}: {e}")).position;
            assert!(p.iter().all(|x| x.is_finite()), "frame {frame}: {p:?}");
            worst.max(penetration(&world, &radii, &p).unwrap_or(f64::NEG_INFINITY))
        })
    }
}

/// The first draft's scene: an ellipsoid in a slot `1.5e-5` radii wider
/// than itself, at the origin, the huge wall's vertices `5e5` away.
#[test]
fn a_narrow_slot_beside_a_huge_wall_is_not_entered() {
    let (d, w) = (505697.6071084646, 1.5389246202314846);
    let slot = Slot {
        huge: [[-w, -d, -335715.78098579904], [-w, -d, 675679.4332311301], [-w, d, 169981.82612266557]],
        wall_x: w,
        cells: 8,
        cell: 0.577828669381309,
        diagonals: 0x1a2c_b982_9e4b_3111,
        radii: [1.5389129349847557, 1.3628762625525963, 1.1039595338715322],
        velocity: [-0.00620530371976086, -0.006629707376687278, 0.027683831287114217],
        gravity: [0.0, -0.006716032095568059, 0.0],
        offset: [0.0; 3],
    };
    let worst = slot.worst_penetration();
    assert!(worst <= 0.0, "penetration {worst:e}");
}

/// The second draft's scene: a sphere in a slot
/// `8.8e-4` radii wider than itself, `6.2e3` from the origin (an `f32`
/// spacing of `2.4e-4`), the huge wall's vertices `8.8e5` away.
#[test]
fn a_huge_wall_measured_beyond_reach_still_forbids_the_push() {
    let (d, w) = (883890.5631233916, 0.28202908337382815);
    let slot = Slot {
        huge: [[w, -d, -601845.4901401768], [w, -d, 1165935.6361066063], [w, d, 282045.0729832148]],
        wall_x: -w,
        cells: 9,
        cell: 0.10404932480862472,
        diagonals: 0x5fd1_e9c0_d6b4_7f24_204c,
        radii: [0.28190470603405804; 3],
        velocity: [0.0013614805835672399, 0.0009994074231155848, 0.0047860733809539265],
        gravity: [0.0, -0.06267937286428805, 0.0],
        offset: [-3585.67570224773, -3245.9799321183946, -3923.4920778259634],
    };
    let worst = slot.worst_penetration();
    assert!(worst <= 0.0, "penetration {worst:e}");
}
