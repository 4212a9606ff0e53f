//! One test suite, instantiated for every `Real` backend (glam style):
//! `f32`, `f64`, `Mpfr<24>`, `Mpfr<53>` and `Mpfr<256>`.
//!
//! Expected values are either exact (chosen so that no rounding happens in
//! any backend) or computed independently with `rug` at the backend's own
//! precision, so every backend is held to "correctly rounded, to nearest".
//!
//! The second half is the MPFR backend's self-check: over thousands of
//! random operation sequences in the normal range, `Mpfr<24>` must give the
//! bits of `f32` and `Mpfr<53>` the bits of `f64`; `Mpfr<25>` and
//! `Mpfr<54>` must not (which shows the check can fail).
#![cfg(feature = "mpfr")]

use rug::Float;
use std::cmp::Ordering;
use sweepslide::geom::{
    Ellipsoid, Feature, Plane, Triangle, Vec3, closest_point_on_triangle, cross, cross_of_edges, dot, max_abs, norm,
    norm_squared, normalize, normalize_near_unit, vec3,
};
use sweepslide::real::with_precision;
use sweepslide::{Mpfr, MpfrDyn, Real};

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

fn r<T: Real>(x: f64) -> T {
    T::from_f64(x)
}

/// `x` rounded to nearest at `bits` bits by rug (the reference rounding).
fn rug_round(bits: u32, x: f64) -> Float {
    Float::with_val(bits, x)
}

/// Asserts that a backend value equals an f64 exactly (sign of zero included).
#[track_caller]
fn assert_is<T: Real>(x: &T, expected: f64) {
    let got = x.to_f64();
    assert!(
        got.to_bits() == expected.to_bits() || (got.is_nan() && expected.is_nan()),
        "{}: got {got:e} ({:?}), expected {expected:e}",
        T::name(),
        x
    );
}

#[track_caller]
fn assert_vec_is<T: Real>(v: &Vec3<T>, expected: [f64; 3]) {
    for i in 0..3 {
        assert_is(&v[i], expected[i]);
    }
}

/// SplitMix64: a small deterministic generator (the tests must be
/// reproducible run to run).
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }

    /// A random f64 with a full random significand, a random sign and a
    /// binary exponent in `[-emax, emax]`: always normal, never zero.
    fn wide(&mut self, emax: i32) -> f64 {
        let mantissa = 1.0 + (self.next_u64() >> 11) as f64 * (-53f64).exp2();
        let e = self.below((2 * emax + 1) as u64) as i32 - emax;
        let sign = if self.next_u64() & 1 == 1 { -1.0 } else { 1.0 };
        sign * mantissa * f64::from(e).exp2()
    }

    /// A multiple of `2^-10` in `(-4, 4)`: exact in every backend.
    fn grid(&mut self) -> f64 {
        (self.below(8191) as f64 - 4095.0) / 1024.0
    }
}

// ---------------------------------------------------------------------------
// The generic checks (one function per topic, run for every backend)
// ---------------------------------------------------------------------------

fn check_arithmetic<T: Real>() {
    let a = r::<T>(1.5);
    let b = r::<T>(-0.75);
    // By value.
    assert_is(&(a.clone() + b.clone()), 0.75);
    assert_is(&(a.clone() - b.clone()), 2.25);
    assert_is(&(a.clone() * b.clone()), -1.125);
    assert_is(&(a.clone() / b.clone()), -2.0);
    assert_is(&(-a.clone()), -1.5);
    // Borrowed right-hand side.
    assert_is(&(a.clone() + &b), 0.75);
    assert_is(&(a.clone() - &b), 2.25);
    assert_is(&(a.clone() * &b), -1.125);
    assert_is(&(a.clone() / &b), -2.0);
    // Compound assignment (the trait bounds give the by-value forms).
    let mut c = a.clone();
    c += b.clone();
    assert_is(&c, 0.75);
    c += b.clone();
    assert_is(&c, 0.0);
    c -= b.clone();
    assert_is(&c, 0.75);
    c -= b.clone();
    assert_is(&c, 1.5);
    c *= b.clone();
    assert_is(&c, -1.125);
    c *= b.clone();
    assert_is(&c, 0.84375);
    c /= b.clone();
    assert_is(&c, -1.125);
    c /= b.clone();
    assert_is(&c, 1.5);
    // Zero and one.
    assert_is(&T::zero(), 0.0);
    assert_is(&T::one(), 1.0);
    assert_is(&(T::zero() + T::one()), 1.0);

    // Inexact operations round to nearest at the backend's precision.
    let bits = T::bits();
    let third = T::one() / r::<T>(3.0);
    assert_eq!(third.to_rug(), rug_round(bits, 1.0) / 3u32, "{}: 1/3", T::name());
    let sum = r::<T>(0.1) + r::<T>(0.2);
    let expected = Float::with_val(bits, &rug_round(bits, 0.1) + &rug_round(bits, 0.2));
    assert_eq!(sum.to_rug(), expected, "{}: 0.1 + 0.2", T::name());
    let prod = r::<T>(0.1) * r::<T>(0.7);
    let expected = Float::with_val(bits, &rug_round(bits, 0.1) * &rug_round(bits, 0.7));
    assert_eq!(prod.to_rug(), expected, "{}: 0.1 * 0.7", T::name());
    let diff = r::<T>(1.0) - r::<T>(1e-3);
    let expected = Float::with_val(bits, &rug_round(bits, 1.0) - &rug_round(bits, 1e-3));
    assert_eq!(diff.to_rug(), expected, "{}: 1 - 0.001", T::name());
    // 1 + u is a tie between 1 and 1 + 2u: ties go to even (1); just above
    // the tie goes up.
    let u = T::unit_roundoff();
    assert_is(&(T::one() + r::<T>(u)), 1.0);
    let above = T::one() + r::<T>(u) * (T::one() + r::<T>(T::machine_epsilon()));
    assert!(above > T::one(), "{}: 1 + u(1 + eps) must round up", T::name());
    // Exact cancellation gives +0 under round to nearest.
    let z = r::<T>(0.3) - r::<T>(0.3);
    assert!(z.is_zero() && !z.is_sign_negative(), "{}: x - x must be +0", T::name());
}

