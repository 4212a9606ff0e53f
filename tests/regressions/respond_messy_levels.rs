//! Walks over flat surfaces whose seams are active although the surface is
//! flat, as exported game levels have them, found by a directed probe in
//! the thirtieth session (about 19,700 runs over T-junctions, faces given
//! twice, decals, unwelded tiles and thin plates, each beside a welded
//! control). An edge or vertex of such a seam, lying in the plane of the
//! face the body stands over, was met as a resting contact with its
//! geometric direction, tilted off the face's normal by the centre's
//! offset from the seam; the cone of that direction and the face's normal
//! is their crease, along the seam, and the body stopped there frame after
//! frame (`Blocked`). The resting band within which such contacts are met
//! grows with the padding, so the walks froze far from the origin in `f32`
//! and, under a thin plate, wherever a sliver's capped padding reached.
//! Such a feature now sets no resting contact (`robust::drop_hidden_features`,
//! R30a). The same seams, met during a sweep at the time of the face under
//! the centre, won the tie with their tilted direction, as the seam of
//! R28a had: a face now stands in for an active edge or vertex too where it
//! lies on or behind the face's plane (`detect::earliest_hit`, R30b).

use std::sync::Arc;
use sweepslide::Real;
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

/// Moves `radii` from `start` for `frames` frames of `velocity` (and
/// `gravity` as a second pass), in `T`, asserting that no frame ends
/// inside; returns the end position.
fn walk<T: Real>(
    mesh: &TriangleMesh,
    radii: [f64; 3],
    start: [f64; 3],
    velocity: [f64; 3],
    gravity: Option<[f64; 3]>,
    frames: usize,
) -> [f64; 3] {
    let world = World::<T>::new(Arc::new(mesh.clone())).unwrap();
    let body = Ellipsoid::<T>::new(radii).unwrap();
    let v = |x: [f64; 3]| -> Vec3<T> { vec3(x[0], x[1], x[2]) };
    let (velocity, gravity) = (v(velocity), gravity.map(v));
    let options = MoveOptions::new(Response::Robust);
    let mut p = v(start);
    for frame in 0..frames {
        p = move_body(&world, &body, &p, &velocity, gravity.as_ref(), &options).unwrap().position;
        assert!(p.iter().all(Real::is_finite), "{} frame {frame}: {p:?}", T::name());
        let depth = penetration(&world, body.radii(), &p);
        assert!(depth.is_none_or(|d| d <= 0.0), "{} frame {frame}: {depth:?} inside", T::name());
    }
    [0, 1, 2].map(|i| p[i].to_f64())
}

/// A 20 x 20 floor at height `y` around `(x, z)`, split at `x`: the two
/// halves' quads, the right one, with `t_junction`, as two quads meeting at
/// the middle of the left one's edge (the seam's edges then belong to one
/// triangle each: active).
fn floor(x: f64, y: f64, z: f64, t_junction: bool) -> TriangleMesh {
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    let mut quad = |q: [[f64; 2]; 4]| {
        let base = vertices.len() as u32;
        vertices.extend(q.map(|[dx, dz]| [x + dx, y, z + dz]));
        triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    };
    quad([[-10.0, -10.0], [-10.0, 10.0], [0.0, 10.0], [0.0, -10.0]]);
    if t_junction {
        quad([[0.0, -10.0], [0.0, 0.0], [10.0, 0.0], [10.0, -10.0]]);
        quad([[0.0, 0.0], [0.0, 10.0], [10.0, 10.0], [10.0, 0.0]]);
    } else {
        quad([[0.0, -10.0], [0.0, 10.0], [10.0, 10.0], [10.0, -10.0]]);
    }
    TriangleMesh::new(vertices, triangles).unwrap()
}

