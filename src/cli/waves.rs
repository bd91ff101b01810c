//! `--waves` and its table: the one setting that reads a file.

use super::{input, Cli, UsageError, WavesArg};
use crate::ocean::{gerstner, Waves};

impl Cli {
    /// `--waves` with its table (`--gerstner-waves`, `--gerstner-count`).
    pub(super) fn waves_setting(&self) -> Result<Waves, UsageError> {
        Ok(match self.waves {
            WavesArg::Fft => {
                if self.gerstner_waves.is_some() || self.gerstner_count.is_some() {
                    return Err(UsageError(
                        "--gerstner-waves and --gerstner-count need --waves gerstner".to_string(),
                    ));
                }
                Waves::Fft
            }
            WavesArg::Gerstner => {
                let mut table = match &self.gerstner_waves {
                    None => gerstner::default_waves(),
                    Some(path) => {
                        let text = crate::input::read_text(
                            "--gerstner-waves",
                            path,
                            gerstner::MAX_TABLE_BYTES,
                        )
                        .map_err(input)?;
                        let format = gerstner::TableFormat::of_path(path);
                        gerstner::parse_waves(&text, format).map_err(|e| {
                            UsageError(format!("--gerstner-waves {}: {e}", path.display()))
                        })?
                    }
                };
                if let Some(m) = self.gerstner_count {
                    if m > table.len() {
                        return Err(UsageError(format!(
                            "--gerstner-count {m}: the table has only {} waves",
                            table.len()
                        )));
                    }
                    table.truncate(m);
                }
                if let Some((factor, sum)) = gerstner::limit_steepness(&mut table) {
                    eprintln!(
                        "vkocean: Gerstner steepness Q scaled by {factor:.3}: the table's Σ Q·k·a was {sum:.3}, and above 1 the surface can fold over"
                    );
                }
                Waves::Gerstner(table)
            }
        })
    }
}