fn check_comparisons<T: Real>() {
    let one = r::<T>(1.0);
    let two = r::<T>(2.0);
    assert!(one < two);
    assert!(two > one);
    assert!(one <= one.clone());
    assert!(one >= one.clone());
    assert!(one != two);
    assert!(one == r::<T>(1.0));
    assert_eq!(one.partial_cmp(&two), Some(Ordering::Less));
    assert_eq!(two.partial_cmp(&one), Some(Ordering::Greater));
    assert_eq!(one.partial_cmp(&one.clone()), Some(Ordering::Equal));
    assert!(r::<T>(-2.0) < r::<T>(-1.0));
    // Signed zeros compare equal but keep their sign bit.
    let pz = r::<T>(0.0);
    let nz = r::<T>(-0.0);
    assert!(pz == nz);
    assert!(!pz.is_sign_negative());
    assert!(nz.is_sign_negative());
    // NaN is unordered and unequal to itself.
    let nan = r::<T>(f64::NAN);
    assert!(nan != nan.clone());
    assert_eq!(nan.partial_cmp(&one), None);
    assert_eq!(one.partial_cmp(&nan), None);
    assert!(!nan.is_finite());
    assert!(!r::<T>(f64::INFINITY).is_finite());
    assert!(!r::<T>(f64::NEG_INFINITY).is_finite());
    assert!(r::<T>(f64::INFINITY) > r::<T>(1e30));
    assert!(one.is_finite());
}

fn check_sqrt<T: Real>() {
    assert_is(&r::<T>(2.25).sqrt(), 1.5);
    assert_is(&r::<T>(1024.0).sqrt(), 32.0);
    assert_is(&r::<T>(0.0).sqrt(), 0.0);
    assert_is(&r::<T>(-0.0).sqrt(), -0.0);
    assert!(!r::<T>(-1.0).sqrt().is_finite(), "{}: sqrt(-1) must be NaN", T::name());
    let bits = T::bits();
    for x in [2.0, 3.0, 0.1, 1e10, 7.25e-5] {
        let got = r::<T>(x).sqrt();
        let expected = rug_round(bits, x).sqrt();
        assert_eq!(got.to_rug(), expected, "{}: sqrt({x})", T::name());
    }
}

fn check_abs<T: Real>() {
    assert_is(&r::<T>(-3.5).abs(), 3.5);
    assert_is(&r::<T>(3.5).abs(), 3.5);
    assert_is(&r::<T>(-0.0).abs(), 0.0);
    assert_is(&r::<T>(f64::NEG_INFINITY).abs(), f64::INFINITY);
    // Exact, even for a value that needs all the backend's bits.
    let x = -(T::one() / r::<T>(3.0));
    assert!(x.abs() == -x.clone());
}

fn check_min_max<T: Real>() {
    let one = r::<T>(1.0);
    let two = r::<T>(-2.0);
    assert_is(&Real::min(one.clone(), two.clone()), -2.0);
    assert_is(&Real::min(two.clone(), one.clone()), -2.0);
    assert_is(&Real::max(one.clone(), two.clone()), 1.0);
    assert_is(&Real::max(two.clone(), one.clone()), 1.0);
    // Equal values: `self` is returned (visible through the sign of zero).
    assert_is(&Real::min(r::<T>(0.0), r::<T>(-0.0)), 0.0);
    assert_is(&Real::min(r::<T>(-0.0), r::<T>(0.0)), -0.0);
    assert_is(&Real::max(r::<T>(0.0), r::<T>(-0.0)), 0.0);
    assert_is(&Real::max(r::<T>(-0.0), r::<T>(0.0)), -0.0);
    // Unordered: `self` is returned.
    let nan = r::<T>(f64::NAN);
    assert!(Real::min(nan.clone(), one.clone()).to_f64().is_nan());
    assert_is(&Real::min(one.clone(), nan.clone()), 1.0);
    assert!(Real::max(nan.clone(), one.clone()).to_f64().is_nan());
    assert_is(&Real::max(one, nan), 1.0);
}

/// `a * b + c` rounded once, computed independently: the product is exact
/// at `2 * bits` bits, then the sum is rounded once to `bits`.
fn exact_fma<T: Real>(a: &T, b: &T, c: &T) -> Float {
    let bits = T::bits();
    let mut p = Float::with_val(2 * bits, a.to_rug());
    p *= b.to_rug();
    Float::with_val(bits, &p + &c.to_rug())
}

fn check_mul_add<T: Real>() {
    let bits = T::bits();
    // a = 1 + 2^-k, b = 1 - 2^-k: a * b = 1 - 2^-2k exactly, which rounds
    // to 1 unfused (2k > bits + 1), so unfused a*b - 1 = 0 but the fused
    // result is -2^-2k.
    let k = bits.div_ceil(2) + 1;
    assert!(k < bits);
    let h = r::<T>((-f64::from(k)).exp2());
    let a = T::one() + &h;
    let b = T::one() - &h;
    let minus_one = -T::one();
    let unfused = a.clone() * &b + &minus_one;
    assert_is(&unfused, 0.0);
    let fused = a.mul_add(&b, &minus_one);
    assert_is(&fused, -(-2.0 * f64::from(k)).exp2());
    assert_eq!(fused.to_rug(), exact_fma(&a, &b, &minus_one));
    // Simple exact cases.
    assert_is(&r::<T>(3.0).mul_add(&r::<T>(4.0), &r::<T>(-5.0)), 7.0);
    assert_is(&r::<T>(0.5).mul_add(&r::<T>(-0.25), &r::<T>(0.125)), 0.0);
    // Random cases against the exact single rounding; count how often
    // fusing actually changes the result, so the test cannot pass with an
    // unfused implementation.
    let mut rng = Rng(0x5eed_0001);
    let mut differs = 0;
    for _ in 0..500 {
        // Quotients fill all the backend's bits (an f64 input alone would
        // leave a 256-bit product exact, and fusing would change nothing).
        let mut full = |e| r::<T>(rng.wide(e)) / r::<T>(rng.wide(1));
        let a = full(6);
        let b = full(6);
        let c = full(12);
        let fused = a.mul_add(&b, &c);
        assert_eq!(fused.to_rug(), exact_fma(&a, &b, &c), "{}: fma({a:?}, {b:?}, {c:?})", T::name());
        if fused != a.clone() * &b + &c {
            differs += 1;
        }
    }
    assert!(differs > 10, "{}: fused and unfused agree too often ({differs}/500)", T::name());
}

