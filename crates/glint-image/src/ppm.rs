//! PPM, Netpbm's portable pixmap, the image format of many ray-tracing
//! courses: a text header (`P6` or `P3`, width, height, maxval), then the
//! samples, row by row from the top, R, G and B, as bytes (`P6`, "raw") or as
//! decimal text (`P3`, "plain"). Like PNG's, the samples are sRGB-encoded
//! display values: sample / maxval. A maxval above 255 takes two bytes a
//! sample, most significant first.
//!
//! The reader is strict, and written here rather than taken from the `image`
//! crate so that each problem is one line saying where it is (the header's
//! line) and what the file promised: students' files are read, and a wrong
//! one must say why.

use std::io::Write;

use crate::output::{Bits, PpmForm};

/// The most pixels a file may claim, so that a header cannot ask for more
/// memory than any image Glint renders needs (`MAX_IMAGE_SIDE` squared).
const MAX_PIXELS: usize = (glint_scene::MAX_IMAGE_SIDE as usize) * (glint_scene::MAX_IMAGE_SIDE as usize);

/// A PPM read: its samples, R, G and B for each pixel, rows from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Ppm {
    pub width: u32,
    pub height: u32,
    pub form: PpmForm,
    /// The value of full intensity, 1 to 65535.
    pub maxval: u16,
    pub samples: Vec<u16>,
}

impl Ppm {
    /// The display value of each sample, in [0, 1].
    pub fn display_values(&self) -> impl Iterator<Item = f32> + '_ {
        let max = f32::from(self.maxval);
        self.samples.iter().map(move |&s| f32::from(s) / max)
    }
}

/// The header `glint render` writes: magic, size, and the maxval of `bits`.
pub(crate) fn header(form: PpmForm, width: u32, height: u32, bits: Bits) -> String {
    let magic = match form {
        PpmForm::Raw => "P6",
        PpmForm::Plain => "P3",
    };
    let maxval = match bits {
        Bits::Eight => 255,
        Bits::Sixteen => 65535,
    };
    format!("{magic}\n{width} {height}\n{maxval}\n")
}

/// Writes one row of samples as they are stored raw (bytes, or big-endian
/// pairs for 16 bits: a PNG's row too) in `form`. Plain rows are broken into
/// lines of at most 70 characters, as the format asks.
pub(crate) fn write_row(form: PpmForm, bits: Bits, raw: &[u8], w: &mut impl Write) -> std::io::Result<()> {
    if form == PpmForm::Raw {
        return w.write_all(raw);
    }
    let samples: Box<dyn Iterator<Item = u16>> = match bits {
        Bits::Eight => Box::new(raw.iter().map(|&b| u16::from(b))),
        Bits::Sixteen => Box::new(raw.chunks_exact(2).map(|b| u16::from_be_bytes([b[0], b[1]]))),
    };
    let mut line = String::new();
    for sample in samples {
        let text = sample.to_string();
        if !line.is_empty() && line.len() + 1 + text.len() > 70 {
            writeln!(w, "{line}")?;
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&text);
    }
    writeln!(w, "{line}")
}

