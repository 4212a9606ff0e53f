//! The fuzz targets' invariants (`fuzz/`, see `docs/fuzzing.md`) as
//! proptest properties, so that plain `cargo test` checks them too.
//!
//! The invariants and their exact MPFR oracles are not copied: this file
//! includes `fuzz/src/oracle.rs`, the module the fuzz targets assert with.
//! Only the input generators differ (proptest strategies here, `arbitrary`
//! decoders there).
//!
//! * `robust_sweep_*` (target `sweep_triangle`): the robust sweep of one
//!   triangle gives `t` in `[0, 1]`, touches at `t` (the exact distance is
//!   1 within the bound), enters nothing before, and agrees with
//!   `Mpfr<256>` on the same rounded input; `robust_sweep_grazing_face_*`
//!   and `robust_sweep_grazing_edge_*` aim at two regimes directly (a
//!   sphere gliding along a plane onto the face near a side, F16 and F17,
//!   and `robust_sweep_grazing_large_face_*` onto faces of 10 to `3e4`
//!   radii, whose plane distance is rounded by their far vertices, F38;
//!   gliding along an edge and entering it within rounding of an end,
//!   F19), which the random directions of the others rarely reach and the
//!   fuzzer's decoder reached for the face only;
//!   `robust_sweep_overlapping_edge_*` at a third (a centre within `10^-k`
//!   of an edge, moving along it, F21).
//! * `robust_moves_*` (target `move_robust`): the robust response never
//!   produces a NaN, never exceeds its iteration bound and never ends a
//!   frame penetrating (exact check), from a start outside the geometry;
//!   `robust_moves_beside_a_fold_hinge_*` aim at a body touching the hinge
//!   of a closed or nearly closed fold from beside it, in the sheets'
//!   plane (F20), which the random soups of the others do not build.
//! * `obj_parser_*` (target `obj_parse`): OBJ text, random or built from
//!   OBJ-like lines, gives an error or a valid mesh, never a panic.
//!
//! Ranges: the sweeps keep the relative magnitude `s` (start to triangle,
//! velocity, in radii) below about 30 (the large faces' up to about
//! `1e5`); the soups are lone triangles and folds (no slots, no
//! coincident layers) and the displacements stay below 0.02 radii per
//! pass. The fuzz targets cover the whole documented range;
//! the regimes left out here are those of the first campaign's findings
//! (docs/fuzzing.md, "Notes per finding": F1, vertex and edge entry times
//! losing accuracy like `u s^2`, F2, slides leaving the frame's candidate
//! box, and F4, coincident layers, all fixed since; F3, slots narrower
//! than the padding, outside the documented range), so that `make test`
//! stays a check of what is meant to hold; the fuzz targets and
//! `tests/regressions/` cover the fixed regimes at their full range.
#![cfg(all(feature = "mpfr", feature = "lab"))]

#[allow(dead_code)]
#[path = "../fuzz/src/oracle.rs"]
mod oracle;

use oracle::{FrameInput, MoveCase, Skip, check_robust_moves, check_sweep};
use proptest::prelude::*;
use std::f64::consts::PI;
use std::path::Path;
use sweepslide::Real;
use sweepslide::world::{TriangleMesh, parse_obj};

type V = [f64; 3];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn mul(a: V, s: f64) -> V {
    a.map(|x| x * s)
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V, b: V) -> V {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn unit(a: V) -> V {
    let l = dot(a, a).sqrt();
    if l > 1e-12 { mul(a, 1.0 / l) } else { [0.0, 0.0, 1.0] }
}

/// Two unit vectors completing the unit `n` to an orthonormal frame.
fn frame(n: V) -> (V, V) {
    let helper = if n[0].abs() < 0.6 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] };
    let u = unit(cross(n, helper));
    (u, cross(n, u))
}

