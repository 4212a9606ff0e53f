//! The paper's scenes moved far from the origin (built-in scenes rounded to
//! `f32` again after the offset, so every backend sees the same geometry).
//! At 1e5 an `f32` coordinate has a spacing of 2^-7 = 0.0078, far coarser
//! than the paddings the faithful responses assume (5e-5).
//!
//! * Robust, f32 and f64, offsets 1e4 and 1e5 (horizontal, and on all three
//!   axes): never inside (exact distance after every frame), at rest in the
//!   corner and the dead end, and sliding as far as the stored positions
//!   allow: at least 99% of what a free body stepping by the ideal
//!   displacement reaches in the same backend (in f32 at 1e5 a step of 0.1
//!   rounds to 0.1015625, so the plain slide ratio there is 1.0156; at 1e4
//!   a step of 0.02 rounds to 0.01953, ratio 0.9766).
//! * Fauerby, f32, pinned: penetrates the corner at 1e5 (ALGORITHMS.md
//!   section 8: 6e-3 at 1e5) and the 10 degree wedge at 1e4.
//! * Linahan, f32, pinned: NaN within 30 frames in the corner, the wedge and
//!   the crease (the same plane hit twice, see `respond_parallel_planes`),
//!   and creeping into the 1 degree wedge at 1e4.

use sweepslide::Real;
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::metrics::{penetration, snag_ratio};
use sweepslide::lab::scenes::{Scene, build};
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::World;

const OFFSETS: [[f64; 3]; 3] = [[1e4, 0.0, 1e4], [1e5, 0.0, 1e5], [1e5, 1e5, 1e5]];

fn v<T: Real>(p: [f64; 3]) -> Vec3<T> {
    vec3(p[0], p[1], p[2])
}

fn f64s<T: Real>(p: &Vec3<T>) -> [f64; 3] {
    [p[0].to_f64(), p[1].to_f64(), p[2].to_f64()]
}

fn far(spec: &str, offset: [f64; 3]) -> Scene {
    build(spec, 1).unwrap().offset(offset, true).unwrap()
}

struct Run<T: Real> {
    name: String,
    positions: Vec<Vec3<T>>,
    pens: Vec<Option<f64>>,
}

impl<T: Real> Run<T> {
    fn max_penetration(&self) -> f64 {
        self.pens.iter().flatten().fold(f64::NEG_INFINITY, |a, b| a.max(*b))
    }

    fn penetrating_frames(&self) -> usize {
        self.pens.iter().flatten().filter(|d| **d > 0.0).count()
    }

    fn first_non_finite(&self) -> Option<usize> {
        self.positions.iter().position(|p| !p.iter().all(Real::is_finite)).map(|k| k - 1)
    }

    fn assert_never_penetrates(&self) {
        for (k, pen) in self.pens.iter().enumerate() {
            let p = f64s(&self.positions[k + 1]);
            assert!(p.iter().all(|x| x.is_finite()), "{}: frame {k}: {p:?}", self.name);
            if let Some(d) = pen {
                assert!(*d <= 0.0, "{}: frame {k}: penetration {d:e} at {p:?}", self.name);
            }
        }
    }
}

/// Runs `s` for its default number of frames; stops after the first
/// non-finite position.
fn simulate<T: Real>(s: &Scene, response: Response) -> Run<T> {
    let world = World::<T>::new(s.mesh.clone()).expect("the mesh fits the backend");
    let body = Ellipsoid::<T>::new(s.radii).unwrap();
    let vel = v::<T>(s.velocity);
    let opts = MoveOptions::new(response);
    let mut p = v::<T>(s.start);
    let name = format!("{} {response:?} {}", s.name, T::name());
    let mut run = Run { name, positions: vec![p.clone()], pens: Vec::new() };
    for k in 0..s.frames {
        let m =
            move_body(&world, &body, &p, &vel, None, &opts).unwrap_or_else(|e| panic!("{}: frame {k}: {e}", run.name));
        p = m.position;
        let finite = p.iter().all(Real::is_finite);
        run.pens.push(if finite { penetration(&world, body.radii(), &p) } else { None });
        run.positions.push(p.clone());
        if !finite {
            break;
        }
    }
    run
}