fn check_from_to_f64<T: Real>() {
    // Representable in every backend (24 bits or fewer).
    let small = [
        0.0,
        -0.0,
        1.0,
        -1.5,
        0.75,
        1024.0,
        16_777_215.0,
        -(1.0 + f64::from(f32::EPSILON)),
        (-100f64).exp2(),
        100f64.exp2(),
        f64::from(0.1f32),
        f64::from(f32::MAX),
        f64::from(f32::MIN_POSITIVE),
    ];
    for x in small {
        assert_is(&r::<T>(x), x);
    }
    if T::bits() >= 53 {
        for x in [0.1, std::f64::consts::PI, -1e300, 1.0 + f64::EPSILON, f64::MAX, f64::MIN_POSITIVE, (-1000f64).exp2()]
        {
            assert_is(&r::<T>(x), x);
        }
    } else {
        // Otherwise from_f64 rounds to nearest at the backend's precision.
        for x in [0.1, std::f64::consts::PI, -1e30, 1.0 + f64::EPSILON, 16_777_217.0] {
            assert_eq!(r::<T>(x).to_rug(), rug_round(T::bits(), x), "{}: from_f64({x})", T::name());
        }
        assert_is(&r::<T>(16_777_217.0), 16_777_216.0); // tie to even
        assert_is(&r::<T>(16_777_219.0), 16_777_220.0); // tie to even
    }
    // to_f64 rounds to nearest.
    let third = T::one() / r::<T>(3.0);
    let expected = if T::bits() >= 53 { 1.0 / 3.0 } else { f64::from(1.0f32 / 3.0) };
    assert_is(&third, expected);
    assert!(r::<T>(f64::NAN).to_f64().is_nan());
    assert_is(&r::<T>(f64::INFINITY), f64::INFINITY);
    assert_is(&r::<T>(f64::NEG_INFINITY), f64::NEG_INFINITY);
}

fn check_constants<T: Real>(bits: u32, name: &str) {
    assert_eq!(T::bits(), bits);
    assert_eq!(T::name(), name);
    assert_eq!(T::unit_roundoff(), (-f64::from(bits)).exp2());
    assert_eq!(T::machine_epsilon(), (1.0 - f64::from(bits)).exp2());
    assert_eq!(T::machine_epsilon(), 2.0 * T::unit_roundoff());
    // The epsilon is the gap between 1 and the next value of the backend.
    let eps = r::<T>(T::machine_epsilon());
    let next = T::one() + &eps;
    assert!(next > T::one());
    assert_is(&(next - T::one()), T::machine_epsilon());
    let half = r::<T>(T::machine_epsilon() / 2.0);
    assert!(T::one() + &half == T::one());
    assert_is(&T::c(0.5), 0.5);
}

fn check_vec_helpers<T: Real>() {
    let a = vec3::<T>(1.0, 2.0, 3.0);
    let b = vec3::<T>(4.0, -5.0, 6.0);
    assert_is(&dot(&a, &b), 12.0);
    assert_vec_is(&cross(&a, &b), [27.0, 6.0, -13.0]);
    assert_vec_is(&cross(&vec3::<T>(1.0, 0.0, 0.0), &vec3::<T>(0.0, 1.0, 0.0)), [0.0, 0.0, 1.0]);
    // a x b is orthogonal to a and b (exact here: small integers).
    assert_is(&dot(&cross(&a, &b), &a), 0.0);
    assert_is(&dot(&cross(&a, &b), &b), 0.0);
    // max_abs: the largest magnitude or the floor, whichever is larger; a
    // NaN component is passed over, as `max` passes over NaN.
    assert_is(&max_abs(&b, T::zero()), 6.0);
    assert_is(&max_abs(&vec3::<T>(-7.0, 2.0, -0.5), T::c(1.0)), 7.0);
    assert_is(&max_abs(&vec3::<T>(-0.25, 0.5, -0.125), T::c(1.0)), 1.0);
    assert_is(&max_abs(&vec3::<T>(f64::NAN, -3.0, 2.0), T::zero()), 3.0);
    assert!(max_abs(&vec3::<T>(-0.0, 0.0, -0.0), T::zero()).is_zero());
    let c = vec3::<T>(2.0, -3.0, 6.0);
    assert_is(&norm_squared(&c), 49.0);
    assert_is(&norm(&c), 7.0);
    // normalize: exact where the norm is, correctly rounded otherwise.
    assert_vec_is(&normalize(&vec3::<T>(0.0, 0.0, -5.0)).unwrap(), [0.0, 0.0, -1.0]);
    let n = normalize(&vec3::<T>(3.0, 0.0, 4.0)).unwrap();
    assert!(n.x == r::<T>(3.0) / r::<T>(5.0));
    assert_is(&n.y, 0.0);
    assert!(n.z == r::<T>(4.0) / r::<T>(5.0));
    // Evaluation order is (x*x + y*y) + z*z: with big = 2^bits, 1 + big is
    // a tie that rounds to big, so the documented order gives 0, while
    // x + (y + z) or (x + z) + y would give 1.
    let big = T::one() / r::<T>(T::unit_roundoff());
    let v = Vec3::new(T::one(), big.clone(), -big);
    let ones = Vec3::new(T::one(), T::one(), T::one());
    assert_is(&dot(&v, &ones), 0.0);
    // The zero vector (and a non-finite one) has no direction: None, never NaN.
    assert!(normalize(&vec3::<T>(0.0, 0.0, 0.0)).is_none());
    assert!(normalize(&vec3::<T>(-0.0, 0.0, -0.0)).is_none());
    assert!(normalize(&vec3::<T>(f64::NAN, 1.0, 0.0)).is_none());
    assert!(normalize(&vec3::<T>(f64::INFINITY, 1.0, 0.0)).is_none());

    // normalize_near_unit: one Newton step from 1 within sqrt(u) of unit
    // length, normalize beyond. Lengths 1 + k sqrt(u) / 4 in scattered
    // directions come out unit to within the documented 4u (the step's
    // 3e^2/8 and the roundings), parallel to the input.
    let u = T::unit_roundoff();
    for k in -4..=4 {
        for d in [[1.0, 2.0, 2.0], [-0.3, 0.9, 0.1], [5.0, -1.0, -7.0], [0.0, 0.0, 1.0]] {
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let scale = (1.0 + f64::from(k) * u.sqrt() / 4.0) / len;
            let a = vec3::<T>(d[0] * scale, d[1] * scale, d[2] * scale);
            let n = normalize_near_unit(&a).expect("finite and near unit");
            let excess = (norm_squared(&n) - T::one()).abs().to_f64();
            assert!(excess <= 8.0 * u, "{}: |n|^2 - 1 = {excess:e} for k = {k}, {d:?}", T::name());
            let skew = norm(&cross(&n, &a)).to_f64();
            assert!(skew <= 4.0 * u * 8.0, "{}: n x a = {skew:e}", T::name());
        }
    }
    assert_vec_is(&normalize_near_unit(&vec3::<T>(0.0, 0.0, -1.0)).unwrap(), [0.0, 0.0, -1.0]);
    // Far from unit length it is normalize, bit for bit.
    let far = vec3::<T>(3.0, -1.0, 4.0);
    assert!(normalize_near_unit(&far) == normalize(&far));
    assert!(normalize_near_unit(&vec3::<T>(0.0, 0.0, 0.0)).is_none());
    assert!(normalize_near_unit(&vec3::<T>(f64::NAN, 1.0, 0.0)).is_none());
    assert!(normalize_near_unit(&vec3::<T>(f64::INFINITY, 0.0, 0.0)).is_none());
}

