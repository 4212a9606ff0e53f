//! # sweepslide
//!
//! Collide-and-slide for a sphere or axis-aligned ellipsoid swept against a
//! static triangle soup: detection of the first touch, then a collision
//! response that stops the body just short of it and slides it along what it
//! touched. Three responses run side by side (Fauerby's recursive
//! `collideWithWorld`, Linahan's iterative `sphere_sweep` and our robust
//! successor), every one generic over the [`Real`] backend (`f32`, `f64`,
//! MPFR at any precision).
//!
//! Numerical sources: Fauerby, *Improved Collision detection and Response*
//! (2003); Linahan, *Improving the Numerical Robustness of Sphere Swept
//! Collision Detection* (2012); Ericson, *Real-Time Collision Detection*
//! (2005) for closest points; Higham, *Accuracy and Stability of Numerical
//! Algorithms* (2002) for the error bounds quoted in the docs.
#![warn(missing_docs)]
// Comparisons are written `!(a > b)` on purpose wherever a NaN must take the
// rejecting branch; clippy's suggested rewrite would change that.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod detect;
pub mod error;
pub mod geom;
#[cfg(feature = "lab")]
pub mod lab;
pub mod real;
#[cfg(feature = "cli")]
pub mod report;
pub mod respond;
pub mod world;

pub use error::{Error, Result};
/// The `nalgebra` this crate's vectors ([`geom::Vec3`]) come from, so that
/// a caller can name its types without pinning the same version.
pub use nalgebra;
pub use real::Real;
#[cfg(feature = "mpfr")]
pub use real::{Mpfr, MpfrDyn};
