//! The command line (clap derive) and its validation into [`RunSettings`]. Bad values are usage
//! errors (exit code 2) with a one-line message.

use std::path::PathBuf;

use clap::{Parser, ValueEnum};

use crate::frontend::RunSettings;
use crate::gpu::PresentMode;
use crate::profile::WARMUP_FRAMES;

/// Largest accepted `--size` side; the device limit is checked again at run time.
pub const MAX_SIDE: u32 = 16384;

#[derive(Parser, Debug)]
#[command(
    name = "vkocean",
    version,
    about = "A real-time FFT ocean on hand-written Vulkan.",
    after_help = "Exit codes: 0 ok, 1 runtime error, 2 bad usage, 3 validation reported warnings or errors.\n\
                  Without a GPU, Mesa's lavapipe (CPU) driver is used; install it with tools/setup."
)]
pub struct Cli {
    /// Render offscreen without a window (default 1 frame; 60 with --profile).
    #[arg(long)]
    pub headless: bool,

    /// Stop after N frames (a window otherwise runs until Esc or close).
    #[arg(long, value_name = "N", value_parser = parse_frames, allow_hyphen_values = true)]
    pub frames: Option<u64>,

    /// Render size in pixels (window inner size, or the headless image).
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "1280x720")]
    pub size: (u32, u32),

    /// Save the last frame as PNG (in a window F12 also saves one).
    #[arg(long, value_name = "PATH")]
    pub screenshot: Option<PathBuf>,

    /// Enable the Khronos validation layer with synchronization validation; prints
    /// "validation: N warnings, M errors" at exit and exits with 3 if there were any.
    #[arg(long)]
    pub validation: bool,

    /// Write GPU timestamps per pass and frame times as JSON (first 5 frames are warm-up).
    #[arg(long, value_name = "PATH")]
    pub profile: Option<PathBuf>,

    /// Use Vulkan device N (see --list-gpus); default: the best one (discrete > integrated > virtual > cpu).
    #[arg(long, value_name = "N")]
    pub gpu: Option<usize>,

    /// List the Vulkan devices and exit.
    #[arg(long)]
    pub list_gpus: bool,

    /// Window presentation mode (falls back to fifo when the surface lacks it).
    #[arg(long, value_enum, value_name = "MODE", default_value_t = PresentModeArg::Fifo)]
    pub present_mode: PresentModeArg,

    /// Test only: record a deliberate synchronization hazard (validation must catch it).
    #[arg(long, hide = true)]
    pub inject_sync_hazard: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PresentModeArg {
    Fifo,
    Mailbox,
    Immediate,
}

fn parse_frames(s: &str) -> Result<u64, String> {
    match s.trim().parse::<i128>() {
        Ok(n) if n >= 1 && n <= u32::MAX as i128 => Ok(n as u64),
        Ok(_) => Err(format!("must be a whole number from 1 to {}", u32::MAX)),
        Err(_) => Err("not a whole number".to_string()),
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or("expected WIDTHxHEIGHT, e.g. 1280x720")?;
    let side = |v: &str| -> Result<u32, String> {
        let n: u64 = v
            .trim()
            .parse()
            .map_err(|_| "expected WIDTHxHEIGHT with whole numbers, e.g. 1280x720".to_string())?;
        if n == 0 || n > MAX_SIDE as u64 {
            return Err(format!("each side must be from 1 to {MAX_SIDE} pixels"));
        }
        Ok(n as u32)
    };
    Ok((side(w)?, side(h)?))
}

/// A command-line value that is wrong (exit code 2).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

impl Cli {
    /// Cross-checks the options and resolves defaults.
    pub fn settings(&self) -> Result<RunSettings, UsageError> {
        for (flag, path) in [
            ("--screenshot", &self.screenshot),
            ("--profile", &self.profile),
        ] {
            let Some(path) = path else { continue };
            let want = if flag == "--screenshot" {
                "png"
            } else {
                "json"
            };
            let ext = path
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            if ext.as_deref() != Some(want) {
                return Err(UsageError(format!(
                    "{flag} {}: the file name must end in .{want}",
                    path.display()
                )));
            }
        }
        let frames = match (self.frames, self.headless, self.profile.is_some()) {
            (Some(n), _, true) if n <= WARMUP_FRAMES => {
                return Err(UsageError(format!(
                    "--profile needs more than {WARMUP_FRAMES} frames (the first {WARMUP_FRAMES} are warm-up); got --frames {n}"
                )))
            }
            (Some(n), _, _) => Some(n),
            (None, true, true) => Some(60),
            (None, true, false) => Some(1),
            (None, false, _) => None,
        };
        Ok(RunSettings {
            headless: self.headless,
            frames,
            size: self.size,
            screenshot: self.screenshot.clone(),
            profile: self.profile.clone(),
            validation: self.validation,
            gpu: self.gpu,
            present_mode: match self.present_mode {
                PresentModeArg::Fifo => PresentMode::Fifo,
                PresentModeArg::Mailbox => PresentMode::Mailbox,
                PresentModeArg::Immediate => PresentMode::Immediate,
            },
            inject_sync_hazard: self.inject_sync_hazard,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes() {
        assert_eq!(parse_size("1280x720"), Ok((1280, 720)));
        assert_eq!(parse_size("64X32"), Ok((64, 32)));
        assert!(parse_size("0x0").is_err());
        assert!(parse_size("100000x10").is_err());
        assert!(parse_size("12x").is_err());
        assert!(parse_size("axb").is_err());
        assert!(parse_size("1280").is_err());
    }

    #[test]
    fn frames() {
        assert_eq!(parse_frames("60"), Ok(60));
        assert!(parse_frames("0").is_err());
        assert!(parse_frames("-3").is_err());
        assert!(parse_frames("1.5").is_err());
        assert!(parse_frames("99999999999").is_err());
    }

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
}