/// `cross_of_edges` on flat caps (a vertex near the middle of the long
/// side, heights `1e-7` to `1e-2` of the length, full significands from
/// quotients) against the exact product of the exact edges at 4096 bits:
/// each component within `u` of itself plus `28 u^2 |y - x| |z - y|`, the
/// documented bound. The plain product of the rounded edges breaks that
/// bound on most of these caps, so the check can fail.
fn check_cross_of_edges<T: Real>() {
    let u = T::unit_roundoff();
    let mut rng = Rng(0x5eed_00ca);
    let mut plain_outside = 0;
    for _ in 0..400 {
        let mut full = |e| r::<T>(rng.wide(e)) / r::<T>(rng.wide(1));
        let x = Vec3::new(full(8), full(8), full(8));
        let dir = Vec3::new(full(0), full(0), full(0));
        let side = Vec3::new(full(0), full(0), full(0));
        let long = r::<T>(1e3) * full(2).abs();
        let along = r::<T>(0.05 + 0.9 * rng.below(1000) as f64 / 1000.0);
        let height = r::<T>((-(rng.below(18) as f64) - 6.0).exp2() * 10.0) * &long;
        let y = x.clone() + (dir.clone() * (long.clone() * along)) + cross(&dir, &side) * height;
        let z = x.clone() + dir * long;
        let got = cross_of_edges(&x, &y, &z);
        let plain = cross(&(y.clone() - &x), &(z.clone() - &y));
        let big = |v: &Vec3<T>| [0, 1, 2].map(|i| Float::with_val(4096, v[i].to_rug()));
        let (xe, ye, ze) = (big(&x), big(&y), big(&z));
        let e = [0, 1, 2].map(|i| Float::with_val(4096, &ye[i] - &xe[i]));
        let f = [0, 1, 2].map(|i| Float::with_val(4096, &ze[i] - &ye[i]));
        let product = |a: &Float, b: &Float| Float::with_val(4096, a * b);
        let exact = [(1, 2), (2, 0), (0, 1)].map(|(j, k)| product(&e[j], &f[k]) - product(&e[k], &f[j]));
        let length = |v: &[Float; 3]| (product(&v[0], &v[0]) + product(&v[1], &v[1]) + product(&v[2], &v[2])).sqrt();
        let lever = (length(&e) * length(&f)).to_f64();
        for i in 0..3 {
            let bound = u * exact[i].to_f64().abs() + 28.0 * u * u * lever;
            let err = Float::with_val(4096, got[i].to_rug() - &exact[i]).to_f64().abs();
            assert!(err <= bound, "{}: component {i} off by {err:e}, bound {bound:e}", T::name());
            if Float::with_val(4096, plain[i].to_rug() - &exact[i]).to_f64().abs() > bound {
                plain_outside += 1;
            }
        }
    }
    assert!(plain_outside > 200, "{}: the plain product broke the bound only {plain_outside} times", T::name());
}

fn check_plane<T: Real>() {
    // Counter-clockwise seen from +z: normal +z, plane z = 1.
    let tri = Triangle::new(vec3::<T>(0.0, 0.0, 1.0), vec3::<T>(2.0, 0.0, 1.0), vec3::<T>(0.0, 2.0, 1.0));
    let plane = Plane::from_triangle(&tri).expect("non-degenerate");
    assert_vec_is(&plane.normal, [0.0, 0.0, 1.0]);
    assert_is(&plane.constant, -1.0);
    assert_is(&plane.signed_distance(&vec3::<T>(5.0, 7.0, 3.0)), 2.0);
    assert_is(&plane.signed_distance(&vec3::<T>(-5.0, 7.0, -2.5)), -3.5);
    assert_is(&plane.signed_distance(&vec3::<T>(0.25, 0.25, 1.0)), 0.0);
    // Clockwise winding flips the normal.
    let flipped = Triangle::new(tri.a.clone(), tri.c.clone(), tri.b.clone());
    let plane = Plane::from_triangle(&flipped).unwrap();
    assert_vec_is(&plane.normal, [0.0, 0.0, -1.0]);
    assert_is(&plane.signed_distance(&vec3::<T>(5.0, 7.0, 3.0)), -2.0);
    // A tilted plane with an exactly representable normal (0, 0.6, 0.8)
    // up to rounding of 3/5, 4/5: distance of a point 5 units along it.
    let tilted = Triangle::new(vec3::<T>(0.0, 0.0, 0.0), vec3::<T>(1.0, 0.0, 0.0), vec3::<T>(0.0, 4.0, -3.0));
    let plane = Plane::from_triangle(&tilted).unwrap();
    assert!(plane.normal.y == r::<T>(3.0) / r::<T>(5.0));
    assert!(plane.normal.z == r::<T>(4.0) / r::<T>(5.0));
    let d = plane.signed_distance(&vec3::<T>(0.0, 3.0, 4.0));
    assert!((d.to_f64() - 5.0).abs() <= 8.0 * T::unit_roundoff() * 5.0, "{}: {d:?}", T::name());
    // Degenerate triangles have no plane.
    let line = Triangle::new(vec3::<T>(0.0, 0.0, 0.0), vec3::<T>(1.0, 1.0, 1.0), vec3::<T>(2.0, 2.0, 2.0));
    assert!(Plane::from_triangle(&line).is_none());
    let point = Triangle::new(vec3::<T>(1.0, 2.0, 3.0), vec3::<T>(1.0, 2.0, 3.0), vec3::<T>(1.0, 2.0, 3.0));
    assert!(Plane::from_triangle(&point).is_none());
}