/// Reads a PPM, `P6` or `P3`, of any maxval from 1 to 65535. Comments (`#` to
/// the end of the line) may stand wherever the header allows whitespace;
/// after the raster only whitespace may follow.
pub fn read_ppm(bytes: &[u8]) -> Result<Ppm, String> {
    let form = match bytes.get(..2) {
        Some(b"P6") => PpmForm::Raw,
        Some(b"P3") => PpmForm::Plain,
        Some([b'#', _]) => return Err("line 1: a comment before the magic number: a PPM starts with P6 or P3".into()),
        Some(b"P1" | b"P2" | b"P4" | b"P5") => {
            let kind = if matches!(bytes[1], b'1' | b'4') { "PBM (bitmap)" } else { "PGM (greymap)" };
            return Err(format!("not a PPM: it starts with {}, a {kind}; a PPM starts with P6 or P3", String::from_utf8_lossy(&bytes[..2])));
        }
        _ if bytes.is_empty() => return Err("truncated: the file is empty".into()),
        _ => return Err(format!("not a PPM: it starts with `{}`, not P6 or P3", shown(&bytes[..bytes.len().min(2)]))),
    };
    let mut text = Text { bytes, pos: 2, line: 1 };
    if !text.at_separator() {
        return Err(format!("line 1: not a PPM: the magic number {} must be followed by whitespace", shown(&bytes[..2])));
    }
    let width = text.header_number("width", u32::MAX)?;
    let height = text.header_number("height", u32::MAX)?;
    let maxval = text.header_number("maxval", 65535)?;
    if maxval == 0 {
        return Err(format!("line {}: the maxval is 0; it must be 1 to 65535", text.line));
    }
    let maxval = maxval as u16;
    let size = format!("{width}x{height}");
    let count = (width as usize).checked_mul(height as usize).and_then(|n| n.checked_mul(3));
    let count = count.filter(|&n| n / 3 <= MAX_PIXELS).ok_or_else(|| format!("the header's size {size} is more pixels than Glint reads"))?;
    let samples = match form {
        PpmForm::Raw => {
            // One whitespace byte ends the header (the maxval is followed by
            // whitespace or a comment, which ends at one); a comment before it
            // is the header's.
            text.skip_comments();
            if text.pos == bytes.len() {
                return Err(format!("truncated: the header ends at the maxval, with none of the {size} pixels"));
            }
            text.pos += 1;
            let wide = maxval > 255;
            let sample_bytes = if wide { 2 } else { 1 };
            let raster = &bytes[text.pos..];
            let needed = count * sample_bytes;
            if raster.len() < needed {
                return Err(format!(
                    "truncated: the header promises {size} pixels ({needed} bytes of samples), but {} bytes follow it",
                    raster.len()
                ));
            }
            if let Some(extra) = raster[needed..].iter().position(|b| !b.is_ascii_whitespace()) {
                return Err(format!(
                    "{} bytes follow the {size} pixels, from byte {}: the header's size or maxval does not match the samples",
                    raster.len() - needed,
                    text.pos + needed + extra
                ));
            }
            let samples: Vec<u16> = if wide {
                raster[..needed].chunks_exact(2).map(|b| u16::from_be_bytes([b[0], b[1]])).collect()
            } else {
                raster[..needed].iter().map(|&b| u16::from(b)).collect()
            };
            if let Some(i) = samples.iter().position(|&s| s > maxval) {
                return Err(format!("sample {i} (pixel {}, {}) is {}, above the maxval {maxval}", i / 3 % width as usize, i / 3 / width as usize, samples[i]));
            }
            samples
        }
        PpmForm::Plain => {
            // Each value takes at least two bytes: the file bounds what is reserved.
            let mut samples = Vec::with_capacity(count.min(bytes.len() / 2));
            while samples.len() < count {
                text.skip_whitespace();
                let Some(&b) = text.bytes.get(text.pos) else {
                    return Err(format!("truncated: the header promises {size} pixels ({count} values), but the file holds {}", samples.len()));
                };
                if b == b'#' {
                    return Err(format!("line {}: a comment among the pixel values: PPM allows comments only in the header", text.line));
                }
                let what = format!("a pixel value (0 to {maxval})");
                let start = text.pos;
                let value = text.number(&what, u32::from(maxval))?;
                if text.bytes.get(text.pos).is_some_and(|&b| !b.is_ascii_whitespace()) {
                    return Err(format!("line {}: expected {what}, a whole number, found `{}`", text.line, text.token(start)));
                }
                samples.push(value as u16);
            }
            text.skip_whitespace();
            if text.pos < bytes.len() {
                return Err(format!("line {}: more values than the {size} pixels the header promises", text.line));
            }
            samples
        }
    };
    Ok(Ppm { width, height, form, maxval, samples })
}

