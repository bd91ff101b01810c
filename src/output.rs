//! Output files (`--screenshot`, `--profile`, `--dump`, bench `--json`) that are all-or-nothing:
//! the path is checked for writability before any GPU work starts (a probe file is created and
//! removed at once), the content goes to a temporary sibling at the end, and only complete files
//! are renamed into place, all of a run's together ([`place_all`]) after a last check for a
//! signal. An error, Ctrl-C or an early exit leaves nothing behind.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// A file that will be written at the end of the run.
#[derive(Debug)]
pub struct PendingFile {
    path: PathBuf,
    temp: PathBuf,
    /// What the file is for, in error messages (e.g. "--screenshot").
    what: &'static str,
}

/// `.NAME.PID.partial` beside `path`, and `path`'s file name.
fn temp_sibling(what: &str, path: &Path) -> anyhow::Result<(PathBuf, String)> {
    let name = path
        .file_name()
        .ok_or_else(|| anyhow::anyhow!("{what} {}: not a file path", path.display()))?
        .to_string_lossy()
        .into_owned();
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((
        parent.join(format!(".{name}.{}.partial", std::process::id())),
        name,
    ))
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
        let (temp, _) = temp_sibling(what, path)?;
        if path.is_dir() {
            anyhow::bail!("{what} {}: is a directory", path.display());
        }
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

    /// Writes `bytes` to the temporary file; [`place_all`] moves it into place.
    pub fn stage(mut self, bytes: &[u8]) -> anyhow::Result<Staged> {
        // From here the staged file owns (and on failure removes) the temporary file.
        let staged = Staged {
            temp: std::mem::take(&mut self.temp),
            path: self.path.clone(),
            what: self.what,
            dir: false,
        };
        let fail = |e: std::io::Error| {
            anyhow::anyhow!(
                "cannot write {} {}: {e}",
                staged.what,
                staged.path.display()
            )
        };
        let mut file = File::create(&staged.temp).map_err(fail)?;
        file.write_all(bytes).map_err(fail)?;
        file.sync_all().map_err(fail)?;
        Ok(staged)
    }

    /// Writes `bytes` and moves the complete file into place (unless a signal came first).
    pub fn commit(self, bytes: &[u8]) -> anyhow::Result<()> {
        place_all(vec![self.stage(bytes)?])
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        // Empty once staged; otherwise remove a probe or partial file.
        if !self.temp.as_os_str().is_empty() {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

/// A complete output in its temporary place (a file, or `--dump`'s directory).
#[derive(Debug)]
pub struct Staged {
    temp: PathBuf,
    path: PathBuf,
    what: &'static str,
    dir: bool,
}

impl Drop for Staged {
    fn drop(&mut self) {
        // Gone after a successful rename; removed otherwise.
        if self.dir {
            let _ = std::fs::remove_dir_all(&self.temp);
        } else {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

/// Moves every staged output into place, unless a signal was caught: then they are all removed.
pub fn place_all(staged: Vec<Staged>) -> anyhow::Result<()> {
    crate::interrupt::check()?;
    for s in &staged {
        std::fs::rename(&s.temp, &s.path)
            .map_err(|e| anyhow::anyhow!("cannot write {} {}: {e}", s.what, s.path.display()))?;
    }
    Ok(())
}

/// A directory of files written at the end of the run (`--dump DIR`). An existing directory
/// gets each file staged beside its final name; a new one is staged whole as a hidden sibling
/// and renamed into place, so a failed or interrupted run creates no directory.
#[derive(Debug)]
pub struct PendingDir {
    path: PathBuf,
    what: &'static str,
    existed: bool,
}

impl PendingDir {
    /// Proves that the directory (or, if it does not exist yet, its parent) is writable.
    pub fn create(what: &'static str, path: &Path) -> anyhow::Result<PendingDir> {
        let shown = path.display();
        let existed = match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => true,
            Ok(_) => anyhow::bail!("{what} {shown}: exists and is not a directory"),
            Err(_) => false,
        };
        if existed {
            // A probe file inside it.
            PendingFile::create(what, &path.join("probe"))?;
        } else {
            let (temp, _) = temp_sibling(what, path)?;
            std::fs::create_dir(&temp).map_err(|e| match e.kind() {
                std::io::ErrorKind::NotFound => anyhow::anyhow!(
                    "cannot create {what} {shown}: its parent directory does not exist"
                ),
                _ => anyhow::anyhow!("cannot create {what} {shown}: {e}"),
            })?;
            let _ = std::fs::remove_dir(&temp);
        }
        Ok(PendingDir {
            path: path.to_path_buf(),
            what,
            existed,
        })
    }

    /// Writes `files` (name, bytes) to their temporary places; [`place_all`] moves them.
    pub fn stage(self, files: &[(&str, Vec<u8>)]) -> anyhow::Result<Vec<Staged>> {
        if self.existed {
            return files
                .iter()
                .map(|(name, bytes)| {
                    PendingFile::create(self.what, &self.path.join(name))?.stage(bytes)
                })
                .collect();
        }
        let (temp, _) = temp_sibling(self.what, &self.path)?;
        let shown = self.path.display();
        let fail = |e: std::io::Error| anyhow::anyhow!("cannot write {} {shown}: {e}", self.what);
        std::fs::create_dir(&temp).map_err(fail)?;
        let staged = Staged {
            temp: temp.clone(),
            path: self.path.clone(),
            what: self.what,
            dir: true,
        };
        for (name, bytes) in files {
            let mut file = File::create(temp.join(name)).map_err(fail)?;
            file.write_all(bytes).map_err(fail)?;
            file.sync_all().map_err(fail)?;
        }
        Ok(vec![staged])
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

/// The first error writing to stdout (other than a closed pipe), for [`stdout_status`].
static STDOUT_ERROR: Mutex<Option<String>> = Mutex::new(None);

/// Writes to stdout. A closed pipe is ignored (`vkocean bench frames | head` must not fail;
/// what the reader stopped reading is lost either way); any other error (a full disk,
/// `/dev/full`) is kept for [`stdout_status`].
pub fn write_stdout(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let result = out.write_all(text.as_bytes()).and_then(|_| out.flush());
    if let Err(e) = result {
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            let mut first = STDOUT_ERROR.lock().unwrap_or_else(|p| p.into_inner());
            first.get_or_insert_with(|| e.to_string());
        }
    }
}

/// `Err` once a write to stdout failed (see [`write_stdout`]).
pub fn stdout_status() -> anyhow::Result<()> {
    match STDOUT_ERROR
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .as_ref()
    {
        Some(e) => anyhow::bail!("cannot write to stdout: {e}"),
        None => Ok(()),
    }
}

/// `println!` to [`write_stdout`].
#[macro_export]
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::output::write_stdout(&(format!($($arg)*) + "\n"))
    };
}
