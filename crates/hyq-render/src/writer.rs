//! Writing frames: one PNG, a directory of numbered PNGs, or an animated GIF.
//!
//! GIF delays are counted in hundredths of a second, so a GIF plays at 100 / round(100 / fps)
//! frames per second (30 fps becomes 3 cs per frame, 33.3 fps); rates above 50 fps are refused
//! because common viewers slow down delays below 2 cs. Each GIF frame gets its own 256-colour
//! palette (NeuQuant quantisation in the `gif` crate), and the animation loops forever.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::error::WriteError;
use crate::frame::Frame;

/// The largest side a GIF can have (its sizes are 16-bit).
pub const GIF_MAX_SIDE_PX: u32 = u16::MAX as u32;
/// The largest GIF frame rate accepted (fps).
pub const GIF_MAX_FPS: f64 = 50.0;

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> WriteError + '_ {
    move |source| WriteError::Io {
        path: path.to_owned(),
        source,
    }
}

fn check_consistent(frame: &Frame, index: usize) -> Result<(), WriteError> {
    if frame.is_consistent() {
        Ok(())
    } else {
        Err(WriteError::Inconsistent {
            index,
            len: frame.rgb.len(),
            width: frame.width,
            height: frame.height,
        })
    }
}

/// Encodes `frame` as an 8-bit RGB PNG into `writer`.
pub fn encode_png<W: Write>(writer: W, frame: &Frame) -> Result<(), WriteError> {
    check_consistent(frame, 0)?;
    if frame.width == 0 || frame.height == 0 {
        return Err(WriteError::Size {
            format: "PNG",
            width: frame.width,
            height: frame.height,
            max: i32::MAX as u32,
        });
    }
    let mut encoder = png::Encoder::new(writer, frame.width, frame.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&frame.rgb)?;
    writer.finish()?;
    Ok(())
}

/// Writes `frame` to a PNG file at `path` (created or replaced).
pub fn write_png(path: impl AsRef<Path>, frame: &Frame) -> Result<(), WriteError> {
    let path = path.as_ref();
    let file = File::create(path).map_err(io_error(path))?;
    let mut out = BufWriter::new(file);
    encode_png(&mut out, frame)?;
    out.flush().map_err(io_error(path))
}

/// Writes frames as numbered PNG files, `frame_000000.png`, `frame_000001.png`, … in a
/// directory (created if missing), all of one size.
#[derive(Debug)]
pub struct PngSequence {
    dir: PathBuf,
    size: Option<(u32, u32)>,
    written: usize,
}

impl PngSequence {
    /// A sequence writing into `dir`, which is created (with its parents) if missing.
    pub fn create(dir: impl AsRef<Path>) -> Result<Self, WriteError> {
        let dir = dir.as_ref();
        std::fs::create_dir_all(dir).map_err(io_error(dir))?;
        Ok(Self {
            dir: dir.to_owned(),
            size: None,
            written: 0,
        })
    }

    /// The path the frame of `index` is written to.
    pub fn path_of(&self, index: usize) -> PathBuf {
        self.dir.join(format!("frame_{index:06}.png"))
    }

    /// Writes the next frame; it must have the first frame's size.
    pub fn push(&mut self, frame: &Frame) -> Result<PathBuf, WriteError> {
        check_size(&mut self.size, frame, self.written)?;
        let path = self.path_of(self.written);
        write_png(&path, frame)?;
        self.written += 1;
        Ok(path)
    }

    /// How many frames were written.
    pub fn frames_written(&self) -> usize {
        self.written
    }
}

/// Writes every frame of `frames` into `dir` as a [`PngSequence`]; returns the files written.
pub fn write_png_sequence(
    dir: impl AsRef<Path>,
    frames: &[Frame],
) -> Result<Vec<PathBuf>, WriteError> {
    let mut seq = PngSequence::create(dir)?;
    frames.iter().map(|f| seq.push(f)).collect()
}

/// Checks a frame against the sequence's size (set by the first frame).
fn check_size(
    size: &mut Option<(u32, u32)>,
    frame: &Frame,
    index: usize,
) -> Result<(), WriteError> {
    check_consistent(frame, index)?;
    let (width, height) = *size.get_or_insert((frame.width, frame.height));
    if (frame.width, frame.height) != (width, height) {
        return Err(WriteError::FrameSize {
            index,
            width,
            height,
            got_width: frame.width,
            got_height: frame.height,
        });
    }
    Ok(())
}