/// The header and plain samples, read as text with their line.
struct Text<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl Text<'_> {
    fn at_separator(&self) -> bool {
        self.bytes.get(self.pos).is_some_and(|&b| b.is_ascii_whitespace() || b == b'#')
    }

    fn skip_whitespace(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos).filter(|b| b.is_ascii_whitespace()) {
            self.line += usize::from(b == b'\n');
            self.pos += 1;
        }
    }

    /// Skips comments up to, not past, the newline that ends each.
    fn skip_comments(&mut self) {
        while self.bytes.get(self.pos) == Some(&b'#') {
            while self.bytes.get(self.pos).is_some_and(|&b| b != b'\n' && b != b'\r') {
                self.pos += 1;
            }
        }
    }

    /// A header field: whitespace and comments before it, then the number,
    /// which must end at whitespace or a comment.
    fn header_number(&mut self, what: &str, max: u32) -> Result<u32, String> {
        loop {
            self.skip_whitespace();
            if self.bytes.get(self.pos) != Some(&b'#') {
                break;
            }
            self.skip_comments();
        }
        if self.pos == self.bytes.len() {
            return Err(format!("truncated: the header ends before the {what}"));
        }
        let value = self.number(&format!("the {what}"), max)?;
        if self.pos < self.bytes.len() && !self.at_separator() {
            return Err(format!("line {}: the {what} must be followed by whitespace or a comment", self.line));
        }
        Ok(value)
    }

    /// The text from `start` to the next whitespace, at most 20 bytes of it.
    fn token(&self, start: usize) -> String {
        let rest = &self.bytes[start..];
        let end = rest.iter().position(u8::is_ascii_whitespace).unwrap_or(rest.len());
        shown(&rest[..end.min(20)])
    }

    /// A decimal number of at most `max`, described as `what` in errors.
    fn number(&mut self, what: &str, max: u32) -> Result<u32, String> {
        let start = self.pos;
        while self.bytes.get(self.pos).is_some_and(u8::is_ascii_digit) {
            self.pos += 1;
        }
        let digits = &self.bytes[start..self.pos];
        if digits.is_empty() {
            return Err(format!("line {}: expected {what}, a whole number, found `{}`", self.line, self.token(start)));
        }
        let value = std::str::from_utf8(digits).ok().and_then(|d| d.parse::<u64>().ok()).unwrap_or(u64::MAX);
        if value > u64::from(max) {
            return Err(format!("line {}: {what} is {}, above {max}", self.line, self.token(start)));
        }
        Ok(value as u32)
    }
}

