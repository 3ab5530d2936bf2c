//! Writing output files without ever leaving a half-written one, or a half-written set, behind.
//!
//! - [`check_outputs`]: before any work, every output path is checked (its folder exists and
//!   is writable, it is not a folder, not an input, not named twice).
//! - [`write_all_atomic`]: all outputs of a command go to temporary files first and are renamed
//!   together at the end, so either every output is written or none is.
//! - [`write_atomic`] / [`write_atomic_with`]: one file, the same way.
//!
//! The temporary files (`.NAME.PID.N.tmp` beside each output) are registered while they exist:
//! [`remove_temporaries`] deletes them, for a signal handler (the `skelfit` binary calls it on
//! SIGINT, SIGTERM and SIGHUP). An output that is a symbolic link is written through to the file
//! it points to (the link stays a link), and an existing output keeps its permissions.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard};
use thiserror::Error;

/// Why an output path cannot be written.
#[derive(Debug, Error)]
pub enum OutputError {
    /// The folder the output goes into does not exist.
    #[error("cannot write {path}: the folder {folder} does not exist; create it first")]
    NoFolder {
        /// The output.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
    },
    /// The output names a folder, or has no file name.
    #[error("cannot write {path}: it is a folder, not a file name")]
    NotAFile {
        /// The output.
        path: PathBuf,
    },
    /// The output is one of the command's inputs.
    #[error("cannot write {path}: it is also an input ({input}); choose another output name")]
    IsInput {
        /// The output.
        path: PathBuf,
        /// The input it would overwrite.
        input: PathBuf,
    },
    /// Two outputs name the same file.
    #[error("{path} is given for two outputs; choose a different name for each")]
    Duplicate {
        /// The output.
        path: PathBuf,
    },
    /// Creating, writing or renaming a file failed.
    #[error("cannot write {path}: {cause}")]
    Io {
        /// The output.
        path: PathBuf,
        /// What the system reported.
        cause: std::io::Error,
    },
}

/// Checks, before any work, that every path of `outputs` can be written: its folder exists and
/// a file can be created in it, it is not a folder, not one of `inputs` (compared after
/// resolving links) and no other output names the same file.
///
/// # Errors
/// The first problem found, as an [`OutputError`].
pub fn check_outputs(outputs: &[&Path], inputs: &[&Path]) -> Result<(), OutputError> {
    let inputs: Vec<(PathBuf, &Path)> = inputs
        .iter()
        .filter_map(|&i| Some((i.canonicalize().ok()?, i)))
        .collect();
    let mut seen: Vec<PathBuf> = Vec::new();
    for &path in outputs {
        let target = target_of(path);
        if target.file_name().is_none() || target.is_dir() {
            return Err(OutputError::NotAFile {
                path: path.to_owned(),
            });
        }
        let folder = folder_of(&target);
        if !folder.is_dir() {
            return Err(OutputError::NoFolder {
                path: path.to_owned(),
                folder: folder.to_owned(),
            });
        }
        let resolved = folder
            .canonicalize()
            .map(|f| f.join(target.file_name().unwrap_or_default()))
            .map_err(|cause| io_error(path, cause))?;
        if let Some((_, input)) = inputs.iter().find(|(i, _)| *i == resolved) {
            return Err(OutputError::IsInput {
                path: path.to_owned(),
                input: input.to_path_buf(),
            });
        }
        if seen.contains(&resolved) {
            return Err(OutputError::Duplicate {
                path: path.to_owned(),
            });
        }
        seen.push(resolved);
        // Writable: create (and remove) a temporary file where the output's will go.
        let (probe, file) = Temporary::create(&target).map_err(|cause| io_error(path, cause))?;
        drop(file);
        drop(probe);
    }
    Ok(())
}

/// Writes every `(path, bytes)` of `files` all-or-nothing: each goes to a temporary file in
/// its folder, flushed to disk; only when all are written are they renamed over their paths.
/// If any write fails, every temporary file is removed and no output is touched.
///
/// # Errors
/// [`OutputError::Io`] naming the file that could not be written.
pub fn write_all_atomic(files: &[(&Path, &[u8])]) -> Result<(), OutputError> {
    let mut staged = Vec::with_capacity(files.len());
    for &(path, bytes) in files {
        let temporary = Temporary::filled(path, |w| w.write_all(bytes))
            .map_err(|cause| io_error(path, cause))?;
        staged.push((path, temporary));
    }
    // Renamed under the registry's lock, so a signal handler waits for the whole set.
    let mut registry = registry();
    let mut result = Ok(());
    for (path, temporary) in staged {
        if result.is_ok() {
            result = temporary
                .commit(&mut registry)
                .map_err(|cause| io_error(path, cause));
        } else {
            temporary.discard(&mut registry);
        }
    }
    result
}

