//! The loops of `hapstab zwidth --compare`: loop flags re-parsed over the base loop's.

use anyhow::{Result, anyhow, bail};
use clap::parser::ValueSource;
use clap::{ArgAction, CommandFactory, FromArgMatches, Parser};

use crate::model::LoopArgs;

/// Re-parses loop flags on top of the base loop's (for --compare).
#[derive(Parser)]
#[command(no_binary_name = true)]
pub(super) struct Override {
    #[command(flatten)]
    pub(super) lp: LoopArgs,
}

/// The loop flags of a --compare spec applied over the base flags.
pub(super) fn compared(base: &LoopArgs, spec: &str) -> Result<LoopArgs> {
    let tokens: Vec<String> = if spec.trim_start().starts_with("--") {
        spec.split_whitespace().map(String::from).collect()
    } else {
        vec!["--velocity".into(), spec.trim().into()]
    };
    let err = |e: clap::Error| {
        let text = e.render().to_string();
        let line = text.lines().next().unwrap_or("invalid flags").to_string();
        anyhow!("--compare '{spec}': {}", line.trim_start_matches("error: "))
    };
    let matches = Override::command()
        .try_get_matches_from(&tokens)
        .map_err(err)?;
    let mut o = Override { lp: base.clone() };
    o.update_from_arg_matches(&matches).map_err(err)?;
    // clap updates an on/off flag even when it is absent (its default "false" counts as
    // given): keep the base loop's value of every flag the spec does not name.
    for id in switch_ids() {
        if matches.value_source(id.as_str()) != Some(ValueSource::CommandLine) {
            restore_switch(&mut o.lp, base, id.as_str())?;
        }
    }
    Ok(o.lp)
}

/// The ids of the on/off flags of the loop flags.
pub(super) fn switch_ids() -> Vec<clap::Id> {
    Override::command()
        .get_arguments()
        .filter(|a| matches!(a.get_action(), ArgAction::SetTrue | ArgAction::SetFalse))
        .map(|a| a.get_id().clone())
        .collect()
}

/// Copies one on/off flag from the base loop flags.
pub(super) fn restore_switch(lp: &mut LoopArgs, base: &LoopArgs, id: &str) -> Result<()> {
    match id {
        "no_arm" => lp.plant.no_arm = base.plant.no_arm,
        _ => bail!("internal: the loop flag --{id} is not handled by --compare"),
    }
    Ok(())
}
