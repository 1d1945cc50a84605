//! The `--csv` file of `hapstab locus`: one row per root and stiffness.

use std::path::Path;

use anyhow::Result;
use hapstab::locus::RootLocus;

use crate::output::csv_num;

/// One row per root and stiffness.
pub(super) fn write_csv(path: &Path, l: &RootLocus) -> Result<()> {
    let mut w = csv::Writer::from_path(path)?;
    w.write_record(["stiffness_n_per_m", "branch", "re", "im", "modulus"])?;
    for (k, roots) in l.stiffness.iter().zip(&l.roots) {
        for (i, z) in roots.iter().enumerate() {
            w.write_record([
                csv_num(*k),
                i.to_string(),
                csv_num(z.re),
                csv_num(z.im),
                csv_num(z.norm()),
            ])?;
        }
    }
    w.flush()?;
    Ok(())
}