/// A unit vector from two angles in `[0, 1)`.
fn direction(a: f64, b: f64) -> V {
    let (theta, phi) = ((1.0 - 2.0 * a).acos(), 2.0 * PI * b);
    [theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin()]
}

// ------------------------------------------------------------ strategies --

/// A triangle of size `10^log_size` around the origin in the plane of a
/// random unit normal: well shaped (angles above about 15 degrees) or a
/// sliver of height `2 * 10^-k` over a base of 2 (shape factor up to about
/// 1000, the sweep checks' range).
fn triangle(log_size: std::ops::Range<f64>) -> impl Strategy<Value = [V; 3]> {
    (
        (0.0..1.0f64, 0.0..1.0f64, 0.0..6.3f64),
        prop::array::uniform3(0.3..2.5f64),
        prop::array::uniform3(-0.5..0.5f64),
        prop_oneof![3 => Just(None), 1 => (0.0..2.9f64, -0.5..1.5f64).prop_map(Some)],
        log_size,
    )
        .prop_map(|((a, b, spin), radii, jitter, sliver, log_size)| {
            let n = direction(a, b);
            let (u0, w0) = frame(n);
            let (s, c) = spin.sin_cos();
            let (u, w) = (add(mul(u0, c), mul(w0, s)), add(mul(w0, c), mul(u0, -s)));
            let size = 10f64.powf(log_size);
            let pts: [[f64; 2]; 3] = match sliver {
                None => std::array::from_fn(|i| {
                    let ang = i as f64 * 2.0 * PI / 3.0 + jitter[i];
                    [radii[i] * ang.cos(), radii[i] * ang.sin()]
                }),
                Some((k, x)) => [[-1.0, 0.0], [1.0, 0.0], [2.0 * x - 1.0, 2.0 * 10f64.powf(-k)]],
            };
            pts.map(|[x, y]| add(mul(u, x * size), mul(w, y * size)))
        })
}

/// A signed small distance beyond touching: exact, a few `f32` or `f64`
/// ulps, a power of ten, or a fraction.
fn gap() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        (-64i32..64).prop_map(|k| f64::from(k) * 2f64.powi(-24)),
        (-64i32..64).prop_map(|k| f64::from(k) * 2f64.powi(-53)),
        (1i32..15, any::<bool>()).prop_map(|(e, neg)| if neg { -(10f64.powi(-e)) } else { 10f64.powi(-e) }),
        -0.5..0.5f64,
    ]
}

/// `(base, vel, tri)`: the unit sphere at `1 + gap` from a point of the
/// triangle (face, edge or vertex) at time `tau`, moving at an angle from
/// head-on (exactly grazing included), the whole case moved by `offset`.
fn sweep_case(offsets: Vec<f64>) -> impl Strategy<Value = (V, V, [V; 3])> {
    (
        triangle(SMALL),
        (0usize..3, 0.0..1.0f64, 0.0..1.0f64, prop::sample::select(vec![0u8, 1, 2])),
        (0.0..1.0f64, 0.0..1.0f64),
        gap(),
        prop_oneof![Just(0.0), Just(PI / 2.0), 0.0..PI / 2.0, (1i32..12).prop_map(|k| PI / 2.0 - 10f64.powi(-k))],
        (0.0..6.3f64, -0.2..1.2f64, -3.0..1.0f64),
        (prop::sample::select(offsets), 0.0..1.0f64, 0.0..1.0f64),
    )
        .prop_map(|(tri, (edge, s, t, kind), (ca, cb), gap, phi, (heading, tau, log_speed), (off, oa, ob))| {
            // The aimed point: on the face, an edge or a vertex.
            let (a, b) = (tri[edge], tri[(edge + 1) % 3]);
            let point = match kind {
                0 => {
                    let (s, t) = if s + t > 1.0 { (1.0 - s, 1.0 - t) } else { (s, t) };
                    add(tri[0], add(mul(sub(tri[1], tri[0]), s), mul(sub(tri[2], tri[0]), t)))
                }
                1 => add(a, mul(sub(b, a), s)),
                _ => a,
            };
            let c = direction(ca, cb);
            let centre = add(point, mul(c, 1.0 + gap));
            let (u, w) = frame(c);
            let side = add(mul(u, heading.cos()), mul(w, heading.sin()));
            let dir = add(mul(c, -phi.cos()), mul(side, phi.sin()));
            let vel = mul(dir, 10f64.powf(log_speed));
            let o = mul(direction(oa, ob), off);
            (add(sub(centre, mul(vel, tau)), o), vel, tri.map(|p| add(p, o)))
        })
}

