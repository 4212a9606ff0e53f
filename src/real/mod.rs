//! The `Real` trait: one scalar interface for `f32`, `f64` and MPFR floats.
//!
//! Every algorithm in this crate is written once, generic over [`Real`], and
//! instantiated per backend. The trait is deliberately small: exactly the
//! operations the algorithms use, each with IEEE-754 round-to-nearest
//! semantics (one rounding per operation, including [`Real::mul_add`]).
//!
//! `num_traits::Float` is not used because it requires `Copy`, which an
//! arbitrary-precision MPFR value (heap-allocated limbs) cannot be. Instead
//! the trait builds on [`nalgebra::Scalar`] and nalgebra's `Closed*Assign`
//! traits so that `nalgebra::Vector3<T>` arithmetic works for every backend.
//!
//! # Faithfulness of the MPFR backend
//! [`Mpfr<24>`] rounds exactly like `f32` and [`Mpfr<53>`] exactly like `f64`
//! for every operation whose operands and result lie in the normal range
//! (MPFR's exponent range is wider, so overflow and subnormal results
//! differ). The test suite checks this bit for bit over thousands of random
//! operation sequences, which makes `Mpfr<BITS>` a continuous precision dial.

mod float;
#[cfg(feature = "mpfr")]
mod mpfr;

#[cfg(feature = "mpfr")]
pub use mpfr::{DYNAMIC, MAX_BITS, MIN_BITS, Mpfr, MpfrDyn, with_precision};

