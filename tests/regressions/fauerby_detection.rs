//! Concrete inputs where Fauerby's detection, kept faithful with its
//! defects, gives a wrong answer, and the robust detection the right one.
//! Each test asserts both behaviours, so it fails if the baseline is
//! silently "fixed" (it must stay the paper's baseline) or if the robust
//! variant regresses.
//!
//! The unit sphere lives in eSpace: centre `base`, moving by `vel` over
//! `t in [0, 1]`. All inputs are exactly representable in `f32`.

use sweepslide::Real;
use sweepslide::detect::{Candidate, DetectOptions, Detection, Hit, earliest_hit};
use sweepslide::geom::{Feature, Triangle, Vec3, vec3};

fn v<T: Real>(p: [f64; 3]) -> Vec3<T> {
    vec3(p[0], p[1], p[2])
}

fn tri<T: Real>(p: [[f64; 3]; 3]) -> Triangle<T> {
    Triangle::new(v(p[0]), v(p[1]), v(p[2]))
}

fn sweep<T: Real>(d: Detection, t: [[f64; 3]; 3], base: [f64; 3], vel: [f64; 3]) -> Option<Hit<T>> {
    d.sweep(&Candidate::lone(0, tri::<T>(t)), &v(base), &v(vel), &DetectOptions::default(), None)
}

fn t_of<T: Real>(h: &Option<Hit<T>>) -> Option<f64> {
    h.as_ref().map(|h| h.t.to_f64())
}

/// In the plane z = 0, front face +z; edge 0 is y = -2, x in [-2, 2].
const FACE: [[f64; 3]; 3] = [[-2.0, -2.0, 0.0], [2.0, -2.0, 0.0], [0.0, 2.0, 0.0]];
/// In the plane z = 0; vertex 1 at (2, 0, 0) points towards -x.
const VERTEX: [[f64; 3]; 3] = [[4.0, -2.0, 0.0], [2.0, 0.0, 0.0], [4.0, 2.0, 0.0]];

/// The sphere 3 below the face moving up by 4 touches the back of the face
/// at t = 0.5. Fauerby culls back faces (the motion is not against the
/// normal), so the sphere passes through; robust detection is two-sided.
#[test]
fn fauerby_back_face_culled_sphere_passes_through() {
    let (base, vel) = ([0.0, 0.0, -3.0], [0.0, 0.0, 4.0]);
    assert!(sweep::<f64>(Detection::Fauerby, FACE, base, vel).is_none(), "Fauerby culls the back face");
    let h = sweep::<f64>(Detection::Robust, FACE, base, vel).expect("robust: the back face is solid");
    assert_eq!((h.t, h.feature), (0.5, Feature::Face), "robust: {h:?}");
    assert_eq!(h.normal, v([0.0, 0.0, -1.0]), "robust: normal towards the sphere");
    assert_eq!(h.point, v([0.0, 0.0, 0.0]), "robust: contact point");
}

/// The sphere starts overlapping vertex 1 (centre 0.5 from it) and moves
/// into it. The vertex quadratic's roots are -0.125 and 0.375; Fauerby
/// rejects the negative one and returns the *exit* time 0.375, when the
/// vertex has passed through the sphere: his contact normal (centre minus
/// vertex) then points along the motion, +x, so a response would push the
/// body on through the triangle. The right answer is a hit at t = 0 with
/// the separating normal -x.
#[test]
fn fauerby_overlapping_vertex_returns_exit_time() {
    let (base, vel) = ([1.5, 0.0, 0.0], [4.0, 0.0, 0.0]);
    let f = sweep::<f64>(Detection::Fauerby, VERTEX, base, vel).expect("Fauerby finds the exit root");
    assert_eq!((f.t, f.feature, f.started_overlapping), (0.375, Feature::Vertex(1), false), "Fauerby: {f:?}");
    assert_eq!(f.normal, v([1.0, 0.0, 0.0]), "Fauerby: normal along the motion");
    let r = sweep::<f64>(Detection::Robust, VERTEX, base, vel).expect("robust: immediate hit");
    assert_eq!((r.t, r.feature, r.started_overlapping), (0.0, Feature::Vertex(1), true), "robust: {r:?}");
    assert_eq!(r.normal, v([-1.0, 0.0, 0.0]), "robust: separating normal");
}