/// Writes `bytes` to `path` atomically: the data goes to a temporary file in the same folder,
/// is flushed to disk, and only then renamed over `path`. If anything fails, `path` is left as it
/// was and the temporary file is removed.
///
/// # Errors
/// Any I/O error creating, writing or renaming the file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomic_with(path, |file| file.write_all(bytes))
}

/// Like [`write_atomic`], but the content is produced by `fill` writing into the temporary file.
///
/// # Errors
/// Any I/O error from `fill` or from creating, syncing or renaming the file.
pub fn write_atomic_with(
    path: &Path,
    fill: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    Temporary::filled(path, fill)?.commit(&mut registry())
}

/// Removes every temporary output file still in progress, and keeps new ones from being
/// created until the process ends. For a signal handler, which then exits: the lock it takes
/// is never released, so that a write cannot start (or a set of renames be cut) after it.
pub fn remove_temporaries() {
    let mut registry = registry();
    for path in registry.drain(..) {
        let _ = std::fs::remove_file(path);
    }
    std::mem::forget(registry);
}

/// The temporary files in progress.
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn registry() -> MutexGuard<'static, Vec<PathBuf>> {
    TEMPORARIES.lock().unwrap_or_else(|p| p.into_inner())
}

fn io_error(path: &Path, cause: std::io::Error) -> OutputError {
    OutputError::Io {
        path: path.to_owned(),
        cause,
    }
}

/// The file an output really is: the target of a symbolic link (followed to its end, relative
/// links against the link's folder), else the path itself.
fn target_of(path: &Path) -> PathBuf {
    let mut target = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::read_link(&target) {
            Ok(next) => target = folder_of(&target).join(next),
            Err(_) => break,
        }
    }
    target
}

/// The folder of a file path (`.` for a bare name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A registered temporary file beside an output; removed on drop unless committed.
struct Temporary {
    /// The temporary file.
    path: PathBuf,
    /// The file it will replace (the output, links resolved).
    target: PathBuf,
    /// Renamed or removed already (nothing left to do on drop).
    done: bool,
}

impl Temporary {
    /// Creates an empty temporary file for `output`.
    fn create(output: &Path) -> std::io::Result<(Self, std::fs::File)> {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let target = target_of(output);
        let name = target
            .file_name()
            .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "no file name"))?;
        let path = folder_of(&target).join(format!(
            ".{}.{}.{}.tmp",
            name.to_string_lossy(),
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        // Created under the lock, so that `remove_temporaries` sees every file that exists.
        let mut registry = registry();
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)?;
        registry.push(path.clone());
        Ok((
            Self {
                path,
                target,
                done: false,
            },
            file,
        ))
    }

    /// A temporary file for `output` holding what `fill` wrote, flushed to disk.
    fn filled(
        output: &Path,
        fill: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
    ) -> std::io::Result<Self> {
        let (temporary, file) = Self::create(output)?;
        let mut writer = std::io::BufWriter::new(file);
        fill(&mut writer)?;
        let file = writer.into_inner().map_err(|e| e.into_error())?;
        // An existing output keeps its permissions.
        if let Ok(metadata) = std::fs::metadata(&temporary.target) {
            file.set_permissions(metadata.permissions())?;
        }
        file.sync_all()?;
        Ok(temporary)
    }

    /// Renames the temporary file over its target; `registry` is the held registry lock.
    /// The file is removed if the rename fails.
    fn commit(mut self, registry: &mut Vec<PathBuf>) -> std::io::Result<()> {
        let result = std::fs::rename(&self.path, &self.target);
        if result.is_err() {
            let _ = std::fs::remove_file(&self.path);
        }
        registry.retain(|p| *p != self.path);
        self.done = true;
        result
    }

    /// Removes the temporary file; `registry` is the held registry lock.
    fn discard(mut self, registry: &mut Vec<PathBuf>) {
        let _ = std::fs::remove_file(&self.path);
        registry.retain(|p| *p != self.path);
        self.done = true;
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.done {
            self.discard_unlocked();
        }
    }
}

impl Temporary {
    /// [`Temporary::discard`] taking the registry lock itself.
    fn discard_unlocked(&mut self) {
        let _ = std::fs::remove_file(&self.path);
        registry().retain(|p| *p != self.path);
        self.done = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_the_old_file() {
        let dir = std::env::temp_dir().join(format!("skelfit-out-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.txt");
        write_atomic(&path, b"old").unwrap();
        let err = write_atomic_with(&path, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("boom"))
        });
        assert!(err.is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "temporary file removed"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
