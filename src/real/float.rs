//! [`Real`] for the hardware floats `f32` and `f64`.

use super::Real;

macro_rules! impl_real_for_float {
    ($t:ty, $name:literal, $to:ident, $dop:ident) => {
        impl Real for $t {
            #[inline]
            fn bits() -> u32 {
                <$t>::MANTISSA_DIGITS
            }
            fn name() -> String {
                $name.to_string()
            }
            #[inline]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline]
            fn to_f64(&self) -> f64 {
                *self as f64
            }
            #[inline]
            fn sqrt(&self) -> Self {
                <$t>::sqrt(*self)
            }
            #[inline]
            fn abs(&self) -> Self {
                <$t>::abs(*self)
            }
            #[inline]
            fn mul_add(&self, a: &Self, b: &Self) -> Self {
                <$t>::mul_add(*self, *a, *b)
            }
            #[inline]
            fn diff_of_products(a: &Self, b: &Self, c: &Self, d: &Self) -> Self {
                $dop(*a, *b, *c, *d)
            }
            #[inline]
            fn is_finite(&self) -> bool {
                <$t>::is_finite(*self)
            }
            #[inline]
            fn is_sign_negative(&self) -> bool {
                <$t>::is_sign_negative(*self)
            }
            #[cfg(feature = "mpfr")]
            fn to_rug(&self) -> rug::Float {
                rug::Float::with_val(<$t>::MANTISSA_DIGITS, *self)
            }
            #[cfg(feature = "mpfr")]
            fn from_rug(x: &rug::Float) -> Self {
                x.$to()
            }
        }
    };
}

impl_real_for_float!(f32, "f32", to_f32, f32_diff_of_products);
impl_real_for_float!(f64, "f64", to_f64, f64_diff_of_products);

/// Exact products of two `f32` fit in an `f64` (48 of its 53 bits), so
/// `a b - c d` is computed with one rounding in `f64` and one to `f32`:
/// within `2u` like Kahan's algorithm, without a (software) fused
/// multiply-add.
fn f32_diff_of_products(a: f32, b: f32, c: f32, d: f32) -> f32 {
    (a as f64 * b as f64 - c as f64 * d as f64) as f32
}

/// Dekker's exact product: `a * b = p + e` exactly (Veltkamp splitting, no
/// fused multiply-add needed; exact barring overflow and underflow).
fn two_product(a: f64, b: f64) -> (f64, f64) {
    const SPLIT: f64 = 134_217_729.0; // 2^27 + 1
    let split = |x: f64| {
        let t = SPLIT * x;
        let hi = t - (t - x);
        (hi, x - hi)
    };
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    let e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    (p, e)
}

/// `a b - c d` in `f64` from exact products (Dekker): `p - q` is exact
/// when the products nearly cancel, so the error is at most about
/// `u |a b - c d| + 2u^2 |a b|`.
fn f64_diff_of_products(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let (p, ep) = two_product(a, b);
    let (q, eq) = two_product(c, d);
    (p - q) + (ep - eq)
}
