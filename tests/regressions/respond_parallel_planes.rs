//! Linahan's crease (Table II, line 17: `crease = n1 x n2` normalised, no
//! guard) when the second sliding plane is parallel to the first: the cross
//! product is exactly zero and the crease, hence the position, is NaN. Two
//! ways to get there, both pinned for the faithful baseline, with the robust
//! response asserted correct on the same input:
//!
//! * opposite planes: a slot narrower than `2 + eps` (eps = 5e-5): the first
//!   plane's `1 + eps` projection puts the destination beyond the touching
//!   distance of the opposite wall (ALGORITHMS.md section 8 says "narrower
//!   than 2 + 2 eps"; observed here: NaN for g = 0, 1e-6, 1e-5, finite for
//!   g = 5e-5 and 9e-5, i.e. the threshold is g < eps);
//! * the same plane twice: in `f32` 1e4 from the origin, the near point of
//!   the first hit on the corner's ramp rounds to a position embedded in that
//!   same ramp, so the second check hits it again at t = 0 (first at frame
//!   13 of the corner scene).

use sweepslide::Real;
use sweepslide::geom::{Ellipsoid, Vec3, cross, vec3};
use sweepslide::lab::metrics::{penetration, snag_ratio};
use sweepslide::lab::scenes::{Scene, build};
use sweepslide::respond::{MoveOptions, Response, Trace, move_body};
use sweepslide::world::World;

fn v<T: Real>(p: [f64; 3]) -> Vec3<T> {
    vec3(p[0], p[1], p[2])
}

fn f64s<T: Real>(p: &Vec3<T>) -> [f64; 3] {
    [p[0].to_f64(), p[1].to_f64(), p[2].to_f64()]
}

fn finite<T: Real>(p: &Vec3<T>) -> bool {
    p.iter().all(Real::is_finite)
}

/// Positions (start first), traces and exact penetrations of a run.
type Run<T> = (Vec<Vec3<T>>, Vec<Trace<T>>, Vec<Option<f64>>);

/// Runs up to `frames` frames; stops after the first non-finite position.
fn simulate<T: Real>(s: &Scene, response: Response, frames: usize) -> Run<T> {
    let world = World::<T>::new(s.mesh.clone()).expect("the mesh fits the backend");
    let body = Ellipsoid::<T>::new(s.radii).unwrap();
    let vel = v::<T>(s.velocity);
    let opts = MoveOptions::new(response);
    let mut p = v::<T>(s.start);
    let (mut positions, mut traces, mut pens) = (vec![p.clone()], Vec::new(), Vec::new());
    for k in 0..frames {
        let m =
            move_body(&world, &body, &p, &vel, None, &opts).unwrap_or_else(|e| panic!("{}: frame {k}: {e}", s.name));
        p = m.position;
        pens.push(if finite(&p) { penetration(&world, body.radii(), &p) } else { None });
        positions.push(p.clone());
        traces.push(m.trace);
        if !finite(&p) {
            break;
        }
    }
    (positions, traces, pens)
}

fn assert_robust_correct<T: Real>(s: &Scene, frames: usize, min_snag: Option<f64>) {
    let (positions, traces, pens) = simulate::<T>(s, Response::Robust, frames);
    assert_eq!(traces.len(), frames, "{} robust {}: stopped early (non-finite)", s.name, T::name());
    for (k, pen) in pens.iter().enumerate() {
        let p = f64s(&positions[k + 1]);
        assert!(p.iter().all(|x| x.is_finite()), "{} robust {}: frame {k}: {p:?}", s.name, T::name());
        if let Some(d) = pen {
            assert!(*d <= 0.0, "{} robust {}: frame {k}: penetration {d:e} at {p:?}", s.name, T::name());
        }
    }
    if let Some(min) = min_snag {
        let snag = snag_ratio(&positions[0], positions.last().unwrap(), s.ideal.unwrap(), frames).unwrap();
        assert!(snag >= min, "{} robust {}: slide ratio {snag}", s.name, T::name());
    }
}

