//! Errors, one enum per job: rendering a frame, writing images, reading records and plotting.

use std::path::PathBuf;

use thiserror::Error;

/// Why a frame could not be rendered (or a renderer built).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum RenderError {
    /// A render or camera setting is out of range.
    #[error("render setting {field} = {value} is invalid: {reason}")]
    InvalidConfig {
        /// The setting's name, e.g. `"camera.elevation_deg"`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What the value must be.
        reason: &'static str,
    },
    /// A slice of the scene has the wrong number of entries for the robot model.
    #[error("{what}: expected {expected} values, got {got}")]
    WrongLength {
        /// What the slice holds, e.g. `"contact flags (one per tracked body: feet, then trunk)"`.
        what: &'static str,
        /// How many the model needs.
        expected: usize,
        /// How many were given.
        got: usize,
    },
    /// A position, orientation or angle in the scene is NaN or infinite.
    #[error("{what} is not finite ({value})")]
    NonFinite {
        /// What holds the value, e.g. `"pose of body lf_lowerleg"` or `"goal"`.
        what: String,
        /// The first non-finite value found.
        value: f64,
    },
    /// The robot model refused the pose (forward kinematics).
    #[error(transparent)]
    Model(#[from] hyq_physics::PhysicsError),
    /// [`crate::Renderer::render_into`] was given a frame of another size than the renderer's.
    #[error("frame is {got_width}×{got_height} pixels, the renderer draws {width}×{height}")]
    FrameSize {
        /// The renderer's width.
        width: u32,
        /// The renderer's height.
        height: u32,
        /// The frame's width.
        got_width: u32,
        /// The frame's height.
        got_height: u32,
    },
}

/// Why an image file (PNG or GIF) could not be written.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum WriteError {
    /// Creating a file or directory, or writing to it, failed.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The GIF encoder failed.
    #[error("GIF encoding failed: {0}")]
    Gif(#[from] gif::EncodingError),
    /// The PNG encoder failed.
    #[error("PNG encoding failed: {0}")]
    Png(#[from] png::EncodingError),
    /// A frame's size differs from the first frame's (an animation has one size).
    #[error(
        "frame {index} is {got_width}×{got_height} pixels, but the animation is {width}×{height}"
    )]
    FrameSize {
        /// The frame's index in the sequence (0-based).
        index: usize,
        /// The sequence's width.
        width: u32,
        /// The sequence's height.
        height: u32,
        /// The frame's width.
        got_width: u32,
        /// The frame's height.
        got_height: u32,
    },
    /// A frame's `rgb` buffer does not hold `width × height × 3` bytes.
    #[error("frame {index} holds {len} bytes, but {width}×{height} RGB needs {}", *width as usize * *height as usize * 3)]
    Inconsistent {
        /// The frame's index in the sequence (0-based).
        index: usize,
        /// The buffer's length.
        len: usize,
        /// The frame's width.
        width: u32,
        /// The frame's height.
        height: u32,
    },
    /// The frame is empty or larger than the format allows.
    #[error(
        "a {width}×{height} frame cannot be written as {format}: each side must be 1 to {max} pixels"
    )]
    Size {
        /// `"GIF"` or `"PNG"`.
        format: &'static str,
        /// The frame's width.
        width: u32,
        /// The frame's height.
        height: u32,
        /// The largest side the format allows.
        max: u32,
    },
    /// The GIF frame rate is outside what GIF delays (1/100 s steps) and viewers support.
    #[error("GIF frame rate {fps} fps is invalid: it must be finite, above 0 and at most 50")]
    Fps {
        /// The rate given.
        fps: f64,
    },
    /// An animation was finished without any frame.
    #[error("the animation has no frame")]
    NoFrames,
}

/// Why step records could not be read, or an episode plotted.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum PlotError {
    /// Reading the records file failed.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A line of a JSONL records file is not a valid step record.
    #[error("{origin} line {line}: not a step record: {source}")]
    Json {
        /// The file (or `"input"`).
        origin: String,
        /// The 1-based line number.
        line: usize,
        /// What serde_json found wrong (names the missing or mistyped key).
        #[source]
        source: serde_json::Error,
    },
    /// A line of a JSONL records file is longer than any step record.
    #[error("{origin} line {line}: longer than {} MiB, which no step record is (is it the right file?)", limit >> 20)]
    LineTooLong {
        /// The file (or `"input"`).
        origin: String,
        /// The 1-based line number.
        line: usize,
        /// The limit (bytes).
        limit: usize,
    },
    /// An episode (or a whole file) holds no step.
    #[error("{what} holds no step to plot")]
    Empty {
        /// What was empty.
        what: String,
    },
    /// A series has another length than the time axis.
    #[error("series {field} has {got} values, but the time axis has {expected}")]
    Length {
        /// The series' name.
        field: &'static str,
        /// The length of `t`.
        expected: usize,
        /// The series' length.
        got: usize,
    },
    /// A value to plot is NaN or infinite.
    #[error("{field} at step index {index} is not finite ({value})")]
    NonFinite {
        /// The series' name.
        field: &'static str,
        /// The 0-based index of the step in the episode.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The exponential-reward scale k_exp given for the R_e curve is not finite and positive.
    #[error("k_exp = {value} is invalid for the R_e curve: it must be finite and above 0")]
    KExp {
        /// The value given.
        value: f64,
    },
    /// The env step duration given for the time axes is not finite and positive.
    #[error("env_dt_s = {value} s is invalid: it must be finite and above 0")]
    EnvDt {
        /// The value given.
        value: f64,
    },
    /// The plotting library failed to draw.
    #[error("drawing {plot} failed: {message}")]
    Draw {
        /// Which plot.
        plot: &'static str,
        /// The library's message.
        message: String,
    },
    /// Writing the PNG failed.
    #[error(transparent)]
    Write(#[from] WriteError),
}
