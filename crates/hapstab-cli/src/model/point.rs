//! One parameter point from the plant and wall flags ([`resolve_point`]).

use anyhow::{Result, bail};
use hapstab::paper::Normalized;
use hapstab::params::{Physical, Wall};

use super::{DEFAULT_WALL, PlantArgs, WallArgs};

/// A fully resolved model for one parameter point.
#[derive(Debug, Clone, Copy)]
pub struct PointModel {
    /// Normalized parameters.
    pub normalized: Normalized,
    /// Physical description, when given in physical units.
    pub physical: Option<Physical>,
}

/// Resolves plant and wall arguments to one parameter point.
pub fn resolve_point(plant: &PlantArgs, wall: &WallArgs) -> Result<PointModel> {
    let normalized_wall = wall.alpha.is_some() || wall.beta.is_some();
    // --alpha/--beta without any physical flag: normalized mode with γ = δ = 0 by default.
    let pm = if normalized_wall && !plant.any_physical() {
        let mut p = plant.clone();
        p.gamma = Some(p.gamma.unwrap_or(0.0));
        p.resolve()?
    } else {
        plant.resolve()?
    };
    let physical_wall = wall.wall_stiffness.is_some() || wall.wall_damping.is_some();
    match pm.physical {
        None => {
            if physical_wall {
                bail!(
                    "--wall-stiffness/--wall-damping need a physical plant; use --alpha/--beta with --gamma/--delta"
                );
            }
            let (Some(alpha), Some(beta)) = (wall.alpha, wall.beta) else {
                bail!("normalized mode needs both --alpha and --beta");
            };
            Ok(PointModel {
                normalized: Normalized::new(alpha, beta, pm.gamma, pm.delta, pm.d)?,
                physical: None,
            })
        }
        Some((eff, s)) => {
            if normalized_wall {
                if physical_wall {
                    bail!(
                        "give the wall either as --alpha/--beta or as --wall-stiffness/--wall-damping"
                    );
                }
                let (Some(alpha), Some(beta)) = (wall.alpha, wall.beta) else {
                    bail!("give both --alpha and --beta");
                };
                let w = hapstab::paper::wall_from_normalized(alpha, beta, eff.mass, s.period);
                let phys = Physical::new(eff, w, s)?;
                return Ok(PointModel {
                    normalized: phys.normalized()?,
                    physical: Some(phys),
                });
            }
            let w = Wall {
                stiffness: wall.wall_stiffness.unwrap_or(DEFAULT_WALL.stiffness),
                damping: wall.wall_damping.unwrap_or(DEFAULT_WALL.damping),
            };
            let phys = Physical::new(eff, w, s)?;
            Ok(PointModel {
                normalized: phys.normalized()?,
                physical: Some(phys),
            })
        }
    }
}
