//! Pushes straight into the seam of a flat, tessellated wall, found by a
//! game developer's review in the twenty-eighth session. The wall's two
//! triangles share a diagonal through the point the body's centre heads
//! for; a floor under the body lifts it by its padding, so the centre runs
//! a hair beside the diagonal. The neighbour's face and the diagonal edge
//! are then reached at the same time up to rounding, and the edge won the
//! tie (the lower triangle index) with its geometric direction: tilted by
//! the centre's offset from the seam, `1.2e-4` in `f32`, not by a rounding.
//! The slide along that tilted plane carried the rest of the push sideways:
//! a push of 200 radii ended `0.014` radii off along the wall, pushes of
//! `2e5` to `1.6e6` radii, slid in parts (`robust::parts`), 0.15 radii
//! off, and one of `1.8e6` radii, just too long for 1,024 parts and slid
//! unsplit, climbed the wall diagonally, 150 radii up and across, over its
//! top (such a pass is refused now). An inactive edge or
//! vertex reached during a sweep with the centre over the face now reports
//! the face normal, as a touch at the start always did.

use std::sync::Arc;
use sweepslide::Real;
use sweepslide::geom::{Ellipsoid, Vec3, vec3};
use sweepslide::lab::metrics::penetration;
use sweepslide::respond::{MoveOptions, Response, move_body};
use sweepslide::world::{TriangleMesh, World};

/// A 10 x 10 wall in the plane `x = 20` and a 60 x 60 floor at `y = -0.5`,
/// two triangles each. The wall is split by its diagonal through
/// `(20, 0, 0)`; with `fan`, into four triangles around that point
/// instead (an inactive vertex there).
fn wall_and_floor(fan: bool) -> TriangleMesh {
    let mut vertices = vec![[20.0, -5.0, -5.0], [20.0, -5.0, 5.0], [20.0, 5.0, 5.0], [20.0, 5.0, -5.0]];
    let mut triangles = if fan {
        vertices.push([20.0, 0.0, 0.0]);
        vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    } else {
        vec![[0, 1, 2], [0, 2, 3]]
    };
    let floor = vertices.len() as u32;
    vertices.extend([[-30.0, -0.5, -30.0], [-30.0, -0.5, 30.0], [30.0, -0.5, 30.0], [30.0, -0.5, -30.0]]);
    triangles.extend([[floor, floor + 1, floor + 2], [floor, floor + 2, floor + 3]]);
    TriangleMesh::new(vertices, triangles).unwrap()
}

/// A sphere of radius 0.5 resting on the floor at the origin, pushed by
/// `push` along `x` in one frame, in `T`: it must stop at the wall where it
/// is, neither sliding along the wall by more than `16 u` of the push (the
/// two planes' normals are exact) nor entering anything.
fn stops_square_at_the_wall<T: Real>(fan: bool, push: f64) {
    let world = World::<T>::new(Arc::new(wall_and_floor(fan))).unwrap();
    let body = Ellipsoid::<T>::sphere(0.5).unwrap();
    let start: Vec3<T> = vec3(0.0, 0.0, 0.0);
    let moved =
        move_body(&world, &body, &start, &vec3(push, 0.0, 0.0), None, &MoveOptions::new(Response::Robust)).unwrap();
    let [x, y, z] = [0, 1, 2].map(|i| moved.position[i].to_f64());
    let drift = 16.0 * T::unit_roundoff() * push;
    let what = format!("{} fan {fan} push {push:e}: ended at ({x}, {y}, {z})", T::name());
    assert!(z.abs() <= drift, "{what}: slid along the wall");
    // The floor's padding lifts it by far less than this.
    assert!(y.abs() <= 1e-3, "{what}: slid up or down the wall");
    assert!((19.49..19.5).contains(&x), "{what}: not at the wall");
    let depth = penetration(&world, body.radii(), &moved.position).unwrap_or(f64::NEG_INFINITY);
    assert!(depth <= 0.0, "{what}: penetration {depth:e}");
}

/// Pushes of 200 radii (one pass) and `8e5` radii (466 parts) into the
/// diagonal seam: in `f32` they ended `0.014` and 0.15 radii off, in `f64`
/// `2.6e-11` and `1.3e-7`.
#[test]
fn a_push_into_a_walls_diagonal_seam_stops_square() {
    for push in [100.0, 4e5] {
        stops_square_at_the_wall::<f32>(false, push);
        stops_square_at_the_wall::<sweepslide::Mpfr<24>>(false, push);
        stops_square_at_the_wall::<f64>(false, push);
    }
}

