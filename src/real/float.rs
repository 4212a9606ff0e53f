//! [`Real`] for the hardware floats `f32` and `f64`.

use super::Real;

macro_rules! impl_real_for_float {
    ($t:ty, $name:literal, $to:ident) => {
        impl Real for $t {
            #[inline]
            fn bits() -> u32 {
                <$t>::MANTISSA_DIGITS
            }
            fn name() -> String {
                $name.to_string()
            }
            #[inline]
            fn min_positive_normal() -> f64 {
                f64::from(<$t>::MIN_POSITIVE)
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
            fn is_finite(&self) -> bool {
                <$t>::is_finite(*self)
            }
            #[inline]
            fn is_sign_negative(&self) -> bool {
                <$t>::is_sign_negative(*self)
            }
            #[inline]
            fn next_toward(&self, up: bool) -> Self {
                if !<$t>::is_finite(*self) {
                    *self
                } else if up {
                    <$t>::next_up(*self)
                } else {
                    <$t>::next_down(*self)
                }
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

impl_real_for_float!(f32, "f32", to_f32);
impl_real_for_float!(f64, "f64", to_f64);
