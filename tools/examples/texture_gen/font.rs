//! Text from the DejaVu Sans Bold font in `textures/fonts/` (its licence beside it),
//! rasterised by `ab_glyph` into coverage: a line of text is laid out with the font's
//! advances and kerning and centred, by its ink, on a whole-pixel point.

use ab_glyph::{point, Font as _, FontVec, Glyph, PxScale, ScaleFont};

/// The font file, relative to the repository.
pub const FONT_PATH: &str = "textures/fonts/DejaVuSans-Bold.ttf";

pub struct Font(FontVec);

/// A pixel's coverage by text: (x, y, coverage ∈ [0, 1]).
pub type Plot<'a> = dyn FnMut(i32, i32, f32) + 'a;

impl Font {
    pub fn load() -> Font {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(FONT_PATH);
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        Font(FontVec::try_from_vec(bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
    }

    /// The ink size (width, height) in pixels of `text` at `px` pixels per em.
    pub fn ink_size(&self, text: &str, px: f32) -> (f32, f32) {
        let (min, max) = ink_bounds(&self.layout(text, px, 0.0, 0.0), &self.0);
        (max.0 - min.0, max.1 - min.1)
    }

    /// Draws `text` at `px` pixels per em with its ink centred on (cx, cy), rounded to
    /// whole pixels so every glyph lands on the same pixel grid wherever it is drawn.
    pub fn draw_centred(&self, text: &str, px: f32, cx: f32, cy: f32, plot: &mut Plot) {
        let (min, max) = ink_bounds(&self.layout(text, px, 0.0, 0.0), &self.0);
        let dx = (cx - (min.0 + max.0) / 2.0).round();
        let dy = (cy - (min.1 + max.1) / 2.0).round();
        for glyph in self.layout(text, px, dx, dy) {
            let Some(outline) = self.0.outline_glyph(glyph) else {
                continue;
            };
            let bounds = outline.px_bounds();
            outline.draw(|x, y, coverage| {
                plot(
                    bounds.min.x as i32 + x as i32,
                    bounds.min.y as i32 + y as i32,
                    coverage,
                )
            });
        }
    }

    /// Glyphs of one line on the baseline y = `y`, starting at x = `x`.
    fn layout(&self, text: &str, px: f32, x: f32, y: f32) -> Vec<Glyph> {
        let scaled = self.0.as_scaled(PxScale::from(px));
        let mut caret = x;
        let mut previous = None;
        let mut glyphs = Vec::new();
        for c in text.chars() {
            let id = self.0.glyph_id(c);
            assert!(id.0 != 0, "{FONT_PATH} has no glyph for {c:?}");
            if let Some(p) = previous {
                caret += scaled.kern(p, id);
            }
            glyphs.push(id.with_scale_and_position(px, point(caret, y)));
            caret += scaled.h_advance(id);
            previous = Some(id);
        }
        glyphs
    }
}

/// The union of the glyphs' pixel bounds: ((min x, min y), (max x, max y)).
fn ink_bounds(glyphs: &[Glyph], font: &FontVec) -> ((f32, f32), (f32, f32)) {
    let mut min = (f32::MAX, f32::MAX);
    let mut max = (f32::MIN, f32::MIN);
    for glyph in glyphs {
        if let Some(outline) = font.outline_glyph(glyph.clone()) {
            let b = outline.px_bounds();
            min = (min.0.min(b.min.x), min.1.min(b.min.y));
            max = (max.0.max(b.max.x), max.1.max(b.max.y));
        }
    }
    (min, max)
}
