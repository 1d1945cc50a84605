//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! `/api/point` gives exactly the library's analysis (its margins and passivity are compared
//! with the command line's in hapstab-cli's `serve_parity`).

use crate::serve_support;

use hapstab::Normalized;
use hapstab::stability::Analysis;
use serve_support::{Server, raw_number};

#[test]
fn point_matches_the_library_analysis() {
    let s = Server::start(&[]);
    for (a, b, g, de, d) in [
        (0.3, 0.5, 0.001, 0.015, 0),
        (0.75, 0.5, 0.001, 0.015, 0),
        (0.05, 0.3, 0.0, 0.0, 3),
    ] {
        let path = format!("/api/point?alpha={a}&beta={b}&gamma={g}&delta={de}&d={d}");
        let r = s.get(&path);
        assert_eq!(r.status, 200, "{}", r.body);
        let lib = Analysis::new(Normalized::new(a, b, g, de, d).unwrap()).unwrap();
        let j = r.json();
        assert_eq!(j["verdict"], lib.verdict.as_str(), "{path}");
        assert_eq!(
            raw_number(&r.body, "\"verdict\"", "spectral_radius"),
            lib.spectral_radius
        );
        let roots = j["roots"].as_array().unwrap();
        assert_eq!(roots.len(), d + 3);
        // the normalized plant's damping is all the device's: passivity applies at any d
        assert!(j["passive"].is_boolean(), "{j}");
    }
}