fn check_closest_point<T: Real>() {
    let tri = Triangle::new(vec3::<T>(0.0, 0.0, 0.0), vec3::<T>(4.0, 0.0, 0.0), vec3::<T>(0.0, 4.0, 0.0));
    let cases: [([f64; 3], [f64; 3], Feature); 10] = [
        ([1.0, 1.0, 5.0], [1.0, 1.0, 0.0], Feature::Face),
        ([1.0, 1.0, -2.0], [1.0, 1.0, 0.0], Feature::Face),
        ([0.5, 2.5, 0.0], [0.5, 2.5, 0.0], Feature::Face),
        ([1.0, -2.0, 3.0], [1.0, 0.0, 0.0], Feature::Edge(0)),
        ([3.0, 3.0, 1.0], [2.0, 2.0, 0.0], Feature::Edge(1)),
        ([-2.0, 1.0, 3.0], [0.0, 1.0, 0.0], Feature::Edge(2)),
        ([-1.0, -1.0, 2.0], [0.0, 0.0, 0.0], Feature::Vertex(0)),
        ([6.0, -1.0, 0.0], [4.0, 0.0, 0.0], Feature::Vertex(1)),
        ([-1.0, 6.0, 0.0], [0.0, 4.0, 0.0], Feature::Vertex(2)),
        ([7.0, 0.5, -3.0], [4.0, 0.0, 0.0], Feature::Vertex(1)),
    ];
    for (p, expected, feature) in cases {
        let (q, f) = closest_point_on_triangle(&vec3::<T>(p[0], p[1], p[2]), &tri);
        assert_eq!(f, feature, "{}: closest feature to {p:?}", T::name());
        assert_vec_is(&q, expected);
    }
}

fn check_ellipsoid<T: Real>() {
    let e = Ellipsoid::<T>::new([2.0, 0.5, 4.0]).unwrap();
    assert!(!e.is_sphere());
    assert_is(&e.min_radius(), 0.5);
    assert_is(&e.max_radius(), 4.0);
    let p = vec3::<T>(3.0, 5.0, -7.0);
    let q = e.to_espace(&p);
    assert_vec_is(&q, [1.5, 10.0, -1.75]);
    assert_vec_is(&e.from_espace(&q), [3.0, 5.0, -7.0]);
    // Power-of-two radii: the round trip is exact for any normal value.
    let mut rng = Rng(0xe11);
    for _ in 0..200 {
        let p = vec3::<T>(rng.wide(20), rng.wide(20), rng.wide(20));
        let back = e.from_espace(&e.to_espace(&p));
        assert!(back == p, "{}: round trip of {p:?} gave {back:?}", T::name());
    }
    let s = Ellipsoid::<T>::sphere(0.25).unwrap();
    assert!(s.is_sphere());
    assert_vec_is(&s.to_espace(&vec3::<T>(1.0, -0.5, 0.125)), [4.0, -2.0, 0.5]);
}

macro_rules! backend_suite {
    ($module:ident, $t:ty, $bits:expr, $name:expr) => {
        mod $module {
            use super::*;
            type T = $t;

            #[test]
            fn arithmetic_by_value_and_by_reference() {
                check_arithmetic::<T>();
            }
            #[test]
            fn comparisons() {
                check_comparisons::<T>();
            }
            #[test]
            fn sqrt_is_correctly_rounded() {
                check_sqrt::<T>();
            }
            #[test]
            fn abs() {
                check_abs::<T>();
            }
            #[test]
            fn min_max() {
                check_min_max::<T>();
            }
            #[test]
            fn mul_add_rounds_once() {
                check_mul_add::<T>();
            }
            #[test]
            fn from_f64_and_to_f64() {
                check_from_to_f64::<T>();
            }
            #[test]
            fn constants_bits_and_name() {
                check_constants::<T>($bits, $name);
            }
            #[test]
            fn vec3_helpers() {
                check_vec_helpers::<T>();
            }
            #[test]
            fn cross_of_exact_edges_within_its_bound() {
                check_cross_of_edges::<T>();
            }
            #[test]
            fn plane_from_triangle_and_signed_distance() {
                check_plane::<T>();
            }
            #[test]
            fn closest_point_on_triangle_regions() {
                check_closest_point::<T>();
            }
            #[test]
            fn ellipsoid_espace_round_trip() {
                check_ellipsoid::<T>();
            }
        }
    };
}

backend_suite!(f32_backend, f32, 24, "f32");
backend_suite!(f64_backend, f64, 53, "f64");
backend_suite!(mpfr24_backend, Mpfr<24>, 24, "mpfr24");
backend_suite!(mpfr53_backend, Mpfr<53>, 53, "mpfr53");
backend_suite!(mpfr256_backend, Mpfr<256>, 256, "mpfr256");

// ---------------------------------------------------------------------------
// Run-time precision
// ---------------------------------------------------------------------------

