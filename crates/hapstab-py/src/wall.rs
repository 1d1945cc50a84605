//! The virtual wall a call is about, from its keyword arguments: K in N/m and B in Ns/m, or
//! the paper's normalized α = KT²/m and β = BT/m (Table I).

use hapstab::AffineFamily;
use hapstab::System;
use hapstab::model::PlantModel;
use hapstab::params::Wall;
use pyo3::prelude::*;

use crate::errors::{Context, bad, finite};
use crate::loops::PyLoop;

/// The wall's keyword arguments as given.
#[derive(Debug, Clone, Copy)]
pub struct WallArgs {
    pub stiffness: Option<f64>,
    pub damping: Option<f64>,
    pub alpha: Option<f64>,
    pub beta: Option<f64>,
}

impl WallArgs {
    /// The loop's analysis object and the wall on it, from a call's wall keywords
    /// (wall_stiffness, wall_damping, alpha, beta), checked by [`WallArgs::resolve`].
    pub fn system_and_wall(
        lp: &PyLoop,
        stiffness: Option<f64>,
        damping: Option<f64>,
        alpha: Option<f64>,
        beta: Option<f64>,
    ) -> PyResult<(System, Wall)> {
        let sys = lp.system()?;
        let args = Self {
            stiffness,
            damping,
            alpha,
            beta,
        };
        let w = args.resolve(lp, sys.family())?;
        Ok((sys, w))
    }

    /// The wall in N/m and Ns/m. α, β on a physical mass-spring-damper loop convert by
    /// K = α·m/T², B = β·m/T; on a normalized loop they are K and B.
    pub fn resolve(&self, lp: &PyLoop, fam: &AffineFamily) -> PyResult<Wall> {
        let w = self.given(lp, fam)?;
        let normalized = self.alpha.is_some() || lp.normalized;
        let units = fam.to_units(w.stiffness, w.damping);
        hapstab::model::check_wall_range(fam, w, units, normalized).py()?;
        Ok(w)
    }

    /// The wall as given, before the range check of [`WallArgs::resolve`].
    fn given(&self, lp: &PyLoop, fam: &AffineFamily) -> PyResult<Wall> {
        match (self.stiffness, self.damping, self.alpha, self.beta) {
            (None, None, Some(a), Some(b)) => normalized_wall(lp, fam, a, b),
            (Some(k), Some(b), None, None) => Ok(Wall {
                stiffness: finite("wall_stiffness", k)?,
                damping: finite("wall_damping", b)?,
            }),
            (_, _, None, None) => Err(bad(
                "wall_stiffness, wall_damping",
                "give both the wall's stiffness K in N/m and its damping B in Ns/m",
            )),
            (None, None, _, _) => Err(bad(
                "alpha, beta",
                "give both the normalized stiffness α and damping β",
            )),
            _ => Err(bad(
                "wall_stiffness, wall_damping, alpha, beta",
                "give the wall either as wall_stiffness/wall_damping (N/m, Ns/m) or as alpha/beta (normalized), not both",
            )),
        }
    }
}

fn normalized_wall(lp: &PyLoop, fam: &AffineFamily, alpha: f64, beta: f64) -> PyResult<Wall> {
    let (alpha, beta) = (finite("alpha", alpha)?, finite("beta", beta)?);
    if lp.normalized {
        return Ok(Wall {
            stiffness: alpha,
            damping: beta,
        });
    }
    if !matches!(lp.lp.plant.model, PlantModel::MassSpringDamper(_)) {
        return Err(bad(
            "alpha, beta",
            "are normalized by the paper's mass m; give wall_stiffness/wall_damping for this plant",
        ));
    }
    let (stiffness, damping) = fam.to_physical(alpha, beta);
    Ok(Wall { stiffness, damping })
}
