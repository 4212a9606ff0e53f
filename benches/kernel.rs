//! The cost of genericity and of precision on two small kernels.
//!
//! * `plane_distance`: the signed distance of a point to a triangle's plane
//!   through the crate's generic code (`Plane::<T>::from_triangle` then
//!   `signed_distance`: two edge vectors, a cross product, a normalisation,
//!   two dot products), against the same operations written by hand for
//!   plain `f64` in the same order.
//! * `det3`: a 3x3 determinant `a . (b x c)` written once over `T: Real`,
//!   against the same expression for plain `f64`.
//!
//! Each runs over a batch of 1024 inputs. `generic_f64 / hand_f64` is the
//! price of the abstraction (ideally 1); `generic_f32` and `generic_mpfr53`
//! against `generic_f64` are the price of precision. Before timing, the
//! generic and hand-written `f64` results are checked to be bit-identical,
//! which confirms the two use the same operation order.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use sweepslide::Real;
use sweepslide::geom::{Plane, Triangle, Vec3, cross, dot, vec3};

const BATCH: usize = 1024;

/// Deterministic inputs (SplitMix64): coordinates in `[-8, 8)`.
fn inputs() -> Vec<[[f64; 3]; 4]> {
    let mut state = 0x6b65_726e_656cu64;
    let mut next = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 * (-49f64).exp2() - 8.0
    };
    (0..BATCH).map(|_| std::array::from_fn(|_| std::array::from_fn(|_| next()))).collect()
}

/// The inputs converted into backend `T` (outside the timed loop).
fn convert<T: Real>(raw: &[[[f64; 3]; 4]]) -> Vec<(Triangle<T>, Vec3<T>)> {
    let v = |p: &[f64; 3]| vec3::<T>(p[0], p[1], p[2]);
    raw.iter().map(|[a, b, c, p]| (Triangle::new(v(a), v(b), v(c)), v(p))).collect()
}

// ---------------------------------------------------------------------------
// Kernel 1: signed distance to a triangle's plane
// ---------------------------------------------------------------------------

fn plane_distance_generic<T: Real>(batch: &[(Triangle<T>, Vec3<T>)]) -> T {
    let mut sum = T::zero();
    for (tri, p) in batch {
        if let Some(plane) = Plane::from_triangle(tri) {
            sum += plane.signed_distance(p);
        }
    }
    sum
}

#[inline]
fn hdot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
fn hcross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

#[inline]
fn hsub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The same operations as `Plane::from_triangle` + `signed_distance`, by
/// hand: n = normalize((b - a) x (c - a)), d = n . p + (-(n . a)).
fn plane_distance_hand(batch: &[[[f64; 3]; 4]]) -> f64 {
    let mut sum = 0.0;
    for [a, b, c, p] in batch {
        let n = hcross(hsub(*b, *a), hsub(*c, *a));
        let len = hdot(n, n).sqrt();
        if len > 0.0 && len.is_finite() {
            let n = [n[0] / len, n[1] / len, n[2] / len];
            let constant = -hdot(n, *a);
            sum += hdot(n, *p) + constant;
        }
    }
    sum
}

// ---------------------------------------------------------------------------
// Kernel 2: 3x3 determinant a . (b x c)
// ---------------------------------------------------------------------------

fn det3_generic<T: Real>(batch: &[(Triangle<T>, Vec3<T>)]) -> T {
    let mut sum = T::zero();
    for (tri, _) in batch {
        sum += dot(&tri.a, &cross(&tri.b, &tri.c));
    }
    sum
}

fn det3_hand(batch: &[[[f64; 3]; 4]]) -> f64 {
    let mut sum = 0.0;
    for [a, b, c, _] in batch {
        sum += hdot(*a, hcross(*b, *c));
    }
    sum
}

// ---------------------------------------------------------------------------

fn kernels(c: &mut Criterion) {
    let raw = inputs();
    let b32 = convert::<f32>(&raw);
    let b64 = convert::<f64>(&raw);
    #[cfg(feature = "mpfr")]
    let bmp = convert::<sweepslide::Mpfr<53>>(&raw);

    // Same operation order: bit-identical results (and Mpfr<53> == f64).
    let hand = plane_distance_hand(&raw);
    assert_eq!(plane_distance_generic(&b64).to_bits(), hand.to_bits());
    #[cfg(feature = "mpfr")]
    assert_eq!(plane_distance_generic(&bmp).to_f64().to_bits(), hand.to_bits());
    let hand = det3_hand(&raw);
    assert_eq!(det3_generic(&b64).to_bits(), hand.to_bits());
    #[cfg(feature = "mpfr")]
    assert_eq!(det3_generic(&bmp).to_f64().to_bits(), hand.to_bits());

    let mut group = c.benchmark_group("plane_distance");
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function(BenchmarkId::new("hand", "f64"), |bn| bn.iter(|| plane_distance_hand(black_box(&raw))));
    group.bench_function(BenchmarkId::new("generic", "f64"), |bn| bn.iter(|| plane_distance_generic(black_box(&b64))));
    group.bench_function(BenchmarkId::new("generic", "f32"), |bn| bn.iter(|| plane_distance_generic(black_box(&b32))));
    #[cfg(feature = "mpfr")]
    group.bench_function(BenchmarkId::new("generic", "mpfr53"), |bn| {
        bn.iter(|| plane_distance_generic(black_box(&bmp)))
    });
    group.finish();

    let mut group = c.benchmark_group("det3");
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function(BenchmarkId::new("hand", "f64"), |bn| bn.iter(|| det3_hand(black_box(&raw))));
    group.bench_function(BenchmarkId::new("generic", "f64"), |bn| bn.iter(|| det3_generic(black_box(&b64))));
    group.bench_function(BenchmarkId::new("generic", "f32"), |bn| bn.iter(|| det3_generic(black_box(&b32))));
    #[cfg(feature = "mpfr")]
    group.bench_function(BenchmarkId::new("generic", "mpfr53"), |bn| bn.iter(|| det3_generic(black_box(&bmp))));
    group.finish();
}

criterion_group!(benches, kernels);
criterion_main!(benches);
