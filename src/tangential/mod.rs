//! Tangential contact: Kalker's creep coefficients, FASTSIM, FaStrip and their strip-patch forms.
//!
//! * [`kalker`] — the linear theory's creep coefficients C11, C22, C23;
//! * [`fastsim`] — FASTSIM on an ellipse (and its packed lanes);
//! * [`fastrip`] — FaStrip;
//! * [`strip_fastsim`] — FASTSIM and FaStrip on the strips of a non-elliptic patch;
//! * [`patch`] — the tangential model of a strip patch and its equivalent ellipse.

pub mod fastrip;
pub mod fastsim;
pub mod kalker;
pub mod patch;
pub mod strip_coefficients;
pub mod strip_fastsim;
