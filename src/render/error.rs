//! Why an image or another output file was not written.

use std::path::PathBuf;

/// A file not written (by `write_atomically`): the output as it was is left in place.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The output names a folder.
    #[error("{}: is a directory", path.display())]
    Directory {
        /// The output as given.
        path: PathBuf,
    },
    /// The output is a device, a pipe or a socket, which renaming a file over would replace.
    #[error("{}: not a regular file (a device, a pipe or a socket): not replaced", path.display())]
    NotRegular {
        /// The output as given.
        path: PathBuf,
    },
    /// The output exists and is read-only.
    #[error("{}: is read-only: not replaced", path.display())]
    ReadOnly {
        /// The output as given.
        path: PathBuf,
    },
    /// The folder the output would go in does not exist.
    #[error("{}: cannot write: there is no folder {}", path.display(), folder.display())]
    NoFolder {
        /// The output as given.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
    },
    /// The output's folder is a file (or a device): "t.ppm/x.png" where t.ppm is an image.
    #[error("{}: cannot write: {} is not a folder", path.display(), folder.display())]
    NotAFolder {
        /// The output as given.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
    },
    /// The output ends in a path separator, which names a folder, not a file.
    #[error("{}: ends in '/', which names a folder: give a file name", path.display())]
    FolderName {
        /// The output as given.
        path: PathBuf,
    },
    /// The symbolic links of the output cannot be followed (a loop, or one that cannot be read).
    #[error("{}: {source}", path.display())]
    Links {
        /// The output as given.
        path: PathBuf,
        /// The system's reason.
        source: std::io::Error,
    },
    /// Creating, writing, syncing or renaming the file failed.
    #[error("{}: cannot write: {source}", path.display())]
    Io {
        /// The output as given.
        path: PathBuf,
        /// The system's reason.
        source: std::io::Error,
    },
    /// The write was given up because it was asked to stop (a signal arrived).
    #[error("{}: cannot write: interrupted", path.display())]
    Cancelled {
        /// The output as given.
        path: PathBuf,
    },
}

impl WriteError {
    /// The output the error is about.
    pub fn path(&self) -> &std::path::Path {
        match self {
            WriteError::Directory { path }
            | WriteError::NotRegular { path }
            | WriteError::ReadOnly { path }
            | WriteError::NoFolder { path, .. }
            | WriteError::NotAFolder { path, .. }
            | WriteError::FolderName { path }
            | WriteError::Links { path, .. }
            | WriteError::Io { path, .. }
            | WriteError::Cancelled { path } => path,
        }
    }
}

/// An image not saved or encoded.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// The output's extension names no format raytree writes.
    #[error("{}: output must end in .png, .ppm or .exr", path.display())]
    UnknownFormat {
        /// The output as given.
        path: PathBuf,
    },
    /// The image file could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// The image could not be encoded in memory.
    #[error("cannot encode the image: {0}")]
    Encode(#[source] std::io::Error),
}