/// Overlapping vertex 1 but moving *away* from it: nothing is in the way
/// (the distance to the triangle only grows). Fauerby returns the exit time
/// 0.125 of the vertex quadratic as a hit, stopping a body that is leaving.
#[test]
fn fauerby_leaving_overlapped_vertex_reports_hit() {
    let (base, vel) = ([1.5, 0.0, 0.0], [-4.0, 0.0, 0.0]);
    let f = sweep::<f64>(Detection::Fauerby, VERTEX, base, vel);
    assert_eq!(t_of(&f), Some(0.125), "Fauerby: exit time reported as a hit: {f:?}");
    assert!(sweep::<f64>(Detection::Robust, VERTEX, base, vel).is_none(), "robust: moving away, no hit");
}

/// The sphere exactly touches vertex 1 at the start (centre 1 from it) and
/// moves into it. The vertex quadratic's roots are exactly 0 and 0.5; the
/// root at t = 0 is rejected (`r1 > 0`), so Fauerby returns 0.5, by which
/// time the vertex has travelled through the sphere to its far side (the
/// normal is +x, along the motion).
#[test]
fn fauerby_rejects_touch_at_t_zero() {
    let (base, vel) = ([1.0, 0.0, 0.0], [4.0, 0.0, 0.0]);
    let f = sweep::<f64>(Detection::Fauerby, VERTEX, base, vel).expect("Fauerby finds the other root");
    assert_eq!((f.t, f.feature), (0.5, Feature::Vertex(1)), "Fauerby: {f:?}");
    assert_eq!(f.normal, v([1.0, 0.0, 0.0]), "Fauerby: normal along the motion");
    let r = sweep::<f64>(Detection::Robust, VERTEX, base, vel).expect("robust: touching, approaching");
    assert_eq!((r.t, r.feature, r.started_overlapping), (0.0, Feature::Vertex(1), false), "robust: {r:?}");
    assert_eq!(r.normal, v([-1.0, 0.0, 0.0]), "robust: separating normal");
}

/// The sphere starts overlapping edge 0 (centre 0.5 outside it, in the
/// triangle's plane) and moves across it into the triangle. Fauerby's edge
/// quadratic has roots -0.125 and 0.375 (where the centre leaves the unit
/// cylinder around the edge on the far side): he returns 0.375, with the
/// normal +y along the motion.
#[test]
fn fauerby_overlapping_edge_returns_exit_time() {
    let (base, vel) = ([0.0, -2.5, 0.0], [0.0, 4.0, 0.0]);
    let f = sweep::<f64>(Detection::Fauerby, FACE, base, vel).expect("Fauerby finds the exit root");
    assert_eq!((f.t, f.feature, f.started_overlapping), (0.375, Feature::Edge(0), false), "Fauerby: {f:?}");
    assert_eq!(f.normal, v([0.0, 1.0, 0.0]), "Fauerby: normal along the motion");
    let r = sweep::<f64>(Detection::Robust, FACE, base, vel).expect("robust: immediate hit");
    assert_eq!((r.t, r.feature, r.started_overlapping), (0.0, Feature::Edge(0), true), "robust: {r:?}");
    assert_eq!(r.point, v([0.0, -2.0, 0.0]), "robust: closest point");
    assert_eq!(r.normal, v([0.0, -1.0, 0.0]), "robust: separating normal");
}