/// Bytes as text in a message: printable ASCII as it is, others escaped.
fn shown(bytes: &[u8]) -> String {
    bytes.iter().flat_map(|&b| std::ascii::escape_default(b)).map(char::from).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(bytes: &[u8]) -> String {
        read_ppm(bytes).unwrap_err()
    }

    #[test]
    fn raw_and_plain_read_the_same_samples() {
        let raw = read_ppm(b"P6\n2 1\n255\n\x00\x80\xff\x01\x02\x03").unwrap();
        assert_eq!((raw.width, raw.height, raw.maxval, raw.form), (2, 1, 255, PpmForm::Raw));
        assert_eq!(raw.samples, [0, 128, 255, 1, 2, 3]);
        let plain = read_ppm(b"P3\n2 1\n255\n0 128 255\n1 2 3\n").unwrap();
        assert_eq!(plain.form, PpmForm::Plain);
        assert_eq!(plain.samples, raw.samples);
        assert_eq!(plain.display_values().collect::<Vec<_>>()[1], 128.0 / 255.0);
    }

    #[test]
    fn every_maxval_from_1_to_65535_reads() {
        let one = read_ppm(b"P3 1 1 1 1 0 1").unwrap();
        assert_eq!((one.maxval, one.samples.as_slice()), (1, &[1, 0, 1][..]));
        assert_eq!(one.display_values().collect::<Vec<_>>(), [1.0, 0.0, 1.0]);
        let thousand = read_ppm(b"P6 1 1 1000\n\x03\xe8\x01\xf4\x00\x00").unwrap();
        assert_eq!(thousand.samples, [1000, 500, 0], "two bytes a sample above 255, most significant first");
        assert_eq!(thousand.display_values().collect::<Vec<_>>(), [1.0, 0.5, 0.0]);
        let full = read_ppm(b"P6 1 1 65535\n\xff\xff\x80\x00\x00\x01").unwrap();
        assert_eq!(full.samples, [65535, 32768, 1]);
        assert_eq!(read_ppm(b"P3 1 1 65535 65535 0 7").unwrap().samples, [65535, 0, 7]);
        assert_eq!(read_ppm(b"P6 1 1 255 \x01\x02\x03").unwrap().samples, [1, 2, 3], "one byte a sample up to 255");
    }

    #[test]
    fn comments_stand_wherever_the_header_has_whitespace() {
        let commented = b"P6# made by a student\n# size:\n2 #wide\n1\n#maxval next\n255#last\n\x01\x02\x03\x04\x05\x06";
        assert_eq!(read_ppm(commented).unwrap().samples, [1, 2, 3, 4, 5, 6]);
        let plain = b"P3\n# comment\n1 1 # size\n255\n10 20 30\n";
        assert_eq!(read_ppm(plain).unwrap().samples, [10, 20, 30]);
        // A raw raster begins right after the whitespace byte after the maxval, even
        // when the raster's first byte is `#` or whitespace.
        assert_eq!(read_ppm(b"P6 1 1 255\n# \n").unwrap().samples, [u16::from(b'#'), 32, 10]);
    }

    #[test]
    fn bad_files_say_what_is_wrong_and_where() {
        let cases: [(&[u8], &str); 17] = [
            (b"", "truncated: the file is empty"),
            (b"P", "not a PPM: it starts with `P`, not P6 or P3"),
            (b"\x89PNG\r\n", "not a PPM: it starts with `\\x89P`, not P6 or P3"),
            (b"P5 1 1 255 \x00", "not a PPM: it starts with P5, a PGM (greymap); a PPM starts with P6 or P3"),
            (b"P7\n", "not a PPM: it starts with `P7`, not P6 or P3"),
            (b"P61 1 255\n", "line 1: not a PPM: the magic number P6 must be followed by whitespace"),
            (b"# by me\nP6 1 1 255\n\x00\x00\x00", "line 1: a comment before the magic number: a PPM starts with P6 or P3"),
            (b"P6\n1 1\n0\n\x00\x00\x00", "line 3: the maxval is 0; it must be 1 to 65535"),
            (b"P6\n1 1\n65536\n\x00\x00\x00", "line 3: the maxval is 65536, above 65535"),
            (b"P6\n1 x\n255\n", "line 2: expected the height, a whole number, found `x`"),
            (b"P6\n-1 1\n255\n", "line 2: expected the width, a whole number, found `-1`"),
            (b"P6\n2 2\n", "truncated: the header ends before the maxval"),
            (b"P6\n2 2\n255", "truncated: the header ends at the maxval, with none of the 2x2 pixels"),
            (b"P6\n2 1\n255\n\x01\x02\x03\x04", "truncated: the header promises 2x1 pixels (6 bytes of samples), but 4 bytes follow it"),
            (b"P6 1 1 255\n\x01\x02\x03\x04\x05\x06", "3 bytes follow the 1x1 pixels, from byte 14: the header's size or maxval does not match the samples"),
            (b"P3\n1 1\n255\n1 2 # blue next\n3\n", "line 4: a comment among the pixel values: PPM allows comments only in the header"),
            (b"P3\n2 1\n255\n1 2 3\n4 5\n", "truncated: the header promises 2x1 pixels (6 values), but the file holds 5"),
        ];
        for (bytes, message) in cases {
            assert_eq!(err(bytes), message, "{}", shown(bytes));
        }
        assert_eq!(err(b"P3\n1 1\n100\n1 2 300\n"), "line 4: a pixel value (0 to 100) is 300, above 100");
        assert_eq!(err(b"P3\n1 1\n255\n1 2 3 4\n"), "line 4: more values than the 1x1 pixels the header promises");
        assert_eq!(err(b"P3\n1 1\n255\n1 2 3.5\n"), "line 4: expected a pixel value (0 to 255), a whole number, found `3.5`");
        assert_eq!(err(b"P6 1 1 100 \x01\x02\x65"), "sample 2 (pixel 0, 0) is 101, above the maxval 100");
        assert_eq!(err(b"P6 1 1 255x\x01\x02\x03"), "line 1: the maxval must be followed by whitespace or a comment");
        // A trailing newline after the raster, as many writers add, is not a problem.
        assert_eq!(read_ppm(b"P6 1 1 255\n\x01\x02\x03\n").unwrap().samples, [1, 2, 3]);
    }

    #[test]
    fn rows_are_written_as_raw_bytes_or_short_text_lines() {
        assert_eq!(header(PpmForm::Raw, 4, 3, Bits::Eight), "P6\n4 3\n255\n");
        assert_eq!(header(PpmForm::Plain, 4, 3, Bits::Sixteen), "P3\n4 3\n65535\n");
        let mut raw = Vec::new();
        write_row(PpmForm::Raw, Bits::Sixteen, &[1, 2, 3, 4, 5, 6], &mut raw).unwrap();
        assert_eq!(raw, [1, 2, 3, 4, 5, 6]);
        let mut plain = Vec::new();
        write_row(PpmForm::Plain, Bits::Sixteen, &[1, 2, 0, 255, 255, 255], &mut plain).unwrap();
        assert_eq!(plain, b"258 255 65535\n");
        let row: Vec<u8> = (0..=255).collect();
        let mut long = Vec::new();
        write_row(PpmForm::Plain, Bits::Eight, &row, &mut long).unwrap();
        let text = String::from_utf8(long).unwrap();
        assert!(text.lines().all(|l| l.len() <= 70) && text.lines().count() > 1, "{text}");
        let numbers: Vec<u8> = text.split_ascii_whitespace().map(|n| n.parse().unwrap()).collect();
        assert_eq!(numbers, row);
    }
}
