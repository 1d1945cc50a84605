//! The wall flags ([`WallArgs`]): (α, β) or (K, B), resolved in a loop's units.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::model::PlantModel as LibPlantModel;
use hapstab::params::Wall;
use hapstab::{AffineFamily, Param};

use super::{DEFAULT_WALL, ResolvedLoop};

/// A wall in either unit system.
#[derive(Args, Debug, Clone, Default)]
pub struct WallArgs {
    /// Normalized virtual stiffness α = KT²/m (the paper's plant only).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["wall_stiffness", "wall_damping"])]
    pub alpha: Option<f64>,
    /// Normalized virtual damping β = BT/m (the paper's plant only).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["wall_stiffness", "wall_damping"])]
    pub beta: Option<f64>,
    /// Virtual stiffness K in N/m [default: 10000 in physical mode].
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["gamma", "delta"])]
    pub wall_stiffness: Option<f64>,
    /// Virtual damping B in Ns/m [default: 10 in physical mode].
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["gamma", "delta"])]
    pub wall_damping: Option<f64>,
}

impl WallArgs {
    /// True when the wall is given normalized (--alpha/--beta).
    pub fn normalized(&self) -> bool {
        self.alpha.is_some() || self.beta.is_some()
    }

    /// The wall flags with the --loop file's wall (if any) where they give none: α and β for
    /// a normalized loop, else K and B (unless the flags give a normalized wall).
    pub fn over_file(&self, rl: &ResolvedLoop) -> WallArgs {
        let mut w = self.clone();
        if let Some(f) = rl.wall {
            if rl.normalized {
                w.alpha.get_or_insert(f.stiffness);
                w.beta.get_or_insert(f.damping);
            } else if !self.normalized() {
                w.wall_stiffness.get_or_insert(f.stiffness);
                w.wall_damping.get_or_insert(f.damping);
            }
        }
        w
    }
}

/// The wall of a resolved loop in the loop's units: K in N/m and B in Ns/m, or (α, β) for a
/// normalized loop. --alpha/--beta on a physical mass-spring-damper plant convert by
/// K = α·m/T², B = β·m/T (Table I).
pub fn resolve_loop_wall(rl: &ResolvedLoop, fam: &AffineFamily, wall: &WallArgs) -> Result<Wall> {
    let wall = &wall.over_file(rl);
    if rl.normalized || wall.normalized() {
        let (Some(alpha), Some(beta)) = (wall.alpha, wall.beta) else {
            bail!("a normalized wall needs both --alpha and --beta");
        };
        hapstab::Normalized::new(alpha, beta, 0.0, 0.0, 0)?;
        if rl.normalized {
            let w = Wall {
                stiffness: alpha,
                damping: beta,
            };
            check_wall_range(fam, w, true)?;
            return Ok(w);
        }
        if !matches!(rl.lp.plant.model, LibPlantModel::MassSpringDamper(_)) {
            bail!(
                "--alpha/--beta are normalized by the paper's mass m; give --wall-stiffness/--wall-damping for this plant"
            );
        }
        let (stiffness, damping) = fam.to_physical(alpha, beta);
        let w = Wall { stiffness, damping };
        check_wall_range(fam, w, false)?;
        return Ok(w);
    }
    let w = Wall {
        stiffness: wall.wall_stiffness.unwrap_or(DEFAULT_WALL.stiffness),
        damping: wall.wall_damping.unwrap_or(DEFAULT_WALL.damping),
    };
    if !w.stiffness.is_finite() {
        bail!(
            "wall stiffness K must be a finite number (got {})",
            w.stiffness
        );
    }
    if !w.damping.is_finite() {
        bail!("wall damping B must be a finite number (got {})", w.damping);
    }
    check_wall_range(fam, w, false)?;
    Ok(w)
}

/// Refuses a wall beyond the representable range ([`hapstab::model::check_wall_range`]),
/// naming its flag: --wall-stiffness/--wall-damping, or --alpha/--beta for a normalized loop.
fn check_wall_range(fam: &AffineFamily, w: Wall, normalized: bool) -> Result<()> {
    let units = fam.to_units(w.stiffness, w.damping);
    hapstab::model::check_wall_range(fam, w, units, normalized).map_err(|e| {
        match e.param().and_then(Param::flag) {
            Some(flag) => anyhow::anyhow!("{flag}: {e}"),
            None => e.into(),
        }
    })
}
