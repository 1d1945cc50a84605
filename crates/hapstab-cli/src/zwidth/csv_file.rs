//! The `--csv` file of `hapstab zwidth`.

use anyhow::{Context, Result};
use hapstab::answer::ZwidthLoop as LoopOut;

use crate::output::{csv_num, csv_opt};

pub(super) fn write_csv(path: &std::path::Path, out: &[LoopOut]) -> Result<()> {
    let mut w =
        csv::Writer::from_path(path).with_context(|| format!("cannot write {}", path.display()))?;
    w.write_record([
        "loop",
        "damping",
        "k_max",
        "k_min",
        "k_max_passive",
        "k_linear",
    ])?;
    let cell = csv_opt;
    for o in out {
        for r in &o.zwidth.table {
            w.write_record([
                o.label.clone(),
                csv_num(r.damping),
                cell(r.k_max),
                cell(r.k_min),
                cell(r.k_max_passive),
                cell(r.k_linear),
            ])?;
        }
    }
    w.flush()?;
    Ok(())
}
