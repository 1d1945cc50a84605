//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! the page is self-contained, and its exports (SVG, CSV, JSON) carry the library's numbers.

use crate::serve_support;

use serve_support::{PAPER_LOOP, PLANT, Server, library_region, raw_number};

#[test]
fn export_svg_csv_json() {
    let s = Server::start(&[]);
    let base = format!("/api/export?{PLANT}&alpha=0.05&beta=0.3");
    let lib = library_region(0.001, 0.015, 1);
    let r = s.get(&format!("{base}&format=svg"));
    assert_eq!(r.status, 200);
    assert_eq!(r.header("content-type"), Some("image/svg+xml"));
    assert!(r.header("content-disposition").unwrap().contains(".svg"));
    assert!(r.body.starts_with("<svg") && r.body.trim_end().ends_with("</svg>"));
    assert!(r.body.contains("class=\"region\"") && r.body.contains("class=\"point\""));
    let r = s.get(&format!("{base}&format=csv"));
    assert_eq!(r.status, 200);
    let mut lines = r.body.lines();
    assert_eq!(lines.next(), Some("layer,polygon,vertex,alpha,beta"));
    let amax_row = r
        .body
        .lines()
        .find(|l| l.starts_with("alpha_max,"))
        .unwrap();
    let am: f64 = amax_row.split(',').nth(3).unwrap().parse().unwrap();
    assert_eq!(am, lib.a_max);
    assert!(r.body.lines().any(|l| l.starts_with("point,")));
    assert!(r.body.lines().filter(|l| l.starts_with("region,")).count() > 10);
    let r = s.get(&format!("{base}&format=json&view=-0.01,0.2,-0.1,1.2"));
    assert_eq!(r.status, 200);
    assert_eq!(raw_number(&r.body, "\"region\":", "alpha_max"), lib.a_max);
    let j = r.json();
    assert_eq!(j["view"][1].as_f64(), Some(0.2));
    assert_eq!(j["point"]["verdict"], "stable");
}

/// The exports of a loop given in physical units speak N/m and Ns/m: the CSV's columns are K
/// and B (its K_max row the library's K_max), the SVG's title names the device and the arm,
/// not γ and δ, and the file names carry T and t_d.
#[test]
fn export_of_a_physical_loop_is_in_newtons() {
    let s = Server::start(&[]);
    let base = format!("/api/export?{PAPER_LOOP}");
    let lp =
        hapstab::Loop::paper(hapstab::Effective::new(1.1, 7.5, 350.0).unwrap(), 1e-3, 1).unwrap();
    let k_max = hapstab::System::of(&lp).unwrap().region().unwrap().a_max
        * hapstab::AffineFamily::of_loop(&lp).unwrap().scale.stiffness;
    let r = s.get(&format!("{base}&format=csv"));
    assert_eq!(r.status, 200, "{}", r.body);
    assert!(
        r.header("content-disposition")
            .unwrap()
            .contains("hapstab-region-T0.001-td0.001.csv")
    );
    assert_eq!(
        r.body.lines().next(),
        Some("layer,polygon,vertex,K_N_per_m,B_Ns_per_m")
    );
    let row = r.body.lines().find(|l| l.starts_with("k_max,")).unwrap();
    let k: f64 = row.split(',').nth(3).unwrap().parse().unwrap();
    assert!((k - k_max).abs() <= 1e-12 * k_max, "{k} vs {k_max}");
    let svg = s.get(&format!("{base}&format=svg")).body;
    let title = svg
        .lines()
        .find(|l| l.contains("Exact stable region"))
        .unwrap();
    assert!(
        title.contains("arm") && !title.contains('γ') && !title.contains('δ'),
        "{title}"
    );
}

#[test]
fn page_is_self_contained() {
    let s = Server::start(&[]);
    let r = s.get("/");
    assert_eq!(r.status, 200);
    assert!(r.header("content-type").unwrap().starts_with("text/html"));
    let csp = r.header("content-security-policy").unwrap();
    assert!(csp.contains("default-src 'none'") && csp.contains("connect-src 'self'"));
    // no external resource: the only URL is the SVG namespace
    let urls: Vec<&str> = r
        .body
        .match_indices("http")
        .map(|(i, _)| &r.body[i..(i + 40).min(r.body.len())])
        .filter(|u| !u.starts_with("http://www.w3.org/2000/svg"))
        .collect();
    assert!(urls.is_empty(), "{urls:?}");
    assert!(!r.body.contains("<script src") && !r.body.contains("<link "));
    // the limits are stated on the page and served as JSON
    assert!(r.body.contains("d ≤ 200"));
    let l = s.get("/api/limits").json();
    assert_eq!(l["d_max"], 200);
}