/// The character of `examples/character.rs` (radii `0.4, 0.9, 0.4`)
/// walking slowly over a T-junction seam `1e4` from the origin in `f32`,
/// gravity summed into the displacement (as Rapier's `move_shape` takes
/// it): it stopped at the seam, `Blocked` from frame 140 on, 0.35 of its
/// walk. The welded floor is the control.
#[test]
fn a_character_walks_over_a_t_junction_far_from_the_origin_in_f32() {
    let (x, y, z) = (1e4, 5e3, -1e4);
    let (speed, frames) = (0.002, 300);
    let start = [x - 0.3, y + 0.9, z + 1.3];
    let run = |t_junction| {
        walk::<f32>(&floor(x, y, z, t_junction), [0.4, 0.9, 0.4], start, [speed, -0.0818, 0.0], None, frames)
    };
    let ideal = speed * frames as f64;
    let (welded, seamed) = (run(false)[0] - start[0], run(true)[0] - start[0]);
    assert!(welded > 0.9 * ideal, "the control walked {welded} of {ideal}");
    assert!(seamed > 0.9 * ideal, "walked {seamed} of {ideal} (the welded floor: {welded})");
}

/// A thin plate (top at `y = 2`) whose underside, `1e-5` lower, is two
/// triangles with a sliver along their seam, and a sphere sliding down over
/// the top in `f32` at the origin: the underside's edges, behind the top's
/// plane, were met as resting contacts within the sliver's capped padding,
/// and the sphere moved 0.0022 of 0.327 along `x` in 60 frames (0.3269
/// without the sliver, and in `f64`).
#[test]
fn a_sphere_slides_over_a_thin_plate_with_a_sliver_underneath_in_f32() {
    let y = 1.999_989_986_419_677_7;
    let vertices = vec![
        [-1.0, y, -2.0],
        [-1.0, y, -1.0],
        [-0.999_989_986_419_677_7, y, -1.5],
        [0.0, y, -1.0],
        [-2.0, y, -1.0],
        [-2.0, 2.0, -2.0],
        [-1.0, 2.0, -1.0],
        [-1.0, 2.0, -2.0],
    ];
    // The sliver, the two underside cells, the top.
    let triangles = vec![[0, 1, 2], [0, 3, 1], [0, 1, 4], [5, 6, 7]];
    let mesh = TriangleMesh::new(vertices, triangles).unwrap();
    let start = [-1.139_174_938_201_904_3, 3.000_003_576_278_686_5, -1.736_238_837_242_126_5];
    let velocity = [0.005_445_078_015_327_454, -0.019_243_918_359_279_633, -0.000_150_834_748_637_862_5];
    let end = walk::<f32>(&mesh, [1.0; 3], start, velocity, Some([0.0, -0.05, 0.0]), 60);
    let (moved, ideal) = (end[0] - start[0], 60.0 * velocity[0]);
    assert!(moved > 0.95 * ideal, "moved {moved} of {ideal} along x");
}