/// `(base, vel, tri)`: the unit sphere gliding almost parallel to an edge
/// (speed along it `10^a`, approach a fraction `10^-b` of that, `b` from 2
/// to 9) from any side of the edge outside the triangle, entering the
/// edge's unit cylinder at time `tau` at a point `10^-k` edge lengths from
/// an end, just on the edge or just beyond it, moving along the edge either
/// way (fuzz finding F19: the entry time is accurate in distance but not
/// along the edge, and an entry on the edge computed beyond its end let the
/// sphere sink into the edge unseen).
fn grazing_edge_case() -> impl Strategy<Value = (V, V, [V; 3])> {
    (
        triangle(SMALL),
        (0usize..3, any::<bool>(), any::<bool>()),
        (1i32..14, any::<bool>()),
        -1.0..1.0f64,
        (-1.0..1.5f64, 2.0..9.0f64, 0.1..0.9f64),
    )
        .prop_map(|(tri, (edge, far_end, forward), (k, on_edge), phi, (log_speed, log_ratio, tau))| {
            let (a, b, third) = (tri[edge], tri[(edge + 1) % 3], tri[(edge + 2) % 3]);
            let (end, other) = if far_end { (b, a) } else { (a, b) };
            let length = dot(sub(other, end), sub(other, end)).sqrt();
            let along = unit(sub(other, end));
            let n = unit(cross(sub(b, a), sub(third, a)));
            // Away from the triangle: the in-plane normal pointing away from
            // the third vertex, turned about the edge by up to 90 degrees.
            let mut out = unit(cross(along, n));
            if dot(out, sub(third, end)) > 0.0 {
                out = mul(out, -1.0);
            }
            let angle = phi * PI / 2.0 * 0.999;
            let w = add(mul(out, angle.cos()), mul(n, angle.sin()));
            let offset = 10f64.powi(-k) * length * if on_edge { 1.0 } else { -1.0 };
            let entry = add(end, add(mul(along, offset), w));
            let speed = 10f64.powf(log_speed);
            let glide = mul(along, if forward { speed } else { -speed });
            let vel = sub(glide, mul(w, speed * 10f64.powf(-log_ratio)));
            (sub(entry, mul(vel, tau)), vel, tri)
        })
}

/// `(base, vel, tri)`: the unit sphere centred `10^-k` (`k` from 1 to 15)
/// from a point of a triangle's edge, in any direction around it (over the
/// face, beside it, under it), moving along the edge with a small part
/// (`10^-b` of its speed, `b` from 0 to 12) towards or away from the edge,
/// or none (fuzz finding F21: overlapping by almost its radius, the
/// edge's direction is off by `u |from| / dist`, and the motion along the
/// edge carried that error into the decision whether it approaches).
fn overlapping_edge_case() -> impl Strategy<Value = (V, V, [V; 3])> {
    (
        triangle(SMALL),
        (0usize..3, 0.05..0.95f64),
        (1i32..16, 0.0..2.0 * PI),
        (-1.0..1.5f64, prop_oneof![Just(None), (0.0..12.0f64, any::<bool>()).prop_map(Some)], any::<bool>()),
    )
        .prop_map(|(tri, (edge, at), (k, around), (log_speed, across, forward))| {
            let (a, b, third) = (tri[edge], tri[(edge + 1) % 3], tri[(edge + 2) % 3]);
            let along = unit(sub(b, a));
            let n = unit(cross(sub(b, a), sub(third, a)));
            let out = unit(cross(along, n));
            let w = add(mul(out, around.cos()), mul(n, around.sin()));
            let base = add(add(a, mul(sub(b, a), at)), mul(w, 10f64.powi(-k)));
            let speed = 10f64.powf(log_speed);
            let glide = mul(along, if forward { speed } else { -speed });
            let vel = match across {
                None => glide,
                Some((b, towards)) => sub(glide, mul(w, speed * 10f64.powf(-b) * if towards { 1.0 } else { -1.0 })),
            };
            (base, vel, tri)
        })
}

