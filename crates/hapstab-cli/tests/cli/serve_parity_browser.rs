//! End-to-end test of the explorer's robust K_max over a box in a real headless Chromium
//! (chromedriver + fantoccini, as hapstab-serve's `e2e`): a link with a box opens with the overlay on,
//! the K_max the page draws is `hapstab kmax --robust --box … --json`'s, the command line's
//! text (with what was checked) sits under the region and the marker is drawn; typing another
//! end of the box redraws it with the command line's new K_max, and the link keeps the box.
//! Screenshot: `target/tmp/serve_e2e_robust_kmax.png`. Skipped without Chromium and
//! chromedriver, like hapstab-serve's `e2e`, whose browser helpers it shares.

use crate::e2e_browser;
use crate::serve_support;

use crate::common;

use std::path::Path;

use e2e_browser::{Browser, R, attr, wait_for};
use fantoccini::{Client, Locator};
use serve_support::Server;

/// The paper's loop in physical units (the command line's default device and arm, d = 0).
const LOOP: &str = "mode=physical&device_mass=0.1&device_damping=1.5&arm_mass=1&arm_damping=6&arm_stiffness=350&period=0.001&d=0";

/// The command line's robust K_max of the default loop over arm-stiffness in [0, hi] and
/// arm-mass in [0.2, 2] at B = 5 Ns/m.
fn cli_k_max(hi: &str) -> f64 {
    let side = format!("arm-stiffness:0:{hi}");
    let j = common::json(&[
        "kmax",
        "--robust",
        "--box",
        &side,
        "--box",
        "arm-mass:0.2:2",
        "--wall-damping",
        "5",
    ]);
    j["k_max"].as_f64().expect("a robust K_max")
}

/// Waits until the page shows a robust K_max other than `old` and returns it.
async fn shown_k_max(c: &Client, old: &str) -> R<String> {
    wait_for(30, "the robust K_max", || async {
        let v = attr(&c.find(Locator::Id("plot")).await?, "data-robust-kmax").await?;
        Ok((!v.is_empty() && v != old).then_some(v))
    })
    .await
}

async fn drive(c: &Client, base: &str, shot: &Path) -> R<()> {
    c.goto(&format!(
        "{base}/?{LOOP}&show=11101&box=arm-stiffness%3A0%3A2000%2Carm-mass%3A0.2%3A2&box_damping=5"
    ))
    .await?;
    let k: f64 = shown_k_max(c, "").await?.parse()?;
    assert_eq!(k.to_bits(), cli_k_max("2000").to_bits(), "{k}");
    let text = c.find(Locator::Id("rk-text")).await?.text().await?;
    assert!(
        text.contains("random plants verified") && text.contains("limited by"),
        "{text}"
    );
    let mark = c.find(Locator::Id("robust-kmax-mark")).await?;
    assert_eq!(attr(&mark, "visibility").await?, "visible");
    // another end of the box, typed
    let hi = c.find(Locator::Css("#box-rows .box-hi")).await?;
    hi.clear().await?;
    hi.send_keys("1500").await?;
    let k2: f64 = shown_k_max(c, &k.to_string()).await?.parse()?;
    assert_eq!(k2.to_bits(), cli_k_max("1500").to_bits(), "{k2}");
    let url = c.current_url().await?;
    assert!(
        url.query()
            .unwrap_or("")
            .contains("box=arm-stiffness%3A0%3A1500"),
        "{url}"
    );
    std::fs::write(shot, c.screenshot().await?)?;
    Ok(())
}

#[test]
fn the_page_draws_the_command_line_robust_k_max() {
    let Some(browser) = Browser::find() else {
        return;
    };
    let server = Server::start(&[]);
    let base = server.base();
    browser.drive(async |c, log_dir| {
        drive(c, &base, &log_dir.join("serve_e2e_robust_kmax.png")).await
    });
}
