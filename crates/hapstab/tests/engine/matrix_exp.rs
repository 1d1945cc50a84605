//! `hapstab::matrix_exp`: E(h) = e^{Ah} − I and Ψ(h) = ∫₀ʰ e^{As} ds against closed forms,
//! on both sides of the order where the work buffers move from the stack to the heap.

use hapstab::matrix_exp::{exp_and_integral, exp_joined};
use hapstab::poly::Mat;

/// Largest |x − y| / max(1, |y|) over two matrices.
fn rel_err(got: &Mat, want: &Mat) -> f64 {
    got.iter()
        .flatten()
        .zip(want.iter().flatten())
        .map(|(x, y)| (x - y).abs() / y.abs().max(1.0))
        .fold(0.0, f64::max)
}

fn diagonal(values: &[f64]) -> Mat {
    let n = values.len();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| if i == j { values[i] } else { 0.0 })
                .collect()
        })
        .collect()
}

/// A diagonal matrix: E = diag(expm1(λh)), Ψ = diag(expm1(λh)/λ), for orders 1 to 12.
#[test]
fn diagonal_matrices_of_every_order() {
    for n in 1..=12 {
        let lambdas: Vec<f64> = (0..n).map(|i| -3.0 + 0.7 * i as f64).collect();
        let h = 0.9;
        let (e, psi) = exp_and_integral(&diagonal(&lambdas), h);
        let want_e = diagonal(&lambdas.iter().map(|l| (l * h).exp_m1()).collect::<Vec<_>>());
        let want_psi = diagonal(
            &lambdas
                .iter()
                .map(|&l| if l == 0.0 { h } else { (l * h).exp_m1() / l })
                .collect::<Vec<_>>(),
        );
        assert!(rel_err(&e, &want_e) < 1e-14, "order {n}: E");
        assert!(rel_err(&psi, &want_psi) < 1e-14, "order {n}: Ψ");
    }
}

/// The undamped oscillator A = [[0, 1], [−ω², 0]]: e^{Ah} = [[c, s/ω], [−ωs, c]] and
/// Ψ(h) = [[s/ω, (1 − c)/ω²], [c − 1, s/ω]] with c = cos ωh, s = sin ωh (E = e^{Ah} − I).
#[test]
fn oscillator_in_closed_form() {
    for (w, h) in [(1.0, 1.0), (3.0, 0.25), (0.01, 1.0), (20.0, 1.0)] {
        let a = vec![vec![0.0, 1.0], vec![-w * w, 0.0]];
        let (e, psi) = exp_and_integral(&a, h);
        let s = (w * h).sin();
        // c − 1 = −2 sin²(ωh/2), free of cancellation for small ωh.
        let cm1 = -2.0 * (w * h / 2.0).sin().powi(2);
        let want_e = vec![vec![cm1, s / w], vec![-w * s, cm1]];
        let want_psi = vec![vec![s / w, -cm1 / (w * w)], vec![cm1, s / w]];
        assert!(rel_err(&e, &want_e) < 1e-13, "ω = {w}: E {e:?}");
        assert!(rel_err(&psi, &want_psi) < 1e-13, "ω = {w}: Ψ {psi:?}");
    }
}

/// A nilpotent shift of order n (ones above the diagonal): e^{Nh} − I has h^k/k! on the k-th
/// superdiagonal and Ψ(h) has h^{k+1}/(k+1)!, exact polynomials (orders 3 and 9).
#[test]
fn nilpotent_shift_is_a_finite_series() {
    for n in [3usize, 9] {
        let a: Mat = (0..n)
            .map(|i| (0..n).map(|j| if j == i + 1 { 1.0 } else { 0.0 }).collect())
            .collect();
        let h = 1.7;
        let (e, psi) = exp_and_integral(&a, h);
        let fact = |k: usize| (1..=k).map(|x| x as f64).product::<f64>();
        for i in 0..n {
            for j in 0..n {
                let (we, wp) = if j >= i {
                    let k = j - i;
                    let we = if k == 0 {
                        0.0
                    } else {
                        h.powi(k as i32) / fact(k)
                    };
                    (we, h.powi(k as i32 + 1) / fact(k + 1))
                } else {
                    (0.0, 0.0)
                };
                assert!(
                    (e[i][j] - we).abs() <= 1e-14 * we.abs().max(1.0),
                    "E[{i}][{j}]"
                );
                assert!(
                    (psi[i][j] - wp).abs() <= 1e-14 * wp.abs().max(1.0),
                    "Ψ[{i}][{j}]"
                );
            }
        }
    }
}

/// E keeps its digits when ‖Ah‖ is tiny (formed without I): E = Ah + (Ah)²/2 to a few ulps, where e^{Ah} − I formed from e^{Ah} would keep none.
#[test]
fn tiny_steps_keep_every_digit_of_e() {
    let a = vec![vec![0.0, 1.0], vec![-4.0, -0.5]];
    let h = 1e-12;
    let (e, psi) = exp_and_integral(&a, h);
    let want = h * (1.0 - 0.25 * h);
    assert!(
        (e[0][1] - want).abs() <= 4.0 * f64::EPSILON * want,
        "{} vs {want}",
        e[0][1]
    );
    // (A²)₁₀ = 2: E₁₀ = −4h + h².
    assert!((e[1][0] - (-4.0 * h + h * h)).abs() <= 4.0 * f64::EPSILON * 4.0 * h);
    assert!((psi[0][0] - h).abs() <= 1e-15 * h);
}

/// e^{A(s+t)} = e^{As}·e^{At}: joining E(0.3) and E(0.7) gives E(1) (orders 2 and 8).
#[test]
fn joined_steps_equal_the_whole_step() {
    for n in [2usize, 8] {
        let a: Mat = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| ((i * 7 + j * 3) % 5) as f64 * 0.3 - 0.6)
                    .collect()
            })
            .collect();
        let (e_s, _) = exp_and_integral(&a, 0.3);
        let (e_t, _) = exp_and_integral(&a, 0.7);
        let (e_1, _) = exp_and_integral(&a, 1.0);
        assert!(rel_err(&exp_joined(&e_s, &e_t), &e_1) < 1e-13, "order {n}");
    }
}

/// h = 0 gives zero matrices; a zero matrix gives E = 0 and Ψ = h·I.
#[test]
fn zero_step_and_zero_matrix() {
    let a = vec![vec![1.0, 2.0], vec![3.0, 4.0]];
    let (e, psi) = exp_and_integral(&a, 0.0);
    assert!(e.iter().chain(&psi).flatten().all(|&x| x == 0.0));
    let (e, psi) = exp_and_integral(&diagonal(&[0.0; 7]), 2.5);
    assert!(e.iter().flatten().all(|&x| x == 0.0));
    assert_eq!(psi, diagonal(&[2.5; 7]));
}
