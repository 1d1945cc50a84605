//! API tests of `hapstab serve` against the real server on an ephemeral loopback port:
//! `/api/region` gives exactly the library's stable region, in normalized and physical mode,
//! with the robust region over γ and the passive triangles (its K_max and the robust region
//! over the arm's stiffness are compared with the command line's in hapstab-cli's
//! `serve_parity`).

use crate::serve_support;

use hapstab::PlantParams;
use serve_support::{Server, library_region, raw_number};

#[test]
fn region_alpha_max_equals_the_library() {
    let s = Server::start(&[]);
    for (g, de, d) in [
        (0.001, 0.015, 0),
        (0.001, 0.015, 1),
        (0.0, 0.0, 2),
        (0.0005, 0.005, 5),
        (0.001, 0.0, 10),
        (5.0, 1.0, 3),
        (0.0, 0.015, 50),
    ] {
        let path = format!("/api/region?gamma={g}&delta={de}&d={d}");
        let r = s.get(&path);
        assert_eq!(r.status, 200, "{path}: {}", r.body);
        let lib = library_region(g, de, d);
        let am = raw_number(&r.body, "\"region\":", "alpha_max");
        let bm = raw_number(&r.body, "\"region\":", "beta_at_alpha_max");
        let area = raw_number(&r.body, "\"region\":", "area");
        assert_eq!(am, lib.a_max, "{path}");
        assert_eq!(bm, lib.b_at_a_max, "{path}");
        assert_eq!(area, lib.area, "{path}");
        let j = r.json();
        assert_eq!(j["params"]["d"], d);
        let polys = j["region"]["polygons"].as_array().unwrap();
        assert_eq!(polys.len(), lib.polygons.len(), "{path}");
        // simplified for drawing, corners kept, never more vertices than the exact polygons
        let sent = j["region"]["vertices_sent"].as_u64().unwrap() as usize;
        let exact: usize = lib.polygons.iter().map(|p| p.vertices.len()).sum();
        assert_eq!(
            j["region"]["vertices_exact"].as_u64().unwrap() as usize,
            exact
        );
        assert!(
            sent <= exact && sent >= 3 * lib.polygons.len(),
            "{sent} of {exact}"
        );
        // every drawn vertex lies on the exact boundary: its neighbourhood straddles it
        // (checked cheaply: the drawn polygon's α extent is the exact one within tolerance)
        let amax_drawn = polys
            .iter()
            .flat_map(|p| p.as_array().unwrap())
            .map(|v| v[0].as_f64().unwrap())
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(amax_drawn <= lib.a_max + 1e-12);
        assert!(amax_drawn >= lib.a_max - 1e-3 * lib.a_max.abs().max(1e-9));
        // overlays
        let lin = &j["linear"];
        assert!((lin["slope"].as_f64().unwrap() - 1.0 / (d as f64 + 0.5)).abs() < 1e-15);
        assert!((lin["alpha_at_beta0"].as_f64().unwrap() - de / (d as f64 + 0.5)).abs() < 1e-15);
        // the passive region: eq. (28)'s triangle (0, −δ), (2δ, 0), (0, δ) at d = 0; the
        // library's region at any d
        let v: Vec<[f64; 2]> = j["passive"]["vertices"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()])
            .collect();
        let a_max = v.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
        let lp = hapstab::Loop::normalized(hapstab::PlantParams::new(g, de).unwrap(), d).unwrap();
        let sw = hapstab::passivity::SampledWall::new(&lp).unwrap();
        let lib_pass = hapstab::passivity::passive_region(&sw, de).unwrap();
        if lib_pass.vertices.is_empty() {
            // no damping of its own (δ = 0): nothing is passive
            assert!(v.is_empty(), "{v:?}");
            continue;
        }
        // drawn chords within the region's tolerance (1e-5 of its size) of the exact K_max
        assert!(a_max <= lib_pass.k_max * (1.0 + 1e-12), "{a_max}");
        assert!(
            a_max >= lib_pass.k_max * (1.0 - 1e-4),
            "{a_max} vs {}",
            lib_pass.k_max
        );
        if d == 0 {
            assert!(
                (a_max - 2.0 * de).abs() <= 1e-12 * de,
                "{a_max} vs 2δ = {}",
                2.0 * de
            );
            let b_max = v.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
            assert!((b_max - de).abs() <= 1e-12 * de, "{b_max}");
        }
    }
}

