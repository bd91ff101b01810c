//! Output files (`--screenshot`, `--profile`) that are all-or-nothing: the path is checked for
//! writability before any GPU work starts (a probe file is created and removed at once), the
//! content goes to a temporary file beside it at the end, and only a complete file is renamed
//! into place. An error, Ctrl-C or an early exit leaves nothing behind.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A file that will be written at the end of the run.
#[derive(Debug)]
pub struct PendingFile {
    path: PathBuf,
    temp: PathBuf,
    /// What the file is for, in error messages (e.g. "--screenshot").
    what: &'static str,
}

impl PendingFile {
    /// Proves that `path` can be written by creating (and removing) its temporary sibling now.
    /// [`PendingFile::create`] for an optional output flag.
    pub fn create_if(
        what: &'static str,
        path: Option<&Path>,
    ) -> anyhow::Result<Option<PendingFile>> {
        path.map(|p| PendingFile::create(what, p)).transpose()
    }

    pub fn create(what: &'static str, path: &Path) -> anyhow::Result<PendingFile> {
        let name = path
            .file_name()
            .ok_or_else(|| anyhow::anyhow!("{what} {}: not a file path", path.display()))?
            .to_string_lossy()
            .into_owned();
        if path.is_dir() {
            anyhow::bail!("{what} {}: is a directory", path.display());
        }
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let temp = parent.join(format!(".{name}.{}.partial", std::process::id()));
        File::create(&temp)
            .map_err(|e| anyhow::anyhow!("cannot write {what} {}: {e}", path.display()))?;
        let _ = std::fs::remove_file(&temp);
        Ok(PendingFile {
            path: path.to_path_buf(),
            temp,
            what,
        })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes `bytes` and moves the complete file into place.
    pub fn commit(self, bytes: &[u8]) -> anyhow::Result<()> {
        let fail = |e: std::io::Error| {
            anyhow::anyhow!("cannot write {} {}: {e}", self.what, self.path.display())
        };
        let mut file = File::create(&self.temp).map_err(fail)?;
        file.write_all(bytes).map_err(fail)?;
        file.sync_all().map_err(fail)?;
        drop(file);
        std::fs::rename(&self.temp, &self.path).map_err(fail)?;
        Ok(())
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        // After a successful commit the temp file no longer exists; otherwise remove the partial.
        let _ = std::fs::remove_file(&self.temp);
    }
}

/// Encodes tightly packed RGBA8 pixels as PNG.
pub fn encode_png(width: u32, height: u32, rgba: &[u8]) -> anyhow::Result<Vec<u8>> {
    use image::ImageEncoder;
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png).write_image(
        rgba,
        width,
        height,
        image::ExtendedColorType::Rgba8,
    )?;
    Ok(png)
}

/// Writes to stdout, ignoring a closed pipe (`vkocean bench frames | head` must not panic; what
/// the reader stopped reading is lost either way).
pub fn write_stdout(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes());
    let _ = out.flush();
}

/// `println!` to [`write_stdout`].
#[macro_export]
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::output::write_stdout(&(format!($($arg)*) + "\n"))
    };
}
