//! `hapstab kmax --robust --box NAME:LO:HI …`: robust K_max of any loop over a box of its
//! parameters, as text or JSON ([`hapstab_serve::robust_box`], the explorer's answer).

use anyhow::{Result, bail};
use hapstab::robust::{BoxSide, RobustOptions};
use hapstab_serve::robust_box::{answer, cost, text_lines};

use crate::model::{LoopArgs, print_loop};
use crate::output::print_json;

/// Runs the robust K_max of the resolved loop over the box at damping B (default 0).
pub fn run(
    args: &LoopArgs,
    sides: &[BoxSide],
    wall_damping: Option<f64>,
    opts: RobustOptions,
    json: bool,
) -> Result<()> {
    let rl = args.resolve(false)?;
    if rl.normalized {
        bail!("kmax --robust --box works in physical units");
    }
    let b = wall_damping.unwrap_or(0.0);
    let cost = cost(&rl.lp, sides, &opts)?;
    crate::budget::check_loop(args, &rl.lp, cost, "the robust K_max")?;
    let out = answer(&rl.lp, sides, b, opts)?;
    if json {
        return print_json(&out);
    }
    print_loop(&rl.lp);
    for line in text_lines(sides, &out.report) {
        println!("{line}");
    }
    Ok(())
}
