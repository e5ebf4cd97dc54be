//! A 5×7 pixel font for the diff map's legend: just the characters its labels
//! use, so that no font file or text-rendering crate is needed.

use image::{Rgb, RgbImage};

pub const GLYPH_HEIGHT: u32 = 7;
/// Five columns and one of spacing.
const ADVANCE: u32 = 6;

/// Rows top to bottom; bit 4 is the leftmost column.
fn glyph(c: char) -> Option<[u8; 7]> {
    Some(match c {
        '0' => [0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110],
        '1' => [0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110],
        '2' => [0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111],
        '3' => [0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110],
        '4' => [0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010],
        '5' => [0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110],
        '6' => [0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110],
        '7' => [0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000],
        '8' => [0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110],
        '9' => [0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100],
        '.' => [0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b01100],
        '-' => [0b00000, 0b00000, 0b00000, 0b11111, 0b00000, 0b00000, 0b00000],
        'e' => [0b00000, 0b00000, 0b01110, 0b10001, 0b11111, 0b10000, 0b01110],
        'A' => [0b01110, 0b10001, 0b10001, 0b11111, 0b10001, 0b10001, 0b10001],
        'B' => [0b11110, 0b10001, 0b10001, 0b11110, 0b10001, 0b10001, 0b11110],
        'D' => [0b11100, 0b10010, 0b10001, 0b10001, 0b10001, 0b10010, 0b11100],
        'F' => [0b11111, 0b10000, 0b10000, 0b11110, 0b10000, 0b10000, 0b10000],
        'I' => [0b01110, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110],
        'L' => [0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b10000, 0b11111],
        'P' => [0b11110, 0b10001, 0b10001, 0b11110, 0b10000, 0b10000, 0b10000],
        'S' => [0b01111, 0b10000, 0b10000, 0b01110, 0b00001, 0b00001, 0b11110],
        ' ' => [0; 7],
        _ => return None,
    })
}

/// Whether every character of `text` can be drawn.
#[cfg(test)]
pub fn can_draw(text: &str) -> bool {
    text.chars().all(|c| glyph(c).is_some())
}

pub fn text_width(text: &str) -> u32 {
    (text.chars().count() as u32 * ADVANCE).saturating_sub(1)
}

/// Draws `text` with its top-left corner at (x, y), clipped to the image; a
/// character outside the font leaves a gap.
pub fn draw_text(image: &mut RgbImage, x: u32, y: u32, text: &str, colour: Rgb<u8>) {
    for (i, c) in text.chars().enumerate() {
        let Some(rows) = glyph(c) else { continue };
        let left = x + i as u32 * ADVANCE;
        for (dy, row) in rows.iter().enumerate() {
            for dx in 0..5 {
                let (px, py) = (left + dx, y + dy as u32);
                if row & (0b10000 >> dx) != 0 && px < image.width() && py < image.height() {
                    image.put_pixel(px, py, colour);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_drawn_where_asked() {
        let mut image = RgbImage::new(20, 10);
        draw_text(&mut image, 2, 1, "1-", Rgb([255, 255, 255]));
        let lit: Vec<(u32, u32)> = image.enumerate_pixels().filter(|p| p.2[0] == 255).map(|p| (p.0, p.1)).collect();
        // The '1' has its stem in column 2 of its glyph; the '-' is one row, five wide.
        assert!(lit.contains(&(4, 1)) && lit.contains(&(4, 7)), "{lit:?}");
        assert!((8..13).all(|x| lit.contains(&(x, 4))), "{lit:?}");
        assert_eq!(lit.iter().filter(|p| p.1 == 4 && p.0 >= 8).count(), 5);
        assert_eq!(text_width("1-"), 11);
        assert!(can_draw("FLIP 0.5 1e-3 ABS DIFF") && !can_draw("?"));
    }
}
