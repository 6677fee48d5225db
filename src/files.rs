//! Reading the files a user names (scenes, meshes, lessons, answer sheets): regular files
//! only, opened so that a FIFO or a device can neither block nor feed bytes forever, and never
//! more than a budget of bytes, so a file that is too large is refused before its contents are
//! held in memory. And where raytree keeps what it can make again (the user's cache folder).

use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The user's cache folder for raytree: `RAYTREE_CACHE`, else the platform's
/// (`~/.cache/raytree` on Linux). None when the platform has none (no home folder).
pub fn cache_dir() -> Option<PathBuf> {
    folder_from("RAYTREE_CACHE")
        .or_else(|| directories::ProjectDirs::from("", "", "raytree").map(|d| d.cache_dir().into()))
}

/// The user's data folder for raytree (where progress is kept): `RAYTREE_DATA`, else the
/// platform's (`~/.local/share/raytree` on Linux). None when the platform has none.
pub fn data_dir() -> Option<PathBuf> {
    folder_from("RAYTREE_DATA")
        .or_else(|| directories::ProjectDirs::from("", "", "raytree").map(|d| d.data_dir().into()))
}

/// The folder an environment variable names. Set but empty counts as not set, as XDG's
/// variables do: an empty path would be the current folder, which the user did not name.
fn folder_from(variable: &str) -> Option<PathBuf> {
    std::env::var_os(variable)
        .filter(|p| !p.is_empty())
        .map(PathBuf::from)
}

/// Why a file was not read.
#[derive(Debug)]
pub enum ReadError {
    /// The path names a directory.
    Directory,
    /// A FIFO, a socket or a device: not something raytree reads.
    NotRegular,
    /// More bytes than the budget (files under /proc report a size of 0, so the size is
    /// counted while reading, not only taken from the metadata).
    TooLarge {
        /// The most bytes that may be read.
        budget: u64,
    },
    /// Bytes that are not UTF-8 text, the first of them at this line and column (from 1; the
    /// column counts characters).
    NotUtf8 {
        /// The line of the first byte that is not UTF-8.
        line: u64,
        /// Its column.
        column: u64,
    },
    /// Opening, inspecting or reading the file failed.
    Io(std::io::Error),
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReadError::Directory => write!(f, "is a directory, not a file"),
            ReadError::NotRegular => {
                write!(f, "not a regular file (a pipe, a socket or a device)")
            }
            ReadError::TooLarge { budget } => {
                write!(f, "larger than the budget of {}", bytes(*budget))
            }
            ReadError::NotUtf8 { line, column } => write!(
                f,
                "not UTF-8 text at line {line}, column {column} (save the file as UTF-8)"
            ),
            ReadError::Io(e) => write!(f, "cannot read: {e}"),
        }
    }
}

/// A byte count as people read it: "16 MiB", "512 KiB", "300 bytes".
pub fn bytes(n: u64) -> String {
    match n {
        n if n >= 1 << 30 && n % (1 << 30) == 0 => format!("{} GiB", n >> 30),
        n if n >= 1 << 20 && n % (1 << 20) == 0 => format!("{} MiB", n >> 20),
        n if n >= 1 << 10 && n % (1 << 10) == 0 => format!("{} KiB", n >> 10),
        n => format!("{n} bytes"),
    }
}

/// Opens `path` for reading without blocking: a FIFO opens at once (with no writer) instead
/// of waiting for one, and is then refused by what the open file is.
fn open(path: &Path) -> std::io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    options.open(path)
}