fn robust_rests<T: Real>() {
    for offset in OFFSETS {
        for spec in ["corner", "dead-end"] {
            let s = far(spec, offset);
            let r = simulate::<T>(&s, Response::Robust);
            r.assert_never_penetrates();
            let n = r.positions.len();
            let (a, b) = (f64s(&r.positions[n - 2]), f64s(&r.positions[n - 1]));
            let step = (0..3).map(|i| (b[i] - a[i]).powi(2)).sum::<f64>().sqrt();
            let speed = s.velocity.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!(step <= 1e-6 * speed, "{}: last step {step:e}, not at rest", r.name);
        }
    }
}

#[test]
fn robust_never_penetrates_and_rests_far_from_origin_f32() {
    robust_rests::<f32>();
}

#[test]
fn robust_never_penetrates_and_rests_far_from_origin_f64() {
    robust_rests::<f64>();
}

fn robust_slides<T: Real>() {
    for offset in OFFSETS {
        for spec in ["floor", "tessellated-floor", "crease", "wedge", "wedge:1", "slot:0.01"] {
            let s = far(spec, offset);
            let ideal = s.ideal.unwrap();
            let r = simulate::<T>(&s, Response::Robust);
            r.assert_never_penetrates();
            let start = &r.positions[0];
            let end = r.positions.last().unwrap();
            let snag = snag_ratio(start, end, ideal, s.frames).unwrap();
            // What a free body stepping by the ideal displacement reaches
            // in this backend at this offset.
            let step = v::<T>(ideal);
            let free = (0..s.frames).fold(start.clone(), |p, _| p + &step);
            let reachable = snag_ratio(start, &free, ideal, s.frames).unwrap();
            assert!(snag >= 0.99 * reachable, "{}: slide ratio {snag}, a free body reaches {reachable}", r.name);
        }
    }
}

#[test]
fn robust_slides_far_from_origin_f32() {
    robust_slides::<f32>();
}

#[test]
fn robust_slides_far_from_origin_f64() {
    robust_slides::<f64>();
}

/// Fauerby in f32: the corner at 1e5 is penetrated by 6.8e-3 (2 frames,
/// the first at frame 7; on all three axes 5.6e-3 on 193 frames), the 10
/// degree wedge at 1e4 by 5.8e-5 (274 frames). Also the depth cap: 190 of
/// 200 frames in the corner at 1e5, where at the origin it never exceeds 3
/// checks.
#[test]
fn fauerby_f32_penetrates_far_from_origin() {
    let r = simulate::<f32>(&far("corner", [1e5, 0.0, 1e5]), Response::Fauerby);
    assert!(r.max_penetration() > 1e-3, "{}: deepest {:e}", r.name, r.max_penetration());
    let r = simulate::<f32>(&far("corner", [1e5, 1e5, 1e5]), Response::Fauerby);
    assert!(r.max_penetration() > 1e-3, "{}: deepest {:e}", r.name, r.max_penetration());
    assert!(r.penetrating_frames() > 100, "{}: {} frames", r.name, r.penetrating_frames());
    let r = simulate::<f32>(&far("wedge", [1e4, 0.0, 1e4]), Response::Fauerby);
    assert!(r.max_penetration() > 0.0, "{}: deepest {:e}", r.name, r.max_penetration());
    assert!(r.penetrating_frames() > 100, "{}: {} frames", r.name, r.penetrating_frames());
}

