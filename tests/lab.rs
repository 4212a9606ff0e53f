//! The lab: metric definitions pinned on hand-computed cases, the exact
//! distance against brute force, and the `sweepslide run` contract.
#![cfg(feature = "cli")]

use proptest::prelude::*;
use rug::Float;
use std::path::Path;
use std::process::Command;
use std::sync::Arc;
use sweepslide::geom::{Vec3, vec3};
use sweepslide::lab::metrics::{
    DRIFT_THRESHOLD, EXACT_BITS, drift, jitter, penetrated, penetration, snag_ratio, triangle_distance_sq, wobble,
};
use sweepslide::lab::{Precision, RunConfig, Scene, run};
use sweepslide::respond::Response;
use sweepslide::world::{TriangleMesh, World};

fn floor() -> World<f64> {
    let v = vec![[-10.0, 0.0, -10.0], [-10.0, 0.0, 10.0], [10.0, 0.0, 10.0], [10.0, 0.0, -10.0]];
    World::new(Arc::new(TriangleMesh::new(v, vec![[0, 1, 2], [0, 2, 3]]).unwrap())).unwrap()
}

#[test]
fn body_inside_a_plane_by_a_tenth_reports_a_tenth() {
    let world = floor();
    // A sphere of radius 1 whose centre is 0.9 above the floor.
    let pen = penetration(&world, &vec3(1.0, 1.0, 1.0), &vec3(0.5, 0.9, 0.5)).unwrap();
    assert_eq!(pen, 1.0 - 0.9, "exact at 512 bits, then rounded once");
    // Radius 2: penetration in world units.
    let pen = penetration(&world, &vec3(2.0, 2.0, 2.0), &vec3(0.5, 1.9, 0.5)).unwrap();
    assert!((pen - 0.1).abs() < 1e-15, "{pen}");
    // Just clear of the floor: negative (the clearance), not penetrating.
    let pen = penetration(&world, &vec3(1.0, 1.0, 1.0), &vec3(0.0, 1.0 + 2f64.powi(-30), 0.0)).unwrap();
    assert_eq!(pen, -(2f64.powi(-30)));
    // Nothing within reach.
    assert_eq!(penetration(&world, &vec3(1.0, 1.0, 1.0), &vec3(0.0, 1.5, 0.0)), None);
}

/// The triangles a body ends inside of, with their depths and whether it
/// entered each from behind: the frame started behind its plane (the
/// floor's front is +y) and one of the frame's passes moved along its
/// front normal, so that Fauerby's detection culled it.
#[test]
fn penetrated_lists_each_triangle_with_whether_it_was_entered_from_behind() {
    let world = floor();
    let r = vec3(1.0, 1.0, 1.0);
    let inside = vec3(0.5, 0.5, 5.0);
    let up = vec3(0.0, 1.0, 0.0);
    let sides = |start: Vec3<f64>, passes: &[&Vec3<f64>]| -> Vec<(u32, f64, bool)> {
        penetrated(&world, &r, &start, &inside, passes).iter().map(|p| (p.triangle, p.depth, p.from_behind)).collect()
    };
    assert_eq!(sides(vec3(0.5, 1.5, 5.0), &[&up]), vec![(0, 0.5, false)]);
    assert_eq!(sides(vec3(0.5, 0.0, 5.0), &[&up]), vec![(0, 0.5, false)], "in the plane: not behind");
    assert_eq!(sides(vec3(0.5, -0.5, 5.0), &[&up]), vec![(0, 0.5, true)]);
    // Behind, but no pass culls the floor: along its plane, or towards its
    // back (the detection checks it), or no pass at all.
    let (along, down) = (vec3(1.0, 0.0, 0.0), vec3(0.0, -1.0, 0.0));
    assert_eq!(sides(vec3(0.5, -0.5, 5.0), &[&along]), vec![(0, 0.5, false)]);
    assert_eq!(sides(vec3(0.5, -0.5, 5.0), &[&along, &down]), vec![(0, 0.5, false)]);
    assert_eq!(sides(vec3(0.5, -0.5, 5.0), &[]), vec![(0, 0.5, false)]);
    // One pass of two culling it is enough.
    assert_eq!(sides(vec3(0.5, -0.5, 5.0), &[&along, &up]), vec![(0, 0.5, true)]);
    assert!(penetrated(&world, &r, &vec3(0.5, -0.5, 5.0), &vec3(0.5, 1.5, 5.0), &[&up]).is_empty(), "not inside");
    // In eSpace: radii (1, 4, 1) reach 4 below the floor.
    let tall = vec3(1.0, 4.0, 1.0);
    let deep = penetrated(&world, &tall, &vec3(0.5, -5.0, 5.0), &vec3(0.5, -3.0, 5.0), &[&up]);
    assert_eq!(deep.iter().map(|p| (p.triangle, p.depth, p.from_behind)).collect::<Vec<_>>(), vec![(0, 0.25, true)]);
    // A wall at x = 2 facing -x beside the floor: a body that came up
    // through the floor ends inside both, and only the floor was entered
    // from behind.
    let v = vec![
        [-10.0, 0.0, -10.0],
        [-10.0, 0.0, 10.0],
        [10.0, 0.0, 10.0],
        [2.0, -10.0, -10.0],
        [2.0, 10.0, 10.0],
        [2.0, -10.0, 10.0],
    ];
    let both = World::new(Arc::new(TriangleMesh::new(v, vec![[0, 1, 2], [3, 5, 4]]).unwrap())).unwrap();
    let step = vec3(0.2, 1.0, 0.0);
    let mut two = penetrated(&both, &r, &vec3(1.0, -0.5, 5.0), &vec3(1.2, 0.5, 5.0), &[&step]);
    two.sort_by_key(|p| p.triangle);
    assert_eq!((two[0].triangle, two[0].depth, two[0].from_behind), (0, 0.5, true));
    assert_eq!((two[1].triangle, two[1].from_behind), (1, false));
    assert!((two[1].depth - 0.2).abs() < 1e-15, "{:?}", two[1]);
}

/// A review's finding (thirty-eighth session): a body beside a triangle,
/// behind its plane's extension, pushed along the plane into its edge is
/// not culled by Fauerby's detection (`n . v = 0`), so when it sinks in
/// (in `f32` `1e5` out both faithful responses went `0.54` radii into
/// such an edge) that counts against the response, as its mirror image in
/// front does; the side of the start alone had excused it.
#[test]
fn a_body_pushed_along_a_plane_into_an_edge_from_behind_it_is_not_excused() {
    let tri = |y: f64| {
        let v = vec![[1e5, 0.0, -1e3], [1e5, 0.0, 1e3], [1e5 + 100.0, 0.0, 0.0]];
        let scene = Scene {
            name: "edge-beside".into(),
            description: "a body beside a triangle's edge, pushed along its plane".into(),
            mesh: Arc::new(TriangleMesh::new(v, vec![[0, 1, 2]]).unwrap()),
            start: [1e5 - 0.9, y, -500.0],
            radii: [1.0; 3],
            velocity: [0.02, 0.0, 0.1],
            gravity: [0.0; 3],
            frames: 300,
            motion: sweepslide::lab::scenes::Motion::Constant,
            ideal: None,
            units_per_meter: 1.0,
        };
        let cfg = RunConfig {
            scene: Arc::new(scene),
            response: Response::Fauerby,
            detection: None,
            precision: Precision::F32,
            seed: 1,
        };
        run(&cfg).unwrap().result
    };
    for y in [0.45, -0.45] {
        let r = tri(y);
        assert!(r.max_penetration > 0.1, "y {y}: {r:?}");
        assert_eq!(r.back_face_frames, 0, "y {y}: {r:?}");
        assert_eq!(r.counted_penetration(), (r.penetrating_frames, r.max_penetration), "y {y}");
    }
}

/// A negative penetration is minus the clearance to the nearest triangle,
/// up to `PENETRATION_REACH` (a review found -7.05 where the clearance was
/// 8.5e-6: a far triangle of a BVH leaf stood in for a wall just outside a
/// box that reached only `1e-6` beyond the radius).
#[test]
fn a_negative_penetration_is_the_clearance_within_reach() {
    use sweepslide::lab::metrics::PENETRATION_REACH;
    // A floor in one BVH leaf; in another, four triangles far away and a
    // long one reaching back over the floor, 3 above it. (A box reaching
    // `1e-6` beyond the radius missed the floor a gap below: no value at
    // all here, a far triangle's in the review's scene.)
    let mut v = vec![[-10.0, 0.0, -10.0], [-10.0, 0.0, 10.0], [10.0, 0.0, 10.0], [10.0, 0.0, -10.0]];
    let mut t = vec![[0, 1, 2], [0, 2, 3]];
    for k in 0..4 {
        let x = 100.0 + 3.0 * f64::from(k);
        let i = v.len() as u32;
        v.extend([[x, 0.0, 0.0], [x + 1.0, 0.0, 0.0], [x, 1.0, 0.0]]);
        t.push([i, i + 1, i + 2]);
    }
    let i = v.len() as u32;
    v.extend([[-5.0, 4.1, -1.0], [-5.0, 4.1, 1.0], [120.0, 5.0, 0.0]]);
    t.push([i, i + 1, i + 2]);
    let world = World::<f64>::new(Arc::new(TriangleMesh::new(v, t).unwrap())).unwrap();
    let r = vec3(1.0, 1.0, 1.0);
    for gap in [8.5e-6, 0.01, 0.04] {
        let pen = penetration(&world, &r, &vec3(0.0, 1.0 + gap, 0.0)).unwrap();
        assert!((pen + gap).abs() < 1e-15, "{gap}: {pen}");
    }
    assert_eq!(penetration(&world, &r, &vec3(0.0, 1.0 + PENETRATION_REACH + 1e-9, 0.0)), None);
    // A wall only, just beyond the radius along x, far from the origin in
    // `f32`: found from either side.
    let v = vec![[1e5 + 1.001, -5.0, -5.0], [1e5 + 1.001, 5.0, -5.0], [1e5 + 1.001, 0.0, 5.0]];
    let world = World::<f32>::new(Arc::new(TriangleMesh::new(v, vec![[0, 1, 2]]).unwrap())).unwrap();
    let wall = f64::from((1e5f64 + 1.001) as f32);
    for x in [1e5, 1e5 + 0.0078125, 1e5 + 0.5] {
        let pen = penetration(&world, &vec3(1.0, 1.0, 1.0), &vec3(x, 0.0, 0.0)).unwrap();
        assert_eq!(pen, 1.0 - (wall - f64::from(x as f32)), "{x}");
    }
}