/// `(base, vel, tri)`: the unit sphere gliding almost parallel to a
/// triangle's plane (approach a fraction `10^-b` of its speed, `b` from 2
/// to 12) and reaching distance 1 from the plane at time `tau` at a point
/// `10^-k` edge lengths from a side, inside the triangle or outside,
/// heading in any direction along the plane (fuzz findings F16 and F17:
/// the plane's time is accurate in distance but not along the track, and
/// a contact point on the face computed outside it let the sphere reach a
/// later feature too deep).
fn grazing_face_case(log_size: std::ops::Range<f64>) -> impl Strategy<Value = (V, V, [V; 3])> {
    (
        triangle(log_size),
        (0usize..3, 0.0..1.0f64, any::<bool>()),
        (1i32..14, any::<bool>()),
        0.0..2.0 * PI,
        (-1.0..1.5f64, 2.0..12.0f64, 0.1..0.9f64),
    )
        .prop_map(|(tri, (edge, along, upper), (k, inside), heading, (log_speed, log_ratio, tau))| {
            let (a, b, third) = (tri[edge], tri[(edge + 1) % 3], tri[(edge + 2) % 3]);
            let n = unit(cross(sub(b, a), sub(third, a)));
            let n = if upper { n } else { mul(n, -1.0) };
            let side = sub(b, a);
            let length = dot(side, side).sqrt();
            // The in-plane normal to the side pointing into the triangle.
            let mut into = unit(cross(n, side));
            if dot(into, sub(third, a)) < 0.0 {
                into = mul(into, -1.0);
            }
            let offset = 10f64.powi(-k) * length * if inside { 1.0 } else { -1.0 };
            let point = add(add(a, mul(side, along)), mul(into, offset));
            let (u, w) = frame(n);
            let glide = mul(add(mul(u, heading.cos()), mul(w, heading.sin())), 10f64.powf(log_speed));
            let vel = sub(glide, mul(n, 10f64.powf(log_speed - log_ratio)));
            let centre = add(point, n);
            (sub(centre, mul(vel, tau)), vel, tri)
        })
}

fn assert_sweep<T: Real>(base: V, vel: V, tri: [V; 3]) -> Result<(), TestCaseError> {
    match check_sweep::<T>(base, vel, tri) {
        Ok(_) => Ok(()),
        Err(e) => Err(TestCaseError::fail(e)),
    }
}

