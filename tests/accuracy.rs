//! README's "Physical accuracy" table: every row within its tolerance, printed as markdown and
//! written to target/accuracy.md. Regenerate the table with
//! `cargo test --release --test accuracy -- --nocapture`.

mod common;

use common::{run, stderr};
use vkocean::ocean::accuracy::{shore_rows, spectrum_rows, Row, Tolerance};
use vkocean::ocean::foam::monahan_fraction;

/// Mean `surface.whitecap_fraction` (%) of frames 51–100 at 0.1 s steps: 5 s of sea after the
/// first frame's warm-up. The fraction is the FFT lattice's foam (assemble.comp), which the
/// foam simulation near the camera neither feeds nor reads: that runs off (at `high` it would
/// be two thirds of each frame's cost on lavapipe).
fn whitecap_percent(preset: &str, quality: &str) -> f64 {
    let out = run(&[
        "--headless",
        "--size",
        "64x36",
        "--foam-sim",
        "off",
        "--preset",
        preset,
        "--quality",
        quality,
        "--frames",
        "100",
        "--dt",
        "0.1",
        "--stats",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    let values: Vec<f64> = text
        .lines()
        .skip(50)
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            v["surface"]["whitecap_fraction"].as_f64().unwrap()
        })
        .collect();
    assert_eq!(values.len(), 50);
    values.iter().sum::<f64>() / 50.0 * 100.0
}

#[test]
fn physical_accuracy_table() {
    let mut rows = spectrum_rows();
    rows.extend(shore_rows());
    // Monahan & O'Muircheartaigh (1980), W = 3.84·10⁻⁶ U10^3.41: within a factor of 2 (the
    // issue's tolerance; the field data scatter about as much) at the breeze and above, at the
    // default quality on lavapipe (`low`) and the one on a GPU (`high`); under 0.1 % when calm.
    let cases = [
        ("breeze", 6.7, "low"),
        ("moderate", 12.3, "low"),
        ("storm", 26.5, "low"),
        ("moderate", 12.3, "high"),
        ("storm", 26.5, "high"),
    ];
    for (preset, u10, quality) in cases {
        let want = monahan_fraction(u10) * 100.0;
        rows.push(Row {
            quantity: format!("whitecap fraction (%), {preset} (U10 {u10} m/s), `{quality}`"),
            literature: format!("Monahan & O'Muircheartaigh (1980): {want:.3}"),
            literature_value: want,
            ours: whitecap_percent(preset, quality),
            tolerance: Tolerance::Factor(2.0),
        });
    }
    let calm = monahan_fraction(2.5) * 100.0;
    rows.push(Row {
        quantity: "whitecap fraction (%), calm (U10 2.5 m/s), `low`".into(),
        literature: format!("Monahan & O'Muircheartaigh (1980): {calm:.4}"),
        literature_value: calm,
        ours: whitecap_percent("calm", "low"),
        tolerance: Tolerance::Below(0.1),
    });
    let mut table =
        String::from("| quantity | literature | ours | tolerance |\n|---|---|---|---|\n");
    for row in &rows {
        table += &row.markdown(4);
        table.push('\n');
    }
    println!("{table}");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/accuracy.md");
    std::fs::write(&path, &table).unwrap();
    let failed: Vec<&Row> = rows.iter().filter(|r| !r.holds()).collect();
    assert!(
        failed.is_empty(),
        "outside their tolerance: {failed:#?}\n{table}"
    );
}