/// The same into the inactive vertex of a fan of four wall triangles.
#[test]
fn a_push_into_an_inactive_vertex_of_a_wall_stops_square() {
    for push in [100.0, 4e5] {
        stops_square_at_the_wall::<f32>(true, push);
        stops_square_at_the_wall::<sweepslide::Mpfr<24>>(true, push);
        stops_square_at_the_wall::<f64>(true, push);
    }
}

/// A convex ridge of `theta` degrees (an inactive edge), its line at
/// `x = 10` pointing at a unit sphere pushed head-on from `x = -191` by
/// `push` along `x`, in `T`: the edge's own direction is the constraint
/// there, and the body must stop square (`z = 0`). The first version of
/// the seam fix took a face's normal wherever the edge's direction was
/// within the touching tolerance of it, and in `f32` the body slid along
/// the ridge's face, 1.7 radii at 1 degree and 3.5 at 2 (a review).
fn stops_square_at_a_ridge<T: Real>(theta: f64, push: f64) {
    let h = 50.0 * (theta.to_radians() / 2.0).tan();
    let vertices = vec![
        [10.0 + h, -50.0, -50.0],
        [10.0, -50.0, 0.0],
        [10.0, 50.0, 0.0],
        [10.0 + h, 50.0, -50.0],
        [10.0 + h, -50.0, 50.0],
        [10.0 + h, 50.0, 50.0],
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]];
    let world = World::<T>::new(Arc::new(TriangleMesh::new(vertices, triangles).unwrap())).unwrap();
    let body = Ellipsoid::<T>::sphere(1.0).unwrap();
    let start: Vec3<T> = vec3(-191.0, 0.0, 0.0);
    let moved =
        move_body(&world, &body, &start, &vec3(push, 0.0, 0.0), None, &MoveOptions::new(Response::Robust)).unwrap();
    let [x, y, z] = [0, 1, 2].map(|i| moved.position[i].to_f64());
    let what = format!("{} ridge {theta} degrees, push {push}: ended at ({x}, {y}, {z})", T::name());
    assert!(z.abs() <= 16.0 * T::unit_roundoff() * push && y == 0.0, "{what}: slid along the ridge");
    assert!((8.99..9.0).contains(&x), "{what}: not at the ridge");
    let depth = penetration(&world, body.radii(), &moved.position).unwrap_or(f64::NEG_INFINITY);
    assert!(depth <= 0.0, "{what}: penetration {depth:e}");
}

#[test]
fn a_push_into_a_gently_convex_ridge_stops_square() {
    let cases = [(1.0, 400.0), (2.0, 400.0), (2.0, 1700.0), (0.1, 400.0)];
    for (theta, push) in cases {
        stops_square_at_a_ridge::<f32>(theta, push);
        stops_square_at_a_ridge::<sweepslide::Mpfr<24>>(theta, push);
        stops_square_at_a_ridge::<f64>(theta, push);
    }
}

/// A 20 x 20 floor of two quads sharing the edge `z = 0`, welded: its
/// vertices and triangles (also the base of
/// `respond_messy_levels.rs`'s seamed floors).
pub(crate) fn seamed_floor() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let vertices = vec![
        [-10.0, 0.0, -10.0],
        [10.0, 0.0, -10.0],
        [10.0, 0.0, 0.0],
        [-10.0, 0.0, 0.0],
        [10.0, 0.0, 10.0],
        [-10.0, 0.0, 10.0],
    ];
    (vertices, vec![[0, 3, 2], [0, 2, 1], [3, 5, 4], [3, 4, 2]])
}

/// A unit sphere falling onto a floor of two coplanar quads, its centre
/// `1.9e-4` radii beside their shared edge, in `T`: the landing must not
/// push it sideways. The neighbour's seam edge and the face under the
/// centre are met at the same time up to rounding, and with the edge's
/// direction (tilted by the offset) the rest of the fall slid the body
/// `1.9e-4` radii off in `f32` (a probe of messy soups, twenty-eighth
/// session: 148 of 1,320 such landings in `f32`, 22 in `f64`).
fn lands_without_sliding_beside_a_seam<T: Real>() {
    let (vertices, triangles) = seamed_floor();
    let world = World::<T>::new(Arc::new(TriangleMesh::new(vertices, triangles).unwrap())).unwrap();
    let body = Ellipsoid::<T>::sphere(1.0).unwrap();
    let start: Vec3<T> = vec3(0.25, 1.001, -1.931e-4);
    let gravity: Vec3<T> = vec3(0.0, -1.0, 0.0);
    let moved =
        move_body(&world, &body, &start, &vec3(0.0, 0.0, 0.0), Some(&gravity), &MoveOptions::new(Response::Robust))
            .unwrap();
    let dz = (moved.position[2].clone() - start[2].clone()).to_f64();
    let dx = (moved.position[0].clone() - start[0].clone()).to_f64();
    assert!(dz.abs().max(dx.abs()) <= 16.0 * T::unit_roundoff(), "{}: slid ({dx:e}, {dz:e}) sideways", T::name());
    let depth = penetration(&world, body.radii(), &moved.position).unwrap_or(f64::NEG_INFINITY);
    assert!(depth <= 0.0, "{}: penetration {depth:e}", T::name());
}

