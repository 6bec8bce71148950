//! The rectangular grid of uniformly loaded elements.

use railcontact::error::{require_finite, require_positive, InputError};

/// A uniform grid of nx × ny rectangular elements; element (i, j) has its centre at
/// (x0 + (i + ½) dx, y0 + (j + ½) dy) and fields are stored row-major, index `j * nx + i`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Number of elements along x [-].
    pub nx: usize,
    /// Number of elements along y [-].
    pub ny: usize,
    /// Element size along x [m].
    pub dx: f64,
    /// Element size along y [m].
    pub dy: f64,
    /// x of the grid's lower edge [m].
    pub x0: f64,
    /// y of the grid's lower edge [m].
    pub y0: f64,
}

impl Grid {
    /// Grid of nx × ny elements of size dx × dy centred on the origin. With odd nx (ny) an element
    /// centre lies on x = 0 (y = 0).
    pub fn centred(nx: usize, ny: usize, dx: f64, dy: f64) -> Self {
        Self {
            nx,
            ny,
            dx,
            dy,
            x0: -0.5 * nx as f64 * dx,
            y0: -0.5 * ny as f64 * dy,
        }
    }

    /// Number of elements nx · ny.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// True when the grid has no element.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// x of the centre of column i [m].
    pub fn x(&self, i: usize) -> f64 {
        self.x0 + (i as f64 + 0.5) * self.dx
    }

    /// y of the centre of row j [m].
    pub fn y(&self, j: usize) -> f64 {
        self.y0 + (j as f64 + 0.5) * self.dy
    }

    /// Element area dx · dy [m²].
    pub fn element_area(&self) -> f64 {
        self.dx * self.dy
    }

    /// `f(x, y)` at every element centre, row-major (e.g. the undeformed gap).
    pub fn sample(&self, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        let mut v = Vec::with_capacity(self.len());
        for j in 0..self.ny {
            for i in 0..self.nx {
                v.push(f(self.x(i), self.y(j)));
            }
        }
        v
    }

    /// At least one element, positive finite sizes, finite origin.
    pub fn validate(&self) -> Result<(), InputError> {
        if self.nx == 0 {
            return Err(InputError::new("nx", 0.0, ">= 1"));
        }
        if self.ny == 0 {
            return Err(InputError::new("ny", 0.0, ">= 1"));
        }
        require_positive("dx", self.dx)?;
        require_positive("dy", self.dy)?;
        require_finite("x0", self.x0)?;
        require_finite("y0", self.y0)?;
        Ok(())
    }

    /// Checks that a field has one value per element.
    pub(crate) fn check_field(&self, name: &'static str, field: &[f64]) -> Result<(), InputError> {
        if field.len() == self.len() {
            Ok(())
        } else {
            Err(InputError::new(name, field.len() as f64, "nx * ny"))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centred_grid_and_sampling() {
        let g = Grid::centred(3, 2, 1e-3, 2e-3);
        assert_eq!((g.len(), g.is_empty()), (6, false));
        assert_eq!((g.x(1), g.y(0), g.y(1)), (0.0, -1e-3, 1e-3));
        assert_eq!(g.element_area(), 2e-6);
        // Row-major: x runs fastest.
        assert_eq!(g.sample(|x, y| x + 10.0 * y)[1], g.x(1) + 10.0 * g.y(0));
        assert!(g.validate().is_ok());
        assert!(Grid::centred(0, 2, 1e-3, 1e-3).validate().is_err());
        assert!(Grid::centred(2, 2, 0.0, 1e-3).validate().is_err());
        assert!(g.check_field("gap", &[0.0; 5]).is_err());
    }
}