/// The character pushed nearly head-on (5% of the push along it) into a
/// wall `1e4` from the origin in `f32`, gravity as a second pass; at
/// `z = 0` the wall's left part, one quad of full height, meets its right
/// part, two quads one above the other, whose shared corner lies in the
/// middle of the left part's edge (a T-junction). The character stopped at
/// that seam, 0.49 of its travel along the wall, where it slides over the
/// welded wall.
#[test]
fn a_character_slides_along_a_wall_with_a_t_junction_far_from_the_origin_in_f32() {
    let (x, y, z, h) = (1e4, 5e3, -1e4, 1.5);
    let mesh = |t_junction: bool| {
        let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
        let mut quad = |q: [[f64; 3]; 4]| {
            let base = vertices.len() as u32;
            vertices.extend(q.map(|[dx, dy, dz]| [x + dx, y + dy, z + dz]));
            triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
        };
        quad([[h, 0.0, -10.0], [h, 4.0, -10.0], [h, 4.0, 0.0], [h, 0.0, 0.0]]);
        if t_junction {
            quad([[h, 0.0, 0.0], [h, 2.0, 0.0], [h, 2.0, 10.0], [h, 0.0, 10.0]]);
            quad([[h, 2.0, 0.0], [h, 4.0, 0.0], [h, 4.0, 10.0], [h, 2.0, 10.0]]);
        } else {
            quad([[h, 0.0, 0.0], [h, 4.0, 0.0], [h, 4.0, 10.0], [h, 0.0, 10.0]]);
        }
        quad([[-h, 0.0, -10.0], [h, 0.0, -10.0], [h, 0.0, 10.0], [-h, 0.0, 10.0]]);
        TriangleMesh::new(vertices, triangles).unwrap()
    };
    let (speed, share): (f64, f64) = (0.0667, 0.05);
    let velocity = [speed, 0.0, speed * share].map(|v| v / (1.0 + share * share).sqrt());
    let start = [x + h - 0.4 * 1.002, y + 0.9 * 1.001, z - 2.0];
    let frames = 1200;
    let run = |t_junction| {
        walk::<f32>(&mesh(t_junction), [0.4, 0.9, 0.4], start, velocity, Some([0.0, -0.0818, 0.0]), frames)[2]
            - start[2]
    };
    let (welded, seamed) = (run(false), run(true));
    assert!(welded > 0.8 * velocity[2] * frames as f64, "the control slid {welded}");
    assert!(seamed > 0.95 * welded, "slid {seamed} along the wall (the welded wall: {welded})");
}

/// The floor of `tests/regressions/respond_seam_hits.rs`'s landings (two
/// quads sharing `z = 0`), with the `z > 0` half split at `x = 0` so that
/// its corner `(0, 0, 0)` lies in the middle of the other half's edge (a
/// T-junction), or given twice, the copy reversed (a two-sided floor).
fn seamed_floor(t_junction: bool) -> TriangleMesh {
    let (welded, quads) = super::respond_seam_hits::seamed_floor();
    if t_junction {
        let mut vertices = welded[..4].to_vec();
        vertices.extend([[-10.0, 0.0, 10.0], [0.0, 0.0, 10.0], [0.0, 0.0, 0.0], [10.0, 0.0, 10.0]]);
        let triangles = vec![[0, 3, 2], [0, 2, 1], [3, 4, 5], [3, 5, 6], [6, 5, 7], [6, 7, 2]];
        TriangleMesh::new(vertices, triangles).unwrap()
    } else {
        let mut vertices = welded.clone();
        vertices.extend(welded);
        let mut triangles = quads.clone();
        triangles.extend(quads.iter().map(|t| [t[0] + 6, t[2] + 6, t[1] + 6]));
        TriangleMesh::new(vertices, triangles).unwrap()
    }
}

/// A sphere dropped onto such a floor a hair beside the seam (`dz` in
/// `f32`, `dz / 1e4` in `f64`) falls straight down: it slid sideways by up
/// to `5.8e-4` radii in `f32` (48 of these 96 landings beyond `16 u`) and
/// by `2e-8` in `f64` (24), where the welded floor gives none. The
/// neighbour's edge, active although the floor is flat, tied with the face
/// under the centre and won with its geometric direction, tilted by the
/// offset (R28a's tie, which only an inactive edge's face stood in for).
fn lands_straight<T: Real>(scale: f64) {
    for t_junction in [true, false] {
        let world = World::<T>::new(Arc::new(seamed_floor(t_junction))).unwrap();
        let body = Ellipsoid::<T>::sphere(1.0).unwrap();
        for dz in [-1.931e-4, 1.931e-4, -5e-5, 5e-5, -1e-3, 1e-3, -3e-4, 3e-4] {
            for x in [0.25, 3.7, -6.1, 1e-4] {
                for g in [1.0, 0.3, 3.0] {
                    let start: Vec3<T> = vec3(x, 1.001, dz * scale);
                    let gravity: Vec3<T> = vec3(0.0, -g, 0.0);
                    let options = MoveOptions::new(Response::Robust);
                    let end = move_body(&world, &body, &start, &Vec3::zeros(), Some(&gravity), &options).unwrap();
                    let side = [0, 2].map(|i| (end.position[i].to_f64() - start[i].to_f64()).abs());
                    assert!(
                        side[0].max(side[1]) <= 16.0 * T::unit_roundoff(),
                        "{} t-junction {t_junction} from ({x}, 1.001, {}) falling {g}: slid {side:?}",
                        T::name(),
                        dz * scale
                    );
                }
            }
        }
    }
}

