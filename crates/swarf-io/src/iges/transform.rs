//! Entity 124 (transformation matrix, IGES 5.3 sec. 4.21): `x' = R x + T` with the
//! 3x3 `R` and `T` given row by row as `R11 R12 R13 T1 R21 ... T3`. An entity's DE
//! field 7 points to its 124; a 124 may itself point to another, applied after it.

use super::{Iges, MAX_DEPTH};
use crate::error::IoError;
use swarf_geom::Point3;

/// An affine map `x -> r x + t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Affine {
    r: [[f64; 3]; 3],
    t: [f64; 3],
}

impl Affine {
    /// The identity.
    pub const IDENTITY: Affine = Affine {
        r: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        t: [0.0; 3],
    };

    /// The image of `p`.
    pub fn apply(&self, p: &Point3) -> Point3 {
        let c = [p.x, p.y, p.z];
        let row =
            |k: usize| self.r[k][0] * c[0] + self.r[k][1] * c[1] + self.r[k][2] * c[2] + self.t[k];
        Point3::new(row(0), row(1), row(2))
    }

    /// `other` after `self`.
    fn then(&self, other: &Affine) -> Affine {
        let mut out = Affine::IDENTITY;
        for i in 0..3 {
            for j in 0..3 {
                out.r[i][j] = (0..3).map(|k| other.r[i][k] * self.r[k][j]).sum();
            }
            out.t[i] = (0..3).map(|k| other.r[i][k] * self.t[k]).sum::<f64>() + other.t[i];
        }
        out
    }
}

impl Iges<'_> {
    /// The map from entity `de`'s definition space to model space (identity when its
    /// DE field 7 is 0).
    ///
    /// # Errors
    /// A pointer that is not a 124, bad matrix values, or a chain deeper than
    /// [`MAX_DEPTH`] (a cycle).
    pub(crate) fn transform_of(&self, de: usize) -> Result<Affine, IoError> {
        let mut map = Affine::IDENTITY;
        let mut at = self.entry(de, &format!("DE {de}"))?.transform;
        let mut depth = 0;
        while at != 0 {
            depth += 1;
            if depth > MAX_DEPTH {
                return Err(self.err(
                    de,
                    format!(
                        "transformation matrix chain deeper than {MAX_DEPTH}; expected no cycle"
                    ),
                ));
            }
            let e = self.entry(at, &format!("DE {de} field 7 (transformation matrix)"))?;
            if e.ty != 124 {
                return Err(self.err(de, format!("field 7 points to DE {at} of type {}; expected a 124 transformation matrix", e.ty)));
            }
            let p = self.params(at, "transformation matrix")?;
            let v = p.reals(self, 1, 12)?;
            let m = Affine {
                r: [[v[0], v[1], v[2]], [v[4], v[5], v[6]], [v[8], v[9], v[10]]],
                t: [v[3], v[7], v[11]],
            };
            map = map.then(&m);
            at = e.transform;
        }
        Ok(map)
    }
}