use nalgebra::{ClosedAddAssign, ClosedDivAssign, ClosedMulAssign, ClosedSubAssign, Scalar};
use num_traits::{One, Zero};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A real-number backend: `f32`, `f64` or [`Mpfr<BITS>`](Mpfr).
///
/// Arithmetic is available by value (`a + b`) and with a borrowed right-hand
/// side (`a + &b`), so MPFR code need not clone the right operand. All
/// operations round to nearest, ties to even, once per operation.
pub trait Real:
    Scalar
    + Zero
    + One
    + PartialOrd
    + ClosedAddAssign
    + ClosedSubAssign
    + ClosedMulAssign
    + ClosedDivAssign
    + Neg<Output = Self>
    + for<'a> Add<&'a Self, Output = Self>
    + for<'a> Sub<&'a Self, Output = Self>
    + for<'a> Mul<&'a Self, Output = Self>
    + for<'a> Div<&'a Self, Output = Self>
    + Send
    + Sync
{
    /// Significand precision in bits, the implicit leading bit included
    /// (24 for `f32`, 53 for `f64`, `BITS` for `Mpfr<BITS>`).
    fn bits() -> u32;

    /// A short name for reports and the command line: `f32`, `f64`,
    /// `mpfr<BITS>` (for example `mpfr53`).
    fn name() -> String;

    /// Converts from `f64`, rounding to nearest. Exact whenever the value is
    /// representable in this backend (always for `f64` and `Mpfr<BITS>` with
    /// `BITS >= 53`).
    fn from_f64(x: f64) -> Self;

    /// Converts to `f64`, rounding to nearest. Exact for `f32`, `f64` and
    /// `Mpfr<BITS>` with `BITS <= 53` in the normal range.
    fn to_f64(&self) -> f64;

    /// Square root, correctly rounded.
    fn sqrt(&self) -> Self;

    /// Absolute value (exact).
    fn abs(&self) -> Self;

    /// `self * a + b` with a single rounding (fused multiply-add).
    fn mul_add(&self, a: &Self, b: &Self) -> Self;

    /// `true` unless the value is NaN or infinite.
    fn is_finite(&self) -> bool;

    /// The IEEE sign bit (`true` for `-0.0` and negative NaN too): the
    /// semantics of Fauerby's bit-level inside-triangle test.
    fn is_sign_negative(&self) -> bool;

    /// The next value of this precision above (`up`) or below: one ulp
    /// away, exact (infinities and NaN stay as they are).
    #[must_use]
    fn next_toward(&self, up: bool) -> Self;

    /// The value converted exactly to an MPFR float at its own precision.
    #[cfg(feature = "mpfr")]
    fn to_rug(&self) -> rug::Float;

    /// An MPFR value rounded to nearest in this backend (exact when
    /// representable).
    #[cfg(feature = "mpfr")]
    fn from_rug(x: &rug::Float) -> Self;

    /// Unit roundoff `u = 2^-bits`: the largest relative error of one
    /// correctly rounded operation in the normal range.
    ///
    /// Exact up to [`FINEST_BITS`] bits; beyond, `2^-FINEST_BITS`. Every
    /// tolerance is a multiple of `u` formed in `f64` (`k u s`, `s >= 1`
    /// a magnitude), so `u` must stay a normal `f64` with room below it:
    /// as `2^-bits` it would underflow to zero from 1,075 bits on (and to a
    /// subnormal from 1,023), leaving every tolerance zero and the robust
    /// response frozen. The floor makes those tolerances wider than the
    /// rounding needs, never narrower.
    #[must_use]
    fn unit_roundoff() -> f64 {
        power_of_two(-i64::from(Self::bits().min(FINEST_BITS)))
    }

    /// Machine epsilon `2 u`: the gap between 1 and the next value (floored
    /// as [`Real::unit_roundoff`]).
    #[must_use]
    fn machine_epsilon() -> f64 {
        2.0 * Self::unit_roundoff()
    }

    /// The smallest positive normal value, as an `f64`: below it results
    /// lose bits to gradual underflow (products' rounding errors are no
    /// longer representable exactly). `f32::MIN_POSITIVE` and
    /// `f64::MIN_POSITIVE`; 0 for MPFR, whose exponent range reaches far
    /// beyond `f64`'s.
    #[must_use]
    fn min_positive_normal() -> f64 {
        0.0
    }

    /// The smaller of two values (`self` when they compare equal or
    /// unordered).
    #[must_use]
    fn min(self, other: Self) -> Self {
        if other < self { other } else { self }
    }

    /// The larger of two values (`self` when they compare equal or
    /// unordered).
    #[must_use]
    fn max(self, other: Self) -> Self {
        if other > self { other } else { self }
    }

    /// `self.max(other.abs())` (exact), for a running maximum of
    /// magnitudes: a backend whose values live on the heap compares the
    /// magnitudes first and builds `|other|` only when it wins.
    #[must_use]
    fn max_abs_of(self, other: &Self) -> Self {
        self.max(other.abs())
    }

    /// A value converted from `f64` (shorthand used by the algorithms for
    /// their constants, so every backend starts from the same bits).
    #[must_use]
    fn c(x: f64) -> Self {
        Self::from_f64(x)
    }

    /// The precision this value carries, for a backend whose values keep
    /// the precision they were created with while [`Real::bits`] is a
    /// thread's setting ([`MpfrDyn`]); `None` for the
    /// fixed-precision backends. [`crate::respond::move_body`] refuses
    /// inputs whose precision differs from the thread's.
    #[must_use]
    fn own_bits(&self) -> Option<u32> {
        None
    }

    /// Runs `f` with this backend computing at `bits` bits on the current
    /// thread, for work handed to other threads: [`MpfrDyn`]'s
    /// precision is a per-thread setting, so a worker must take the
    /// caller's [`Real::bits`] (as [`crate::respond::move_bodies`] does).
    /// For every other backend `f` simply runs, whatever `bits` says.
    ///
    /// # Errors
    /// [`crate::Error::PrecisionOutOfRange`] for [`MpfrDyn`] unless
    /// `MIN_BITS <= bits <= MAX_BITS` (`f` does not run).
    fn with_bits<R>(bits: u32, f: impl FnOnce() -> R) -> Result<R, crate::Error> {
        let _ = bits;
        Ok(f())
    }
}

/// The finest precision whose unit roundoff the tolerances use
/// ([`Real::unit_roundoff`]): `2^-960` leaves 62 binary orders of
/// magnitude above `f64`'s smallest normal for the tolerances' factors.
pub const FINEST_BITS: u32 = 960;

/// `2^e` exactly for `-1022 <= e <= 1023`, built from its bit pattern (no
/// `exp2` call on the hot path).
#[inline]
fn power_of_two(e: i64) -> f64 {
    debug_assert!((-1022..=1023).contains(&e));
    f64::from_bits(((e + 1023) as u64) << 52)
}
