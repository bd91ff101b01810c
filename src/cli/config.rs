//! `--config FILE.toml`: a file of settings, turned into command-line flags.

use std::path::PathBuf;

use clap::Parser;

use super::values::require_extension;
use super::{Cli, UsageError};

/// Largest `--config` file read (bytes).
const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Expands `--config FILE.toml` (anywhere in `args`): the file's settings become flags inserted
/// right after the program name, so the command line's own flags, coming later, win.
pub fn with_config(args: Vec<std::ffi::OsString>) -> Result<Vec<std::ffi::OsString>, UsageError> {
    use clap::CommandFactory;
    let mut paths = Vec::new();
    let mut iter = args.iter().skip(1);
    while let Some(arg) = iter.next() {
        let arg = arg.to_string_lossy();
        if arg == "--" {
            break;
        } else if arg == "--config" {
            paths.extend(iter.next().map(PathBuf::from));
        } else if let Some(value) = arg.strip_prefix("--config=") {
            paths.push(PathBuf::from(value));
        }
    }
    if paths.len() > 1 {
        return Err(UsageError(
            "--config given more than once: one file per run (put the settings in one file; flags on the command line override it)".to_string(),
        ));
    }
    let Some(path) = paths.pop() else {
        return Ok(args);
    };
    require_extension("--config", Some(&path), "toml")?;
    let shown = path.display().to_string();
    let fail = |what: String| UsageError(format!("--config {shown}: {what}"));
    let text = crate::input::read_text("--config", &path, MAX_CONFIG_BYTES)
        .map_err(|e| UsageError(e.0))?;
    let doc: toml_edit::DocumentMut = text.parse().map_err(|e: toml_edit::TomlError| {
        let mut reason = crate::ocean::gerstner::toml_error_line(&e);
        if reason.contains("overflow") {
            reason.push_str(&format!(
                " (TOML integers stop at {}: write a larger seed as a string, e.g. seed = \"{}\")",
                i64::MAX,
                u64::MAX
            ));
        }
        fail(reason)
    })?;
    let command = Cli::command();
    let mut extra: Vec<std::ffi::OsString> = Vec::new();
    let mut seen: Vec<(String, &str)> = Vec::new();
    for (key, item) in doc.as_table().iter() {
        let long = key.replace('_', "-");
        if let Some((_, first)) = seen.iter().find(|(l, _)| *l == long) {
            return Err(fail(format!(
                "keys '{first}' and '{key}' name the same setting"
            )));
        }
        seen.push((long.clone(), key));
        let arg = command
            .get_arguments()
            .find(|a| a.get_long() == Some(long.as_str()) && !a.is_hide_set())
            .filter(|_| !["config", "help", "version"].contains(&long.as_str()))
            .ok_or_else(|| fail(format!("unknown key '{key}'")))?;
        let flag = matches!(arg.get_action(), clap::ArgAction::SetTrue);
        let value = item
            .as_value()
            .ok_or_else(|| fail(format!("key '{key}': expected a value, not a table")))?;
        let scalar = |v: &toml_edit::Value| -> Option<String> {
            match v {
                toml_edit::Value::Integer(i) => Some(i.value().to_string()),
                toml_edit::Value::Float(f) => Some(f.value().to_string()),
                toml_edit::Value::String(s) => Some(s.value().clone()),
                _ => None,
            }
        };
        match (flag, value) {
            (true, toml_edit::Value::Boolean(b)) => {
                if *b.value() {
                    extra.push(format!("--{long}").into());
                }
            }
            (true, _) => return Err(fail(format!("key '{key}': expected true or false"))),
            (false, toml_edit::Value::Array(list)) => {
                let parts: Option<Vec<String>> = list.iter().map(scalar).collect();
                let parts = parts
                    .ok_or_else(|| fail(format!("key '{key}': expected a list of numbers")))?;
                extra.push(format!("--{long}={}", parts.join(",")).into());
            }
            (false, v) => {
                let text = scalar(v)
                    .ok_or_else(|| fail(format!("key '{key}': expected a number or a string")))?;
                extra.push(format!("--{long}={text}").into());
            }
        }
    }
    // Check the file's settings on their own, so an error names the file.
    let mut alone = vec![args[0].clone()];
    alone.extend(extra.iter().cloned());
    if let Err(e) = Cli::try_parse_from(&alone) {
        let text = e.to_string();
        let first = text.lines().next().unwrap_or("invalid value");
        return Err(fail(first.trim_start_matches("error: ").to_string()));
    }
    let mut out = vec![args[0].clone()];
    out.extend(extra);
    out.extend(args.into_iter().skip(1));
    Ok(out)
}
