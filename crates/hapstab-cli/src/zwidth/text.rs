//! The text output of `hapstab zwidth`: each loop's regions, K_max and table, and the
//! comparison of several loops.

use hapstab::answer::ZwidthLoop as LoopOut;
use hapstab::zwidth::ZWidth;

use crate::model::{self, LoopInput};
use crate::output::{eng, sig};

pub(super) fn kn(x: f64) -> String {
    eng(x, "N/m", 6)
}

pub(super) fn ns(x: f64) -> String {
    eng(x, "Ns/m", 6)
}

pub(super) fn print_loop(o: &LoopOut, titled: bool) {
    if titled {
        println!("== {} ==", o.label);
    }
    if let LoopInput::Physical { lp, .. } = &o.input {
        model::print_loop(lp);
    }
    let z = &o.zwidth;
    match z.k_max {
        Some(k) => {
            let nonneg = z
                .k_max_nonnegative_damping
                .map(|w| format!("; with B ≥ 0: {} at B = {}", kn(w.stiffness), ns(w.damping)))
                .unwrap_or_else(|| "; nothing stable with B ≥ 0".into());
            println!(
                "stable      K_max = {} at B = {}{nonneg}; area {} N²·s/m²",
                kn(k.stiffness),
                ns(k.damping),
                sig(z.stable_area, 5)
            );
        }
        None => println!("stable      no stable wall"),
    }
    print_passive(z);
    if let Some(l) = z.linear {
        println!(
            "linear (22) K < (b + B)/(t_d + T/2) = ({} + B)/{}",
            ns(l.damping),
            eng(l.effective_delay, "s", 6)
        );
    }
    print_table(z);
}

pub(super) fn print_passive(z: &ZWidth) {
    match (&z.passive, &z.device_damping) {
        (Some(p), _) if p.vertices.is_empty() => {
            println!("passive     none: the device has no damping (b = 0)");
        }
        (Some(p), _) => {
            let inside = match z.passive_inside_stable {
                Some(true) => "inside the stable region",
                Some(false) => "NOT inside the stable region",
                None => "",
            };
            println!(
                "passive     b = {}: K_max = {} at B = {}; area {} N²·s/m²; {inside}",
                ns(p.device_damping),
                kn(p.k_max),
                ns(p.b_at_k_max),
                sig(p.area, 5)
            );
        }
        (None, hapstab::passivity::DeviceDamping::NotApplicable { reason }) => {
            println!("passive     not applicable: {reason}");
        }
        (None, _) => {}
    }
    if let Some(w) = z.k_max_passive_with_arm {
        println!(
            "with arm    K_max = {} at B = {} by eq. (28) with the arm's damping counted \
             (b = b_L + b_H): towards this operator only",
            kn(w.stiffness),
            ns(w.damping)
        );
    }
}

pub(super) fn opt(x: Option<f64>) -> String {
    x.map_or_else(|| "—".into(), kn)
}

pub(super) fn print_table(z: &ZWidth) {
    println!(
        "  {:>12}  {:>14}  {:>14}  {:>14}  {:>14}",
        "B", "K_max stable", "K_min stable", "K_max passive", "linear (22)"
    );
    for r in &z.table {
        println!(
            "  {:>12}  {:>14}  {:>14}  {:>14}  {:>14}",
            ns(r.damping),
            opt(r.k_max),
            opt(r.k_min),
            opt(r.k_max_passive),
            opt(r.k_linear)
        );
    }
}

pub(super) fn print_comparison(out: &[LoopOut]) {
    let Some(base) = out.first().filter(|_| out.len() > 1) else {
        return;
    };
    println!();
    println!("compared with '{}':", base.label);
    let bk = base.zwidth.k_max.map(|w| w.stiffness);
    for o in &out[1..] {
        let k = o.zwidth.k_max.map(|w| w.stiffness);
        let ratio = match (k, bk) {
            (Some(k), Some(b)) => format!("K_max ×{}", sig(k / b, 4)),
            _ => "K_max —".into(),
        };
        println!(
            "  {:<24} stable area ×{}, {ratio}",
            o.label,
            sig(o.zwidth.stable_area / base.zwidth.stable_area, 4)
        );
    }
}