#[test]
fn a_landing_beside_a_floors_seam_does_not_slide() {
    lands_without_sliding_beside_a_seam::<f32>();
    lands_without_sliding_beside_a_seam::<sweepslide::Mpfr<24>>();
    lands_without_sliding_beside_a_seam::<f64>();
}

/// A sphere of radius 1.17 pushed 2,111 radii a frame for four frames into
/// a wall tessellated far finer than it (a 24 x 24 patch of cells
/// `3.5e-3` wide, each split by a diagonal, inside a frame of large
/// quads), in `T`: it must stop square. With cells smaller than the
/// offset a tie allows (`sqrt(2 d)`, `d` the touching tolerance), the
/// vertex met can lie a few triangles from the face under the centre, and
/// before the face was taken by its contact point's distance as well as by
/// a shared vertex the body slid 1.1 radii up the wall in `f32` (the
/// review of R28a's rework, found by its probe of fine walls).
fn stops_square_at_a_finely_tessellated_wall<T: Real>() {
    let (n, cell, x, y0, z0) = (24usize, 3.508315443463e-3, 38.75689488004768, 8.504965370613986, -9.724464116000762);
    let mut vertices = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            vertices.push([x, y0 + cell * j as f64, z0 + cell * i as f64]);
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.extend([[a, d, b], [b, d, c]]);
        }
    }
    // Large quads around the patch, so that a slide does not end at its
    // border.
    let (big, side) = (1e4, cell * n as f64);
    let ys = [-big, y0, y0 + side, big];
    let zs = [-big, z0, z0 + side, big];
    for j in 0..3 {
        for i in 0..3 {
            if (i, j) == (1, 1) {
                continue;
            }
            let b = vertices.len() as u32;
            vertices.extend([
                [x, ys[j], zs[i]],
                [x, ys[j], zs[i + 1]],
                [x, ys[j + 1], zs[i + 1]],
                [x, ys[j + 1], zs[i]],
            ]);
            triangles.extend([[b, b + 1, b + 2], [b, b + 2, b + 3]]);
        }
    }
    let world = World::<T>::new(Arc::new(TriangleMesh::new(vertices, triangles).unwrap())).unwrap();
    let radius = 1.1694384811545087;
    let body = Ellipsoid::<T>::sphere(radius).unwrap();
    let start: Vec3<T> = vec3(14.28802847597925, 8.552699852667851, -9.677408738422587);
    let push: Vec3<T> = vec3(2468.7263113119748, 0.0, 0.0);
    let options = MoveOptions::new(Response::Robust);
    let mut p = start.clone();
    for frame in 0..4 {
        p = move_body(&world, &body, &p, &push, None, &options).unwrap().position;
        let [dx, dy, dz] = [0, 1, 2].map(|i| (p[i].clone() - start[i].clone()).to_f64() / radius);
        let what = format!("{} frame {frame}: moved ({dx}, {dy}, {dz}) radii", T::name());
        assert!(dy.abs().max(dz.abs()) <= 1e-3, "{what}: slid along the wall");
        let gap = (x - p[0].to_f64()) / radius - 1.0;
        assert!((0.0..0.02).contains(&gap), "{what}: gap {gap:e} radii to the wall");
    }
}

#[test]
fn a_push_into_a_finely_tessellated_wall_stops_square() {
    stops_square_at_a_finely_tessellated_wall::<f32>();
    stops_square_at_a_finely_tessellated_wall::<sweepslide::Mpfr<24>>();
    stops_square_at_a_finely_tessellated_wall::<f64>();
}

