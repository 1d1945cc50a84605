//! The `--out` file of `hapstab map`: CSV or NPY, one record per grid point.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::{Context, Result};
use clap::ValueEnum;
use hapstab::map::AxisRange;

use super::Values;
use super::axes::{Grid, axis_label};

/// Layout of the `--out` file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(super) enum Format {
    /// Comma-separated values with a header.
    Csv,
    /// NumPy .npy structured array.
    Npy,
}

/// The column names of the output file.
pub(super) fn columns(x: Grid, y: Grid, v: &Values) -> Vec<&'static str> {
    let mut cols = vec![axis_label(x.name), axis_label(y.name), "stable"];
    if v.radius.is_some() {
        cols.push("spectral_radius");
    }
    cols
}

/// The grid values of an axis as shortest round-trip decimal text, formatted once.
pub(super) fn axis_text(r: &AxisRange) -> Vec<String> {
    let mut buf = ryu::Buffer::new();
    (0..r.n)
        .map(|i| buf.format(r.value(i)).to_owned())
        .collect()
}

/// Writes the map as CSV: the axis values are formatted once per axis and every record is
/// assembled from borrowed bytes (no allocation per field).
pub(super) fn write_csv(path: &Path, x: Grid, y: Grid, v: &Values) -> Result<()> {
    let file = File::create(path).with_context(|| format!("cannot write {}", path.display()))?;
    let mut w = csv::WriterBuilder::new()
        .buffer_capacity(1 << 20)
        .from_writer(file);
    w.write_record(columns(x, y, v))?;
    let (xs, ys) = (axis_text(&x.range), axis_text(&y.range));
    let mut buf = ryu::Buffer::new();
    for (iy, yt) in ys.iter().enumerate() {
        for (ix, xt) in xs.iter().enumerate() {
            let k = iy * xs.len() + ix;
            w.write_field(xt)?;
            w.write_field(yt)?;
            w.write_field(if v.stable[k] { "1" } else { "0" })?;
            if let Some(r) = &v.radius {
                w.write_field(buf.format(r[k]))?;
            }
            w.write_record(None::<&[u8]>)?;
        }
    }
    w.flush()
        .with_context(|| format!("cannot write {}", path.display()))
}

/// The NPY 1.0 header for `points` records of the map's columns: magic, version, header
/// length, and the dict padded with spaces to a multiple of 64 bytes ending in a newline.
pub(super) fn npy_header(cols: &[&str], points: usize) -> Vec<u8> {
    let fields: Vec<String> = cols
        .iter()
        .map(|c| format!("('{c}', '{}')", if *c == "stable" { "|u1" } else { "<f8" }))
        .collect();
    let dict = format!(
        "{{'descr': [{}], 'fortran_order': False, 'shape': ({points},), }}",
        fields.join(", ")
    );
    let total = (10 + dict.len() + 1).div_ceil(64) * 64;
    let mut h = b"\x93NUMPY\x01\x00".to_vec();
    h.extend_from_slice(&((total - 10) as u16).to_le_bytes());
    h.extend_from_slice(dict.as_bytes());
    h.resize(total - 1, b' ');
    h.push(b'\n');
    h
}

/// Writes the map as a NumPy structured array (see the documentation of [`super`]).
pub(super) fn write_npy(path: &Path, x: Grid, y: Grid, v: &Values) -> Result<()> {
    let fail = || format!("cannot write {}", path.display());
    let file = File::create(path).with_context(fail)?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    let (xr, yr) = (&x.range, &y.range);
    w.write_all(&npy_header(&columns(x, y, v), xr.n * yr.n))
        .with_context(fail)?;
    let xs: Vec<[u8; 8]> = (0..xr.n).map(|i| xr.value(i).to_le_bytes()).collect();
    for iy in 0..yr.n {
        let yb = yr.value(iy).to_le_bytes();
        for (ix, xb) in xs.iter().enumerate() {
            let k = iy * xr.n + ix;
            w.write_all(xb).with_context(fail)?;
            w.write_all(&yb).with_context(fail)?;
            w.write_all(&[v.stable[k] as u8]).with_context(fail)?;
            if let Some(r) = &v.radius {
                w.write_all(&r[k].to_le_bytes()).with_context(fail)?;
            }
        }
    }
    w.flush().with_context(fail)
}
