//! Numerical helpers shared by the physics: elliptic integrals, splines, interpolation, roots.

pub mod elliptic;
pub mod interp;
pub mod roots;
pub mod spline;
