//! [`OutputError`], the error of every output writer and reader.

use core::fmt;
use std::io;

/// Why a file that needs HDF5 was refused by a build without the cargo feature `hdf5`.
pub const NO_HDF5: &str = "this gsph was built without HDF5 (cargo feature `hdf5`)";

/// An error while writing or reading output files.
#[derive(Debug)]
pub enum OutputError {
    /// A file-system error.
    Io(io::Error),
    /// An error reported by the HDF5 library.
    #[cfg(feature = "hdf5")]
    Hdf5(hdf5::Error),
    /// Inconsistent data or a file that does not have the expected layout.
    Format(String),
    /// The file needs a cargo feature this build was compiled without (the message names
    /// it, e.g. [`NO_HDF5`]).
    Unsupported(String),
}

impl fmt::Display for OutputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (kind, msg) = match self {
            Self::Io(e) => (Some("I/O error"), e.to_string()),
            #[cfg(feature = "hdf5")]
            Self::Hdf5(e) => (Some("HDF5 error"), e.to_string()),
            Self::Format(m) => (Some("bad output data"), m.clone()),
            Self::Unsupported(m) => (None, m.clone()),
        };
        let one_line: Vec<&str> = msg.split_whitespace().collect();
        match kind {
            Some(kind) => write!(f, "{kind}: {}", one_line.join(" ")),
            None => write!(f, "{}", one_line.join(" ")),
        }
    }
}

impl core::error::Error for OutputError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            Self::Io(e) => Some(e),
            #[cfg(feature = "hdf5")]
            Self::Hdf5(e) => Some(e),
            Self::Format(_) | Self::Unsupported(_) => None,
        }
    }
}

impl From<io::Error> for OutputError {
    fn from(e: io::Error) -> Self {
        Self::Io(e)
    }
}

#[cfg(feature = "hdf5")]
impl From<hdf5::Error> for OutputError {
    fn from(e: hdf5::Error) -> Self {
        Self::Hdf5(e)
    }
}
