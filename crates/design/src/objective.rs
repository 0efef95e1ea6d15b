//! What a design minimizes over its load cases: the worst load intensity
//! (the paper's), or the worst stress below the surface, the von Mises
//! stress `s = sqrt(3 J2)` or the largest shear (Tresca) `(s1 - s3) / 2`,
//! with its gradient in the stress tensor for the descent's model rows
//! (`crate::subsurface`).

use elcon_influence::Stress;
use faer::{Mat, Side};

/// What a design minimizes over its load cases.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Objective {
    /// The worst load intensity `max_k w_k F_k / (A_k r_l)` (the paper's).
    #[default]
    Pressure,
    /// The worst von Mises stress below the surface over r_l.
    VonMises,
    /// The worst largest shear stress (Tresca: half the principal
    /// stresses' spread) below the surface over r_l.
    MaxShear,
}

impl Objective {
    /// Every objective, in the order messages list them.
    pub const ALL: [Objective; 3] = [
        Objective::Pressure,
        Objective::VonMises,
        Objective::MaxShear,
    ];

    /// Its name in a scene's `design.objective`: "pressure", "von-mises",
    /// "max-shear"; [`FromStr`](std::str::FromStr) reads it back.
    pub const fn name(self) -> &'static str {
        match self {
            Objective::Pressure => "pressure",
            Objective::VonMises => "von-mises",
            Objective::MaxShear => "max-shear",
        }
    }

    /// Whether it is a stress below the surface (needs a body with a
    /// field).
    pub fn is_stress(self) -> bool {
        self != Objective::Pressure
    }

    /// Its stress measure of a tensor (0 for the pressure objective).
    pub fn measure(self, s: &Stress) -> f64 {
        match self {
            Objective::Pressure => 0.0,
            Objective::VonMises => s.von_mises(),
            Objective::MaxShear => s.tresca(),
        }
    }

    /// `ds/dsigma` at `s`, in the order (xx, yy, zz, xy, xz, yz), each
    /// shear counted for both of its tensor entries (so that
    /// `g . dsigma` is the measure's first-order change).
    pub fn gradient(self, s: &Stress) -> [f64; 6] {
        match self {
            Objective::Pressure => [0.0; 6],
            Objective::VonMises => {
                let vm = s.von_mises();
                if vm <= 0.0 {
                    return [0.0; 6];
                }
                let h = 0.5 / vm;
                [
                    h * (2.0 * s.xx - s.yy - s.zz),
                    h * (2.0 * s.yy - s.zz - s.xx),
                    h * (2.0 * s.zz - s.xx - s.yy),
                    3.0 * s.xy / vm,
                    3.0 * s.xz / vm,
                    3.0 * s.yz / vm,
                ]
            }
            Objective::MaxShear => tresca_gradient(s),
        }
    }
}

elcon_num::named!(Objective, "objective");
#[cfg(feature = "serde")]
elcon_num::named_serde!(Objective);

/// Tresca's gradient `(n1 n1^T - n3 n3^T) / 2` from the principal
/// directions (faer's self-adjoint eigensolver; eigenvalues increasing).
fn tresca_gradient(s: &Stress) -> [f64; 6] {
    let a = Mat::from_fn(3, 3, |i, j| match (i.min(j), i.max(j)) {
        (0, 0) => s.xx,
        (1, 1) => s.yy,
        (2, 2) => s.zz,
        (0, 1) => s.xy,
        (0, 2) => s.xz,
        _ => s.yz,
    });
    let Ok(eigen) = a.self_adjoint_eigen(Side::Lower) else {
        return [0.0; 6];
    };
    let u = eigen.U();
    let (n3, n1) = (u.col(0), u.col(2));
    let e = |i: usize, j: usize| 0.5 * (n1[i] * n1[j] - n3[i] * n3[j]);
    [
        e(0, 0),
        e(1, 1),
        e(2, 2),
        2.0 * e(0, 1),
        2.0 * e(0, 2),
        2.0 * e(1, 2),
    ]
}