#[test]
fn ellipsoid_penetration_is_in_espace_units() {
    let world = floor();
    // Radii (1, 2, 1): centre 1.8 above the floor is 0.9 in eSpace: 0.1 inside.
    let pen = penetration(&world, &vec3(1.0, 2.0, 1.0), &vec3(0.0, 1.8, 0.0)).unwrap();
    assert!((pen - 0.1).abs() < 1e-15, "{pen}");
}

#[test]
fn straight_motion_and_rest_have_zero_jitter() {
    let line: Vec<Vec3<f64>> = (0..40).map(|k| vec3(0.1 * k as f64, 0.0, 0.0)).collect();
    assert_eq!(jitter(&line, 0.1), 0.0);
    let rest: Vec<Vec3<f64>> = (0..40).map(|_| vec3(3.0, 1.0, 2.0)).collect();
    assert_eq!(jitter(&rest, 0.1), 0.0);
}

#[test]
fn back_and_forth_has_the_jitter_the_formula_gives() {
    // 9 positions, 8 displacements: K = 2 (the last two): +0.1 then -0.1.
    let xs = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.6];
    let path: Vec<Vec3<f64>> = xs.iter().map(|&x| vec3(x, 0.0, 0.0)).collect();
    // (|0.1| + |-0.1| - |0|) / (2 * 0.1) = 1.
    let j = jitter(&path, 0.1);
    assert!((j - 1.0).abs() < 1e-12, "{j}");
    // A longer wiggle: K = 4 of 16 displacements, alternating 0.05 and -0.05.
    let mut x = 0.0;
    let mut path: Vec<Vec3<f64>> = vec![vec3(x, 0.0, 0.0)];
    for k in 0..16 {
        x += if k < 12 {
            0.1
        } else if k % 2 == 0 {
            0.05
        } else {
            -0.05
        };
        path.push(vec3(x, 0.0, 0.0));
    }
    let j = jitter(&path, 0.1);
    assert!((j - (0.2 - 0.0) / 0.4).abs() < 1e-12, "{j}");
}

/// Wobble scores a sliding body's sideways zigzag in proportion to its
/// size, where jitter scores its square; a body that stops, slows down or
/// turns once without turning back does not wobble.
#[test]
fn wobble_is_linear_in_a_sliding_zigzag_and_zero_for_steady_changes() {
    // 80 frames: K = 20 steps of 0.1 along x, alternating +-a along y.
    let zigzag = |a: f64| -> Vec<Vec3<f64>> {
        (0..=80).map(|k| vec3(0.1 * k as f64, if k % 2 == 0 { 0.0 } else { a }, 0.0)).collect()
    };
    for a in [1e-3, 1e-2] {
        let path = zigzag(a);
        // 19 step changes of 2a, the first step +a sideways and the last
        // -a: (19 * 2a - 2a) / (2 * 20 * 0.1) = 9a, which is 0.9 a / speed.
        let w = wobble(&path, 0.1);
        assert!((w - 9.0 * a).abs() < 1e-12, "a {a}: wobble {w}");
        // The path's excess: 20 (sqrt(0.01 + a^2) - ...) ~ a^2 / (2 * 0.1) per step.
        let j = jitter(&path, 0.1);
        assert!(j < 0.6 * a * a / 0.01, "a {a}: jitter {j}");
    }
    assert!(jitter(&zigzag(4e-3), 0.1) < 1e-3, "the zigzag that jitter misses");
    assert!(wobble(&zigzag(4e-3), 0.1) > 1e-3);
    // Stopping, slowing down steadily, and one turn: no wobble (beyond the
    // rounding of the positions, about `1e-16` of a step).
    let stop: Vec<Vec3<f64>> = (0..=80).map(|k| vec3(0.1 * k.min(70) as f64, 0.0, 0.0)).collect();
    assert!(wobble(&stop, 0.1) < 1e-14, "{}", wobble(&stop, 0.1));
    let mut x = 0.0;
    let slowing: Vec<Vec3<f64>> = (0..=80)
        .map(|k| {
            x += 0.1 / f64::from(k + 1);
            vec3(x, 0.0, 0.0)
        })
        .collect();
    assert!(wobble(&slowing, 0.1) < 1e-14, "{}", wobble(&slowing, 0.1));
    let turn: Vec<Vec3<f64>> = (0..=80)
        .map(|k| if k <= 70 { vec3(0.1 * k as f64, 0.0, 0.0) } else { vec3(7.0, 0.1 * (k - 70) as f64, 0.0) })
        .collect();
    assert!(wobble(&turn, 0.1) < 1e-14, "{}", wobble(&turn, 0.1));
    assert!(jitter(&turn, 0.1) > 1e-3, "jitter scores the turn");
    // At rest, toggling between two points 0.01 apart: about 0.01 / speed
    // in both.
    let toggle: Vec<Vec3<f64>> = (0..=80).map(|k| vec3(if k % 2 == 0 { 0.0 } else { 0.01 }, 0.0, 0.0)).collect();
    let (w, j) = (wobble(&toggle, 0.1), jitter(&toggle, 0.1));
    assert!((w - 0.09).abs() < 1e-12 && (j - 0.1).abs() < 1e-12, "wobble {w}, jitter {j}");
    // Not computable with a NaN position; nothing to compare with two steps.
    let mut nan = toggle.clone();
    nan[3] = vec3(f64::NAN, 0.0, 0.0);
    assert!(wobble(&nan, 0.1).is_nan());
    assert_eq!(wobble(&toggle[..3], 0.1), 0.0);
}

/// A review's finding (thirty-eighth session): Fauerby's response slides
/// along `fold:5` in `f64` zigzagging across the fold every frame (+-2.5
/// degrees), a jitter of `6.7e-4` that passed as steady; its wobble shows
/// it. The robust response slides the same fold steadily.
#[test]
fn fauerbys_zigzag_along_a_fold_shows_in_its_wobble_not_its_jitter() {
    let scene = Arc::new(sweepslide::lab::scenes::build("fold:5", 1).unwrap());
    let result = |response| {
        run(&RunConfig { scene: scene.clone(), response, detection: None, precision: Precision::F64, seed: 1 })
            .unwrap()
            .result
    };
    let f = result(Response::Fauerby);
    assert!(f.jitter < 1e-3 && f.wobble > 1e-2, "jitter {}, wobble {}", f.jitter, f.wobble);
    let r = result(Response::Robust);
    assert!(r.jitter < 1e-6 && r.wobble < 1e-6, "jitter {}, wobble {}", r.jitter, r.wobble);
}

#[test]
fn snag_ratio_is_progress_over_ideal() {
    let s = snag_ratio(&vec3::<f64>(0.0, 1.0, 0.0), &vec3(5.0, 1.0, 3.0), [0.1, 0.0, 0.0], 100).unwrap();
    assert!((s - 0.5).abs() < 1e-15);
    assert_eq!(snag_ratio(&vec3::<f64>(0.0, 0.0, 0.0), &vec3(1.0, 0.0, 0.0), [0.0; 3], 10), None);
}