/// The whole of a regular file of at most `budget` bytes. The checks are made on the file
/// opened, not on the path, so a file swapped for a FIFO in between is still refused.
pub fn read_bounded(path: &Path, budget: u64) -> Result<Vec<u8>, ReadError> {
    let file = open(path).map_err(|e| match e.raw_os_error() {
        Some(libc::EISDIR) => ReadError::Directory,
        _ => ReadError::Io(e),
    })?;
    let meta = file.metadata().map_err(ReadError::Io)?;
    if meta.is_dir() {
        return Err(ReadError::Directory);
    }
    if !meta.is_file() {
        return Err(ReadError::NotRegular);
    }
    if meta.len() > budget {
        return Err(ReadError::TooLarge { budget });
    }
    let mut out = Vec::new();
    out.try_reserve_exact(meta.len() as usize)
        .map_err(|_| ReadError::TooLarge { budget: meta.len() })?;
    // Whole chunks (files under /proc may refuse reads of odd sizes), until the end or until
    // more than the budget has come.
    let mut chunk = vec![0u8; 1 << 16];
    let mut file = file;
    loop {
        match file.read(&mut chunk) {
            Ok(0) => return Ok(out),
            Ok(n) => {
                out.extend_from_slice(&chunk[..n]);
                if out.len() as u64 > budget {
                    return Err(ReadError::TooLarge { budget });
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(ReadError::Io(e)),
        }
    }
}

/// The budget for the text files of lessons and of grading (exercises, READMEs, the scenes a
/// lesson varies, answer sheets, the progress file): far above any real one, far below what
/// would trouble a laptop.
pub const TEXT_BUDGET: u64 = 16 << 20;

/// `read_bounded` as UTF-8 text; other bytes are refused with the place of the first.
pub fn read_text(path: &Path, budget: u64) -> Result<String, ReadError> {
    String::from_utf8(read_bounded(path, budget)?).map_err(|e| {
        let before = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line_start = before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        let this_line = std::str::from_utf8(&before[line_start..]).expect("valid up to here");
        ReadError::NotUtf8 {
            line: before.iter().filter(|&&b| b == b'\n').count() as u64 + 1,
            column: this_line.chars().count() as u64 + 1,
        }
    })
}

/// As the system's errors are reported: the reason of a failed read or open itself, the
/// others as their message.
impl From<ReadError> for std::io::Error {
    fn from(e: ReadError) -> std::io::Error {
        match e {
            ReadError::Io(e) => e,
            e => std::io::Error::other(e.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("raytree-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    #[test]
    fn a_file_within_the_budget_is_read_whole() {
        let path = scratch("ten.txt");
        std::fs::write(&path, b"0123456789").unwrap();
        assert_eq!(read_bounded(&path, 10).unwrap(), b"0123456789");
        assert!(matches!(
            read_bounded(&path, 9),
            Err(ReadError::TooLarge { budget: 9 })
        ));
    }

    #[test]
    fn devices_directories_and_fifos_are_refused_at_once() {
        assert!(matches!(
            read_bounded(Path::new("/dev/zero"), 1 << 20),
            Err(ReadError::NotRegular)
        ));
        assert!(matches!(
            read_bounded(Path::new("/tmp"), 1 << 20),
            Err(ReadError::Directory)
        ));
        let fifo = scratch("fifo");
        let _ = std::fs::remove_file(&fifo);
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: mkfifo reads a NUL-terminated path and touches no Rust memory.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || tx.send(read_bounded(&fifo, 1 << 20).map(|_| ())));
        let result = rx
            .recv_timeout(std::time::Duration::from_secs(5))
            .expect("reading a FIFO must not block");
        assert!(matches!(result, Err(ReadError::NotRegular)), "{result:?}");
    }

    /// /proc files report a size of 0 and then produce far more bytes than that.
    #[test]
    fn a_proc_file_is_cut_at_the_budget() {
        let path = Path::new("/proc/self/pagemap");
        if path.exists() {
            assert!(matches!(
                read_bounded(path, 4096),
                Err(ReadError::TooLarge { budget: 4096 })
            ));
        }
    }

    #[test]
    fn byte_counts_read_as_people_say_them() {
        assert_eq!(bytes(16 << 20), "16 MiB");
        assert_eq!(bytes(3 << 30), "3 GiB");
        assert_eq!(bytes(1000), "1000 bytes");
    }
}