/// A soup piece in units of the body's largest radius `r`: a lone
/// triangle, or a fold (two quads hinged on a common edge, dihedral angle
/// from razor-thin to nearly flat).
fn piece() -> impl Strategy<Value = Vec<[V; 3]>> {
    prop_oneof![
        (triangle(SMALL), prop::array::uniform3(-3.0..3.0f64)).prop_map(|(t, at)| vec![t.map(|p| add(p, at))]),
        (
            (0.0..1.0f64, 0.0..1.0f64, 0.0..6.3f64),
            prop_oneof![
                0.05..6.23f64,
                (1i32..12, any::<bool>()).prop_map(|(k, s)| PI + if s { 1.0 } else { -1.0 } * 10f64.powi(-k))
            ],
            1.0..8.0f64,
            prop::array::uniform3(-3.0..3.0f64),
            any::<bool>(),
        )
            .prop_map(|((a, b, spin), angle, size, at, diagonal)| {
                let e = direction(a, b);
                let (u0, w0) = frame(e);
                let u = add(mul(u0, spin.cos()), mul(w0, spin.sin()));
                let w = add(mul(u, angle.cos()), mul(cross(e, u), angle.sin()));
                let p = sub(at, mul(e, size));
                let e2 = mul(e, 2.0 * size);
                let quad = |p: V, a: V, b: V, d: bool| {
                    let (q, r, s) = (add(p, a), add(add(p, a), b), add(p, b));
                    if d { vec![[p, q, r], [p, r, s]] } else { vec![[p, q, s], [q, r, s]] }
                };
                let mut t = quad(p, e2, mul(u, size), diagonal);
                t.extend(quad(p, e2, mul(w, size), !diagonal));
                t
            }),
    ]
}

/// A move scenario: radii, a soup of 1 to 4 pieces, a start, 1 to 6
/// frames with an optional gravity, moved by `offset`. The body starts
/// beside a point of one of the triangles, `1 + 10^-k` radii away along its
/// normal or a random direction (`k` from 0 to 8), and moves `10^-3` to 3 radii per
/// pass, so most cases meet the geometry (a review found the first version,
/// which started anywhere in a box of 8 radii and moved at most 0.02,
/// meeting nothing in 600 sampled cases:
/// `move_cases_meet_the_geometry` now guards that).
fn move_case(offsets: Vec<f64>) -> impl Strategy<Value = MoveCase> {
    (
        (-2.0..2.0f64, prop::array::uniform2(-2.0..2.0f64), any::<bool>()),
        prop::collection::vec(piece(), 1..4),
        ((0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64), (0.0..1.0f64, 0.0..1.0f64, any::<bool>()), 0i32..9),
        prop::collection::vec((0.0..1.0f64, 0.0..1.0f64, -3.0..0.5f64), 1..6),
        prop_oneof![Just(None), (-3.0..-1.7f64).prop_map(Some)],
        (prop::sample::select(offsets), 0.0..1.0f64, 0.0..1.0f64),
    )
        .prop_map(
            |(
                (log_r, ratios, ellipsoid),
                pieces,
                ((which, s, t), (da, db, normal), k),
                pushes,
                gravity,
                (off, oa, ob),
            )| {
                let r = 10f64.powf(log_r);
                let radii = if ellipsoid { [r, r * 2f64.powf(ratios[0]), r * 2f64.powf(ratios[1])] } else { [r; 3] };
                let big = radii.iter().copied().fold(0.0, f64::max);
                let o = mul(direction(oa, ob), off);
                let place = |p: V| add(mul(p, big), o);
                let soup: Vec<[V; 3]> = pieces.into_iter().flatten().collect();
                // A point of one triangle (`s`, `t` folded into it), then
                // `1 + 10^-k` away in units of the largest radius.
                let tri = soup[((which * soup.len() as f64) as usize).min(soup.len() - 1)];
                let (s, t) = if s + t > 1.0 { (1.0 - s, 1.0 - t) } else { (s, t) };
                let point = add(tri[0], add(mul(sub(tri[1], tri[0]), s), mul(sub(tri[2], tri[0]), t)));
                // Along the triangle's normal (either side: touching its
                // face there) or any way (often inside another part of it).
                let away = if normal {
                    mul(unit(cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]))), if da < 0.5 { 1.0 } else { -1.0 })
                } else {
                    direction(da, db)
                };
                let start = add(point, mul(away, 1.0 + 10f64.powi(-k)));
                let triangles = soup.into_iter().map(|t| t.map(place)).collect();
                let gravity = gravity.map(|g: f64| [0.0, -(10f64.powf(g)) * big, 0.0]);
                let frames = pushes
                    .into_iter()
                    .map(|(a, b, log_speed)| FrameInput {
                        velocity: mul(direction(a, b), 10f64.powf(log_speed) * big),
                        gravity,
                    })
                    .collect();
                MoveCase { triangles, radii, start: place(start), frames }
            },
        )
}

