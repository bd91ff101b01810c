//! The CLI's defaults and refusals.

use super::*;

#[test]
fn headless_defaults() {
    let cli = Cli::parse_from(["vkocean", "--headless"]);
    assert_eq!(cli.settings().unwrap().frames, Some(1));
    let cli = Cli::parse_from(["vkocean", "--headless", "--profile", "p.json"]);
    assert_eq!(cli.settings().unwrap().frames, Some(60));
    let cli = Cli::parse_from([
        "vkocean",
        "--headless",
        "--profile",
        "p.json",
        "--frames",
        "5",
    ]);
    assert!(cli.settings().is_err());
    let cli = Cli::parse_from(["vkocean", "--screenshot", "s.jpg"]);
    assert!(cli.settings().is_err());
}
