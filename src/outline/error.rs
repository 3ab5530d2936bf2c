//! Why an outline could not be read or turned into a skeleton.

use std::path::PathBuf;

/// Errors of the outline stage: reading, validating, skeletonising and inflating a 2D outline.
#[derive(Debug, thiserror::Error)]
pub enum OutlineError {
    /// The outline file could not be read or written.
    #[error("cannot access {path}: {cause}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error (part of the message, hence not a `source()`, which would print it
        /// twice in an error chain).
        cause: std::io::Error,
    },
    /// The file extension is neither `.csv` nor `.svg`.
    #[error(
        "unknown outline format {extension:?}: give a .csv of x,y points or an .svg with a path"
    )]
    UnknownFormat {
        /// The extension found.
        extension: String,
    },
    /// A line of a CSV file or an SVG path could not be parsed.
    #[error("cannot parse the outline at {location}: {message}")]
    Parse {
        /// Where (e.g. `line 3`, `path command 5`).
        location: String,
        /// What was wrong.
        message: String,
    },
    /// A coordinate is NaN or infinite.
    #[error("point {index} has a non-finite coordinate: give finite numbers")]
    NonFinite {
        /// Index of the point.
        index: usize,
    },
    /// Fewer than three distinct points.
    #[error(
        "the outline has {count} points; a closed outline needs at least 3: draw a closed shape"
    )]
    TooFewPoints {
        /// Number of points found.
        count: usize,
    },
    /// The same point appears twice (other than a final point closing the outline).
    #[error("points {first} and {second} are the same point ({x}, {y}): remove repeated points")]
    DuplicatePoint {
        /// Index of the first occurrence.
        first: usize,
        /// Index of the repetition.
        second: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// The path does not come back to its start.
    #[error("the outline is open: its end is {gap} away from its start (at most {allowed} allowed): close the path (SVG 'Z') or repeat the first point at the end")]
    OpenPath {
        /// Distance from the last point to the first.
        gap: f64,
        /// The largest gap accepted as closed.
        allowed: f64,
    },
    /// Two edges of the outline cross or touch.
    #[error("the outline intersects itself: edge {first} crosses edge {second} near ({x}, {y}): draw a simple outline without loops")]
    SelfIntersecting {
        /// Index of the first edge (from point `first` to the next point).
        first: usize,
        /// Index of the second edge.
        second: usize,
        /// x of the crossing.
        x: f64,
        /// y of the crossing.
        y: f64,
    },
    /// The outline encloses no area.
    #[error("the outline encloses no area: draw a shape with an inside")]
    ZeroArea,
    /// An option is out of its range.
    #[error("option {name} = {value} is out of range: {expected}")]
    InvalidOption {
        /// Name of the option.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The valid range, in words.
        expected: &'static str,
    },
    /// The straight skeleton could not be completed (numerically degenerate outline).
    #[error("the straight skeleton did not finish after {events} events: simplify the outline (larger simplification tolerance)")]
    StraightSkeleton {
        /// Events processed before giving up.
        events: usize,
    },
    /// A level-of-detail operation failed.
    #[error(transparent)]
    Lod(#[from] crate::lod::LodError),
    /// The inflated mesh could not be built.
    #[error("the inflated mesh is invalid: {0}")]
    Mesh(#[from] crate::mesh::MeshError),
    /// No outline was given to assemble.
    #[error("no outlines were given: give at least one outline")]
    NoParts,
}
