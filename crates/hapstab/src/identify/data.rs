//! A recording: time, commanded force and measured position, uniformly sampled, loaded from
//! CSV text or given as arrays, and checked before any estimation.
//!
//! The checks, each naming its column: every value finite; time strictly increasing and
//! uniform (every step within [`UNIFORM_TOLERANCE`] of the mean step, which becomes the
//! sampling period T); the force not constant (it must excite the plant); at least
//! [`MIN_SAMPLES`] samples.

use super::error::{IdResult, IdentifyError};

/// Relative deviation of a time step from the mean step above which the time column is not
/// uniformly sampled: 10⁻³ of T tolerates the rounding of times written with six digits, and
/// refuses a dropped sample or a jittery clock, which break the exact sampled model.
pub const UNIFORM_TOLERANCE: f64 = 1e-3;

/// Fewest samples accepted, whatever the model: below this no residual test means anything.
pub const MIN_SAMPLES: usize = 20;

/// The names of the three columns (header names in a CSV file).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Columns {
    /// Time in s.
    pub time: String,
    /// Commanded force in N.
    pub force: String,
    /// Measured position in m.
    pub position: String,
}

impl Default for Columns {
    fn default() -> Self {
        Columns {
            time: "time".into(),
            force: "force".into(),
            position: "position".into(),
        }
    }
}

impl Columns {
    /// Parses `t,f,x`: the time, force and position column names, comma separated.
    pub fn parse(text: &str) -> IdResult<Self> {
        let names: Vec<&str> = text.split(',').map(str::trim).collect();
        match names.as_slice() {
            [t, f, x] if !t.is_empty() && !f.is_empty() && !x.is_empty() => Ok(Columns {
                time: (*t).into(),
                force: (*f).into(),
                position: (*x).into(),
            }),
            _ => Err(IdentifyError::Data(format!(
                "columns '{text}': give three names, time,force,position"
            ))),
        }
    }
}

/// A checked recording (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Time in s, uniform.
    pub time: Vec<f64>,
    /// Commanded force F_k in N, held over the sample that follows it.
    pub force: Vec<f64>,
    /// Measured position y_k in m.
    pub position: Vec<f64>,
    /// The sampling period T in s: the mean time step.
    pub period: f64,
}

impl Record {
    /// Checks three equally long columns and takes the mean time step as the period
    /// (module doc); `columns` names them in errors.
    pub fn new(
        time: Vec<f64>,
        force: Vec<f64>,
        position: Vec<f64>,
        columns: &Columns,
    ) -> IdResult<Self> {
        let n = time.len();
        if force.len() != n || position.len() != n {
            return Err(IdentifyError::Data(format!(
                "the columns differ in length ({} time, {} force, {} position samples)",
                n,
                force.len(),
                position.len()
            )));
        }
        if n < MIN_SAMPLES {
            return Err(IdentifyError::Data(format!(
                "{n} samples: too few to identify a plant (at least {MIN_SAMPLES})"
            )));
        }
        for (name, col) in [
            (&columns.time, &time),
            (&columns.force, &force),
            (&columns.position, &position),
        ] {
            if let Some(i) = col.iter().position(|v| !v.is_finite()) {
                return Err(column(
                    name,
                    format!("sample {} is {} (not a number)", i + 1, col[i]),
                ));
            }
        }
        let period = uniform_period(&time, &columns.time)?;
        let (lo, hi) = force
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        if hi == lo {
            return Err(column(
                &columns.force,
                format!("constant ({lo} N): no excitation, the plant cannot be identified"),
            ));
        }
        Ok(Record {
            time,
            force,
            position,
            period,
        })
    }

    /// Reads comma-separated text with a header line naming the columns (lines starting
    /// with `#` and blank lines are skipped), then checks it as [`Record::new`].
    pub fn from_csv(text: &str, columns: &Columns) -> IdResult<Self> {
        let table = CsvText::parse(text)?;
        let find = |want: &str| table.index(want).ok_or_else(|| table.missing(want));
        let idx = [
            find(&columns.time)?,
            find(&columns.force)?,
            find(&columns.position)?,
        ];
        let mut cols = table.columns(&idx)?.into_iter();
        let mut next = || cols.next().unwrap_or_default();
        let (t, f, x) = (next(), next(), next());
        Record::new(t, f, x, columns)
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True when there are no samples (never, for a checked record).
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }
}

/// Comma-separated text with a header line naming its columns; blank lines and lines
/// starting with `#` are skipped (the recordings and frequency responses `identify` reads).
pub(crate) struct CsvText<'a> {
    /// The header's names, trimmed and unquoted.
    names: Vec<&'a str>,
    /// The data lines with their line numbers (from 0).
    lines: Vec<(usize, &'a str)>,
}

impl<'a> CsvText<'a> {
    /// Splits off the header; an error when there is none.
    pub(crate) fn parse(text: &'a str) -> IdResult<Self> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let Some((_, header)) = lines.next() else {
            return Err(IdentifyError::Data("empty: no header line".into()));
        };
        let names = header
            .split(',')
            .map(|h| h.trim().trim_matches('"'))
            .collect();
        Ok(Self {
            names,
            lines: lines.collect(),
        })
    }

    /// The position of a column in the header.
    pub(crate) fn index(&self, want: &str) -> Option<usize> {
        self.names.iter().position(|h| *h == want)
    }

    /// The error of a column missing from the header, listing the header.
    pub(crate) fn missing(&self, want: &str) -> IdentifyError {
        column(
            want,
            format!("not in the header (it has: {})", self.names.join(", ")),
        )
    }

    /// The columns at `idx` as numbers; a cell that is not one is an error naming its column
    /// and line.
    pub(crate) fn columns(&self, idx: &[usize]) -> IdResult<Vec<Vec<f64>>> {
        let mut cols = vec![Vec::with_capacity(self.lines.len()); idx.len()];
        for &(line_no, line) in &self.lines {
            let cells: Vec<&str> = line.split(',').collect();
            for (&i, col) in idx.iter().zip(cols.iter_mut()) {
                let cell = cells.get(i).map_or("", |c| c.trim());
                let v = cell.parse::<f64>().map_err(|_| {
                    column(
                        self.names[i],
                        format!("line {}: '{cell}' is not a number", line_no + 1),
                    )
                })?;
                col.push(v);
            }
        }
        Ok(cols)
    }
}

fn column(name: &str, reason: String) -> IdentifyError {
    IdentifyError::Column {
        column: name.to_string(),
        reason,
    }
}

/// The mean time step, after checking that time increases and every step is within
/// [`UNIFORM_TOLERANCE`] of it.
fn uniform_period(time: &[f64], name: &str) -> IdResult<f64> {
    if let Some(i) = time.windows(2).position(|w| w[1] <= w[0]) {
        return Err(column(
            name,
            format!(
                "not increasing: sample {} ({} s) follows {} s",
                i + 2,
                time[i + 1],
                time[i]
            ),
        ));
    }
    let n = time.len();
    let period = (time[n - 1] - time[0]) / (n - 1) as f64;
    for (i, w) in time.windows(2).enumerate() {
        let step = w[1] - w[0];
        if (step - period).abs() > UNIFORM_TOLERANCE * period {
            return Err(column(
                name,
                format!(
                    "not uniformly sampled: the step from sample {} to {} is {step:e} s, the mean step {period:e} s",
                    i + 1,
                    i + 2
                ),
            ));
        }
    }
    Ok(period)
}