/// Linahan in f32: NaN at frame 13 (corner, 1e4), 7 (corner, 1e5), 25
/// (10 degree wedge, 1e4), 28 (crease, 1e4); creeps into the 1 degree wedge
/// at 1e4 (1.6e-5 deep on 250 frames) instead.
#[test]
fn linahan_f32_fails_far_from_origin() {
    for (spec, offset) in [
        ("corner", [1e4, 0.0, 1e4]),
        ("corner", [1e5, 0.0, 1e5]),
        ("wedge", [1e4, 0.0, 1e4]),
        ("crease", [1e4, 0.0, 1e4]),
    ] {
        let r = simulate::<f32>(&far(spec, offset), Response::Linahan);
        let nan = r.first_non_finite();
        assert!(nan.is_some_and(|k| k < 30), "{}: first non-finite frame {nan:?}", r.name);
    }
    let r = simulate::<f32>(&far("wedge:1", [1e4, 0.0, 1e4]), Response::Linahan);
    assert_eq!(r.first_non_finite(), None, "{}", r.name);
    assert!(r.max_penetration() > 0.0, "{}: deepest {:e}", r.name, r.max_penetration());
    assert!(r.penetrating_frames() > 100, "{}: {} frames", r.name, r.penetrating_frames());
}

/// A robust `f32` move far from the origin whose last sweep is free: the
/// body rests in the skin band above the plane `x + y = 2e5` (padding
/// capped at 0.01), and rounding the final world position (spacing 2^-7
/// there, up to 0.0068 radii of shift along this diagonal normal) carried
/// it 1.07e-4 radii inside (a review in the nineteenth session). The
/// rounded position is now measured again and pushed out
/// (`respond::robust`, `land`).
#[test]
fn robust_f32_final_rounding_does_not_sink_into_a_diagonal_plane() {
    let vertices = vec![
        [99700.0, 100300.0, 99700.0],
        [100300.0, 99700.0, 99700.0],
        [100300.0, 99700.0, 100300.0],
        [99700.0, 100300.0, 100300.0],
    ];
    let mesh = sweepslide::world::TriangleMesh::new(vertices, vec![[0, 1, 2], [0, 2, 3]]).unwrap();
    let world = World::<f32>::new(std::sync::Arc::new(mesh)).unwrap();
    let body = Ellipsoid::<f32>::sphere(1.0).unwrap();
    let start: Vec3<f32> = v([100002.484375, 99999.0078125, 99998.640625]);
    let velocity: Vec3<f32> = Vec3::new(-7.0113005e-5, 8.7787936e-5, 6.4355496e-5);
    let gravity: Vec3<f32> = Vec3::new(-0.03535534, -0.03535534, 0.0);
    let m = move_body(&world, &body, &start, &velocity, Some(&gravity), &MoveOptions::new(Response::Robust)).unwrap();
    let pen = penetration(&world, body.radii(), &m.position).unwrap();
    assert!(pen <= 0.0, "inside by {pen:e} at {:?}", f64s(&m.position));
}

