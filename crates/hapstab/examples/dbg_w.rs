use hapstab::AffineFamily;
use hapstab::model::*;
use hapstab::params::Effective;
fn main() {
    let lp = Loop::new(
        Plant::mass_spring_damper(Effective::new(1.0, 1.0, 0.0).unwrap()).unwrap(),
        1.4174875607165099e-5,
        Delay::samples(0).unwrap(),
        VelocityEstimator::LowPass { cutoff_hz: 1.0 },
    )
    .unwrap();
    let fam = AffineFamily::of_loop(&lp).unwrap();
    for &(a, b) in &[
        (4.372439336049043e-9, 7.658306200191728e-8),
        (1e-5, 7.658306200191728e-8),
        (3e-5, 7.658306200191728e-8),
    ] {
        let w = hapstab::argument::winding(&fam, a, b);
        let c = fam.coefficients(a, b);
        println!(
            "a={a} b={b}: winding {w:?} schur {} ivs {:?}",
            hapstab::stability::schur_stable(&c),
            hapstab::boundary::stable_alpha_intervals(&fam, b)
        );
        let r = hapstab::stability::roots(&c).unwrap();
        println!(
            "  roots {:?}",
            r.iter()
                .map(|z| (z.norm() - 1.0, z.arg()))
                .collect::<Vec<_>>()
        );
    }
}