#[test]
fn landings_beside_a_t_junction_or_on_a_doubled_floor_fall_straight_f32() {
    lands_straight::<f32>(1.0);
}

#[test]
fn landings_beside_a_t_junction_or_on_a_doubled_floor_fall_straight_f64() {
    lands_straight::<f64>(1e-4);
}

/// A sphere of radius 0.5 on a floor pushed `push` straight into the seam
/// of `tests/regressions/respond_seam_hits.rs`'s wall given twice, the copy
/// reversed (a two-sided wall), `offset` from the origin: the copy's
/// diagonal, active (an edge of four triangles), tied with the face and
/// carried the push along the wall, as before R28a: `0.014` radii for a
/// push of 100 in `f32` at the origin, `0.037` at `1e3`, and `9e-8` for
/// `4e5` in `f64`. It must stop square, within `16 u` of the push.
fn stops_square_at_a_doubled_wall<T: Real>(offset: f64, push: f64) {
    let o = [offset, offset * 0.5, -offset];
    let mut vertices: Vec<[f64; 3]> = Vec::new();
    let wall = [[20.0, -5.0, -5.0], [20.0, -5.0, 5.0], [20.0, 5.0, 5.0], [20.0, 5.0, -5.0]];
    vertices.extend(wall);
    vertices.extend(wall);
    vertices.extend([[-30.0, -0.5, -30.0], [-30.0, -0.5, 30.0], [30.0, -0.5, 30.0], [30.0, -0.5, -30.0]]);
    let vertices = vertices.into_iter().map(|v| [v[0] + o[0], v[1] + o[1], v[2] + o[2]]).collect();
    let triangles = vec![[0, 1, 2], [0, 2, 3], [4, 6, 5], [4, 7, 6], [8, 9, 10], [8, 10, 11]];
    let world = World::<T>::new(Arc::new(TriangleMesh::new(vertices, triangles).unwrap())).unwrap();
    let body = Ellipsoid::<T>::sphere(0.5).unwrap();
    let start: Vec3<T> = vec3(o[0], o[1], o[2]);
    let options = MoveOptions::new(Response::Robust);
    let end = move_body(&world, &body, &start, &vec3(push, 0.0, 0.0), None, &options).unwrap().position;
    let [x, y, z] = [0, 1, 2].map(|i| end[i].to_f64() - start[i].to_f64());
    let what = format!("{} offset {offset:e} push {push:e}: moved ({x}, {y}, {z})", T::name());
    assert!(z.abs() <= 16.0 * T::unit_roundoff() * push, "{what}: slid along the wall");
    assert!(y.abs() <= 1e-3 && (19.49..19.5).contains(&x), "{what}: not square at the wall");
    assert!(penetration(&world, body.radii(), &end).is_none_or(|d| d <= 0.0), "{what}: inside");
}

#[test]
fn a_push_into_a_doubled_wall_stops_square_f32() {
    for offset in [0.0, 1e3] {
        stops_square_at_a_doubled_wall::<f32>(offset, 100.0);
    }
}

#[test]
fn a_push_into_a_doubled_wall_stops_square_f64() {
    stops_square_at_a_doubled_wall::<f64>(0.0, 4e5);
}