/// The GIF delay (hundredths of a second) for a frame rate; errors outside (0, 50] fps.
pub fn gif_delay_cs(fps: f64) -> Result<u16, WriteError> {
    if !(fps.is_finite() && fps > 0.0 && fps <= GIF_MAX_FPS) {
        return Err(WriteError::Fps { fps });
    }
    // fps ≤ 50 makes 100 / fps ≥ 2, and fps > 0 with a finite quotient keeps it within u16
    // for any rate a video would use; the clamp covers tiny rates.
    Ok((100.0 / fps).round().clamp(2.0, f64::from(u16::MAX)) as u16)
}

/// An animated GIF written frame by frame (nothing is kept in memory but the encoder's
/// buffers), looping forever.
pub struct GifWriter<W: Write> {
    encoder: gif::Encoder<W>,
    /// The file written, for error messages (`None` for a writer given by the caller).
    path: Option<PathBuf>,
    width: u32,
    height: u32,
    delay_cs: u16,
    written: usize,
}

impl<W: Write> std::fmt::Debug for GifWriter<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GifWriter")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("delay_cs", &self.delay_cs)
            .field("written", &self.written)
            .finish_non_exhaustive()
    }
}

impl GifWriter<BufWriter<File>> {
    /// A GIF file at `path` (created or replaced) of `width × height` frames at `fps`.
    pub fn create(
        path: impl AsRef<Path>,
        width: u32,
        height: u32,
        fps: f64,
    ) -> Result<Self, WriteError> {
        // Check the arguments before touching the file system.
        gif_delay_cs(fps)?;
        check_gif_size(width, height)?;
        let path = path.as_ref();
        let file = File::create(path).map_err(io_error(path))?;
        let mut gif = Self::new(BufWriter::new(file), width, height, fps)?;
        gif.path = Some(path.to_owned());
        Ok(gif)
    }
}

fn check_gif_size(width: u32, height: u32) -> Result<(u16, u16), WriteError> {
    match (u16::try_from(width), u16::try_from(height)) {
        (Ok(w), Ok(h)) if w > 0 && h > 0 => Ok((w, h)),
        _ => Err(WriteError::Size {
            format: "GIF",
            width,
            height,
            max: GIF_MAX_SIDE_PX,
        }),
    }
}

impl<W: Write> GifWriter<W> {
    /// A GIF of `width × height` frames at `fps` written to `writer`.
    pub fn new(writer: W, width: u32, height: u32, fps: f64) -> Result<Self, WriteError> {
        let delay_cs = gif_delay_cs(fps)?;
        let (w, h) = check_gif_size(width, height)?;
        let mut encoder = gif::Encoder::new(writer, w, h, &[])?;
        encoder.set_repeat(gif::Repeat::Infinite)?;
        Ok(Self {
            encoder,
            path: None,
            width,
            height,
            delay_cs,
            written: 0,
        })
    }

    /// The delay between frames, in hundredths of a second.
    pub fn delay_cs(&self) -> u16 {
        self.delay_cs
    }

    /// Appends a frame; it must have the GIF's size.
    pub fn push(&mut self, frame: &Frame) -> Result<(), WriteError> {
        check_size(&mut Some((self.width, self.height)), frame, self.written)?;
        // `check_gif_size` bounded both sides to u16 when the writer was made.
        let (w, h) = (self.width as u16, self.height as u16);
        // Speed 10 of NeuQuant's 1..=30: a good palette at a few ms per 480×360 frame.
        let mut gif_frame = gif::Frame::from_rgb_speed(w, h, &frame.rgb, 10);
        gif_frame.delay = self.delay_cs;
        self.encoder.write_frame(&gif_frame)?;
        self.written += 1;
        Ok(())
    }

    /// How many frames were written.
    pub fn frames_written(&self) -> usize {
        self.written
    }

    /// Writes the GIF trailer, flushes and returns the writer; errors if no frame was written.
    pub fn finish(self) -> Result<W, WriteError> {
        if self.written == 0 {
            return Err(WriteError::NoFrames);
        }
        let path = self.path.unwrap_or_else(|| PathBuf::from("GIF output"));
        let mut out = self.encoder.into_inner()?;
        out.flush().map_err(io_error(&path))?;
        Ok(out)
    }
}

/// Writes `frames` as an animated GIF at `fps` to `path`.
pub fn write_gif(path: impl AsRef<Path>, frames: &[Frame], fps: f64) -> Result<(), WriteError> {
    let first = frames.first().ok_or(WriteError::NoFrames)?;
    let path = path.as_ref();
    let mut gif = GifWriter::create(path, first.width, first.height, fps)?;
    for f in frames {
        gif.push(f)?;
    }
    gif.finish()?;
    Ok(())
}
