//! Output plumbing of the file sinks: a file written under a temporary name next to its final
//! path and renamed into place only when complete ([`AtomicFile`]), and a writer that keeps
//! the first I/O error instead of handing it to a library that may not recover from it
//! ([`Guarded`]).

use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// A file created as `.NAME.PID.N.part` in the directory of `path`; [`AtomicFile::commit`]
/// renames it to `path`, so concurrent runs or a crash never leave a half-written file under
/// the final name (a killed run leaves the `.part` file, which `contrail recover` salvages).
/// Dropped without [`AtomicFile::commit`], the temporary file is removed.
pub struct AtomicFile {
    file: BufWriter<File>,
    tmp: PathBuf,
    path: PathBuf,
    committed: bool,
    /// Bytes written, and how many of them have been handed to the disk's writeback.
    written: u64,
    started: u64,
}

/// Every this many bytes the data written is handed to the disk's writeback, so that
/// [`AtomicFile::commit`] — which the run waits for — only syncs the tail (`fsync` takes
/// about 1 ms per MB on the ext4 disk of the development machine). Linux: the writeback is
/// started, not waited for (`sync_file_range(SYNC_FILE_RANGE_WRITE)`, the way RocksDB's
/// `bytes_per_sync` works). An `fdatasync` here blocked the writer thread on the disk for
/// each 2 MB: four recorded 120×4 strip runs in the service slept 166 times in the disk
/// (`perf` sched switches in state D, 2026-11-27), 26 times with the writeback started only;
/// the runs' wall time was the same on this machine (the writer's queue absorbed the waits),
/// a slower disk would stall the solver once the queue is full.
pub const SYNC_EVERY: u64 = 2 << 20;

impl AtomicFile {
    /// Create the temporary file (and the directory of `path` if needed).
    pub fn create(path: &Path) -> io::Result<Self> {
        let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
        if let Some(d) = dir {
            std::fs::create_dir_all(d)?;
        }
        let name = path
            .file_name()
            .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path has no file name"))?;
        static SERIAL: AtomicUsize = AtomicUsize::new(0);
        let tmp_name = format!(
            ".{}.{}.{}.part",
            name.to_string_lossy(),
            std::process::id(),
            SERIAL.fetch_add(1, Ordering::Relaxed)
        );
        let tmp = dir.map_or_else(|| PathBuf::from(&tmp_name), |d| d.join(&tmp_name));
        let file = File::create(&tmp)?;
        Ok(AtomicFile {
            file: BufWriter::new(file),
            tmp,
            path: path.to_path_buf(),
            committed: false,
            written: 0,
            started: 0,
        })
    }

    /// The temporary path the data is written to until [`AtomicFile::commit`].
    pub fn temp_path(&self) -> &Path {
        &self.tmp
    }

    /// Flush, sync and rename the file to its final path.
    pub fn commit(mut self) -> io::Result<PathBuf> {
        self.file.flush()?;
        self.file.get_ref().sync_all()?;
        std::fs::rename(&self.tmp, &self.path)?;
        self.committed = true;
        Ok(self.path.clone())
    }

    /// Remove the temporary file (after a failed write).
    pub fn discard(self) {
        drop(self);
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Start writing `len` bytes of `file` from `offset` back to the disk without waiting for it.
#[cfg(target_os = "linux")]
fn start_writeback(file: &File, offset: u64, len: u64) -> io::Result<()> {
    use std::os::fd::AsRawFd;
    let (Ok(offset), Ok(len)) = (i64::try_from(offset), i64::try_from(len)) else {
        return Ok(());
    };
    // SAFETY: a plain system call on an open descriptor; it reads no memory of ours.
    let r = unsafe { libc::sync_file_range(file.as_raw_fd(), offset, len, libc::SYNC_FILE_RANGE_WRITE) };
    if r == 0 {
        Ok(())
    } else {
        Err(io::Error::last_os_error())
    }
}

/// Elsewhere the commit syncs everything.
#[cfg(not(target_os = "linux"))]
fn start_writeback(_file: &File, _offset: u64, _len: u64) -> io::Result<()> {
    Ok(())
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.file.write(buf)?;
        self.written += n as u64;
        if self.written - self.started >= SYNC_EVERY {
            self.file.flush()?;
            start_writeback(self.file.get_ref(), self.started, self.written - self.started)?;
            self.started = self.written;
        }
        Ok(n)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.file.flush()
    }
}

impl Seek for AtomicFile {
    fn seek(&mut self, pos: SeekFrom) -> io::Result<u64> {
        self.file.seek(pos)
    }
}

/// The first I/O error seen by a [`Guarded`] writer.
#[derive(Clone, Default)]
pub struct FirstError(Arc<Mutex<Option<io::Error>>>);

impl FirstError {
    fn set(&self, e: io::Error) {
        if let Ok(mut g) = self.0.lock() {
            g.get_or_insert(e);
        }
    }

