//! The crate's one error type.

use crate::respond::MAX_ROUNDS;
use std::fmt;
use std::path::PathBuf;

/// Everything that can go wrong with input given to this crate.
///
/// Bad input is always reported, never repaired silently: a triangle that
/// cannot be used is an error naming its index, an OBJ problem names its
/// line.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum Error {
    /// A coordinate (of a vertex, position, velocity, gravity, ...) is NaN
    /// or infinite.
    #[error("{what} has a non-finite coordinate ({value})")]
    NonFinite {
        /// What the coordinate belongs to, for example `vertex 12` or `velocity`.
        what: String,
        /// The offending value as given.
        value: f64,
    },
    /// A triangle whose three vertices are (nearly) collinear or coincide.
    #[error("triangle {index} is degenerate (zero area): {reason}")]
    DegenerateTriangle {
        /// Index of the triangle in the input.
        index: usize,
        /// Why it was rejected.
        reason: String,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {vertex}, but there are only {vertex_count} vertices")]
    VertexIndexOutOfRange {
        /// Index of the triangle.
        triangle: usize,
        /// The vertex index it names.
        vertex: usize,
        /// How many vertices there are.
        vertex_count: usize,
    },
    /// A mesh without any triangle.
    #[error("the mesh has no triangle")]
    EmptyMesh,
    /// A mesh whose every triangle is invalid (degenerate, non-finite, or
    /// naming a missing vertex), from the lenient constructors, which would
    /// otherwise have skipped them: the first one's error says why.
    #[error("none of the mesh's {count} triangle(s) is valid; the first: {first}")]
    NoValidTriangle {
        /// How many triangles were given.
        count: usize,
        /// Why the first was rejected (with its file and line for OBJ input).
        first: Box<Error>,
    },
    /// A radius that is zero, negative, NaN or infinite, or that the
    /// precision cannot hold as a normal number with a finite inverse
    /// ([`crate::geom::Ellipsoid::new`]).
    #[error(
        "radius along {axis} must be positive and finite, and a normal number of this precision (and of f64) whose \
         inverse is finite, got {}",
        Num(*.value)
    )]
    InvalidRadius {
        /// `x`, `y` or `z`.
        axis: char,
        /// The value given.
        value: f64,
    },
    /// An MPFR precision outside what MPFR and this crate support.
    #[error("precision of {bits} bits is out of range ({min}..={max})")]
    PrecisionOutOfRange {
        /// The precision asked for.
        bits: u32,
        /// The smallest accepted.
        min: u32,
        /// The largest accepted.
        max: u32,
    },
    /// A lab scene with zero velocity and no gravity: nothing would move
    /// (the lab's `run` refuses it). [`crate::respond::move_body`] never returns
    /// it: a still body is a valid move.
    #[error("velocity and gravity are both zero: nothing to simulate")]
    ZeroVelocity,
    /// A malformed Wavefront OBJ file.
    #[error("{path}:{line}: {message}")]
    Obj {
        /// The file.
        path: PathBuf,
        /// 1-based line number of the offending statement.
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// A file could not be read or written.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// A value that is out of its documented range (an option, a count, ...).
    #[error("{what}: {message}")]
    InvalidArgument {
        /// The argument.
        what: String,
        /// What is wrong with it.
        message: String,
    },
}

/// Shorthand for `Result<T, sweepslide::Error>`.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// The error for option `what` (kept out of line: a valid option costs a
/// comparison).
#[cold]
#[inline(never)]
pub(crate) fn out_of_range(what: &str, message: String) -> Error {
    Error::InvalidArgument { what: what.into(), message }
}

/// `Ok` for a finite `x >= 0`, else [`Error::InvalidArgument`] naming `what`.
#[inline(always)]
pub(crate) fn not_negative(what: &str, x: f64) -> Result<(), Error> {
    if (0.0..=f64::MAX).contains(&x) {
        Ok(())
    } else {
        Err(out_of_range(what, format!("must be finite and not negative, got {}", Num(x))))
    }
}

/// `Ok` for a finite `x > 0`, else [`Error::InvalidArgument`] naming `what`.
#[inline(always)]
pub(crate) fn positive(what: &str, x: f64) -> Result<(), Error> {
    if x > 0.0 && x <= f64::MAX {
        Ok(())
    } else {
        Err(out_of_range(what, format!("must be finite and positive, got {}", Num(x))))
    }
}

/// `Ok` for `least <= n <= MAX_ROUNDS`, else [`Error::InvalidArgument`]
/// naming `what`.
#[inline(always)]
pub(crate) fn count(what: &str, n: u32, least: u32) -> Result<(), Error> {
    if (least..=MAX_ROUNDS).contains(&n) {
        Ok(())
    } else {
        Err(out_of_range(what, format!("must lie in {least}..={MAX_ROUNDS}, got {n}")))
    }
}

/// A number as a message shows it: plainly between `1e-4` and `1e15`,
/// in scientific notation beyond (`1e-320` rather than its 320 digits).
pub(crate) struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}
