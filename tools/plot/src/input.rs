//! Reading `vkocean bench frames` output: the JSON report (one bar of `passes`) and the CSV
//! (one series of `frames`). Errors name the file.

use std::path::Path;

use serde_json::Value;

use crate::{runtime, Error, TOTAL_NAMES};

pub(crate) fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

fn read_text(path: &Path) -> Result<String, Error> {
    std::fs::read_to_string(path)
        .map_err(|e| runtime(format!("cannot read {}: {e}", path.display())))
}

/// One `passes` bar: the run's timed passes in report order.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    pub label: String,
    pub device: Option<String>,
    /// (pass name, median GPU ms > 0).
    pub passes: Vec<(String, f64)>,
}

/// Reads a bench frames / `--profile` JSON report.
pub fn read_run(path: &Path) -> Result<Run, Error> {
    let shown = path.display();
    let value: Value = serde_json::from_str(&read_text(path)?)
        .map_err(|e| runtime(format!("{shown}: not valid JSON: {e}")))?;
    let entries = value.get("passes").and_then(Value::as_array).ok_or_else(|| {
        runtime(format!(
            "{shown}: no \"passes\" array (expected the --json of vkocean bench frames or --profile)"
        ))
    })?;
    let mut passes = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        let name = entry
            .get("name")
            .and_then(Value::as_str)
            .ok_or_else(|| runtime(format!("{shown}: passes[{i}] has no \"name\" string")))?;
        let median = match entry.get("gpu_ms").and_then(|g| g.get("median")) {
            None | Some(Value::Null) => continue,
            Some(m) => m
                .as_f64()
                .filter(|m| m.is_finite() && *m >= 0.0)
                .ok_or_else(|| {
                    runtime(format!(
                        "{shown}: passes[{i}] ({name}): gpu_ms.median {m} is not a number >= 0"
                    ))
                })?,
        };
        if median > 0.0 && !TOTAL_NAMES.contains(&name) {
            passes.push((name.to_string(), median));
        }
    }
    if passes.is_empty() {
        return Err(runtime(format!(
            "{shown}: no pass has a GPU median above 0 (no timestamps?)"
        )));
    }
    let setting = |key: &str| {
        value
            .get("settings")
            .and_then(|s| s.get(key))
            .and_then(Value::as_str)
    };
    let label = match (setting("quality"), setting("size")) {
        (Some(q), Some(s)) => format!("{q} {s}"),
        (Some(one), None) | (None, Some(one)) => one.to_string(),
        (None, None) => path
            .file_stem()
            .map_or_else(|| file_name(path), |s| s.to_string_lossy().into_owned()),
    };
    Ok(Run {
        label,
        device: value
            .get("device")
            .and_then(Value::as_str)
            .map(str::to_string),
        passes,
    })
}

/// The `frames` chart's data: per CSV row the frame index and its GPU and CPU ms (`None`: an
/// empty cell).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FrameSeries {
    pub frame: Vec<f64>,
    pub gpu_ms: Vec<Option<f64>>,
    pub cpu_ms: Vec<Option<f64>>,
}

/// Reads a bench frames `--csv`.
pub fn read_frames(path: &Path) -> Result<FrameSeries, Error> {
    let shown = path.display();
    let text = read_text(path)?;
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty());
    let Some((_, header)) = lines.next() else {
        return Err(runtime(format!(
            "{shown}: empty CSV (expected the --csv of vkocean bench frames)"
        )));
    };
    let header: Vec<&str> = header.split(',').map(str::trim).collect();
    let column = |name: &str| {
        header.iter().position(|h| *h == name).ok_or_else(|| {
            runtime(format!(
                "{shown}: the header has no {name} column (expected the --csv of vkocean bench frames)"
            ))
        })
    };
    let (frame_col, gpu_col, cpu_col) = (column("frame")?, column("gpu_ms")?, column("cpu_ms")?);
    let mut series = FrameSeries::default();
    for (line, row) in lines {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        if cells.len() != header.len() {
            return Err(runtime(format!(
                "{shown}:{line}: {} cells, the header has {}",
                cells.len(),
                header.len()
            )));
        }
        let number = |col: usize| -> Result<Option<f64>, Error> {
            let cell = cells[col];
            if cell.is_empty() {
                return Ok(None);
            }
            cell.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v >= 0.0)
                .map(Some)
                .ok_or_else(|| {
                    runtime(format!(
                        "{shown}:{line}: {} {cell:?} is not a number >= 0",
                        header[col]
                    ))
                })
        };
        let frame = number(frame_col)?
            .ok_or_else(|| runtime(format!("{shown}:{line}: empty frame cell")))?;
        series.frame.push(frame);
        series.gpu_ms.push(number(gpu_col)?);
        series.cpu_ms.push(number(cpu_col)?);
    }
    if series.frame.is_empty() {
        return Err(runtime(format!("{shown}: no frames, only a header")));
    }
    if series
        .gpu_ms
        .iter()
        .chain(&series.cpu_ms)
        .all(Option::is_none)
    {
        return Err(runtime(format!("{shown}: no gpu_ms or cpu_ms values")));
    }
    Ok(series)
}
