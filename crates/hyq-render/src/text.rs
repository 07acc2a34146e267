//! Text for the overlay and the plots, from a font bundled with the crate.
//!
//! The font is DejaVu Sans, cut down to Latin, Greek and a few symbols (see
//! `assets/fonts/README.md` for how, and `assets/fonts/LICENSE-DejaVu.txt` for its licence), so
//! that frames and plots look the same on every machine, with or without system fonts. The
//! overlay draws each glyph's outline as a vector path with tiny-skia's anti-aliased filler,
//! so no pixel is touched by hand.

use std::collections::HashMap;

use ab_glyph::{Font, FontRef, GlyphId, OutlineCurve};
use tiny_skia::{FillRule, Paint, Path, PathBuilder, Pixmap, Transform};

/// DejaVu Sans (Book), subset.
pub const SANS: &[u8] = include_bytes!("../assets/fonts/DejaVuSans-subset.ttf");
/// DejaVu Sans Bold, subset.
pub const SANS_BOLD: &[u8] = include_bytes!("../assets/fonts/DejaVuSans-Bold-subset.ttf");

/// Parses a bundled font.
pub(crate) fn bundled(bytes: &'static [u8]) -> FontRef<'static> {
    // The bundled fonts are compiled in and parsed by this crate's tests (`text::tests`), so a
    // failure here is a broken build, not bad input.
    #[allow(clippy::expect_used)]
    FontRef::try_from_slice(bytes).expect("the bundled font parses")
}

/// One glyph at font-unit scale: its outline (none for blanks) and its advance.
struct Glyph {
    id: GlyphId,
    path: Option<Path>,
    advance: f32,
}

/// A font with its glyph outlines cached as tiny-skia paths in font units.
pub(crate) struct TextPainter {
    font: FontRef<'static>,
    units_per_em: f32,
    glyphs: HashMap<char, Glyph>,
}

impl TextPainter {
    pub(crate) fn new(font: FontRef<'static>) -> Self {
        // Every TrueType font declares its units per em; 2048 (DejaVu's) is the fallback.
        let units_per_em = font.units_per_em().unwrap_or(2048.0);
        Self {
            font,
            units_per_em,
            glyphs: HashMap::new(),
        }
    }

    fn glyph(&mut self, c: char) -> &Glyph {
        let font = &self.font;
        self.glyphs.entry(c).or_insert_with(|| {
            let id = font.glyph_id(c);
            let advance = font.h_advance_unscaled(id);
            let path = font.outline(id).and_then(|outline| {
                let mut pb = PathBuilder::new();
                let mut last: Option<ab_glyph::Point> = None;
                for curve in &outline.curves {
                    let (start, end) = match curve {
                        OutlineCurve::Line(a, b) => (*a, *b),
                        OutlineCurve::Quad(a, _, c) => (*a, *c),
                        OutlineCurve::Cubic(a, _, _, d) => (*a, *d),
                    };
                    // A new contour starts wherever a curve does not continue the last one.
                    if last != Some(start) {
                        if last.is_some() {
                            pb.close();
                        }
                        pb.move_to(start.x, start.y);
                    }
                    match curve {
                        OutlineCurve::Line(_, b) => pb.line_to(b.x, b.y),
                        OutlineCurve::Quad(_, b, c) => pb.quad_to(b.x, b.y, c.x, c.y),
                        OutlineCurve::Cubic(_, b, c, d) => {
                            pb.cubic_to(b.x, b.y, c.x, c.y, d.x, d.y)
                        }
                    }
                    last = Some(end);
                }
                pb.close();
                pb.finish()
            });
            Glyph { id, path, advance }
        })
    }

    /// The width in pixels of `text` at `size_px` (pixels per em).
    pub(crate) fn width(&mut self, text: &str, size_px: f32) -> f32 {
        let scale = size_px / self.units_per_em;
        let mut width = 0.0;
        let mut prev: Option<GlyphId> = None;
        for c in text.chars() {
            let (id, advance) = {
                let g = self.glyph(c);
                (g.id, g.advance)
            };
            if let Some(p) = prev {
                width += self.font.kern_unscaled(p, id) * scale;
            }
            width += advance * scale;
            prev = Some(id);
        }
        width
    }

    /// Fills `text` with `paint`, its baseline starting at (`x`, `baseline`) in pixels;
    /// returns the advance width.
    pub(crate) fn draw(
        &mut self,
        pixmap: &mut Pixmap,
        text: &str,
        size_px: f32,
        x: f32,
        baseline: f32,
        paint: &Paint,
    ) -> f32 {
        let scale = size_px / self.units_per_em;
        let mut pen = x;
        let mut prev: Option<GlyphId> = None;
        for c in text.chars() {
            let kern = match prev {
                Some(p) => self.font.kern_unscaled(p, self.font.glyph_id(c)) * scale,
                None => 0.0,
            };
            pen += kern;
            let g = self.glyph(c);
            if let Some(path) = &g.path {
                // Font units have y up; the image has y down.
                let t = Transform::from_row(scale, 0.0, 0.0, -scale, pen, baseline);
                pixmap.fill_path(path, paint, FillRule::Winding, t, None);
            }
            pen += g.advance * scale;
            prev = Some(g.id);
        }
        pen - x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bundled_fonts_parse_and_cover_digits_letters_and_symbols() {
        for bytes in [SANS, SANS_BOLD] {
            let font = bundled(bytes);
            for c in "0123456789 azAZ.,:+-−·×ΔθₙΣ_()=".chars() {
                assert_ne!(font.glyph_id(c).0, 0, "glyph for {c:?} is missing");
            }
        }
    }

    #[test]
    fn wider_text_measures_wider() {
        let mut painter = TextPainter::new(bundled(SANS));
        let short = painter.width("1.0", 14.0);
        let long = painter.width("1000.0", 14.0);
        assert!(short > 10.0 && long > short + 20.0, "{short} {long}");
    }
}