#[test]
fn physical_mode_matches_the_library() {
    let s = Server::start(&[]);
    let path = "/api/region?mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&delay_time=0.002";
    let r = s.get(path);
    assert_eq!(r.status, 200, "{}", r.body);
    let eff = hapstab::Effective::new(1.1, 7.5, 350.0).unwrap();
    let pp = PlantParams::from_physical(&eff, 0.001).unwrap();
    let lib = library_region(pp.gamma, pp.delta, 2);
    assert_eq!(raw_number(&r.body, "\"region\":", "alpha_max"), lib.a_max);
    let j = r.json();
    assert_eq!(j["params"]["d"], 2);
    let kpa = j["physical"]["k_per_unit"].as_f64().unwrap();
    assert!((kpa - 1.1 / 1e-6).abs() < 1e-6);
    assert!((j["physical"]["b_per_unit"].as_f64().unwrap() - 1100.0).abs() < 1e-9);
}

#[test]
fn robust_region_is_inside_the_nominal_one() {
    let s = Server::start(&[]);
    let r = s.get("/api/region?gamma=0&delta=1&d=0&robust=1&gamma_lo=0&gamma_hi=9.8696");
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let rob = &j["robust"];
    assert_eq!(rob["empty"], false);
    let ram = rob["alpha_max"].as_f64().unwrap();
    for g in [0.0, 9.8696] {
        assert!(ram <= library_region(g, 1.0, 0).a_max + 1e-9);
    }
    // Colgate's passive triangle (0, −1), (2, 0), (0, 1) lies inside the robust region
    // (Section VIII-A): its tip α = 2δ = 2 at β = 0 is below the robust α_max.
    assert!(ram > 2.0, "{ram}");
    assert!(rob["method"].as_str().unwrap().contains("robust_region"));
}

/// Physical mode, d = 0: the passive triangle is the device's own δ_L = b_L·T/m (passive for
/// any operator); eq. (28) with the arm's damping counted, δ = (b_L + b_H)·T/m, is the second.
#[test]
fn physical_passive_region_counts_the_devices_own_damping() {
    let s = Server::start(&[]);
    let lp = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=0";
    let r = s.get(&format!("/api/region?{lp}"));
    assert_eq!(r.status, 200, "{}", r.body);
    let j = r.json();
    let own = 1.5e-3 / 1.1;
    // the triangles of eq. (28) reach α = 2δ at β = 0, sent in N/m: K = 2δ·m/T² = 2b/T
    let k_max = |v: &serde_json::Value| {
        v["vertices"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p[0].as_f64().unwrap())
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    assert!(
        close(k_max(&j["passive"]), 2.0 * 1.5 / 1e-3),
        "{}",
        j["passive"]
    );
    assert!(
        close(k_max(&j["passive_with_arm"]), 2.0 * 7.5 / 1e-3),
        "{}",
        j["passive_with_arm"]
    );
    // a spring wall α = 3δ_L lies outside the device's own triangle, inside eq. (28)'s
    let alpha = 3.0 * own;
    let r = s.get(&format!("/api/point?{lp}&alpha={alpha}&beta=0"));
    assert_eq!(r.status, 200, "{}", r.body);
    let p = r.json();
    assert_eq!(p["passive"], false, "{p}");
    assert_eq!(p["passive_with_arm"], true, "{p}");
    // without an arm there is one triangle, the device's own
    let bare = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=0&arm_damping=0&arm_stiffness=0&period=0.001&d=0";
    let j = s.get(&format!("/api/region?{bare}")).json();
    assert!(j["passive_with_arm"].is_null(), "{j}");
    assert!(close(k_max(&j["passive"]), 2.0 * 1.5 / 1e-3), "{j}");
}