#[test]
fn with_precision_sets_and_restores_dynamic_bits() {
    let before = MpfrDyn::bits();
    assert_eq!(before, 53, "default dynamic precision");
    let (bits, prec, name, third) = with_precision(100, || {
        let x = MpfrDyn::from_f64(1.0) / MpfrDyn::from_f64(3.0);
        (MpfrDyn::bits(), x.as_rug().prec(), MpfrDyn::name(), x)
    })
    .unwrap();
    assert_eq!(bits, 100);
    assert_eq!(prec, 100);
    assert_eq!(name, "mpfr100");
    assert_eq!(*third.as_rug(), Float::with_val(100, 1) / 3u32);
    // The value keeps its precision after the scope ends...
    assert_eq!(third.as_rug().prec(), 100);
    // ...and new values get the old precision again.
    assert_eq!(MpfrDyn::bits(), before);
    assert_eq!(MpfrDyn::from_f64(1.0).as_rug().prec(), before);

    // Nested scopes restore the enclosing one.
    with_precision(80, || {
        assert_eq!(MpfrDyn::bits(), 80);
        with_precision(30, || assert_eq!(MpfrDyn::from_f64(0.0).as_rug().prec(), 30)).unwrap();
        assert_eq!(MpfrDyn::bits(), 80);
    })
    .unwrap();
    assert_eq!(MpfrDyn::bits(), before);

    // MpfrDyn at 24 and 53 bits behaves as f32 / f64.
    let x = with_precision(24, || (MpfrDyn::from_f64(0.1) * MpfrDyn::from_f64(0.7)).to_f64()).unwrap();
    assert_eq!(x, f64::from(0.1f32 * 0.7f32));
    let x = with_precision(53, || (MpfrDyn::from_f64(0.1) * MpfrDyn::from_f64(0.7)).to_f64()).unwrap();
    assert_eq!(x, 0.1 * 0.7);

    // Extremes accepted.
    assert_eq!(with_precision(2, MpfrDyn::bits).unwrap(), 2);
    assert_eq!(MpfrDyn::bits(), before);
}

#[test]
fn with_precision_restores_after_a_panic() {
    let before = MpfrDyn::bits();
    let caught = std::panic::catch_unwind(|| {
        with_precision(77, || {
            assert_eq!(MpfrDyn::bits(), 77);
            panic!("inside with_precision");
        })
    });
    assert!(caught.is_err());
    assert_eq!(MpfrDyn::bits(), before);
}

#[test]
fn with_precision_is_per_thread() {
    with_precision(64, || {
        let other = std::thread::spawn(MpfrDyn::bits).join().unwrap();
        assert_eq!(other, 53);
        assert_eq!(MpfrDyn::bits(), 64);
    })
    .unwrap();
}

/// A box `[-10, 10]^3` without its top, as triangles facing inwards.
fn open_box() -> std::sync::Arc<sweepslide::world::TriangleMesh> {
    let h = 10.0;
    let v =
        vec![[-h, 0.0, -h], [h, 0.0, -h], [h, 0.0, h], [-h, 0.0, h], [-h, h, -h], [h, h, -h], [h, h, h], [-h, h, h]];
    let t = vec![
        [0, 2, 1],
        [0, 3, 2],
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ];
    std::sync::Arc::new(sweepslide::world::TriangleMesh::new(v, t).unwrap())
}

/// `move_bodies` computes at the caller's run-time precision on rayon's
/// workers (found by a review: they ran at the default 53 bits on 24-bit
/// values, differed from `move_body` for every body and let them into the
/// walls).
#[test]
fn move_bodies_runs_at_the_callers_dynamic_precision() {
    use sweepslide::respond::{BodyMove, MoveOptions, Response, move_bodies, move_body};
    use sweepslide::world::World;
    for bits in [12, 24, 113] {
        with_precision(bits, || {
            let world = World::<MpfrDyn>::new(open_box()).unwrap();
            let body = Ellipsoid::<MpfrDyn>::new([0.4, 0.9, 0.4]).unwrap();
            let opts = MoveOptions::new(Response::Robust);
            let moves: Vec<BodyMove<MpfrDyn>> = (0..64)
                .map(|i| BodyMove {
                    body: body.clone(),
                    position: vec3(-9.0 + 0.27 * f64::from(i), 0.9 + 1e-3 * f64::from(i), 9.5),
                    velocity: vec3(0.3, -0.05, 0.7),
                    gravity: Some(vec3(0.0, -0.3, 0.0)),
                })
                .collect();
            let batch = move_bodies(&world, &moves, &opts);
            for (m, b) in moves.iter().zip(batch) {
                let one = move_body(&world, &m.body, &m.position, &m.velocity, m.gravity.as_ref(), &opts).unwrap();
                let b = b.unwrap();
                assert_eq!(b.position, one.position, "{bits} bits");
                assert!(b.position.iter().all(|x| x.as_rug().prec() == bits), "{bits} bits");
            }
        })
        .unwrap();
    }
}

/// A floor `y = 0` over `[-8, 8]^2` in 2 x 2 squares, split along their
/// diagonals (internal edges everywhere), and two walls `x = 3` and
/// `z = 3` facing the origin: a corner.
fn tessellated_corner() -> std::sync::Arc<sweepslide::world::TriangleMesh> {
    let n = 8u32;
    let mut v = Vec::new();
    let mut t = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            v.push([-8.0 + 2.0 * f64::from(i), 0.0, -8.0 + 2.0 * f64::from(j)]);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c) = (a + 1, a + n + 1);
            t.extend([[a, c + 1, b], [a, c, c + 1]]);
        }
    }
    let base = v.len() as u32;
    v.extend([[3.0, 0.0, -8.0], [3.0, 0.0, 8.0], [3.0, 4.0, 8.0], [3.0, 4.0, -8.0]]);
    v.extend([[-8.0, 0.0, 3.0], [8.0, 0.0, 3.0], [8.0, 4.0, 3.0], [-8.0, 4.0, 3.0]]);
    t.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    t.extend([[base + 4, base + 6, base + 5], [base + 4, base + 7, base + 6]]);
    std::sync::Arc::new(sweepslide::world::TriangleMesh::new(v, t).unwrap())
}

