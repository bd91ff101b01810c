//! `vkocean bench fft`: bad values are usage errors; a small run prints the table and writes JSON
//! rows with positive timings.

mod common;

use common::{run, scratch, stderr};

#[test]
fn bench_fft_rejects_bad_values() {
    for (args, needle) in [
        (vec!["bench", "fft", "--sizes", "100"], "power of two"),
        (vec!["bench", "fft", "--sizes", "2048"], "power of two"),
        (vec!["bench", "fft", "--sizes", "32"], "power of two"),
        (
            vec!["bench", "fft", "--sizes", "256,x"],
            "not a whole number",
        ),
        (vec!["bench", "fft", "--batch", "0"], "--batch"),
        (vec!["bench", "fft", "--runs", "-2"], "--runs"),
        (
            vec!["bench", "fft", "--json", "out.txt"],
            "must end in .json",
        ),
        (vec!["bench", "nothing"], "nothing"),
    ] {
        let out = run(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn bench_fft_writes_rows() {
    let dir = scratch("bench-fft");
    let json = dir.join("fft.json");
    let out = run(&[
        "bench",
        "fft",
        "--sizes",
        "64,128",
        "--batch",
        "2",
        "--runs",
        "3",
        "--json",
        json.to_str().unwrap(),
        "--validation",
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("validation: 0 warnings, 0 errors"), "{err}");
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("gpu_ms") && table.contains("rustfft_ms") && table.contains("ratio"),
        "{table}"
    );
    let rows: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = rows.as_array().expect("an array of rows");
    assert_eq!(rows.len(), 2);
    for (row, n) in rows.iter().zip([64, 128]) {
        assert_eq!(row["n"], n);
        assert_eq!(row["batch"], 2);
        let (gpu, cpu, ratio) = (
            row["gpu_ms"].as_f64().unwrap(),
            row["rustfft_ms"].as_f64().unwrap(),
            row["ratio"].as_f64().unwrap(),
        );
        assert!(gpu > 0.0 && cpu > 0.0, "{row}");
        assert!((ratio - gpu / cpu).abs() < 1e-9 * ratio.max(1.0), "{row}");
    }
}