/// A 20 x 20 floor at `y = 0` welded along `x = 0`, with, given a
/// `sliver` width, a crack-filler lying in it along that seam: a flat cap
/// from `(0, 0, -10)` to `(0, 0, 10)` whose third vertex is that far off
/// the seam's middle, over the right half.
fn sliver_floor(sliver: Option<f64>) -> TriangleMesh {
    let mut vertices = vec![
        [-10.0, 0.0, -10.0],
        [-10.0, 0.0, 10.0],
        [0.0, 0.0, 10.0],
        [0.0, 0.0, -10.0],
        [10.0, 0.0, 10.0],
        [10.0, 0.0, -10.0],
    ];
    let mut triangles = vec![[0, 1, 2], [0, 2, 3], [3, 2, 4], [3, 4, 5]];
    if let Some(width) = sliver {
        vertices.push([width, 0.0, 0.0]);
        triangles.push([3, 2, 6]);
    }
    TriangleMesh::new(vertices, triangles).unwrap()
}

/// Slow walks over a sliver lying in a floor ([`sliver_floor`]) in `f32` at
/// the origin, gravity as a second pass: a unit sphere and the character of
/// `examples/character.rs`. The sliver's normal, the product of rounded
/// edges, was ill-conditioned (angle factor about `1e6`), so its padding
/// was the cap `0.01`, and its edges, which lie in the floor, had that
/// padding too: the body was held `0.01` off them and a walk of `0.002` a
/// frame stopped at the seam, 0.38 to 0.80 of its path (the character
/// 0.45; since R30a bobbing in place). An edge's distance does not use the
/// normal, and it has had the plain padding since R31a; since R33a the
/// normal is the exact edges' product and the face's padding is the plain
/// one too. The floor without the sliver is the control.
#[test]
fn slow_walks_over_a_sliver_lying_in_a_floor_go_the_whole_way_in_f32() {
    for (radii, height, speed) in [([1.0; 3], 1.0, 0.002), ([1.0; 3], 1.0, 0.001), ([0.4, 0.9, 0.4], 0.9, 0.002)] {
        let frames = (1.0 / speed) as usize;
        let start = [-0.5, height, 0.3];
        let run = |sliver: bool| {
            walk::<f32>(
                &sliver_floor(sliver.then_some(1e-5)),
                radii,
                start,
                [speed, 0.0, 0.0],
                Some([0.0, -0.05, 0.0]),
                frames,
            )[0] - start[0]
        };
        let ideal = speed * frames as f64;
        let (welded, seamed) = (run(false), run(true));
        assert!(welded > 0.95 * ideal, "{radii:?} at {speed}: the control walked {welded} of {ideal}");
        assert!(seamed > 0.95 * ideal, "{radii:?} at {speed}: walked {seamed} of {ideal} (welded: {welded})");
    }
}

/// The walks of [`slow_walks_over_a_sliver_lying_in_a_floor_go_the_whole_way_in_f32`]
/// keep the control's height. Between R31a and R33a the sliver's face had
/// the capped padding `0.01` (its normal's tilt factor about `1e6`), and a
/// body whose centre passed over it hopped by up to `0.01` radii and fell
/// back (`0.0099` for the unit sphere, `0.0089` for the character, `0.0071`
/// over a sliver `1e-3` wide). Its normal is now the exact edges' product,
/// its face's padding the plain one.
#[test]
fn slow_walks_over_a_sliver_lying_in_a_floor_keep_their_height_in_f32() {
    for (radii, height, width) in [([1.0; 3], 1.0, 1e-5), ([0.4, 0.9, 0.4], 0.9, 1e-5), ([1.0; 3], 1.0, 1e-3)] {
        let heights = |mesh: &TriangleMesh| {
            let world = World::<f32>::new(Arc::new(mesh.clone())).unwrap();
            let body = Ellipsoid::<f32>::new(radii).unwrap();
            let options = MoveOptions::new(Response::Robust);
            let (velocity, gravity): (Vec3<f32>, Vec3<f32>) = (vec3(0.002, 0.0, 0.0), vec3(0.0, -0.05, 0.0));
            let mut p: Vec3<f32> = vec3(-0.5, height, 0.3);
            let mut range = (f32::INFINITY, f32::NEG_INFINITY);
            for frame in 0..500 {
                p = move_body(&world, &body, &p, &velocity, Some(&gravity), &options).unwrap().position;
                if frame >= 20 {
                    range = (range.0.min(p[1]), range.1.max(p[1]));
                }
            }
            assert!(p[0] > 0.45, "{radii:?}: walked to {}", p[0]);
            range
        };
        let (welded, seamed) = (heights(&sliver_floor(None)), heights(&sliver_floor(Some(width))));
        assert_eq!(welded.0, welded.1, "{radii:?}: the control's height changed");
        assert_eq!(
            seamed, welded,
            "{radii:?} over a sliver {width:e} wide: heights {seamed:?}, the control {welded:?}"
        );
    }
}