/// Beyond 1,022 bits `2^-bits` is no longer a normal `f64`: the unit
/// roundoff is floored at `2^-FINEST_BITS` so that the tolerances built
/// from it stay positive (a review found them all zero from 1,023 bits on:
/// on a tessellated floor the robust response then stopped, blocked, at
/// every frame and left the body near its start instead of in the
/// corner). The slides at 200 and 1,100 bits end within rounding of each
/// other, in the corner.
#[test]
fn tolerances_stay_positive_beyond_the_f64_exponent_range() {
    use sweepslide::real::FINEST_BITS;
    use sweepslide::respond::{MoveOptions, Response, move_body};
    use sweepslide::world::World;
    let mesh = tessellated_corner();
    let slide = |bits| {
        with_precision(bits, || {
            assert!(MpfrDyn::unit_roundoff() >= (-f64::from(FINEST_BITS)).exp2());
            let world = World::<MpfrDyn>::new(mesh.clone()).unwrap();
            let body = Ellipsoid::<MpfrDyn>::new([0.5, 0.7, 0.5]).unwrap();
            let opts = MoveOptions::new(Response::Robust);
            let mut p: Vec3<MpfrDyn> = vec3(-2.0, 0.7, -2.3);
            let (v, g): (Vec3<MpfrDyn>, Vec3<MpfrDyn>) = (vec3(0.31, 0.0, 0.23), vec3(0.0, -0.2, 0.0));
            for _ in 0..80 {
                p = move_body(&world, &body, &p, &v, Some(&g), &opts).unwrap().position;
            }
            [0, 1, 2].map(|i| p[i].to_f64())
        })
        .unwrap()
    };
    let (fine, finer) = (slide(200), slide(1100));
    // In the corner, the centre half a radius from each wall.
    assert!((fine[0] - 2.5).abs() < 1e-3 && (fine[2] - 2.5).abs() < 1e-3, "{fine:?}");
    for i in 0..3 {
        assert!((fine[i] - finer[i]).abs() < 1e-9, "{fine:?} at 200 bits, {finer:?} at 1,100");
    }
}

/// `MpfrDyn` inputs made at another precision than the thread's are
/// refused (a world, a body or a position from another `with_precision`
/// scope), not silently mixed.
#[test]
fn mixed_dynamic_precisions_are_refused() {
    use sweepslide::Error;
    use sweepslide::respond::{MoveOptions, Response, move_body};
    use sweepslide::world::World;
    let at = |bits| {
        with_precision(bits, || {
            let world = World::<MpfrDyn>::new(open_box()).unwrap();
            let body = Ellipsoid::<MpfrDyn>::sphere(0.5).unwrap();
            let p: Vec3<MpfrDyn> = vec3(0.0, 1.0, 0.0);
            (world, body, p)
        })
        .unwrap()
    };
    let (w24, b24, p24) = at(24);
    let (w53, b53, p53) = at(53);
    let opts = MoveOptions::new(Response::Robust);
    with_precision(53, || {
        let v: Vec3<MpfrDyn> = vec3(0.1, -0.1, 0.0);
        assert!(move_body(&w53, &b53, &p53, &v, None, &opts).is_ok());
        for (what, result) in [
            ("world", move_body(&w24, &b53, &p53, &v, None, &opts)),
            ("body", move_body(&w53, &b24, &p53, &v, None, &opts)),
            ("position", move_body(&w53, &b53, &p24, &v, None, &opts)),
        ] {
            match result {
                Err(Error::InvalidArgument { what: w, message }) => {
                    assert_eq!(w, what);
                    assert!(message.contains("24-bit values") && message.contains("53 bits"), "{message}");
                }
                other => panic!("{what}: expected InvalidArgument, got {:?}", other.map(|m| m.position)),
            }
        }
    })
    .unwrap();
}

// ---------------------------------------------------------------------------
// Bit-exact self-check: Mpfr<24> == f32, Mpfr<53> == f64
// ---------------------------------------------------------------------------

const REGS: usize = 8;
/// Results are kept in registers only while their magnitude lies in
/// `[2^-30, 2^30]` (or they are zero): then every operation below stays in
/// the normal range of f32 (products >= 2^-60, cancellations of products
/// land on a grid no finer than 2^-107, magnitudes <= 3 * 2^60).
const KEEP_MIN: f64 = 9.313_225_746_154_785e-10; // 2^-30
const KEEP_MAX: f64 = 1_073_741_824.0; // 2^30

#[derive(Clone, Debug)]
struct Instr {
    op: u8,
    src: [usize; 6],
    dst: usize,
    /// The value a register is reset to when a result leaves the range.
    refill: f64,
}

#[derive(Clone, Debug)]
struct Program {
    init: [f64; REGS],
    ops: Vec<Instr>,
}

const OP_NAMES: [&str; 9] = ["add", "sub", "mul", "div", "sqrt", "dot", "cross", "mul_add", "normalize"];

fn random_program(rng: &mut Rng, len: usize) -> Program {
    let init = std::array::from_fn(|_| rng.wide(8));
    let ops = (0..len)
        .map(|_| Instr {
            op: rng.below(OP_NAMES.len() as u64) as u8,
            src: std::array::from_fn(|_| rng.below(REGS as u64) as usize),
            dst: rng.below(REGS as u64) as usize,
            refill: rng.wide(8),
        })
        .collect();
    Program { init, ops }
}

/// Runs a program in backend `T`; returns every result (as f64 bits) with
/// the name of the operation that produced it.
fn run_program<T: Real>(p: &Program) -> Vec<(u64, &'static str)> {
    let mut reg: Vec<T> = p.init.iter().map(|&x| T::from_f64(x)).collect();
    let mut trace = Vec::with_capacity(p.ops.len() * 3);
    for ins in &p.ops {
        let [a, b, c, d, e, f] = ins.src.map(|i| reg[i].clone());
        let results: Vec<T> = match ins.op {
            0 => vec![a + &b],
            1 => vec![a - b],
            2 => vec![a * &b],
            3 if b.is_zero() => vec![],
            3 => vec![a / b],
            4 => vec![a.abs().sqrt()],
            5 => vec![dot(&Vec3::new(a, b, c), &Vec3::new(d, e, f))],
            6 => {
                let v = cross(&Vec3::new(a, b, c), &Vec3::new(d, e, f));
                vec![v.x.clone(), v.y.clone(), v.z.clone()]
            }
            7 => vec![a.mul_add(&b, &c)],
            _ => match normalize(&Vec3::new(a, b, c)) {
                Some(n) => vec![n.x.clone(), n.y.clone(), n.z.clone()],
                None => vec![],
            },
        };
        for (k, v) in results.into_iter().enumerate() {
            let x = v.to_f64();
            trace.push((x.to_bits(), OP_NAMES[ins.op as usize]));
            let m = x.abs();
            let slot = (ins.dst + k) % REGS;
            reg[slot] = if m > KEEP_MAX || (m != 0.0 && m < KEEP_MIN) { T::from_f64(ins.refill) } else { v };
        }
    }
    trace
}