/// Robust `f32` in a 120 degree trough at (1e5, 1e5, -1e5), with an
/// ellipsoid of radii (0.5, 0.5, 20) and a sphere, random pushes of 0.001
/// to 3 radii plus gravity, 200 frames per seed: never inside. Before the
/// final position was checked after its rounding, the ellipsoid ended
/// inside (by up to 1.5e-3 radii) in several seeds.
#[test]
fn robust_f32_far_trough_never_penetrates_after_rounding() {
    let offset = [1e5, 1e5, -1e5];
    for radii in [[0.5, 0.5, 20.0], [1.0, 1.0, 1.0]] {
        let scale = radii.iter().fold(0.0f64, |a, b| a.max(*b));
        let half = 60f64.to_radians();
        let mut vertices = Vec::new();
        let mut triangles = Vec::new();
        for side in [-1.0f64, 1.0] {
            let (dx, dy) = (side * half.sin() * 200.0, half.cos() * 200.0);
            let b = vertices.len() as u32;
            for [x, y, z] in [[0.0, 0.0, -200.0], [0.0, 0.0, 200.0], [dx, dy, 200.0], [dx, dy, -200.0]] {
                vertices.push([x * scale + offset[0], y * scale + offset[1], z * scale + offset[2]]);
            }
            triangles.extend(if side > 0.0 {
                [[b, b + 1, b + 2], [b, b + 2, b + 3]]
            } else {
                [[b, b + 2, b + 1], [b, b + 3, b + 2]]
            });
        }
        let mesh = sweepslide::world::TriangleMesh::new(vertices, triangles).unwrap();
        let world = World::<f32>::new(std::sync::Arc::new(mesh)).unwrap();
        let body = Ellipsoid::<f32>::new(radii).unwrap();
        let options = MoveOptions::new(Response::Robust);
        for seed in 0..6u64 {
            let mut rng = sweepslide::lab::rng::Rng::new(seed);
            let mut p: Vec3<f32> = v([offset[0], offset[1] + 6.0 * scale / half.sin(), offset[2]]);
            let gravity: Vec3<f32> = v([0.0, -0.2 * scale, 0.0]);
            for frame in 0..200 {
                let s = [0.001, 0.05, 0.5, 3.0][(rng.unit() * 4.0) as usize] * scale;
                let push = [(rng.unit() - 0.5) * s, (rng.unit() - 0.7) * s, (rng.unit() - 0.5) * s];
                let m = move_body(&world, &body, &p, &v(push), Some(&gravity), &options).unwrap();
                assert!(m.position.iter().all(|x| x.is_finite()), "seed {seed} frame {frame}: {:?}", m.position);
                let pen = penetration(&world, body.radii(), &m.position);
                assert!(
                    pen.is_none_or(|d| d <= 0.0),
                    "radii {radii:?} seed {seed} frame {frame}: inside by {pen:?} from {:?} pushed {push:?}",
                    f64s(&p)
                );
                p = m.position;
            }
        }
    }
}

/// Robust `f64` in a 90 degree trough whose apex runs through (1e15, 1e15),
/// where `f64` coordinates are 0.125 apart: a unit sphere sliding down one
/// wall ended 0.0277 inside (a review in the nineteenth session). The
/// re-check after the final rounding had pushed along the nearest wall's
/// normal only, which the other wall blocked; it now moves by the shortest
/// push that clears every wall within reach.
#[test]
fn robust_f64_trough_at_1e15_stays_out_after_rounding() {
    let (o, half) = (1e15f64, 100.0 * 45f64.to_radians().sin());
    let vertices = vec![
        [o, o, -100.0],
        [o, o, 100.0],
        [o + half, o + half, 100.0],
        [o + half, o + half, -100.0],
        [o - half, o + half, 100.0],
        [o - half, o + half, -100.0],
    ];
    let mesh =
        sweepslide::world::TriangleMesh::new(vertices, vec![[0, 1, 2], [0, 2, 3], [0, 4, 1], [0, 5, 4]]).unwrap();
    let world = World::<f64>::new(std::sync::Arc::new(mesh)).unwrap();
    let body = Ellipsoid::<f64>::sphere(1.0).unwrap();
    let options = MoveOptions::new(Response::Robust);
    let mut p: Vec3<f64> = v([1e15, 1e15 + 1.625, 0.11]);
    for frame in 0..20 {
        let m = move_body(&world, &body, &p, &v([0.0, 0.0, 0.01]), Some(&v([0.0, -0.2, 0.0])), &options).unwrap();
        let pen = penetration(&world, body.radii(), &m.position);
        assert!(pen.is_none_or(|d| d <= 0.0), "frame {frame}: inside by {pen:?} at {:?}", f64s(&m.position));
        p = m.position;
    }
    // Still in the trough, above its apex: coordinates here are 0.125
    // apart and the rounding's bound keeps the body about 0.15 clear of
    // both walls, beyond the exact check's reach, so the check above sees
    // nothing; a body that went through would be below the apex (a review
    // found `None` passing).
    let [x, y, _] = f64s(&p);
    assert!((x - 1e15).abs() < 0.5 && (1.4..2.0).contains(&(y - 1e15)), "{:?}", f64s(&p));
}