/// The drift starts at the first frame that moves as the ideal does (the
/// fall onto the floor before it is the approach), measures only the
/// displacement across the ideal, in radii (eSpace for an ellipsoid), is
/// exactly zero for a slide along it, even where `f32` positions far from
/// the origin cannot move by exactly the ideal, and is absent where no
/// frame ever moves as the ideal does, or the positions' rounding is too
/// coarse to tell.
#[test]
fn drift_is_the_distance_off_the_ideal_line_after_the_approach() {
    let ideal = [0.1, 0.0, 0.0];
    let falling = [(0.0, 1.05, 0.0), (0.1, 1.03, 0.0), (0.2, 1.0, 0.0)];
    let path = |rest: &[(f64, f64, f64)]| -> Vec<_> {
        falling.iter().chain(rest).map(|&(x, y, z)| vec3::<f64>(x, y, z)).collect::<Vec<_>>()
    };
    let straight = path(&[(0.3, 1.0, 0.0), (0.4, 1.0, 0.0), (0.5, 1.0, 0.0)]);
    assert_eq!(drift(&straight, ideal, [0.5; 3]), Some(0.0));
    // Turned aside by 0.05 world units (0.1 radii) after the approach; the
    // fall before it (0.05) is not counted.
    let aside = path(&[(0.3, 1.0, 0.0), (0.4, 1.0, 0.05), (0.5, 1.0, 0.05)]);
    let d = drift(&aside, ideal, [0.5; 3]).unwrap();
    assert!((d - 0.1).abs() < 1e-15, "{d}");
    // An ellipsoid that sinks 0.009 world units, 0.01 of its vertical
    // radius, while it slides; its progress along the ideal does not count.
    let sinking = path(&[(0.3, 1.0, 0.0), (0.45, 0.991, 0.0), (0.5, 0.991, 0.0)]);
    let d = drift(&sinking, ideal, [0.4, 0.9, 0.4]).unwrap();
    assert!((d - 0.01).abs() < 1e-15, "{d}");
    // In f32 at 1e5 a step of 0.1 rounds to 0.09375 or 0.1015625: still a
    // slide along the ideal, with no drift.
    let far: Vec<_> = (0..20).map(|k| vec3::<f32>(1e5 + 0.1 * f64::from(k), 1.0, 1e5)).collect();
    assert!(far.windows(2).any(|w| w[1].x - w[0].x != 0.1_f32), "the steps round");
    assert_eq!(drift(&far, ideal, [1.0; 3]), Some(0.0));
    // A step of 0.01 at 4e4 is below the rounding of the positions there:
    // no frame can be told to slide as the ideal does.
    let coarse: Vec<_> = (0..20).map(|k| vec3::<f32>(4e4 + 0.01 * f64::from(k), 1.0, 4e4)).collect();
    assert_eq!(drift(&coarse, [0.01, 0.0, 0.0], [1.0; 3]), None);
    // Never sliding as the ideal does (still falling, or stopped), no
    // ideal, a NaN position: no drift.
    assert_eq!(drift(&path(&[]), ideal, [0.5; 3]), None);
    let stopped = path(&[(0.2, 1.0, 0.0), (0.2, 1.0, 0.0)]);
    assert_eq!(drift(&stopped, ideal, [0.5; 3]), None);
    assert_eq!(drift(&straight, [0.0; 3], [0.5; 3]), None);
    let mut broken = straight.clone();
    broken[4].y = f64::NAN;
    assert_eq!(drift(&broken, ideal, [0.5; 3]), None);
}

/// Brute force: the minimum of the squared distance over a fine barycentric
/// grid refined around the best cell, at 512 bits.
fn brute_distance_sq(p: [f64; 3], t: [[f64; 3]; 3]) -> f64 {
    let mut best = f64::INFINITY;
    let (mut u0, mut v0, mut h) = (0.0f64, 0.0f64, 1.0f64);
    for _ in 0..60 {
        let (mut bu, mut bv) = (u0, v0);
        for i in -8..=8 {
            for j in -8..=8 {
                let (u, v) = ((u0 + i as f64 * h / 8.0).clamp(0.0, 1.0), (v0 + j as f64 * h / 8.0).clamp(0.0, 1.0));
                if u + v > 1.0 {
                    continue;
                }
                let q: Vec<Float> = (0..3)
                    .map(|k| {
                        let mut x = Float::with_val(EXACT_BITS, t[0][k]);
                        x += Float::with_val(EXACT_BITS, t[1][k] - t[0][k]) * u;
                        x += Float::with_val(EXACT_BITS, t[2][k] - t[0][k]) * v;
                        x
                    })
                    .collect();
                let d2: Float = (0..3)
                    .map(|k| Float::with_val(EXACT_BITS, &q[k] - p[k]).square())
                    .fold(Float::new(EXACT_BITS), |a, b| a + b);
                let d2 = d2.to_f64();
                if d2 < best {
                    best = d2;
                    (bu, bv) = (u, v);
                }
            }
        }
        (u0, v0, h) = (bu, bv, h / 2.0);
    }
    best
}

fn exact(p: [f64; 3]) -> [Float; 3] {
    p.map(|x| Float::with_val(EXACT_BITS, x))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// The exact distance agrees with brute force, including points placed
    /// near edges and vertices (the offsets below put the foot point within
    /// 1e-9 of an edge or vertex half the time).
    #[test]
    fn exact_distance_matches_brute_force(
        t in prop::array::uniform3(prop::array::uniform3(-2.0f64..2.0)),
        w in prop::array::uniform3(0.0f64..1.0),
        lift in -1.0f64..1.0,
        snap in 0usize..4,
    ) {
        let a = nalgebra::Vector3::from(t[0]);
        let b = nalgebra::Vector3::from(t[1]);
        let c = nalgebra::Vector3::from(t[2]);
        // Reasonably shaped triangles (shape factor max|edge|^2 / |cross| at
        // most 10, smallest angle about 6 degrees): on slivers the grid
        // search of the reference, in barycentric coordinates, is too
        // anisotropic to converge.
        let area2 = (b - a).cross(&(c - a)).norm();
        let longest = [(b - a).norm_squared(), (c - b).norm_squared(), (a - c).norm_squared()].into_iter().fold(0.0, f64::max);
        prop_assume!(area2 > 1e-3 && longest / area2 <= 10.0);
        let n = (b - a).cross(&(c - a)).normalize();
        let s = w[0] + w[1] + w[2];
        let mut foot = (a * w[0] + b * w[1] + c * w[2]) / s;
        match snap {
            0 => foot = a + (b - a) * w[0] + n * 1e-9,         // on edge 0
            1 => foot = c + (c - b) * (0.5 * w[1]),           // beyond vertex c, outside
            2 => foot = b + (b - a) * 1e-9,                   // just past vertex b
            _ => {}
        }
        let p = foot + n * lift;
        let exact_d2 = triangle_distance_sq(&exact(p.into()), &exact(t[0]), &exact(t[1]), &exact(t[2])).to_f64();
        let brute = brute_distance_sq(p.into(), t);
        prop_assert!(exact_d2 <= brute * (1.0 + 1e-9) + 1e-18, "exact {exact_d2} above brute force {brute}");
        prop_assert!(brute - exact_d2 <= 1e-9 * brute.max(1e-6), "exact {exact_d2} far below brute force {brute}");
    }
}

fn sweepslide(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_sweepslide")).args(args).output().expect("the CLI runs")
}

const CONTRACT: [&str; 19] = [
    "scene",
    "response",
    "detection",
    "precision",
    "frames",
    "max_penetration",
    "penetrating_frames",
    "back_face_frames",
    "max_front_penetration",
    "jitter",
    "max_iterations",
    "max_pass_iterations",
    "mean_iterations",
    "nan_frames",
    "embedded_frames",
    "decision_flips",
    "final_position",
    "ns_per_move",
    "units_per_meter",
];