const PROGRAMS: usize = 3000;
const PROGRAM_LEN: usize = 24;

/// Compares `Mpfr<BITS>` against the hardware float `H` over the same
/// random programs. Returns (results compared, mismatches, first mismatch).
fn compare_programs<M: Real, H: Real>(seed: u64, round_to_h: fn(f64) -> f64) -> (usize, usize, Option<String>) {
    let mut rng = Rng(seed);
    let mut compared = 0;
    let mut mismatches = 0;
    let mut first = None;
    for n in 0..PROGRAMS {
        let p = random_program(&mut rng, PROGRAM_LEN);
        let hw = run_program::<H>(&p);
        let mp = run_program::<M>(&p);
        // A divergence in a data-dependent branch shows as a length change.
        if hw.len() != mp.len() {
            mismatches += 1;
            first.get_or_insert_with(|| format!("program {n}: trace lengths {} vs {}", hw.len(), mp.len()));
            continue;
        }
        for (i, ((h, op), (m, _))) in hw.iter().zip(&mp).enumerate() {
            compared += 1;
            let hv = f64::from_bits(*h);
            assert!(hv == 0.0 || hv.is_normal(), "{}: result left the normal range: {hv:e}", H::name());
            let mv = round_to_h(f64::from_bits(*m));
            if hv.to_bits() != mv.to_bits() {
                mismatches += 1;
                first.get_or_insert_with(|| {
                    format!("program {n}, result {i} ({op}): {} gives {hv:e}, {} gives {mv:e}", H::name(), M::name())
                });
            }
        }
    }
    (compared, mismatches, first)
}

fn to_f32_bits(x: f64) -> f64 {
    f64::from(x as f32)
}

fn identity(x: f64) -> f64 {
    x
}

#[test]
fn mpfr24_reproduces_f32_bit_for_bit() {
    let (compared, mismatches, first) = compare_programs::<Mpfr<24>, f32>(0xf32, identity);
    assert!(compared > PROGRAMS * PROGRAM_LEN / 2, "too few results compared: {compared}");
    assert_eq!(mismatches, 0, "{mismatches} of {compared} results differ; first: {first:?}");
}

#[test]
fn mpfr53_reproduces_f64_bit_for_bit() {
    let (compared, mismatches, first) = compare_programs::<Mpfr<53>, f64>(0xf64, identity);
    assert!(compared > PROGRAMS * PROGRAM_LEN / 2, "too few results compared: {compared}");
    assert_eq!(mismatches, 0, "{mismatches} of {compared} results differ; first: {first:?}");
}

/// The self-check must be able to fail: one bit more (or less) precision,
/// even rounded back to the hardware format, does not reproduce it.
#[test]
fn neighbouring_precisions_do_not_reproduce_hardware_floats() {
    let (_, m25, _) = compare_programs::<Mpfr<25>, f32>(0xf32, to_f32_bits);
    let (_, m23, _) = compare_programs::<Mpfr<23>, f32>(0xf32, to_f32_bits);
    let (_, m54, _) = compare_programs::<Mpfr<54>, f64>(0xf64, identity);
    let (_, m52, _) = compare_programs::<Mpfr<52>, f64>(0xf64, identity);
    assert!(m25 > 100, "Mpfr<25> rounded to f32 matched f32 too often ({m25} mismatches)");
    assert!(m23 > 100, "Mpfr<23> matched f32 too often ({m23} mismatches)");
    assert!(m54 > 100, "Mpfr<54> rounded to f64 matched f64 too often ({m54} mismatches)");
    assert!(m52 > 100, "Mpfr<52> matched f64 too often ({m52} mismatches)");
}

/// Every op kind in the random programs is really exercised.
#[test]
fn random_programs_cover_every_operation() {
    let mut rng = Rng(0xf32);
    let mut counts = [0usize; OP_NAMES.len()];
    for _ in 0..PROGRAMS {
        for (_, op) in run_program::<f32>(&random_program(&mut rng, PROGRAM_LEN)) {
            counts[OP_NAMES.iter().position(|n| *n == op).unwrap()] += 1;
        }
    }
    for (name, count) in OP_NAMES.iter().zip(counts) {
        assert!(count > 1000, "operation {name} ran only {count} times");
    }
}

/// The crate's geometry kernels (plane distance, closest point) built from
/// those operations are bit-exact too.
fn geometry_trace<T: Real>(seed: u64) -> Vec<u64> {
    let mut rng = Rng(seed);
    let mut out = Vec::new();
    for _ in 0..2000 {
        let mut v = || vec3::<T>(rng.grid(), rng.grid(), rng.grid());
        let tri = Triangle::new(v(), v(), v());
        let p = v();
        if let Some(plane) = Plane::from_triangle(&tri) {
            out.push(plane.signed_distance(&p).to_f64().to_bits());
        }
        let (q, feature) = closest_point_on_triangle(&p, &tri);
        out.extend(q.iter().map(|x| x.to_f64().to_bits()));
        out.extend(cross_of_edges(&tri.a, &tri.b, &tri.c).iter().map(|x| x.to_f64().to_bits()));
        out.push(match feature {
            Feature::Face => 0,
            Feature::Edge(i) => 1 + u64::from(i),
            Feature::Vertex(i) => 4 + u64::from(i),
        });
    }
    out
}

#[test]
fn geometry_kernels_are_bit_exact_across_backends() {
    assert_eq!(geometry_trace::<f32>(7), geometry_trace::<Mpfr<24>>(7));
    assert_eq!(geometry_trace::<f64>(7), geometry_trace::<Mpfr<53>>(7));
    // And the comparison can fail: f32 and f64 disagree somewhere.
    assert_ne!(geometry_trace::<f32>(7), geometry_trace::<f64>(7));
}