/// Embedded 0.5 above the face, moving down. Fauerby's face test takes the
/// point `base - n + t0 vel` with t0 clamped to 0: (0, 0, -0.5), half a unit
/// *below* the triangle, as the contact point (his normal is then right by
/// luck, since the point lies straight below the centre). The robust
/// contact is the closest point (0, 0, 0).
#[test]
fn fauerby_embedded_face_contact_point_off_the_triangle() {
    let (base, vel) = ([0.0, 0.0, 0.5], [0.0, 0.0, -1.0]);
    let f = sweep::<f64>(Detection::Fauerby, FACE, base, vel).expect("Fauerby: face hit at t = 0");
    assert_eq!((f.t, f.feature), (0.0, Feature::Face), "Fauerby: {f:?}");
    assert_eq!(f.point, v([0.0, 0.0, -0.5]), "Fauerby: contact point off the plane");
    let r = sweep::<f64>(Detection::Robust, FACE, base, vel).expect("robust: immediate hit");
    assert_eq!((r.t, r.feature, r.started_overlapping), (0.0, Feature::Face, true), "robust: {r:?}");
    assert_eq!(r.point, v([0.0, 0.0, 0.0]), "robust: contact on the triangle");
}

/// A plate with far vertices: the triangle (-4096,0,0) (4096,0,0)
/// (0,4096,0) approached edge-on, in its own plane, from y = -1.25: the
/// sphere touches edge 0 at t = 0.25 exactly. In f32 Fauerby's edge
/// coefficients (|e|^2 ~ 6.7e7 times |w|^2 ~ 1.7e7, nearly cancelling
/// against (e.w)^2) lose every significant bit and the edge is missed, so
/// the sphere passes into the plate. In f64 the same code finds it.
#[test]
fn fauerby_f32_misses_edge_with_far_vertices() {
    let plate = [[-4096.0, 0.0, 0.0], [4096.0, 0.0, 0.0], [0.0, 4096.0, 0.0]];
    let (base, vel) = ([0.0, -1.25, 0.0], [0.0, 1.0, 0.0]);
    assert!(sweep::<f32>(Detection::Fauerby, plate, base, vel).is_none(), "Fauerby f32 misses the edge");
    assert_eq!(t_of(&sweep::<f64>(Detection::Fauerby, plate, base, vel)), Some(0.25), "Fauerby f64 finds it");
    let r = sweep::<f32>(Detection::Robust, plate, base, vel).expect("robust f32 finds it");
    assert_eq!((r.t, r.feature), (0.25, Feature::Edge(0)), "robust f32: {r:?}");
    assert_eq!(r.point, v([0.0, 0.0, 0.0]), "robust f32: contact point");
}

/// A whole wall missed: the square [-4096, 4096] x [0, 8192] in the plane
/// z = 0, two triangles with far vertices, front face +z. The sphere starts
/// 0.75 above the plane and 0.75 outside the wall's lower edge, and moves by
/// (0, 1, -1), ending with its centre 0.25 *below* the plane, inside the
/// square: it passes through the wall. It first touches the edge when
/// sqrt(2) (0.75 - t) = 1, at t = 0.75 - 1/sqrt 2. Fauerby in f32: the face
/// test only looks at the plane entry point, which lies before t = 0 and
/// outside, and the edge quadratics cancel to noise: no hit on either
/// triangle. The robust variant finds the edge.
#[test]
fn fauerby_f32_misses_whole_wall_with_far_vertices() {
    let wall = [
        [[-4096.0, 0.0, 0.0], [4096.0, 0.0, 0.0], [4096.0, 8192.0, 0.0]],
        [[-4096.0, 0.0, 0.0], [4096.0, 8192.0, 0.0], [-4096.0, 8192.0, 0.0]],
    ];
    let tris: Vec<Candidate<f32>> = (0..2).map(|i| Candidate::lone(i, tri(wall[i as usize]))).collect();
    let (base, vel) = (v::<f32>([0.0, -0.75, 0.75]), v::<f32>([0.0, 1.0, -1.0]));
    let opts = DetectOptions::default();
    let f = earliest_hit(Detection::Fauerby, &tris, &base, &vel, &opts);
    assert!(f.is_none(), "Fauerby f32 misses the whole wall: {f:?}");
    let r = earliest_hit(Detection::Robust, &tris, &base, &vel, &opts).expect("robust f32 hits the wall");
    let exact = 0.75 - std::f64::consts::FRAC_1_SQRT_2;
    assert!((f64::from(r.t) - exact).abs() <= 1e-6, "robust f32: t = {}, exact {exact}", r.t);
    assert_eq!((r.feature, r.triangle), (Feature::Edge(0), 0), "robust f32: {r:?}");
    // The same wall in f64: Fauerby finds it, so it is the precision.
    let tris64: Vec<Candidate<f64>> = (0..2).map(|i| Candidate::lone(i, tri(wall[i as usize]))).collect();
    let f64_hit = earliest_hit(Detection::Fauerby, &tris64, &v([0.0, -0.75, 0.75]), &v([0.0, 1.0, -1.0]), &opts)
        .expect("Fauerby f64 hits the wall");
    assert!((f64_hit.t - exact).abs() <= 1e-12, "Fauerby f64: {f64_hit:?}");
}

