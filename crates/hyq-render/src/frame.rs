//! The rendered image: 8-bit RGB, row-major, no padding.

/// One rendered image: `height` rows of `width` pixels, each pixel three bytes (red, green,
/// blue), rows top to bottom, no padding.
///
/// `rgb` is exactly the buffer a NumPy `uint8` array of shape `(height, width, 3)` holds
/// (C order), which is what Gymnasium's `render_mode="rgb_array"` returns.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `height × width × 3` bytes: pixel (x, y) channel c is at `(y · width + x) · 3 + c`.
    pub rgb: Vec<u8>,
}

impl Frame {
    /// A black frame of the given size.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            rgb: vec![0; width as usize * height as usize * 3],
        }
    }

    /// The NumPy shape of this frame: `[height, width, 3]`.
    pub fn shape(&self) -> [usize; 3] {
        [self.height as usize, self.width as usize, 3]
    }

    /// The pixel at column `x`, row `y` (row 0 at the top), or `None` outside the frame.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 3;
        self.rgb.get(i..i + 3).map(|p| [p[0], p[1], p[2]])
    }

    /// Whether `rgb` holds exactly `width × height × 3` bytes.
    pub fn is_consistent(&self) -> bool {
        self.rgb.len() == self.width as usize * self.height as usize * 3
    }
}