/// Robust `f32` near the origin, a body that crosses 84 radii of a
/// tessellated 60 degree ramp in one frame: its last contacts' coordinates
/// relative to the frame's start are about 84, each rounded by `u` times
/// that, while its padding scaled with 1 (the distance to the nearest
/// vertex and the remaining displacement were small): it rested 2.7e-6
/// radii inside (a review in the nineteenth session). The padding's `s`
/// now includes the position relative to the frame's start.
#[test]
fn robust_f32_fast_frame_rests_outside_a_ramp() {
    let a = 60f64.to_radians();
    let (t, n) = ([a.cos(), a.sin(), 0.0], [-a.sin(), a.cos(), 0.0]);
    let (cell, along, across) = (0.5, 600usize, 20usize);
    let mut vertices = Vec::new();
    for i in 0..=along {
        for j in 0..=across {
            let (u, z) = (i as f64 * cell - 150.0, j as f64 * cell - 5.0);
            vertices.push([u * t[0], u * t[1], z]);
        }
    }
    let id = |i: usize, j: usize| (i * (across + 1) + j) as u32;
    let mut triangles = Vec::new();
    for i in 0..along {
        for j in 0..across {
            triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mesh = sweepslide::world::TriangleMesh::new(vertices, triangles).unwrap();
    let world = World::<f32>::new(std::sync::Arc::new(mesh)).unwrap();
    let body = Ellipsoid::<f32>::sphere(1.0).unwrap();
    let start: Vec3<f32> = v([-0.8883037567138672, 0.4614448547363281, -0.21475455164909363]);
    let velocity: Vec3<f32> = v([42.32965823820892, 73.31711873560432, -0.08119475700441978]);
    let gravity: Vec3<f32> = v([-n[0] * 0.1, -n[1] * 0.1, 0.0]);
    let m = move_body(&world, &body, &start, &velocity, Some(&gravity), &MoveOptions::new(Response::Robust)).unwrap();
    let pen = penetration(&world, body.radii(), &m.position).unwrap();
    assert!(pen <= 0.0, "inside by {pen:e} at {:?}", f64s(&m.position));
}

/// A review (R36a, thirty-sixth session): an upright ellipsoid walked at
/// 1.5 m/s (240 Hz, gravity as a second pass) into the wedge between a
/// floor and the sloping underside of a model (the teapot's, scaled to
/// 100 m), `1e4` from the origin in `f32` (`2.9e4` radii in eSpace). The
/// two planes meet at 22 degrees in eSpace. Each frame's slide along their
/// crease was rounded to the same neighbouring `f32` step, `3.5e-4` radii
/// towards the apex, and the skin's restoring pushes, mostly across the
/// coordinates' spacing, were rounded away: the body ended up to `1e-4`
/// radii inside the ceiling once every 40 frames or so. The final
/// rounding in a crease now never moves the body towards a plane it
/// touched where another neighbouring value does not.
#[test]
fn robust_f32_walking_into_a_far_wedge_is_not_rounded_into_its_ceiling() {
    use std::sync::Arc;
    use sweepslide::world::TriangleMesh;
    let corners: [[f32; 3]; 6] = [
        [9983.503, 2.199254, 9974.773],
        [9984.035, 0.974_121_87, 9975.797],
        [9980.473, 0.974_121_87, 9977.988],
        [9800.0, 0.0, 9800.0],
        [10200.0, 0.0, 10200.0],
        [10200.0, 0.0, 9800.0],
    ];
    let vertices = corners.iter().map(|c| c.map(f64::from)).collect();
    let mesh = Arc::new(TriangleMesh::new(vertices, vec![[0, 1, 2], [3, 4, 5]]).unwrap());
    let world = World::<f32>::new(mesh).unwrap();
    let radii = [0.35, 0.9, 0.35];
    let body = Ellipsoid::<f32>::new(radii).unwrap();
    let velocity = [f64::from(f32::from_bits(0x3b08_03f9)), 0.0, f64::from(f32::from_bits(0x3bc1_2dbb))];
    let gravity = v::<f32>([0.0, f64::from(f32::from_bits(0xba5f_3b64)), 0.0]);
    // 40 frames back from where the review's body was, in the open part
    // of the wedge, 2 mm higher.
    let mut p = v::<f32>([9982.735 - 40.0 * velocity[0], 0.9025, 9975.6035 - 40.0 * velocity[2]]);
    let options = MoveOptions::new(Response::Robust);
    let mut deepest = f64::NEG_INFINITY;
    for frame in 0..400 {
        p = move_body(&world, &body, &p, &v(velocity), Some(&gravity), &options)
            .unwrap_or_else(|e| panic!("frame {frame}: {e}"))
            .position;
        deepest = deepest.max(penetration(&world, &v(radii), &p).unwrap_or(f64::NEG_INFINITY));
    }
    assert!(deepest < 0.0, "inside by {deepest:e} (eSpace)");
}

/// The review of R36a's fix (R36c): a sphere pressed straight into the
/// crease of a randomly rotated 90-degree wedge, its faces split into
/// triangles 3.7 radii across, `9.75e3` radii out in `f32`, comes to rest.
/// The fix's first version chose another neighbouring value even where
/// rounding to nearest returned the body to its start, and set it
/// creeping along the crease, `4.3e-5` radii a frame, without end.
#[test]
fn robust_f32_pressed_into_a_far_crease_comes_to_rest() {
    use std::sync::Arc;
    use sweepslide::world::TriangleMesh;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/regressions/data/creep-corner.obj");
    let world = World::<f32>::new(Arc::new(TriangleMesh::from_obj_file(&path).unwrap())).unwrap();
    let body = Ellipsoid::<f32>::new([1.0; 3]).unwrap();
    let velocity = v::<f32>([-0.005176280027014394, -0.0030110471946237357, 0.007028324247549164]);
    let gravity = v::<f32>([-0.004170090028134843, -0.002425745480347622, 0.005662125060128937]);
    let mut p = v::<f32>([-1858.7474578902682, 9463.68512968848, 1460.3855154861142]);
    let options = MoveOptions::new(Response::Robust);
    let mut last = Vec::new();
    for frame in 0..400 {
        p = move_body(&world, &body, &p, &velocity, Some(&gravity), &options)
            .unwrap_or_else(|e| panic!("frame {frame}: {e}"))
            .position;
        assert!(penetration(&world, &v([1.0; 3]), &p).unwrap_or(f64::NEG_INFINITY) < 0.0, "frame {frame} inside");
        if frame >= 300 {
            last.push(f64s(&p).map(f64::to_bits));
        }
    }
    last.dedup();
    assert_eq!(last.len(), 1, "still moving over the last 100 frames: {:?} -> {:?}", last.first(), last.last());
}

/// The resting band reaches `2 pad` from a triangle, and from about
/// `2.1e4` radii out in `f32` the padding exceeds half its cap
/// `max_padding`: there the scan that finds the resting contacts stopped
/// at `1 + max_padding` and missed triangles between it and `1 + 2 pad`,
/// which the sweeps then met one by one without moving the body (found
/// tracing the sawtooth of `docs/findings.md`, "A sawtooth in tight
/// notches far out in `f32`": in the notch's corner two of its three
/// planes lay in that gap, and gravity slid the body along one plane
/// only). A unit sphere `3e4` out (padding `7.2e-3`) resting `1.17e-2`
/// from a wall and pushed straight into it now meets the wall as a
/// resting contact, with no sweep.
#[test]
fn robust_f32_far_body_meets_a_wall_in_its_resting_band_beyond_the_cap_without_sweeping() {
    use std::sync::Arc;
    use sweepslide::respond::StopReason;
    use sweepslide::world::TriangleMesh;
    let vertices = vec![[29998.0, 29998.0, 30000.0], [29998.0, 30003.0, 30000.0], [30003.0, 29998.0, 30000.0]];
    let world = World::<f32>::new(Arc::new(TriangleMesh::new(vertices, vec![[0, 1, 2]]).unwrap())).unwrap();
    let body = Ellipsoid::<f32>::new([1.0; 3]).unwrap();
    // 518 of the `f32` spacing at 3e4 (2^-9) from the plane: a gap of
    // 0.01171875, between `max_padding` (0.01) and twice the padding.
    let p = v::<f32>([30000.0, 30000.0, 30000.0 - 518.0 / 512.0]);
    let m = move_body(&world, &body, &p, &v([0.0, 0.0, 0.1]), None, &MoveOptions::new(Response::Robust)).unwrap();
    assert_eq!(m.position, p, "a body within its resting band stays");
    assert_eq!(m.trace.stop, StopReason::Blocked);
    assert_eq!(m.trace.iterations, 0, "the wall was swept for, not met as a resting contact");
}

/// A flat floor `y = x0 / 2` of 24 x 24 cells with alternating diagonals,
/// centred on `(x0, x0 / 2, -x0)`, cells `cell` wide.
fn far_floor(x0: f64, cell: f64) -> std::sync::Arc<sweepslide::world::TriangleMesh> {
    let (y0, z0) = (x0 / 2.0, -x0);
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for j in 0..=24 {
        for i in 0..=24 {
            vertices.push([x0 + cell * (f64::from(i) - 12.0), y0, z0 + cell * (f64::from(j) - 12.0)]);
        }
    }
    for j in 0..24u32 {
        for i in 0..24u32 {
            let k = j * 25 + i;
            let (a, b, c, d) = (k, k + 1, k + 26, k + 25);
            if (i + j) % 2 == 0 {
                triangles.extend([[a, d, c], [a, c, b]]);
            } else {
                triangles.extend([[a, d, b], [b, d, c]]);
            }
        }
    }
    std::sync::Arc::new(sweepslide::world::TriangleMesh::new(vertices, triangles).unwrap())
}

/// Bodies touching a flat tessellated floor far out in `f32`, where the
/// final rounding `R` is a sizeable part of the radius: still, or pushed
/// along the floor under gravity, each ends clear of it and above it. A
/// review (session 39) found the skin's push, which reaches `1 + pad + 2R`
/// beyond the radius, working on candidates gathered `1.05` radii out:
/// with `R` a radius (an ellipsoid `(0.1, 1, 1)` a million units out)
/// a still body touching the floor ended half a radius through it. The
/// gathers now reach as far as the skin's checks look; and from `R` of
/// half a radius on the move is refused (next test).
#[test]
fn robust_f32_bodies_touching_a_far_floor_stay_clear_of_it_and_above_it() {
    let opts = MoveOptions::new(Response::Robust);
    for (x0, radii) in [
        (1e6, [1.0, 1.0, 1.0]),
        (3e5, [0.1, 1.0, 1.0]),
        (3e5, [0.1, 0.1, 0.1]),
        (1e6, [1.0, 0.4, 1.0]),
        (4.5e5, [0.1, 1.0, 1.0]),
        (4.5e5, [0.1, 0.1, 1.0]),
    ] {
        let world = World::<f32>::new(far_floor(x0, 43.0 * radii[0].min(radii[2]))).unwrap();
        let body = Ellipsoid::<f32>::new(radii).unwrap();
        for k in 0..8 {
            let k = f64::from(k);
            let start = v::<f32>([x0 + 0.37 * radii[0] * k, x0 / 2.0 + radii[1], -x0 + 0.53 * radii[2] * k]);
            for (push, gravity) in [([0.0; 3], None), ([0.0, 0.0, 0.2 * radii[2]], Some([0.0, -0.05 * radii[1], 0.0]))]
            {
                let g = gravity.map(v::<f32>);
                let moved = move_body(&world, &body, &start, &v(push), g.as_ref(), &opts).unwrap();
                let end = f64s(&moved.position);
                let pen = penetration(&world, body.radii(), &moved.position).unwrap_or(f64::NEG_INFINITY);
                let what = format!("radii {radii:?} at {x0:e}, start {:?}, push {push:?}: {end:?}", f64s(&start));
                assert!(pen <= 0.0, "{what}: {pen} inside");
                assert!(end[1] > x0 / 2.0, "{what}: below the floor");
            }
        }
    }
}

/// Beyond half a radius of final rounding the robust move is refused with
/// a typed error naming the position (the review's body, an `f32`
/// ellipsoid `(0.1, 1, 1)` a million units out, ten million radii along
/// `x`); the faithful responses still move.
#[test]
fn robust_f32_move_whose_rounding_exceeds_half_a_radius_is_refused() {
    let world = World::<f32>::new(far_floor(1e6, 4.3)).unwrap();
    let body = Ellipsoid::<f32>::new([0.1, 1.0, 1.0]).unwrap();
    let start = v::<f32>([1e6, 5e5 + 1.0, -1e6]);
    let e = move_body(&world, &body, &start, &v([0.0, 0.0, 0.2]), None, &MoveOptions::new(Response::Robust))
        .expect_err("refused");
    let text = e.to_string();
    assert!(text.contains("position") && text.contains("cannot keep its gap"), "{text}");
    for response in [Response::Fauerby, Response::Linahan] {
        assert!(move_body(&world, &body, &start, &v([0.0, 0.0, 0.2]), None, &MoveOptions::new(response)).is_ok());
    }
    // Just within: a unit sphere there (`R` about 0.1 radii) moves.
    let sphere = Ellipsoid::<f32>::new([1.0; 3]).unwrap();
    assert!(move_body(&world, &sphere, &start, &v([0.0, 0.0, 0.2]), None, &MoveOptions::new(Response::Robust)).is_ok());
}

/// A far floor with a ceiling `gap` above it (one quad each, facing each
/// other), centred on `(x0, x0 / 2, -x0)`.
fn far_duct(x0: f64, gap: f64) -> std::sync::Arc<sweepslide::world::TriangleMesh> {
    let (y0, z0, h) = (x0 / 2.0, -x0, 50.0);
    let vertices = vec![
        [x0 - h, y0, z0 - h],
        [x0 + h, y0, z0 - h],
        [x0 + h, y0, z0 + h],
        [x0 - h, y0, z0 + h],
        [x0 - h, y0 + gap, z0 - h],
        [x0 + h, y0 + gap, z0 - h],
        [x0 + h, y0 + gap, z0 + h],
        [x0 - h, y0 + gap, z0 + h],
    ];
    let triangles = vec![[0, 3, 2], [0, 2, 1], [4, 5, 6], [4, 6, 7]];
    std::sync::Arc::new(sweepslide::world::TriangleMesh::new(vertices, triangles).unwrap())
}

/// The same bodies in a far duct whose ceiling lies from 0.3 to 2 radii
/// above them, where the push that restores the skin below (up to
/// `1 + pad + R` from the floor, `R` up to 0.46 radii here) could carry
/// them into a ceiling the frame did not gather: every move ends clear of
/// both (the frame's gathers reach as far as the skin's checks look).
#[test]
fn robust_f32_bodies_touching_a_far_duct_floor_stay_clear_of_its_ceiling() {
    let opts = MoveOptions::new(Response::Robust);
    for x0 in [2e5, 3e5, 4e5, 4.5e5] {
        for gap in [2.3, 2.6, 2.9, 3.2, 3.5, 4.0] {
            let world = World::<f32>::new(far_duct(x0, gap)).unwrap();
            let body = Ellipsoid::<f32>::new([0.1, 1.0, 1.0]).unwrap();
            for k in 0..8 {
                let k = f64::from(k);
                let start = v::<f32>([x0 + 0.037 * k, x0 / 2.0 + 1.0, -x0 + 0.53 * k]);
                for (push, gravity) in [([0.0; 3], None), ([0.0, 0.0, 0.2], Some([0.0, -0.05, 0.0]))] {
                    let g = gravity.map(v::<f32>);
                    let moved = move_body(&world, &body, &start, &v(push), g.as_ref(), &opts).unwrap();
                    let pen = penetration(&world, body.radii(), &moved.position).unwrap_or(f64::NEG_INFINITY);
                    let end = f64s(&moved.position);
                    assert!(pen <= 0.0, "x0 {x0:e}, gap {gap}, start {k}, push {push:?}: {end:?} {pen} inside");
                }
            }
        }
    }
}