/// A unit sphere pushed along the normal of a lone flat cap in `f64`: long
/// edge `4e5`, third vertex `1.8e-4` off its middle (tilt factor about
/// `5e8`). The side tests, with the cap's tilted normal, placed the foot
/// outside the face, and the sweep met an edge instead, farther than the
/// face by up to the inradius squared over two; the first version of R31a,
/// which gave edge and vertex contacts the plain padding, let the sphere
/// end `1.6e-10` inside from the first frame on (a review, thirty-first
/// session; the face's padding had kept it `0.01` clear). Edge and vertex
/// contacts now add that excess (`robust::side_excess`).
#[test]
fn a_sphere_pushed_onto_a_long_flat_cap_stays_out_f64() {
    let vertices = vec![
        [91_605.497_945_589_58, -99_055.513_371_561_7, 147_636.167_712_511_9],
        [-91_605.497_945_589_58, 99_055.513_371_561_7, -147_636.167_712_511_9],
        [6_218.756_038_037_029, -6_724.509_581_134_333_5, 10_022.469_212_504_63],
    ];
    let mesh = TriangleMesh::new(vertices, vec![[0, 1, 2]]).unwrap();
    let start = [-57_494.903_657_251_28, 62_171.270_223_623_89, -92_660.735_733_745_94];
    let velocity = [0.145_026_275_646_800_1, -0.437_838_518_269_744_2, -0.383_750_975_622_698_94];
    walk::<f64>(&mesh, [1.0; 3], start, velocity, None, 20);
}

/// Bodies pushed onto lone flat caps in `f32` (from a directed probe,
/// thirty-third session: caps `1e2` to `3e3` long and `1e-3` to 10 high,
/// turned at random, spheres and ellipsoids pushed at them; 20 of 12,000
/// runs ended inside with the old code, none now). The cap's unit normal,
/// the product of two rounded edges, was tilted by a few `u` times `1 /
/// sin` of its largest angle (`3e3` to `2.4e5` here), up to 0.05 radians,
/// and the distance to the face, taken hundreds of radii from the nearest
/// vertex, was off by up to radii; the padding, capped at `0.01`, could not
/// cover it: these three ended 0.56, 0.75 and 0.019 radii inside. The
/// normal of a triangle whose shape factor exceeds 4 is now the product of
/// the exact edges (`geom::cross_of_edges`), tilted by a few `u`.
#[test]
fn bodies_pushed_onto_lone_flat_caps_stay_out_f32() {
    type Case = ([[f64; 3]; 3], [f64; 3], [f64; 3], [f64; 3]);
    let cases: [Case; 3] = [
        (
            [
                [785.111_553_830_249_1, -583.009_751_886_996_1, -976.450_886_650_580_1],
                [-788.064_146_934_360_6, 587.155_760_820_46, 972.993_096_476_992_8],
                [516.629_926_081_174_6, -383.305_333_946_376_2, -643.756_514_782_941_7],
            ],
            [1.0; 3],
            [-188.526_456_469_824_27, 138.507_166_200_904_1, 226.770_808_387_334_9],
            [1.329_624_803_841_695_1, 0.835_488_296_488_375_6, 0.576_417_586_939_888_2],
        ),
        (
            [
                [-794.987_603_207_645_7, 546.337_349_808_747_1, 728.308_068_437_876],
                [787.073_870_591_311, -538.271_896_291_337_7, -720.218_904_662_321_6],
                [-203.688_514_228_630_4, 140.960_489_829_352_4, 186.914_673_507_104],
            ],
            [1.441_422_420_386_954_8, 1.089_718_857_756_820_6, 1.152_133_029_869_812_5],
            [516.697_709_436_555_2, -349.970_750_249_225_03, -473.589_766_328_888_7],
            [-0.312_615_269_218_149_9, -1.693_304_653_189_022_3, 0.905_735_053_196_449_2],
        ),
        (
            [
                [-543.007_900_192_724_5, -619.829_387_114_003_9, -1_159.871_727_958_991_4],
                [546.569_490_962_546_1, 615.662_349_055_712_1, 1_158.546_146_657_523_9],
                [-374.643_549_422_625_03, -428.819_299_917_638_26, -801.325_916_694_077_3],
            ],
            [1.0; 3],
            [-14.164_726_373_446_287, -18.216_316_772_156_73, -33.732_376_629_870_24],
            [0.041_024_807_404_356_475, -0.188_151_683_729_523_68, -0.015_538_688_155_530_112],
        ),
    ];
    for (vertices, radii, start, velocity) in cases {
        let mesh = TriangleMesh::new(vertices.to_vec(), vec![[0, 1, 2]]).unwrap();
        walk::<f32>(&mesh, radii, start, velocity, None, 12);
    }
}