/// The share of `cases` sampled from `strategy` (a fixed seed) in which
/// the robust response met a contact or pushed the body out in some frame,
/// in `T`: a guard that a generator reaches the geometry.
fn meeting_share<T: Real>(strategy: impl Strategy<Value = MoveCase>, cases: usize) -> f64 {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    use sweepslide::geom::{Ellipsoid, vec3};
    use sweepslide::respond::{MoveOptions, Response, move_body};
    let mut runner = TestRunner::deterministic();
    let mut met = 0;
    for _ in 0..cases {
        let case = strategy.new_tree(&mut runner).expect("a case").current();
        let vertices = case.triangles.iter().flatten().copied().collect();
        let indices = (0..case.triangles.len() as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
        let Ok(mesh) = TriangleMesh::new_skipping_invalid(vertices, indices) else { continue };
        let (Ok(world), Ok(body)) = (sweepslide::world::World::<T>::new(mesh.into()), Ellipsoid::<T>::new(case.radii))
        else {
            continue;
        };
        let v = |p: [f64; 3]| vec3::<T>(p[0], p[1], p[2]);
        let mut p = v(case.start);
        for f in &case.frames {
            let gravity = f.gravity.map(v);
            let Ok(m) =
                move_body(&world, &body, &p, &v(f.velocity), gravity.as_ref(), &MoveOptions::new(Response::Robust))
            else {
                break;
            };
            if !m.trace.contacts.is_empty() || m.trace.depenetration > 0.0 {
                met += 1;
                break;
            }
            p = m.position;
        }
    }
    met as f64 / cases as f64
}

/// The move generators reach the geometry: most of their cases meet a
/// triangle (the first `move_case` met none in 600 samples).
#[test]
fn move_cases_meet_the_geometry() {
    let f32_share = meeting_share::<f32>(move_case(vec![NEAR, 1.0e3, 3.0e4]), 400);
    let f64_share = meeting_share::<f64>(move_case(vec![NEAR, 1.0e5]), 400);
    assert!(f32_share > 0.5 && f64_share > 0.5, "shares meeting the geometry: f32 {f32_share}, f64 {f64_share}");
}

/// A body beside the hinge of a fold closed or nearly closed (the two
/// sheets within `10^-3` to `10^-14` radians of each other, or exactly on
/// each other) or open by up to 0.15 radians, in (or within `10^-8` of)
/// the plane of the sheets and touching the hinge (gap 0 or `10^-k`),
/// pushed along the hinge, towards it or anywhere, for four frames
/// (fuzz finding F20: one triangle of such a hinge sees it concave, from
/// the fold's inside, and its contact used to take the face normal there).
/// Sheets `10` to `10^4` radii long, each quad wound either way, built in
/// eSpace and mapped to the body's radii.
fn hinge_case(offsets: Vec<f64>) -> impl Strategy<Value = MoveCase> {
    (
        ((0.0..1.0f64, 0.0..1.0f64), (0.0..1.0f64, 0.0..1.0f64)),
        prop_oneof![
            Just(0.0),
            (3i32..15, any::<bool>()).prop_map(|(k, s)| if s { 1.0 } else { -1.0 } * 10f64.powi(-k)),
            -0.15..0.15f64,
        ],
        (1.0..4.0f64, 1.0..4.0f64, any::<bool>(), any::<bool>()),
        (prop_oneof![Just([1.0; 3]), prop::array::uniform3(-1.5..1.5f64).prop_map(|l| l.map(f64::exp2))], -0.4..0.4f64),
        (
            prop_oneof![Just(0.0), (8i32..16, -0.5..0.5f64).prop_map(|(k, x)| x * 10f64.powi(-k))],
            prop_oneof![Just(0.0), (2i32..15).prop_map(|k| 10f64.powi(-k))],
        ),
        (0u8..3, (0.0..1.0f64, 0.0..1.0f64), -2.0..1.0f64, any::<bool>()),
        (prop::sample::select(offsets), 0.0..1.0f64, 0.0..1.0f64),
    )
        .prop_map(
            |((ha, sa), phi, (log_size, width, flip1, flip2), (radii, along), (theta, gap), push, (off, oa, ob))| {
                let h = direction(ha.0, ha.1);
                let (u0, w0) = frame(h);
                let s = unit(add(mul(u0, sa.0 - 0.5), mul(w0, sa.1 - 0.5)));
                let n = cross(h, s);
                let s2 = add(mul(s, phi.cos()), mul(n, phi.sin()));
                let (lh, w) = (10f64.powf(log_size), 10f64.powf(log_size) * width / 2.0);
                let p0 = mul(h, -0.5 * lh);
                let quad = |d: V, flip: bool| {
                    let (a, b, c, e) =
                        (p0, add(p0, mul(h, lh)), add(add(p0, mul(h, lh)), mul(d, w)), add(p0, mul(d, w)));
                    if flip { vec![[a, c, b], [a, e, c]] } else { vec![[a, b, c], [a, c, e]] }
                };
                let mut soup = quad(s, flip1);
                soup.extend(quad(s2, flip2));
                let out = add(mul(s, -theta.cos()), mul(n, theta.sin()));
                let centre = add(mul(h, along * lh), mul(out, 1.0 + gap));
                let (kind, (da, db), log_speed, back) = push;
                let dir = match kind {
                    0 => mul(h, if back { -1.0 } else { 1.0 }),
                    1 => unit(add(mul(out, -1.0), mul(direction(da, db), 0.5))),
                    _ => direction(da, db),
                };
                let o = mul(direction(oa, ob), off);
                let world = |p: V| add([p[0] * radii[0], p[1] * radii[1], p[2] * radii[2]], o);
                let v = mul(dir, 10f64.powf(log_speed));
                let velocity = [v[0] * radii[0], v[1] * radii[1], v[2] * radii[2]];
                MoveCase {
                    triangles: soup.into_iter().map(|t| t.map(world)).collect(),
                    radii,
                    start: world(centre),
                    frames: vec![FrameInput { velocity, gravity: None }; 4],
                }
            },
        )
}

fn assert_moves<T: Real>(case: &MoveCase) -> Result<(), TestCaseError> {
    match check_robust_moves::<T>(case) {
        Ok(Ok(()) | Err(Skip::StartsInside | Skip::PaddingCap)) => Ok(()),
        Ok(Err(skip)) => Err(TestCaseError::fail(format!("generator left the range: {skip:?} for {case:?}"))),
        Err(e) => Err(TestCaseError::fail(e)),
    }
}

/// One OBJ-like line: vertices (plain, weighted, short, odd numbers),
/// faces (every index form, negative and out-of-range indices), other
/// statements, comments, garbage.
fn obj_line() -> impl Strategy<Value = String> {
    let num = prop_oneof![
        (-20i32..20).prop_map(|k| k.to_string()),
        (-1e6..1e6f64).prop_map(|x| x.to_string()),
        Just("1e309".to_string()),
        Just("nan".to_string()),
        Just("-0".to_string()),
        "[0-9.eE+-]{1,8}",
    ];
    let corner = (-12i32..12, 0u8..5).prop_map(|(i, form)| match form {
        0 => format!("{i}"),
        1 => format!("{i}/1"),
        2 => format!("{i}//2"),
        3 => format!("{i}/1/2"),
        _ => format!("{i}/"),
    });
    prop_oneof![
        6 => prop::collection::vec(num, 2..5).prop_map(|c| format!("v {}", c.join(" "))),
        6 => prop::collection::vec(corner, 0..6).prop_map(|c| format!("f {}", c.join(" "))),
        1 => prop::sample::select(vec!["vt 0 1", "vn 0 1 0", "o a", "g b", "s 1", "usemtl m", "l 1 2", "p 1", "# c", ""])
            .prop_map(str::to_string),
        1 => "\\PC{0,20}",
    ]
}

fn check_obj(text: &str) -> Result<(), TestCaseError> {
    let path = Path::new("prop.obj");
    let parsed = parse_obj(text, path);
    match TriangleMesh::from_obj_str(text, path) {
        Err(_) => Ok(()),
        Ok(mesh) => {
            let data = parsed.map_err(|e| TestCaseError::fail(format!("mesh from text parse_obj rejects: {e}")))?;
            prop_assert!(!mesh.is_empty());
            prop_assert_eq!(mesh.len() + mesh.skipped().len(), data.triangles.len(), "a triangle dropped silently");
            for t in 0..mesh.len() as u32 {
                prop_assert!(mesh.triangle(t).validate(t as usize).is_ok(), "kept triangle {} is invalid", t);
            }
            Ok(())
        }
    }
}

const NEAR: f64 = 0.0;

/// Triangle sizes from `1e-3` to 10 radii (`triangle`'s `log_size`).
const SMALL: std::ops::Range<f64> = -3.0..1.0;

proptest! {
    #![proptest_config(ProptestConfig { cases: 1500, ..ProptestConfig::default() })]

    #[test]
    fn robust_sweep_f32((base, vel, tri) in sweep_case(vec![NEAR, 30.0, 1.0e3, 1.0e5])) {
        assert_sweep::<f32>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_f64((base, vel, tri) in sweep_case(vec![NEAR, 30.0, 1.0e3, 1.0e5])) {
        assert_sweep::<f64>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_grazing_face_f32((base, vel, tri) in grazing_face_case(SMALL)) {
        assert_sweep::<f32>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_grazing_face_f64((base, vel, tri) in grazing_face_case(SMALL)) {
        assert_sweep::<f64>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_grazing_large_face_f32((base, vel, tri) in grazing_face_case(1.0..4.5)) {
        assert_sweep::<f32>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_grazing_large_face_f64((base, vel, tri) in grazing_face_case(1.0..4.5)) {
        assert_sweep::<f64>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_grazing_edge_f32((base, vel, tri) in grazing_edge_case()) {
        assert_sweep::<f32>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_grazing_edge_f64((base, vel, tri) in grazing_edge_case()) {
        assert_sweep::<f64>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_overlapping_edge_f32((base, vel, tri) in overlapping_edge_case()) {
        assert_sweep::<f32>(base, vel, tri)?;
    }

    #[test]
    fn robust_sweep_overlapping_edge_f64((base, vel, tri) in overlapping_edge_case()) {
        assert_sweep::<f64>(base, vel, tri)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    #[test]
    fn robust_moves_f32(case in move_case(vec![NEAR, 1.0e3, 3.0e4])) {
        assert_moves::<f32>(&case)?;
    }

    #[test]
    fn robust_moves_f64(case in move_case(vec![NEAR, 1.0e5])) {
        assert_moves::<f64>(&case)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 20000, ..ProptestConfig::default() })]

    #[test]
    fn robust_moves_beside_a_fold_hinge_f32(case in hinge_case(vec![NEAR, 1.0e3, 3.0e4])) {
        assert_moves::<f32>(&case)?;
    }

    #[test]
    fn robust_moves_beside_a_fold_hinge_f64(case in hinge_case(vec![NEAR, 1.0e5])) {
        assert_moves::<f64>(&case)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn obj_parser_random_text(text in "\\PC{0,200}") {
        check_obj(&text)?;
    }

    #[test]
    fn obj_parser_obj_like_lines(lines in prop::collection::vec(obj_line(), 0..24), crlf in any::<bool>()) {
        check_obj(&lines.join(if crlf { "\r\n" } else { "\n" }))?;
    }
}