/// The 14 triangles of the review's case: a valley of 0.3 degrees (its
/// faces split into fans around midpoints) above a floor, 500 units out.
#[rustfmt::skip]
const VALLEY: [[[f64; 3]; 3]; 14] = [
    [[1019.9241287857757, -53.56221982269787, 446.4377801773021], [1020.0643546697277, -53.56221982269787, 500.0], [1020.0160631104361, -52.56887126622574, 481.55402525228226]],
    [[1020.0643546697277, -53.56221982269787, 500.0], [1020.0643546697277, -51.06642627430828, 500.0], [1020.0160631104361, -52.56887126622574, 481.55402525228226]],
    [[1020.0643546697277, -51.06642627430828, 500.0], [1019.9241287857757, -51.06642627430828, 446.4377801773021], [1020.0160631104361, -52.56887126622574, 481.55402525228226]],
    [[1019.9241287857757, -51.06642627430828, 446.4377801773021], [1019.9241287857757, -53.56221982269787, 446.4377801773021], [1020.0160631104361, -52.56887126622574, 481.55402525228226]],
    [[1019.9241287857757, -51.06642627430828, 446.4377801773021], [1020.0643546697277, -51.06642627430828, 500.0], [1019.9241287857757, 53.56221982269787, 446.4377801773021]],
    [[1020.0643546697277, -51.06642627430828, 500.0], [1020.0643546697277, 53.56221982269787, 500.0], [1019.9241287857757, 53.56221982269787, 446.4377801773021]],
    [[1020.0643546697277, -53.56221982269787, 500.0], [1019.9241287857757, -53.56221982269787, 553.5622198226979], [1020.0643546697277, -51.06642627430828, 500.0]],
    [[1019.9241287857757, -53.56221982269787, 553.5622198226979], [1019.9241287857757, -51.06642627430828, 553.5622198226979], [1020.0643546697277, -51.06642627430828, 500.0]],
    [[1020.0643546697277, -51.06642627430828, 500.0], [1019.9241287857757, -51.06642627430828, 553.5622198226979], [1019.9898947853044, -2.286744494457629, 528.4415158247119]],
    [[1019.9241287857757, -51.06642627430828, 553.5622198226979], [1019.9241287857757, 53.56221982269787, 553.5622198226979], [1019.9898947853044, -2.286744494457629, 528.4415158247119]],
    [[1019.9241287857757, 53.56221982269787, 553.5622198226979], [1020.0643546697277, 53.56221982269787, 500.0], [1019.9898947853044, -2.286744494457629, 528.4415158247119]],
    [[1020.0643546697277, 53.56221982269787, 500.0], [1020.0643546697277, -51.06642627430828, 500.0], [1019.9898947853044, -2.286744494457629, 528.4415158247119]],
    [[-39080.25741867891, -11.717181278212932, -39580.25741867891], [41080.25741867891, -11.717181278212932, -39580.25741867891], [41080.25741867891, -11.717181278212932, 40580.25741867891]],
    [[-39080.25741867891, -11.717181278212932, -39580.25741867891], [41080.25741867891, -11.717181278212932, 40580.25741867891], [-39080.25741867891, -11.717181278212932, 40580.25741867891]],
];

/// A sphere of radius 0.89 pushed 813 radii along the floor into a
/// shallow valley, with gravity, in `T`: the valley's bottom edge ties
/// with a face, and the edge's direction, between the two faces' normals,
/// is the constraint. Taking the face's hit there (before a face stood in
/// only where the edge's direction does not lie between the faces'
/// normals) slid the body 0.26 radii along the valley in `f32` (a review
/// of R28a's rework, its probe's seed 961). Not every valley is settled
/// so: where the edge's direction lies outside the faces' normals, a body
/// can still slide along one face until the other stops it, as before
/// R28a (`docs/algorithms.md`, "Internal edges").
fn stops_square_in_a_shallow_valley<T: Real>() {
    let vertices: Vec<[f64; 3]> = VALLEY.iter().flatten().copied().collect();
    let triangles = (0..VALLEY.len() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    let world = World::<T>::new(Arc::new(TriangleMesh::new(vertices, triangles).unwrap())).unwrap();
    let radius = 0.8902517623610299;
    let body = Ellipsoid::<T>::sphere(radius).unwrap();
    let start: Vec3<T> = vec3(718.2701416338341, -10.826929515851901, 500.0);
    let (push, gravity): (Vec3<T>, Vec3<T>) = (vec3(723.7085062161678, 0.0, 0.0), vec3(0.0, -radius, 0.0));
    let p =
        move_body(&world, &body, &start, &push, Some(&gravity), &MoveOptions::new(Response::Robust)).unwrap().position;
    let dz = (p[2].clone() - start[2].clone()).to_f64() / radius;
    assert!(dz.abs() <= 0.01, "{}: slid {dz} radii along the valley", T::name());
    let depth = penetration(&world, body.radii(), &p).unwrap_or(f64::NEG_INFINITY);
    assert!(depth <= 0.0, "{}: penetration {depth:e}", T::name());
}

#[test]
fn a_push_into_a_shallow_valley_stops_square() {
    stops_square_in_a_shallow_valley::<f32>();
    stops_square_in_a_shallow_valley::<sweepslide::Mpfr<24>>();
    stops_square_in_a_shallow_valley::<f64>();
}