#[test]
fn run_json_has_the_contract_fields_for_every_scene_response_and_hardware_precision() {
    for (scene, _, _) in sweepslide::lab::scenes::BUILTIN {
        for response in ["fauerby", "linahan", "robust"] {
            for precision in ["f32", "f64"] {
                let out = sweepslide(&[
                    "run",
                    "--scene",
                    scene,
                    "--response",
                    response,
                    "--precision",
                    precision,
                    "--frames",
                    "40",
                    "--json",
                ]);
                assert!(
                    out.status.success(),
                    "{scene} {response} {precision}: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
                let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
                for field in CONTRACT {
                    assert!(v.get(field).is_some(), "{scene} {response} {precision}: missing {field}");
                }
                assert_eq!(v["frames"], 40);
                assert_eq!(v["final_position"].as_array().map(Vec::len), Some(3));
                if response == "robust" {
                    assert_eq!(v["penetrating_frames"], 0, "{scene} {precision}");
                    assert_eq!(v["nan_frames"], 0, "{scene} {precision}");
                    assert_eq!(v["embedded_frames"], 0, "{scene} {precision}");
                }
            }
        }
    }
}

#[test]
fn a_negative_radius_is_refused_with_its_reason_in_both_forms() {
    for args in [vec!["--radius", "-1"], vec!["--radius=-1"], vec!["--radii", "-1,1,1"], vec!["--radii=-1,1,1"]] {
        let mut all = vec!["run", "--scene", "floor", "--frames", "2"];
        all.extend(&args);
        let out = sweepslide(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("must be positive"), "{args:?}: {stderr}");
    }
}

#[test]
fn units_per_meter_sets_the_faithful_responses_eps_and_is_refused_where_eps_rounds_away() {
    let run = |upm: &str, extra: &[&str]| {
        let mut args = vec!["run", "--scene", "floor", "--frames", "2", "--units-per-meter", upm];
        args.extend(extra);
        sweepslide(&args)
    };
    let eps_line = |upm: &str| {
        let out = run(upm, &["--response", "fauerby"]);
        assert!(out.status.success(), "{upm}: {}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .find(|l| l.trim_start().starts_with("eps"))
            .unwrap_or("")
            .to_string()
    };
    assert!(eps_line("100").contains("5.000e-3 eSpace units"), "{}", eps_line("100"));
    assert!(eps_line("1").contains("5.000e-5 eSpace units"), "{}", eps_line("1"));
    for bad in ["0", "-1", "nan", "inf"] {
        let out = run(bad, &[]);
        assert_eq!(out.status.code(), Some(2), "{bad}: {}", String::from_utf8_lossy(&out.stderr));
    }
    // The robust response (the default) has no eps: the flag would change
    // nothing, and is refused rather than ignored (a review, session 36).
    let out = run("100", &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && stderr.contains("no such constant"), "{stderr}");
    for (upm, rounds) in [("1e-300", "rounds to zero in f32"), ("1e300", "rounds to infinity in f32")] {
        let out = run(upm, &["--response", "linahan", "--precision", "f32"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && stderr.contains(rounds), "{upm}: {stderr}");
    }
}

#[test]
fn negative_numbers_work_in_both_forms() {
    for args in [["--velocity", "-0.1,0,0"], ["--velocity=-0.1,0,0", "--seed=2"]] {
        let mut all = vec!["run", "--scene", "floor", "--frames", "5", "--json", "--start", "0,1.5,0"];
        all.extend(args);
        let out = sweepslide(&all);
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert!(v["final_position"][0].as_f64().unwrap() < -0.4, "moved towards -x: {v}");
    }
    let out = sweepslide(&["run", "--scene=floor", "--offset=-1e5,0,-1e5", "--frames", "5", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn unknown_names_and_bad_numbers_exit_with_code_2() {
    for args in [
        vec!["run", "--scene", "nowhere"],
        vec!["run", "--scene", "wedge:abc"],
        vec!["run", "--scene", "wedge:200"],
        vec!["run", "--scene", "floor", "--response", "quake"],
        vec!["run", "--scene", "floor", "--precision", "f16"],
        vec!["run", "--scene", "floor", "--precision", "mpfr1"],
        vec!["run", "--scene", "floor", "--velocity", "1,2"],
        vec!["run", "--scene", "floor", "--velocity", "1,nan,2"],
        vec!["run", "--scene", "floor", "--radius", "-1"],
        vec!["run", "--scene", "floor", "--radii", "1,0,1"],
        vec!["run", "--scene", "floor", "--velocity", "0,0,0"],
        vec!["run", "--mesh", "/nonexistent.obj"],
        vec!["report", "--shard", "3/2"],
        vec!["frobnicate"],
    ] {
        let out = sweepslide(&args);
        let code = out.status.code();
        let expected = if args.contains(&"/nonexistent.obj") { 1 } else { 2 };
        assert_eq!(code, Some(expected), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        assert!(!out.stderr.is_empty(), "{args:?} explains itself");
    }
    // No scene, or two: the message names every way to give one.
    for args in [vec!["run"], vec!["run", "--scene", "floor", "--case", "x.json"]] {
        let out = sweepslide(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(["--scene", "--mesh", "--case"].iter().all(|a| stderr.contains(a)), "{args:?}: {stderr}");
    }
}

#[test]
fn trace_csv_has_one_row_per_frame() {
    let dir = std::env::temp_dir().join(format!("sweepslide-trace-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("t.csv");
    // A run that fails leaves no empty trace behind.
    let args = ["run", "--scene", "floor", "--velocity", "0,0,0", "--gravity", "0,0,0", "--trace"];
    let out = sweepslide(&[&args[..], &[path.to_str().unwrap()]].concat());
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(!path.exists());
    let out = sweepslide(&["run", "--scene", "corner", "--frames", "12", "--trace", path.to_str().unwrap()]);
    assert!(out.status.success());
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.lines().count(), 13);
    assert!(text.starts_with("frame,x,y,z,penetration,from_behind,iterations,stop,flip,embedded\n"));
}

/// A body of radius 1.2 in a slot 2.01 wide has no free position: the
/// robust response says, frame by frame, that it could not push the body
/// out (`Trace::embedded`), in the run's metrics, its frames, the CLI's
/// summary and the trace; the same body in a slot it fits, and the
/// faithful responses, which never push out, count none.
#[test]
fn runs_count_the_frames_the_robust_response_could_not_push_out_of() {
    let slot = sweepslide::lab::scenes::build("slot:0.01", 1).unwrap();
    let embedded = |radius: f64, response| {
        let scene = Arc::new(Scene { radii: [radius; 3], frames: 10, ..slot.clone() });
        run(&RunConfig { scene, response, detection: None, precision: Precision::F64, seed: 1 }).unwrap()
    };
    let stuck = embedded(1.2, Response::Robust);
    assert_eq!(stuck.result.embedded_frames, 10, "{:?}", stuck.result);
    assert!(stuck.frames.iter().all(|f| f.embedded));
    assert!(stuck.result.max_penetration > 0.19, "{:?}", stuck.result);
    assert_eq!(embedded(1.0, Response::Robust).result.embedded_frames, 0);
    for response in [Response::Fauerby, Response::Linahan] {
        assert_eq!(embedded(1.2, response).result.embedded_frames, 0, "{response:?}");
    }
    let dir = std::env::temp_dir().join(format!("sweepslide-embedded-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("t.csv");
    let out = sweepslide(&[
        "run",
        "--scene",
        "slot:0.01",
        "--radius",
        "1.2",
        "--frames",
        "3",
        "--trace",
        path.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("embedded      3 frame(s)"));
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.lines().skip(1).all(|l| l.ends_with(",true")), "{text}");
}

#[test]
fn runs_are_deterministic_across_thread_counts() {
    let scene = Arc::new(sweepslide::lab::scenes::build("terrain:16", 3).unwrap());
    let configs: Vec<RunConfig> = [Precision::F32, Precision::F64, Precision::Mpfr(40)]
        .into_iter()
        .flat_map(|precision| {
            Response::ALL.map(|response| RunConfig {
                scene: scene.clone(),
                response,
                detection: None,
                precision,
                seed: 3,
            })
        })
        .collect();
    let strip = |r: sweepslide::lab::RunResult| sweepslide::lab::RunResult { ns_per_move: 0.0, ..r };
    let one: Vec<_> =
        sweepslide::lab::run_all(&configs, 1, &|_| {}).unwrap().into_iter().map(|o| strip(o.unwrap().result)).collect();
    let two: Vec<_> =
        sweepslide::lab::run_all(&configs, 2, &|_| {}).unwrap().into_iter().map(|o| strip(o.unwrap().result)).collect();
    assert_eq!(one, two);
    let single = strip(run(&configs[4]).unwrap().result);
    assert_eq!(single, one[4]);
}

/// The shared meshes (`../shared/meshes`), or `None`, saying the test is
/// skipped, where there are none.
fn shared_meshes() -> Option<Vec<std::path::PathBuf>> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/meshes");
    let meshes = sweepslide::lab::scenes::meshes_in(&dir);
    if meshes.is_empty() {
        eprintln!("skipped: no meshes in {}", dir.display());
        return None;
    }
    Some(meshes)
}

#[test]
fn every_shared_mesh_runs() {
    let Some(meshes) = shared_meshes() else { return };
    for mesh in meshes {
        for response in ["fauerby", "linahan", "robust"] {
            let out = sweepslide(&[
                "run",
                "--mesh",
                mesh.to_str().unwrap(),
                "--response",
                response,
                "--precision",
                "f32",
                "--frames",
                "60",
                "--json",
            ]);
            assert!(out.status.success(), "{}: {}", mesh.display(), String::from_utf8_lossy(&out.stderr));
            let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            if response == "robust" {
                assert_eq!(v["penetrating_frames"], 0, "{}", mesh.display());
                assert_eq!(v["nan_frames"], 0, "{}", mesh.display());
            }
        }
    }
}

/// The fuzz-found failures kept as lab scenes (`scenes/fuzz/`, finding
/// files of the `compare_responses` target): each reproduces in the lab
/// what the fuzzer recorded for Fauerby's or Linahan's response (an exact
/// penetration or a NaN position, in the recorded precision), and the
/// robust response runs every one of them clean in `f32` and `f64`.
#[test]
fn fuzz_found_scenes_reproduce_and_the_robust_response_passes_them() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fuzz");
    let cases = sweepslide::lab::scenes::cases_in(&dir);
    assert!(cases.len() >= 5, "{} cases in {}", cases.len(), dir.display());
    for path in cases {
        let finding: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let scene = Arc::new(sweepslide::lab::Scene::from_case_file(&path).unwrap());
        let result = |response, precision| {
            run(&RunConfig { scene: scene.clone(), response, detection: None, precision, seed: 1 }).unwrap().result
        };
        let recorded = match finding["response"].as_str().unwrap() {
            "fauerby" => Response::Fauerby,
            _ => Response::Linahan,
        };
        for precision in [Precision::F32, Precision::F64] {
            let r = result(Response::Robust, precision);
            assert_eq!((r.penetrating_frames, r.nan_frames), (0, 0), "{} {precision}: {r:?}", path.display());
        }
        let precision = Precision::parse(finding["precision"].as_str().unwrap()).unwrap();
        let r = result(recorded, precision);
        match finding["kind"].as_str().unwrap() {
            "nan" => assert!(r.nan_frames > 0, "{}: {r:?}", path.display()),
            _ => {
                assert!(r.max_penetration > 0.0 && r.penetrating_frames > 0, "{}: {r:?}", path.display());
                // Every one of these enters its triangles from behind, which
                // Fauerby's one-sided detection passes by design: the
                // report does not count them against the rounding claims.
                assert_eq!(r.back_face_frames, r.penetrating_frames, "{}: {r:?}", path.display());
                assert_eq!(r.counted_penetration(), (0, 0.0), "{}: {r:?}", path.display());
            }
        }
        // Exactly as recorded: the failing frame ends where the fuzzer saw
        // it end, bit for bit (the case's decimals are read correctly
        // rounded), with the recorded penetration. Checked for the `f64`
        // findings: the one `f32` finding (`grazing-start`) was recorded on
        // earlier code, whose faithful response ended its frame 0 one `f32`
        // ulp away (at 1.1e5) from today's, and today's fuzz oracle skips
        // it (its start is a hair inside, `StartsInside`).
        if precision != Precision::F64 {
            continue;
        }
        let out =
            run(&RunConfig { scene: scene.clone(), response: recorded, detection: None, precision, seed: 1 }).unwrap();
        let k = usize::try_from(finding["frame"].as_u64().unwrap()).unwrap();
        let to = finding["to"].as_array().unwrap();
        for (i, x) in to.iter().enumerate() {
            let got = out.frames[k].position[i];
            match x.as_f64() {
                Some(x) => assert_eq!(got.to_bits(), x.to_bits(), "{} frame {k}: {got} vs {x}", path.display()),
                None => assert!(got.is_nan(), "{} frame {k}: {got} vs {x}", path.display()),
            }
        }
        if let Some(depth) = finding["failure"].as_str().unwrap().strip_prefix("Penetration(") {
            let depth: f64 = depth.trim_end_matches(')').parse().unwrap();
            assert_eq!(out.frames[k].penetration, Some(depth), "{}", path.display());
        }
    }
}

/// The robust response meets the contacts a body rests on without sweeping
/// to them (one sweep per pass on a floor, where finding the floor again
/// took a second), and meets them as the sweeps would: on the seams of the
/// tessellated floor and the step noses of the staircase, the triangle and
/// feature of every contact agree with the `Mpfr<256>` replay (run with the
/// same tolerances) in `f32` and `f64`.
#[test]
fn resting_contacts_are_met_without_sweeps_and_as_the_sweeps_would() {
    for name in ["floor", "tessellated-floor", "staircase", "corner"] {
        let scene = Arc::new(sweepslide::lab::scenes::build(name, 1).unwrap());
        for precision in [Precision::F32, Precision::F64] {
            let cfg =
                RunConfig { scene: scene.clone(), response: Response::Robust, detection: None, precision, seed: 1 };
            let r = run(&cfg).unwrap().result;
            assert_eq!((r.decision_flips, r.plane_flips, r.penetrating_frames), (0, 0, 0), "{name} {precision}");
            // Sweeps per move: one on the floors (the velocity's; the
            // gravity's is projected away by the floor it rests on), a few
            // on the stairs (each pass at most two: the step's riser and
            // nose), and almost none resting in the corner (the push is
            // blocked by the two planes it rests on; a review found only the
            // floor checked).
            let (most, at_most_per_pass) = match name {
                "floor" | "tessellated-floor" => (1.05, 2),
                "staircase" => (3.5, 2),
                _ => (0.5, 2),
            };
            assert!(r.mean_iterations < most, "{name} {precision}: {} sweeps per move", r.mean_iterations);
            assert!(r.max_pass_iterations <= at_most_per_pass, "{name} {precision}: {}", r.max_pass_iterations);
        }
    }
}

/// Far from the origin in `f32` the final rounding can undo the padding,
/// and the robust response rests in a band twice its bound wider
/// (`RobustOptions::rounding_ulps`). The replay scales that bound too: with
/// its own, a body resting 0.03 radii above the floor at `1e5` was, for the
/// replay, a body above its band that slides free, and every frame counted
/// as a decision flip with another number of planes (299 of 300 until the
/// twentieth session).
#[test]
fn the_replay_keeps_the_resting_band_far_from_the_origin() {
    let scene = sweepslide::lab::scenes::build("floor", 1).unwrap().offset([1e5, 0.0, 1e5], true).unwrap();
    let scene = Arc::new(sweepslide::lab::scenes::Scene { frames: 40, ..scene });
    let cfg = RunConfig { scene, response: Response::Robust, detection: None, precision: Precision::F32, seed: 1 };
    let r = run(&cfg).unwrap().result;
    assert!(r.mean_iterations >= 1.0, "the body slides over the floor: {} sweeps per move", r.mean_iterations);
    assert_eq!((r.decision_flips, r.plane_flips, r.penetrating_frames), (0, 0, 0));
}

/// A velocity that is a positive multiple of the scene's keeps the ideal
/// slide, scaled, so a search finding's command reports the snag ratio it
/// was found with; any other velocity, or gravity that the surfaces do not
/// take whole, drops it.
#[test]
fn a_scaled_velocity_scales_the_ideal_slide() {
    use sweepslide::lab::scenes::build;
    let wedge = build("wedge", 1).unwrap();
    let [vx, vy, vz] = wedge.velocity;
    let ideal = wedge.ideal.unwrap();
    let scaled = wedge.clone().with_velocity([vx * 0.25, vy * 0.25, vz * 0.25]).ideal.unwrap();
    assert_eq!(scaled, ideal.map(|v| v * 0.25));
    assert_eq!(wedge.clone().with_velocity([-vx, vy, -vz]).ideal, None, "the opposite direction");
    assert_eq!(wedge.clone().with_velocity([vx, vy + 1e-3, vz]).ideal, None, "another direction");
    assert_eq!(wedge.clone().with_velocity([0.0; 3]).ideal, None, "no motion");
    let falling = sweepslide::lab::scenes::Scene { gravity: [0.0, -0.01, 0.0], ..wedge.clone() };
    assert_eq!(falling.with_velocity(wedge.velocity).ideal, None, "gravity");
    // On a floor that takes the gravity whole (the ideal is the push, the
    // gravity perpendicular to it) the ideal stays; a gravity with a part
    // along the push drops it.
    let messy = build("messy-floor:12", 1).unwrap();
    assert_eq!(messy.ideal, Some(messy.velocity));
    let doubled = messy.velocity.map(|v| v * 2.0);
    assert_eq!(messy.clone().with_velocity(doubled).ideal, Some(doubled), "a floor under gravity");
    let tilted = sweepslide::lab::scenes::Scene { gravity: [0.01, -0.02, 0.0], ..messy.clone() };
    assert_eq!(tilted.with_velocity(doubled).ideal, None, "gravity along the push");
    let snag = |v: &str| {
        let out = sweepslide(&["run", "--scene", "wedge", "--frames", "300", &format!("--velocity={v}")]);
        assert!(out.status.success(), "{out:?}");
        String::from_utf8(out.stdout).unwrap().lines().find(|l| l.contains("snag ratio")).map(str::to_string)
    };
    assert!(snag("-0.05,0,0.01").is_some_and(|l| l.contains("1.000000")), "{:?}", snag("-0.05,0,0.01"));
    assert_eq!(snag("-0.05,0,0.02"), None);
    let with_gravity =
        sweepslide(&["run", "--scene", "wedge", "--frames", "30", "--velocity=-0.05,0,0.01", "--gravity=0,-0.01,0"]);
    assert!(with_gravity.status.success(), "{with_gravity:?}");
    assert!(!String::from_utf8_lossy(&with_gravity.stdout).contains("snag ratio"), "gravity drops the ideal");
}

/// Another body than the scene's drops the ideal slide: a sphere three
/// times as wide does not fit the slot the scene's slides through (it once
/// reported a snag ratio of 1 there), and an ellipsoid slides in eSpace.
#[test]
fn another_body_drops_the_ideal_slide() {
    use sweepslide::lab::scenes::build;
    let slot = build("slot:0.1", 1).unwrap();
    assert!(slot.ideal.is_some());
    assert_eq!(slot.clone().with_radii(slot.radii).ideal, slot.ideal, "the scene's own body");
    assert_eq!(slot.clone().with_radii([3.0; 3]).ideal, None, "a wider sphere");
    assert_eq!(slot.clone().with_radii([1.0, 0.5, 1.0]).ideal, None, "an ellipsoid");
    let snag = |body: &[&str]| {
        let out = sweepslide(&[&["run", "--scene", "slot:0.1", "--frames", "20"], body].concat());
        assert!(out.status.success(), "{out:?}");
        String::from_utf8(out.stdout).unwrap().contains("snag ratio")
    };
    assert!(snag(&["--radius", "1"]));
    assert!(!snag(&["--radius", "3"]));
    assert!(!snag(&["--radii=1,0.5,1"]));
}

/// `command` split as a POSIX shell splits it, for the quoting that the
/// search prints (single quotes, and `\'` between them).
fn shell_words(command: &str) -> Vec<String> {
    let (mut words, mut word, mut quoted, mut chars) = (Vec::new(), String::new(), false, command.chars());
    while let Some(c) = chars.next() {
        match c {
            '\'' => quoted = !quoted,
            '\\' if !quoted => word.extend(chars.next()),
            ' ' if !quoted => words.extend((!word.is_empty()).then(|| std::mem::take(&mut word))),
            c => word.push(c),
        }
    }
    words.extend((!word.is_empty()).then_some(word));
    words
}

/// The search's mesh family, on the shared meshes: the robust response
/// never fails there either, and a mesh finding's command reproduces its
/// run bit for bit (start, push, gravity, body, offset and walk seed).
#[test]
fn random_search_over_meshes_reproduces_its_findings() {
    use sweepslide::lab::RunResult;
    use sweepslide::lab::search::search;
    let Some(meshes) = shared_meshes() else { return };
    // A seed whose 25 trials include a mesh's findings.
    let outcome = search(8, 25, 2, &meshes, &|_| {}).unwrap();
    let on_mesh_trials: usize = outcome.trials.iter().filter(|(f, _)| f.starts_with("mesh:")).map(|(_, n)| n).sum();
    assert!(on_mesh_trials > 0 && outcome.trials.values().sum::<usize>() == 25, "{:?}", outcome.trials);
    let findings = outcome.findings;
    let on_meshes: Vec<_> = findings.iter().filter(|f| f.command.contains("--mesh=")).collect();
    assert!(!on_meshes.is_empty(), "no finding on a mesh in 25 trials");
    // Compared as JSON, where a NaN equals itself; without the timing.
    let timeless = |r: &RunResult| serde_json::to_string(&RunResult { ns_per_move: 0.0, ..r.clone() }).unwrap();
    for f in &findings {
        assert_ne!(f.result.response, "robust", "{f:?}");
    }
    for f in on_meshes {
        let args: Vec<String> = shell_words(&f.command).into_iter().skip(1).chain(["--json".into()]).collect();
        let out = sweepslide(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert!(out.status.success(), "{}: {}", f.command, String::from_utf8_lossy(&out.stderr));
        let again: RunResult = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(timeless(&again), timeless(&f.result), "{}", f.command);
    }
}

#[test]
fn velocity_given_on_the_command_line_replaces_a_cases_recorded_velocities() {
    let dir = std::env::temp_dir().join(format!("sweepslide-velocity-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scripted.json");
    let floor = "[[-50,0,-50],[-50,0,50],[50,0,50]], [[-50,0,-50],[50,0,50],[50,0,-50]]";
    let text = format!(
        r#"{{"triangles": [{floor}], "radii": [1,1,1], "start": [0,1.5,0],
        "frames": [{{"velocity": [0.1,0,0], "gravity": null}}, {{"velocity": [0.2,0,0], "gravity": null}}]}}"#
    );
    std::fs::write(&path, text).unwrap();
    let x_after = |extra: &[&str]| {
        let mut args = vec!["run", "--case", path.to_str().unwrap(), "--json"];
        args.extend(extra);
        let out = sweepslide(&args);
        assert!(out.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&out.stderr));
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        (v["final_position"][0].as_f64().unwrap(), v["final_position"][2].as_f64().unwrap())
    };
    let (x, z) = x_after(&[]);
    assert!((x - 0.3).abs() < 1e-9 && z == 0.0, "the recorded motion: {x}, {z}");
    let (x, z) = x_after(&["--velocity=0,0,0.5"]);
    assert!(x == 0.0 && (z - 1.0).abs() < 1e-9, "the velocity asked for: {x}, {z}");
}

/// A review's finding (twenty-first session): a failed `run --trace F`
/// deleted a file `F` the user already had (the trace was created empty
/// before the run to check that it could be written, and removed when the
/// run failed), and `--trace` naming the run's own case file overwrote
/// it. Now an existing file is left as it was until the run succeeds, a
/// trace file this run created is removed, and the input is refused.
#[test]
fn a_failed_run_leaves_an_existing_trace_file_alone_and_the_input_is_never_the_trace() {
    let dir = std::env::temp_dir().join(format!("sweepslide-trace-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let kept = dir.join("kept.csv");
    std::fs::write(&kept, "precious\n").unwrap();
    // A run that fails (its push overflows `f32` in radii), after the
    // arguments were accepted.
    let failing = |trace: &std::path::Path| {
        sweepslide(&[
            "run",
            "--scene",
            "floor",
            "--velocity=1e38,0,0",
            "--precision",
            "f32",
            "--trace",
            trace.to_str().unwrap(),
        ])
    };
    let out = failing(&kept);
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("overflows this precision"));
    assert_eq!(std::fs::read_to_string(&kept).unwrap(), "precious\n");
    let fresh = dir.join("fresh.csv");
    let _ = std::fs::remove_file(&fresh);
    let out = failing(&fresh);
    assert_eq!(out.status.code(), Some(2));
    assert!(!fresh.exists(), "a trace file this run created is not left empty");
    let case = dir.join("case.json");
    let text = r#"{"triangles": [[[-5,0,-5],[5,0,5],[5,0,-5]]], "radii": [1,1,1], "start": [0,2,0],
        "frames": [{"velocity": [0,-0.5,0], "gravity": null}]}"#;
    std::fs::write(&case, text).unwrap();
    let out = sweepslide(&["run", "--case", case.to_str().unwrap(), "--trace", case.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("would overwrite"));
    assert_eq!(std::fs::read_to_string(&case).unwrap(), text);
    let out = sweepslide(&["run", "--scene", "floor", "--frames", "3", "--trace", kept.to_str().unwrap()]);
    assert!(out.status.success());
    assert_eq!(std::fs::read_to_string(&kept).unwrap().lines().count(), 4, "a header and three frames");
}

#[test]
fn bad_scene_parameters_and_frame_counts_exit_with_code_2() {
    for args in [
        ["run", "--scene", "floor:5", "--frames", "3"],
        ["run", "--scene", "staircase:20.7", "--frames", "3"],
        ["run", "--scene", "floor", "--frames", "0"],
        ["run", "--scene", "floor", "--frames", "18446744073709551615"],
    ] {
        let out = sweepslide(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
        assert!(String::from_utf8_lossy(&out.stderr).starts_with("error: "), "{args:?}");
    }
}

/// A review's findings (twenty-first session): input that the scene's or
/// the run's rounding would silently change into something else. A slot
/// clearance below `1.2e-7` rounded to none in the scene's `f32`
/// coordinates (`slot:1e-8` ran as `slot:0`); a velocity of `1e-50` ran
/// as a body at rest in `f32`. Both are refused now, and the least values
/// that survive the rounding still run.
#[test]
fn input_that_rounds_to_nothing_is_refused() {
    for (args, needle) in [
        (["run", "--scene", "slot:1e-8", "--precision", "f64", "--velocity=0,0,0.1"], "rounds to 0"),
        (["run", "--scene", "floor", "--precision", "f32", "--velocity=1e-50,0,0"], "rounds to zero in f32"),
        (["run", "--scene", "floor", "--precision", "f32", "--gravity=0,-1e-50,0"], "rounds to zero in f32"),
    ] {
        let out = sweepslide(&[&args[..], &["--frames", "3"]].concat());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
    }
    for args in [["run", "--scene", "slot:1.2e-7"], ["run", "--scene", "floor"]] {
        let out = sweepslide(&[&args[..], &["--precision", "f32", "--frames", "3"]].concat());
        assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    }
    // A mesh's scene is steered, and its velocity rounded to `f32` every
    // frame whatever the precision: `1e-50` left the body at rest in `f64`
    // and `1e39` was reported as an infinite velocity, though finite (a
    // review, thirty-eighth session).
    let dir = std::env::temp_dir().join(format!("sweepslide-steered-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("floor.obj");
    std::fs::write(&mesh, "v -5 0 -5\nv 5 0 5\nv 5 0 -5\nf 1 2 3\n").unwrap();
    for (velocity, needle) in
        [("--velocity=1e-50,0,0", "rounds to zero in f32"), ("--velocity=1e39,0,0", "rounds to infinity in f32")]
    {
        let out =
            sweepslide(&["run", "--mesh", mesh.to_str().unwrap(), "--precision", "f64", velocity, "--frames", "3"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{velocity}: {stderr}");
        assert!(stderr.contains(needle) && stderr.contains("steered"), "{velocity}: {stderr}");
    }
    let out = sweepslide(&[
        "run",
        "--mesh",
        mesh.to_str().unwrap(),
        "--precision",
        "f64",
        "--velocity=0.1,0,0",
        "--frames",
        "3",
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A review's finding (twenty-sixth session): values given for a built-in
/// scene on the command line bypassed the rounding to `f32` that the
/// scene's own inputs get, so `--start=0,5.1,0` started the `f64` run at
/// 5.1 and the `f32` run at 5.099999904632568, and a comparison of
/// precisions compared different inputs. Now they are rounded alike, and a
/// value that `f32` cannot hold is refused.
#[test]
fn values_given_for_a_built_in_scene_are_rounded_to_f32_like_its_own() {
    let end = |precision: &str| {
        let out = sweepslide(&[
            "run",
            "--scene",
            "floor",
            "--start=0,5.1,0",
            "--velocity=0.1,0,0",
            "--frames",
            "1",
            "--precision",
            precision,
            "--json",
        ]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        json["final_position"].clone()
    };
    let expected = serde_json::json!([0.1f32 as f64, 5.1f32 as f64, 0.0]);
    assert_eq!(end("f64"), expected);
    assert_eq!(end("f32"), expected);
    let out = sweepslide(&["run", "--scene", "floor", "--start=0,1e39,0", "--frames", "1"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--start: 1e39 rounds to infinity in f32"));
    // An offset is added before the rounding; one beyond `f32`'s range is
    // refused by name (it used to be reported as a mesh without a valid
    // triangle).
    let out = sweepslide(&["run", "--scene", "floor", "--offset=1e39,0,0", "--frames", "1"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--offset: 1e39 rounds to infinity in f32"));
}

/// A run that reaches a NaN position has no jitter to speak of: it is NaN
/// (written `"NaN"` in JSON), not the 0 of a body at rest that it used to
/// be (a review, twenty-first session: Linahan's NaN runs counted as
/// evidence that it comes to rest).
#[test]
fn jitter_of_a_run_with_nan_frames_is_nan() {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fuzz/linahan-nan-narrow-slot.json");
    let scene = Arc::new(Scene::from_case_file(&case).unwrap());
    let cfg = RunConfig { scene, response: Response::Linahan, detection: None, precision: Precision::F64, seed: 1 };
    let r = run(&cfg).unwrap().result;
    assert!(r.nan_frames > 0, "the case no longer reaches NaN: {r:?}");
    assert!(r.jitter.is_nan(), "jitter {}", r.jitter);
    assert!(serde_json::to_string(&r).unwrap().contains(r#""jitter":"NaN""#));
}

/// A review's finding (twenty-first session): a triangle that collapses
/// when its vertices are rounded into the run's precision (here one
/// `1e8` from the origin with sides of 1, in `f32`) ran with no word; it
/// collides as the segment it became, and the run now says so.
#[test]
fn triangles_degenerate_in_the_runs_precision_are_noted() {
    let vertices =
        vec![[1e8, 0.0, 0.0], [1e8 + 1.0, 0.0, 0.0], [1e8, 0.0, 1.0], [0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    let mesh = Arc::new(TriangleMesh::new(vertices, vec![[0, 2, 1], [3, 5, 4]]).unwrap());
    assert_eq!(World::<f32>::new(mesh.clone()).unwrap().degenerate_in_backend(), [0]);
    assert_eq!(World::<f64>::new(mesh).unwrap().degenerate_in_backend(), Vec::<u32>::new());
    let dir = std::env::temp_dir().join(format!("sweepslide-degenerate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("collapsing.obj");
    std::fs::write(
        &path,
        "v 100000000 0 0\nv 100000001 0 0\nv 100000000 0 1\nv 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\nf 4 6 5\n",
    )
    .unwrap();
    let noted = |precision: &str| {
        let args = ["run", "--mesh", path.to_str().unwrap(), "--precision", precision, "--start=0.3,2,0.3"];
        let out = sweepslide(&[&args[..], &["--velocity=0,-0.1,0", "--frames", "3"]].concat());
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let json = sweepslide(&[&args[..], &["--velocity=0,-0.1,0", "--frames", "3", "--json"]].concat());
        let v: serde_json::Value = serde_json::from_slice(&json.stdout).expect("one JSON object");
        let counted = v["degenerate_triangles"].as_u64().expect("the count is in the JSON");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let said = stderr.contains("1 triangle(s) of the scene are degenerate");
        assert_eq!(said, counted == 1, "{precision}: note and count disagree");
        // The note names the triangle by its line (a review, session 36:
        // it gave the count alone).
        assert_eq!(said, stderr.contains("collapsing.obj:7"), "{stderr}");
        said
    };
    assert!(noted("f32"));
    assert!(!noted("f64"));
}

/// A finding file records the response and precision that failed: a run
/// with others says so and how to reproduce it, a run with the same says
/// nothing (fixed in the twenty-first session without a test: a review).
#[test]
fn a_finding_run_with_another_response_or_precision_says_how_to_reproduce_it() {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fuzz/linahan-nan-narrow-slot.json");
    let case = case.to_str().unwrap();
    let stderr = |args: &[&str]| {
        let out = sweepslide(&[&["run", "--case", case, "--frames", "2"], args].concat());
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let other = stderr(&[]);
    assert!(other.contains("records response `linahan`") && other.contains("pass --response linahan"), "{other}");
    assert!(other.contains("records precision `f32`") && other.contains("pass --precision f32"), "{other}");
    let same = stderr(&["--response", "linahan", "--precision", "f32"]);
    assert!(!same.contains("records"), "{same}");
    // A value the command line does not know is not offered as a flag
    // (a review, twenty-sixth session: `pass --response bogus`).
    let mut finding: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(case).unwrap()).unwrap();
    (finding["response"], finding["precision"]) = ("bogus".into(), "f99".into());
    let bogus = std::env::temp_dir().join(format!("sweepslide-bogus-{}.json", std::process::id()));
    std::fs::write(&bogus, finding.to_string()).unwrap();
    let out = sweepslide(&["run", "--case", bogus.to_str().unwrap(), "--frames", "2"]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{said}");
    assert!(said.contains("records an unknown response `bogus`"), "{said}");
    assert!(said.contains("records an unknown precision `f99`") && !said.contains("pass --"), "{said}");
    // Nor is a value that is no string passed over (a review, thirty-eighth
    // session).
    finding["response"] = 5.into();
    std::fs::write(&bogus, finding.to_string()).unwrap();
    let out = sweepslide(&["run", "--case", bogus.to_str().unwrap(), "--frames", "2"]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(said.contains("records an unknown response `5`"), "{said}");
    std::fs::remove_file(&bogus).unwrap();
}

/// The random search on a few trials: every finding is what its kind says
/// (penetration, NaN, jitter, wobble, freeze, drift), comes with the command that reproduces it,
/// and none is the robust response's; the faithful ones fail somewhere.
#[test]
fn random_search_findings_are_what_they_say_and_none_is_the_robust_responses() {
    use sweepslide::lab::search::{FREEZE, FailureKind, search};
    // A seed whose 40 trials include a freeze, a wobble and an ellipsoid's
    // finding (a change to the families or their draws may need another).
    let outcome = search(8, 40, 1, &[], &|_| {}).unwrap();
    assert_eq!(outcome.trials.values().sum::<usize>(), 40);
    assert!(outcome.trials.keys().all(|f| !f.starts_with("mesh:")), "{:?}", outcome.trials);
    assert!(outcome.ellipsoids > 0 && outcome.ellipsoids < 40);
    let findings = outcome.findings;
    assert!(findings.iter().any(|f| f.result.response != "robust"), "no finding in 40 trials");
    assert!(findings.iter().any(|f| f.kind == FailureKind::Freeze), "no freeze in 40 trials");
    assert!(findings.iter().any(|f| f.kind == FailureKind::Wobble), "no zigzag along a slide in 40 trials");
    assert!(findings.iter().any(|f| f.command.contains("--radii=")), "no ellipsoid's finding in 40 trials");
    for f in &findings {
        let r = &f.result;
        assert_ne!(r.response, "robust", "{f:?}");
        // An ellipsoid has no ideal slide to freeze against or drift from.
        let slides = matches!(f.kind, FailureKind::Freeze | FailureKind::Drift | FailureKind::Wobble);
        assert!(!(f.command.contains("--radii=") && slides), "{f:?}");
        match f.kind {
            FailureKind::Penetration => assert!(r.penetrating_frames > 0 && f.value > 0.0, "{f:?}"),
            FailureKind::Nan => assert!(r.nan_frames > 0, "{f:?}"),
            FailureKind::Jitter => assert!(r.jitter > 1e-3, "{f:?}"),
            FailureKind::Freeze => assert!(r.snag.is_some_and(|s| s < FREEZE && s == f.value), "{f:?}"),
            FailureKind::Drift => assert!(r.drift.is_some_and(|d| d >= DRIFT_THRESHOLD && d == f.value), "{f:?}"),
            FailureKind::Wobble => assert!(r.wobble > 1e-3 && r.wobble == f.value, "{f:?}"),
        }
        let base = r.scene.split([':', '@']).next().unwrap();
        assert!(f.command.starts_with(&format!("sweepslide run --scene {base}")), "{f:?}");
        assert!(f.command.ends_with(&format!("--response {} --precision {}", r.response, r.precision)), "{f:?}");
    }
}

/// A mesh whose triangles all collapse at one of the search's offsets
/// (sides of `1e-17`, valid where given) stopped the search with a panic
/// (a review, session 29); the search now names the mesh and the offset.
#[test]
fn a_mesh_that_collapses_at_a_search_offset_is_named() {
    use sweepslide::Error;
    use sweepslide::lab::search::search;
    let dir = std::env::temp_dir().join(format!("sweepslide-collapsing-search-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("specks.obj");
    std::fs::write(&path, "v 0 0 0\nv 1e-17 0 0\nv 0 1e-17 0\nv 1 1 1\nv 1.0000000000000002 1 1\nv 1 1.0000000000000002 1\nf 1 2 3\nf 4 5 6\n")
        .unwrap();
    match search(1, 200, 2, std::slice::from_ref(&path), &|_| {}) {
        Err(Error::InvalidArgument { what, message }) => {
            assert!(what.contains("specks.obj") && message.contains("1e4 radii"), "{what}: {message}");
        }
        other => panic!("expected the mesh to be named, got {:?}", other.map(|o| o.trials)),
    }
    let out = sweepslide(&["search", "--trials", "200", "--jobs", "2", "--meshes", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A review (session 36): `search --meshes` ran a mesh whose faces it had
/// skipped, and statements it had ignored, without a word, where `run` and
/// `report` say both; and `--trials 18446744073709551615` built its whole
/// plan before any run, until memory ran out. The search now passes each
/// mesh's load notes on, and refuses a trial count beyond its cap.
#[test]
fn a_search_says_what_its_meshes_left_out_and_caps_its_trials() {
    use std::cell::RefCell;
    use sweepslide::Error;
    use sweepslide::lab::search::{MAX_TRIALS, search};
    let dir = std::env::temp_dir().join(format!("sweepslide-search-notes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("patchy.obj");
    std::fs::write(&path, "o floor\nv -5 0 -5\nv 5 0 -5\nv -5 0 5\nv 5 0 5\nf 1 3 2\nf 1 1 2\nf 2 3 4\n").unwrap();
    let notes = RefCell::new(Vec::new());
    search(1, 1, 1, std::slice::from_ref(&path), &|line| notes.borrow_mut().push(line.to_string())).unwrap();
    let notes = notes.into_inner().join("\n");
    assert!(notes.contains("patchy.obj:7") && notes.contains("`o`"), "{notes}");
    let out = sweepslide(&["search", "--trials", "1", "--jobs", "1", "--meshes", dir.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success() && stderr.contains("patchy.obj:7"), "{stderr}");
    for trials in [0, MAX_TRIALS + 1] {
        match search(1, trials, 1, &[], &|_| {}) {
            Err(Error::InvalidArgument { message, .. }) => {
                assert!(message.contains("1 to 1000000 trials"), "{message}")
            }
            other => panic!("{trials} trials: {:?}", other.map(|o| o.trials)),
        }
    }
    let out = sweepslide(&["search", "--trials", "18446744073709551615"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && stderr.contains("1 to 1000000 trials"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Runs beyond 112 bits: the judge computed at a fixed 512 bits, whose
/// own rounding of `1 - d` (`1e-153`) exceeds such a run's clearances, and
/// the decisions were replayed in `Mpfr<256>`, coarser than the run. At
/// 600 bits the robust response was judged `1e-153` inside in 16 of 30
/// frames of `corner:45` and flipped 6 decisions on `tessellated-floor:40`
/// (a review, session 29); its 256-bit runs did neither. The judge now
/// computes at `4 p + 64` bits and the replay at `2 p`.
#[test]
fn runs_beyond_the_judges_and_replays_precision_are_judged_finer() {
    use sweepslide::lab::metrics::judge_bits;
    use sweepslide::lab::runner::reference_bits;
    assert_eq!(judge_bits::<f64>(), EXACT_BITS);
    assert_eq!(judge_bits::<sweepslide::Mpfr<600>>(), 2464);
    assert_eq!(reference_bits(Precision::F32), 256);
    assert_eq!(reference_bits(Precision::Mpfr(128)), 256);
    assert_eq!(reference_bits(Precision::Mpfr(600)), 1200);
    assert_eq!(reference_bits(Precision::Mpfr(60_000)), sweepslide::real::MAX_BITS);
    for spec in ["corner:45", "tessellated-floor:40"] {
        let mut scene = sweepslide::lab::scenes::build(spec, 1).unwrap();
        scene.frames = 30;
        let cfg = RunConfig {
            scene: Arc::new(scene),
            response: Response::Robust,
            detection: None,
            precision: Precision::Mpfr(600),
            seed: 1,
        };
        let r = sweepslide::lab::run(&cfg).unwrap().result;
        assert_eq!((r.penetrating_frames, r.max_penetration), (0, 0.0), "{spec}");
        assert_eq!((r.decision_flips, r.plane_flips), (0, 0), "{spec}");
    }
}

/// `search --trials 0` ran nothing and printed an empty summary (a review,
/// session 29); it is refused, and a search's summary names its counts.
#[test]
fn a_search_without_trials_is_refused_and_its_summary_names_its_counts() {
    let out = sweepslide(&["search", "--trials", "0"]);
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--trials"));
    let out = sweepslide(&["search", "--trials", "2", "--jobs", "1"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let summary = String::from_utf8_lossy(&out.stderr);
    assert!(summary.contains("in 2 trials (seed 1); trials per family: "), "{summary}");
}

/// The messy floor is what its description says: every vertex on `y = 0`,
/// and seams the adjacency finds *active* inside the floor (T-junctions,
/// faces given twice, decals, slivers and near-welded tiles share no edge
/// with a single neighbour), where the tessellated floor has none; and
/// every response walks the scene's character over it, in `f32` at the
/// origin and `1e4` away, without entering it and with its ideal slide
/// (within what rounding the position costs far out: 0.2% at `1e4`).
#[test]
fn the_messy_floor_has_active_seams_and_every_response_walks_over_them() {
    use sweepslide::lab::scenes::build;
    let interior_active = |spec: &str| {
        let scene = build(spec, 1).unwrap();
        let mesh = &scene.mesh;
        let edge = mesh.bounds().max.x - 1e-3;
        let mut active = 0;
        for t in 0..mesh.len() as u32 {
            let tri = mesh.triangle(t);
            let corners = [tri.a, tri.b, tri.c];
            for i in 0..3u8 {
                let (p, q) = (corners[i as usize], corners[(i as usize + 1) % 3]);
                let inside = [p, q].iter().all(|v| v.x.abs() < edge && v.z.abs() < edge);
                active += usize::from(inside && mesh.active(t).edge(i));
            }
        }
        (scene, active)
    };
    let (messy, active) = interior_active("messy-floor");
    assert!(messy.mesh.vertices().iter().all(|v| v.y == 0.0), "a vertex off the floor's plane");
    assert!(active > 200, "{active} active edges inside the messy floor");
    assert_eq!(interior_active("tessellated-floor").1, 0, "the tessellated floor's seams are all internal");
    for offset in [[0.0; 3], [1e4, 0.0, 1e4]] {
        let scene = Arc::new(messy.offset(offset, true).unwrap());
        assert!(scene.mesh.skipped().is_empty(), "a flaw rounded away at {offset:?}");
        for response in Response::ALL {
            let cfg = RunConfig { scene: scene.clone(), response, detection: None, precision: Precision::F32, seed: 1 };
            let r = run(&cfg).unwrap().result;
            let snag = r.snag.unwrap();
            assert_eq!(r.penetrating_frames, 0, "{response:?} at {offset:?}");
            assert!((snag - 1.0).abs() < 5e-3, "{response:?} at {offset:?}: snag ratio {snag}");
        }
    }
}

/// Below `atan(1/2)`, `26.57` degrees, a crease's push slid along its far
/// slope climbs it for good: the scene's ideal slide is that climb, not the
/// crease's line (the drift metric found the line wrong there: no frame
/// ever moved as it does). At 30 degrees the push comes back down into the
/// crease and slides along it.
#[test]
fn a_shallow_crease_slides_up_its_far_slope() {
    for (angle, climbs) in [(10.0, true), (26.5, true), (30.0, false)] {
        let scene = Arc::new(sweepslide::lab::scenes::build(&format!("crease:{angle}"), 1).unwrap());
        let ideal = scene.ideal.unwrap();
        assert_eq!(ideal[0] < 0.0, climbs, "crease:{angle}: {ideal:?}");
        let cfg = RunConfig { scene, response: Response::Robust, detection: None, precision: Precision::F64, seed: 1 };
        let r = run(&cfg).unwrap().result;
        let drift = r.drift.unwrap_or_else(|| panic!("crease:{angle}: no frame slid as the ideal does"));
        assert!(drift < 1e-4, "crease:{angle}: drift {drift}");
        assert!(r.snag.is_some_and(|s| (s - 1.0).abs() < 3e-3), "crease:{angle}: {:?}", r.snag);
    }
}

/// The random search's drift finding on a tilted floor (seed 3): at a
/// seam Linahan's three checks turn and slow the body, which slides on
/// `0.072` radii off the ideal line; the robust and Fauerby's responses
/// keep to it (`docs/findings.md`, "The random search").
#[test]
fn linahan_drifts_off_a_tilted_floor_at_a_seam() {
    let mut scene = sweepslide::lab::scenes::build("tilted-floor:4.04", 1)
        .unwrap()
        .offset([-4.0, 11.0, 2.0], true)
        .unwrap()
        .with_velocity([2.179250568151474e-1, -2.685859426856041e-2, -7.877729833126068e-2]);
    scene.frames = 60;
    let scene = Arc::new(scene);
    let drift = |response| {
        let cfg = RunConfig { scene: scene.clone(), response, detection: None, precision: Precision::F32, seed: 1 };
        run(&cfg).unwrap().result.drift.unwrap()
    };
    assert!(drift(Response::Linahan) > 0.05, "{}", drift(Response::Linahan));
    assert!(drift(Response::Robust) < 1e-5, "{}", drift(Response::Robust));
    assert!(drift(Response::Fauerby) < 1e-5, "{}", drift(Response::Fauerby));
}