/// An ellipsoid pushed down a wall onto a flat cap lying against it, in
/// `f32` (a review's directed probe, thirty-third session: caps up to
/// `1.6e5` long beside a wall ended up to 0.97 radii inside in 23 of 1,848
/// runs after R33a, 70 before, and 1 after R33b, `3.3e-4` deep beside a
/// cap `7.4e4` long). After meeting the wall the slide reached the cap's
/// long edge at `t = 0.315`, but the sweep reported the cap's face at
/// `t = 0.59`, a radius past the edge: the face window's tolerance (F38's
/// fix) grew with the shape factor (`2.8e4` here, 390 radii from the
/// start: 10 radii), far beyond its sides. It now grows with the normal's
/// tilt, about 1 for a cap's exact normal (R33b). The body ended 0.97
/// radii inside; the cap alone and the wall alone were cleared.
#[test]
fn an_ellipsoid_pushed_down_a_wall_onto_a_flat_caps_edge_stays_out_f32() {
    let vertices = vec![
        [-482.551_340_783_401_3, 8.486_721_634_451_204, 60.914_049_344_950_43],
        [477.263_563_833_377_8, -13.842_712_250_822_903, -68.968_666_341_834_45],
        [377.074_832_433_202_46, -11.515_176_834_396_438, -55.378_232_529_828_49],
        [-490.689_829_078_199_24, 1.101_632_083_621_298_7, 59.838_220_360_290_88],
        [484.477_826_728_723_1, -21.584_973_003_108_82, -72.122_038_619_734_97],
        [485.045_024_626_317_46, -6.175_552_288_616_277, -70.579_713_654_749_97],
        [-490.122_631_180_604_86, 16.511_052_798_113_845, 61.380_545_325_275_89],
    ];
    let mesh = TriangleMesh::new(vertices, vec![[0, 1, 2], [3, 4, 5], [3, 5, 6]]).unwrap();
    let radii = [1.437_099_662_304_783, 0.993_265_901_404_454_7, 1.361_917_621_068_905_2];
    let start = [70.056_165_764_047_12, -2.214_112_438_912_787, -13.638_622_777_016_353];
    let velocity = [-0.675_451_021_242_216_6, -3.613_022_826_163_784, -1.166_366_910_473_989];
    let end = walk::<f32>(&mesh, radii, start, velocity, None, 3);
    // It rests on the cap's edge, about a radius above where it was stopped.
    assert!(end[1] > -3.5, "ended at {end:?}");
}