/// The plane constant taken from one vertex far from the origin: the
/// slanted triangle (o-8, o-8, o-6) (o+8, o-8, o+6) (o, o+8, o), o = 20000,
/// normal (-0.6, 0, 0.8); the sphere at (o, o, o+3) moving by (0, 0, -8) is
/// 2.4 from the plane and approaches it at 6.4 per unit time, so it touches
/// at t = 1.4 / 6.4 = 7/32 exactly. Fauerby's signed distance in f32
/// subtracts two numbers of magnitude ~1.9e4 (ulp 2^-9 ~ 2e-3): his t is
/// late by ~6e-5, a penetration of ~4e-4 along the normal. The robust test
/// works relative to the centre and is within a few f32 ulps.
#[test]
fn fauerby_f32_plane_constant_far_from_origin_penetrates() {
    let o = 20000.0;
    let slanted = [[o - 8.0, o - 8.0, o - 6.0], [o + 8.0, o - 8.0, o + 6.0], [o, o + 8.0, o]];
    let (base, vel) = ([o, o, o + 3.0], [0.0, 0.0, -8.0]);
    let exact = 7.0 / 32.0;
    let f = t_of(&sweep::<f32>(Detection::Fauerby, slanted, base, vel)).expect("Fauerby f32 hits");
    let depth = (f - exact) * 6.4;
    assert!(depth > 1e-4, "Fauerby f32 stops {depth:e} inside the plane (t = {f})");
    let r = t_of(&sweep::<f32>(Detection::Robust, slanted, base, vel)).expect("robust f32 hits");
    assert!(((r - exact) * 6.4).abs() <= 1e-6, "robust f32: t = {r}, exact {exact}");
    let r64 = t_of(&sweep::<f64>(Detection::Robust, slanted, base, vel)).expect("robust f64 hits");
    assert!(((r64 - exact) * 6.4).abs() <= 1e-14, "robust f64: t = {r64}, exact {exact}");
}

/// Zero velocity: Fauerby normalises it (0/0 = NaN) and relies on NaN
/// failing his front-facing comparison; the robust test needs no special
/// case. Neither may report a hit or produce a NaN, overlapping or not.
#[test]
fn zero_velocity_gives_no_hit_and_no_nan() {
    for base in [[0.0, 0.0, 0.5], [0.0, 0.0, 3.0], [1.5, 0.0, 0.0]] {
        for d in [Detection::Fauerby, Detection::Robust] {
            for t in [FACE, VERTEX] {
                let h = sweep::<f32>(d, t, base, [0.0; 3]);
                assert!(h.is_none(), "{} at {base:?}: {h:?}", d.name());
            }
        }
    }
}