fn linahan_nan_in_slot<T: Real>(g: &str) {
    let s = build(&format!("slot:{g}"), 1).unwrap();
    let (positions, traces, _) = simulate::<T>(&s, Response::Linahan, 1);
    let t = &traces[0];
    assert!(!finite(&positions[1]), "{} linahan {}: expected NaN, got {:?}", s.name, T::name(), f64s(&positions[1]));
    assert!(t.contacts.len() >= 2, "{} linahan {}: {} contacts", s.name, T::name(), t.contacts.len());
    let (n1, n2) = (&t.contacts[0].plane_normal, &t.contacts[1].plane_normal);
    // The walls are x = -(1 + g/2) and x = 1 + g/2: the body (moving +x)
    // meets the right wall first, then the left one.
    assert_eq!(f64s(n1), [-1.0, 0.0, 0.0], "{} linahan {}", s.name, T::name());
    assert_eq!(f64s(n2), [1.0, 0.0, 0.0], "{} linahan {}", s.name, T::name());
    assert_eq!(f64s(&cross(n1, n2)), [0.0; 3], "{} linahan {}: the crease is 0 / 0", s.name, T::name());
    assert_robust_correct::<T>(&s, 50, Some(0.99));
}

fn slot_opposite_planes<T: Real>() {
    for g in ["0", "0.000001", "0.00001"] {
        linahan_nan_in_slot::<T>(g);
    }
    // Just wider than 2 + eps: the projected destination stays clear of
    // the opposite wall and Linahan slides.
    for g in ["0.00005", "0.00009"] {
        let s = build(&format!("slot:{g}"), 1).unwrap();
        let (positions, _, pens) = simulate::<T>(&s, Response::Linahan, 50);
        assert!(positions.iter().all(finite), "{} linahan {}", s.name, T::name());
        assert!(pens.iter().flatten().all(|d| *d <= 0.0), "{} linahan {}", s.name, T::name());
    }
}

#[test]
fn linahan_crease_nan_for_opposite_planes_in_narrow_slot_f32() {
    slot_opposite_planes::<f32>();
}

#[test]
fn linahan_crease_nan_for_opposite_planes_in_narrow_slot_f64() {
    slot_opposite_planes::<f64>();
}

/// The corner scene 1e4 from the origin, f32: Linahan's frame 13 hits the
/// ramp (triangle 3) at t = 0.0046, then the same triangle again at t = 0,
/// overlapping; equal normals, zero cross product, NaN position. Robust on
/// the same scene: finite, never inside, at rest in the corner.
#[test]
fn linahan_crease_nan_for_same_plane_hit_twice_f32_far_from_origin() {
    let s = build("corner", 1).unwrap().offset([1e4, 0.0, 1e4], true).unwrap();
    let (positions, traces, _) = simulate::<f32>(&s, Response::Linahan, s.frames);
    let k = traces.len() - 1;
    assert!(!finite(&positions[k + 1]), "{}: Linahan stayed finite for {} frames", s.name, s.frames);
    assert!(k < 50, "{}: NaN came late, at frame {k} (was 13)", s.name);
    let t = &traces[k];
    assert!(t.contacts.len() >= 2, "frame {k}: {} contacts", t.contacts.len());
    let (c1, c2) = (&t.contacts[0], &t.contacts[1]);
    assert_eq!(c1.hit.triangle, c2.hit.triangle, "frame {k}: the same triangle twice");
    assert_eq!(f64s(&c1.plane_normal), f64s(&c2.plane_normal), "frame {k}: the same plane twice");
    assert!(c2.hit.started_overlapping && c2.hit.t == 0.0, "frame {k}: second hit at t = 0, overlapping: {:?}", c2.hit);
    assert_eq!(f64s(&cross(&c1.plane_normal, &c2.plane_normal)), [0.0; 3], "frame {k}");

    assert_robust_correct::<f32>(&s, s.frames, None);
    let (positions, _, _) = simulate::<f32>(&s, Response::Robust, s.frames);
    let n = positions.len();
    assert_eq!(f64s(&positions[n - 1]), f64s(&positions[n - 2]), "{}: robust rests in the corner", s.name);
}
