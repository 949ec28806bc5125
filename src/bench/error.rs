//! Why a benchmark stopped: its input, the job, a backend, or a file it writes.
//! The messages name the file or the input, as the other commands' do.

use std::path::PathBuf;

use crate::accel::AccelError;
use crate::film::FilmError;
use crate::render::job::JobError;
use crate::scene::LoadError;

#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    #[error(transparent)]
    Load(#[from] LoadError),
    #[error(transparent)]
    Accel(#[from] AccelError),
    #[error(transparent)]
    Job(#[from] JobError),
    #[error(transparent)]
    Film(#[from] FilmError),
    #[error(transparent)]
    Denoise(#[from] crate::film::denoise::DenoiseError),
    #[error("{}: the reference is {}x{}, the render {}x{}", path.display(), got.0, got.1, want.0, want.1)]
    ReferenceSize {
        path: PathBuf,
        got: (usize, usize),
        want: (usize, usize),
    },
    #[error("{0}: no triangles to trace")]
    NoTriangles(String),
    #[error("{0}: no triangles or CSG objects to trace")]
    NothingToTrace(String),
    #[error("thread counts must be at least 1")]
    ZeroThreads,
    #[error("building a thread pool")]
    ThreadPool(#[source] rayon::ThreadPoolBuildError),
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    #[error("creating {}", path.display())]
    CreateDir {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("writing {}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("writing {}", path.display())]
    WriteImage {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("renaming into {}", path.display())]
    Rename {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A plotting error (plotters' errors carry their backend's type; the text is what counts).
    #[error("{0}")]
    Plot(String),
}

pub type Result<T, E = BenchError> = std::result::Result<T, E>;

impl BenchError {
    /// An io error while writing `path`.
    pub fn write(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> BenchError + '_ {
        move |source| BenchError::Write {
            path: path.to_path_buf(),
            source,
        }
    }

    pub fn plot(e: impl std::fmt::Display) -> BenchError {
        BenchError::Plot(e.to_string())
    }
}
