//! Numerical helpers shared by the physics: dense solves, elliptic integrals, interpolation,
//! quadrature, roots, splines.

pub mod dense;
pub mod elliptic;
pub mod interp;
pub mod quadrature;
pub mod roots;
pub mod spline;
