//! The bootstrap option: 95 % intervals of the parameters without the Jacobian's linear
//! approximation, by resampling the residuals (Efron & Tibshirani, *An Introduction to the
//! Bootstrap*, 1993, §9.5, "bootstrapping residuals"). Each replicate is the fitted response
//! plus residuals drawn with replacement from the fit's own (centred) residuals, refitted by
//! output error from the estimate; the interval is the 2.5 % and 97.5 % quantiles of the
//! replicates' estimates (the percentile interval, §13.3). Valid when the residuals are
//! white — the whiteness test of the report says whether they are.

use rayon::prelude::*;
use serde::Serialize;

use super::Identification;
use super::arx::Start;
use super::data::Record;
use super::error::{IdResult, IdentifyError};
use super::output_error::refine;
use crate::splitmix::SplitMix;

/// One parameter's bootstrap interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BootstrapInterval {
    /// The parameter's name.
    pub name: String,
    /// The 2.5 % and 97.5 % quantiles of its replicates.
    pub ci95: [f64; 2],
}

/// The bootstrap's intervals.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Bootstrap {
    /// Replicates drawn.
    pub replicates: usize,
    /// Replicates whose refit converged (the quantiles are over these).
    pub converged: usize,
    /// Each free parameter's interval.
    pub parameters: Vec<BootstrapInterval>,
}

/// The residual bootstrap of a time-domain identification (module doc): `replicates`
/// refits of the runs `records` the identification was made from, drawn with `seed`.
pub fn bootstrap(
    records: &[Record],
    id: &Identification,
    replicates: usize,
    seed: u64,
) -> IdResult<Bootstrap> {
    if id.source != "time" {
        return Err(IdentifyError::Data(
            "the bootstrap resamples the residuals of a time recording".into(),
        ));
    }
    let measured: Vec<f64> = records
        .iter()
        .flat_map(|r| r.position.iter().copied())
        .collect();
    let mut residuals: Vec<f64> = measured
        .iter()
        .zip(&id.predicted)
        .map(|(m, p)| m - p)
        .collect();
    let mean = residuals.iter().sum::<f64>() / residuals.len() as f64;
    residuals.iter_mut().for_each(|e| *e -= mean);
    let start = Start {
        values: id.parameters.iter().map(|p| p.value).collect(),
        offset: id.position_offset.value,
    };
    let offsets: Vec<f64> = id.position_offsets.iter().map(|o| o.value).collect();
    let free = id.spec.free();
    let draws: Vec<Vec<f64>> = (0..replicates)
        .into_par_iter()
        .filter_map(|i| {
            let mut rng = SplitMix::stream(seed, i);
            let mut at = 0;
            let resampled: Vec<Record> = records
                .iter()
                .map(|r| {
                    let mut r = r.clone();
                    for y in r.position.iter_mut() {
                        let j = (rng.next_f64() * residuals.len() as f64) as usize;
                        *y = id.predicted[at] + residuals[j.min(residuals.len() - 1)];
                        at += 1;
                    }
                    r
                })
                .collect();
            let fit = refine(&resampled, &id.spec, &start, &offsets).ok()?;
            Some(free.iter().map(|&k| fit.values[k]).collect())
        })
        .collect();
    let parameters = free
        .iter()
        .enumerate()
        .map(|(k, &i)| {
            let mut v: Vec<f64> = draws.iter().map(|d| d[k]).collect();
            v.sort_by(f64::total_cmp);
            BootstrapInterval {
                name: id.parameters[i].name.clone(),
                ci95: [quantile(&v, 0.025), quantile(&v, 0.975)],
            }
        })
        .collect();
    Ok(Bootstrap {
        replicates,
        converged: draws.len(),
        parameters,
    })
}

/// The p-quantile of sorted values (linear interpolation, numpy's default); NaN when empty.
fn quantile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let h = p * (sorted.len() - 1) as f64;
    let (i, f) = (h.floor() as usize, h.fract());
    let next = sorted[(i + 1).min(sorted.len() - 1)];
    sorted[i] + f * (next - sorted[i])
}