    /// A copy of the error, if one happened (it stays set).
    pub fn get(&self) -> Option<io::Error> {
        let g = self.0.lock().ok()?;
        let e = g.as_ref()?;
        Some(
            e.raw_os_error()
                .map_or_else(|| io::Error::new(e.kind(), e.to_string()), io::Error::from_raw_os_error),
        )
    }

    /// Whether an error happened.
    pub fn is_set(&self) -> bool {
        match self.0.lock() {
            Ok(g) => g.is_some(),
            Err(_) => true,
        }
    }
}

/// A writer that, after its first error, keeps that error in a [`FirstError`] and quietly
/// drops everything written after it. The caller checks the error after each operation; the
/// library writing through it (the mcap writer, which panics when an I/O error leaves it
/// half-way through a chunk) never sees a failure.
pub struct Guarded<W> {
    inner: W,
    error: FirstError,
    pos: u64,
}

impl<W> Guarded<W> {
    /// Wrap `inner`; errors go to `error`.
    pub fn new(inner: W, error: FirstError) -> Self {
        Guarded { inner, error, pos: 0 }
    }

    /// The wrapped writer.
    pub fn into_inner(self) -> W {
        self.inner
    }

    fn failed(&self) -> bool {
        self.error.is_set()
    }
}

impl<W: Write> Write for Guarded<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if !self.failed() {
            if let Err(e) = self.inner.write_all(buf) {
                self.error.set(e);
            }
        }
        self.pos += buf.len() as u64;
        Ok(buf.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        if !self.failed() {
            if let Err(e) = self.inner.flush() {
                self.error.set(e);
            }
        }
        Ok(())
    }
}

impl<W: Seek> Seek for Guarded<W> {
    fn seek(&mut self, pos: SeekFrom) -> io::Result<u64> {
        if !self.failed() {
            match self.inner.seek(pos) {
                Ok(p) => {
                    self.pos = p;
                    return Ok(p);
                }
                Err(e) => self.error.set(e),
            }
        }
        // after a failure positions are only bookkeeping: the output is discarded anyway
        self.pos = match pos {
            SeekFrom::Start(p) => p,
            SeekFrom::Current(d) | SeekFrom::End(d) => self.pos.saturating_add_signed(d),
        };
        Ok(self.pos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer that fails like a full disk after `room` bytes.
    struct Full {
        room: usize,
    }
    impl Write for Full {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            if buf.len() > self.room {
                return Err(io::Error::from_raw_os_error(28));
            }
            self.room -= buf.len();
            Ok(buf.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn the_first_error_is_kept_and_later_writes_are_dropped() {
        let err = FirstError::default();
        let mut g = Guarded::new(Full { room: 4 }, err.clone());
        g.write_all(b"abc").unwrap();
        g.write_all(b"defg").unwrap();
        g.write_all(b"h").unwrap();
        assert!(err.is_set());
        let e = err.get().unwrap();
        assert!(e.to_string().contains("No space left on device"), "{e}");
        assert_eq!(g.into_inner().room, 1);
    }

    #[test]
    fn atomic_file_appears_only_on_commit() {
        let dir = std::env::temp_dir().join(format!("contrail-atomic-{}", std::process::id()));
        let path = dir.join("out.bin");
        let mut f = AtomicFile::create(&path).unwrap();
        let tmp = f.temp_path().to_path_buf();
        f.write_all(b"data").unwrap();
        assert!(!path.exists() && tmp.exists());
        f.commit().unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"data");
        assert!(!tmp.exists());
        let g = AtomicFile::create(&path).unwrap();
        let tmp = g.temp_path().to_path_buf();
        g.discard();
        assert!(!tmp.exists());
        assert_eq!(std::fs::read(&path).unwrap(), b"data");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
