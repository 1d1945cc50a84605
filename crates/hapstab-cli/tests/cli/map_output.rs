//! `hapstab map` files: the CSV against `check` at grid points, the NPY read back (by a
//! reader written from the NumPy format specification) against the CSV, and the heatmap.

use crate::common;

use common::hapstab;
use std::path::Path;

/// The plant and grid of the tests: γ = 0.001, δ = 0.015, d = 2, (α, β) over the stable region
/// (about half the points stable).
const GRID: [&str; 12] = [
    "map",
    "--x",
    "alpha:-0.005:0.1:41",
    "--y",
    "beta:0:0.4:23",
    "--gamma",
    "0.001",
    "--delta",
    "0.015",
    "--delay",
    "2",
    "--radius",
];

fn run_map(extra: &[&str]) {
    let out = hapstab().args(GRID).args(extra).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// CSV rows as (alpha, beta, stable, spectral_radius), after checking the header.
fn read_csv(path: &Path) -> Vec<(f64, f64, bool, f64)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("alpha,beta,stable,spectral_radius"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 4, "{l}");
            assert!(f[2] == "0" || f[2] == "1", "{l}");
            (
                f[0].parse().unwrap(),
                f[1].parse().unwrap(),
                f[2] == "1",
                f[3].parse().unwrap(),
            )
        })
        .collect()
}

/// A minimal .npy reader for format 1.0 from the specification: magic "\x93NUMPY", version
/// bytes, little-endian u16 header length, a Python-literal dict, then the raw records.
fn read_npy(path: &Path) -> (String, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..6], b"\x93NUMPY");
    assert_eq!((bytes[6], bytes[7]), (1, 0));
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    assert_eq!((10 + len) % 64, 0, "header not aligned to 64 bytes");
    let header = std::str::from_utf8(&bytes[10..10 + len])
        .unwrap()
        .to_string();
    assert!(header.ends_with('\n'));
    (header, bytes[10 + len..].to_vec())
}

#[test]
fn npy_holds_the_same_records_as_the_csv() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, npy) = (dir.path().join("m.csv"), dir.path().join("m.npy"));
    run_map(&["--out", csv.to_str().unwrap()]);
    run_map(&["--out", npy.to_str().unwrap(), "--format", "npy"]);
    let rows = read_csv(&csv);
    assert_eq!(rows.len(), 41 * 23);
    let (header, data) = read_npy(&npy);
    let dict = header.trim_end();
    assert_eq!(
        dict,
        "{'descr': [('alpha', '<f8'), ('beta', '<f8'), ('stable', '|u1'), \
         ('spectral_radius', '<f8')], 'fortran_order': False, 'shape': (943,), }"
    );
    const RECORD: usize = 8 + 8 + 1 + 8;
    assert_eq!(data.len(), rows.len() * RECORD);
    let f64_at = |b: &[u8]| f64::from_le_bytes(b.try_into().unwrap());
    for (k, (rec, row)) in data.chunks_exact(RECORD).zip(&rows).enumerate() {
        let got = (
            f64_at(&rec[0..8]),
            f64_at(&rec[8..16]),
            rec[16] == 1,
            f64_at(&rec[17..25]),
        );
        assert!(rec[16] <= 1, "record {k}");
        // Shortest round-trip text parses back to the very same doubles.
        assert_eq!(got, *row, "record {k}");
    }
    // x varies fastest: record iy·nx + ix.
    assert_eq!(rows[1].1, rows[0].1);
    assert!(rows[1].0 > rows[0].0);
    assert_eq!(rows[41].0, rows[0].0);
}

#[test]
fn csv_matches_check_at_grid_points() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("m.csv");
    run_map(&["--out", csv.to_str().unwrap()]);
    let rows = read_csv(&csv);
    let (mut stable, mut unstable) = (0, 0);
    for k in (0..rows.len()).step_by(37) {
        let (a, b, s, rho) = rows[k];
        let out = hapstab()
            .args([
                "check", "--gamma", "0.001", "--delta", "0.015", "--delay", "2",
            ])
            .args([
                "--alpha",
                &a.to_string(),
                "--beta",
                &b.to_string(),
                "--json",
            ])
            .output()
            .unwrap();
        assert!(out.status.success());
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let check_rho = v["spectral_radius"].as_f64().unwrap();
        // Bisection on the Schur–Cohn test (map) against the roots (check).
        assert!(
            (rho - check_rho).abs() < 1e-9,
            "point {k}: {rho} vs {check_rho}"
        );
        if (rho - 1.0).abs() > 1e-6 {
            assert_eq!(v["stable"].as_bool().unwrap(), s, "point {k}: ρ = {rho}");
            if s { stable += 1 } else { unstable += 1 }
        }
    }
    assert!(
        stable >= 5 && unstable >= 5,
        "{stable} stable, {unstable} unstable"
    );
}

/// Pixels of exactly the stable colour (palette blue) in a PNG.
fn blue_pixels(png: &Path) -> usize {
    let img = image::open(png).unwrap().to_rgb8();
    img.pixels().filter(|p| p.0 == [0, 114, 178]).count()
}

#[test]
fn plot_draws_the_stable_cells() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("map");
    let out = hapstab()
        .args(&GRID[..11])
        .args(["--plot", stem.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success());
    let svg = std::fs::read_to_string(dir.path().join("map.svg")).unwrap();
    assert!(svg.contains("stable (Schur–Cohn)"));
    assert!(blue_pixels(&dir.path().join("map.png")) > 10_000);
    // Beyond the linear condition α < (β + δ)/(d + 1/2) < 0.41 nothing is stable: no blue.
    let stem = dir.path().join("none");
    let out = hapstab()
        .args(["map", "--x", "alpha:2:3:20", "--y", "beta:0:1:20"])
        .args(["--gamma", "0.001", "--delta", "0.015", "--delay", "2"])
        .args(["--plot", stem.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(blue_pixels(&dir.path().join("none.png")), 0);
}

#[test]
fn format_needs_an_output_file() {
    let out = hapstab()
        .args([
            "map",
            "--x",
            "alpha:0:1:10",
            "--y",
            "beta:0:1:10",
            "--format",
            "npy",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
