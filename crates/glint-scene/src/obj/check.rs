//! Checks of OBJ and MTL text before `tobj` reads it: `tobj` accepts NaN and
//! infinities, divides by a `w` of 1e-40, skips short faces and reports other
//! problems without a place, so each statement Glint reads is checked here
//! first and a failure names its line.

use glam::Vec3;

use crate::quoted;

/// A problem found by [`check_obj`] or [`check_mtl`]: the 1-based line and
/// what is wrong.
type LineError = (usize, String);

/// A finite 32-bit number (what `tobj` stores), or what is wrong with `word`.
fn finite_value(word: &str, what: &str) -> Result<f32, String> {
    match word.parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("{what}: {} is not a finite number", quoted(word))),
        Err(_) => Err(format!("{what}: {} is not a number", quoted(word))),
    }
}

/// Checks the OBJ statements Glint reads (`v`, `vt`, `vn`, `f`, `l`): their
/// value counts, that numbers are finite, that `v`'s `w` leaves the position
/// finite, that a face has at least 3 vertices and that every index names an
/// element defined before it (negative indices count back from the last).
/// Returns the line of each face, in file order (the order `tobj` keeps).
pub(super) fn check_obj(source: &str) -> Result<Vec<usize>, LineError> {
    let (mut positions, mut texcoords, mut normals) = (0usize, 0usize, 0usize);
    let mut face_lines = Vec::new();
    for (i, line) in source.lines().enumerate() {
        let at = |message: String| (i + 1, message);
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let values: Vec<&str> = words.collect();
        match key {
            "v" => {
                if !matches!(values.len(), 3 | 4 | 6) {
                    return Err(at(format!(
                        "vertex position: `v` takes x y z, then w or r g b; found {} value(s)",
                        values.len()
                    )));
                }
                let numbers = values
                    .iter()
                    .map(|w| finite_value(w, "vertex position"))
                    .collect::<Result<Vec<f32>, _>>()
                    .map_err(at)?;
                if let [x, y, z, w] = numbers[..]
                    && (w == 0.0 || !(Vec3::new(x, y, z) / w).is_finite())
                {
                    let w = quoted(values[3]);
                    return Err(at(format!("vertex position: w = {w} takes the vertex beyond the range of 32-bit floats")));
                }
                positions += 1;
            }
            "vt" => {
                if !matches!(values.len(), 2 | 3) {
                    return Err(at(format!("texture coordinate: `vt` takes u v [w]; found {} value(s)", values.len())));
                }
                values.iter().try_for_each(|w| finite_value(w, "texture coordinate").map(drop)).map_err(at)?;
                texcoords += 1;
            }
            "vn" => {
                if values.len() != 3 {
                    return Err(at(format!("vertex normal: `vn` takes x y z; found {} value(s)", values.len())));
                }
                values.iter().try_for_each(|w| finite_value(w, "vertex normal").map(drop)).map_err(at)?;
                normals += 1;
            }
            "f" | "l" => {
                let (min, what) = if key == "f" { (3, "a face") } else { (2, "a line") };
                if values.len() < min {
                    return Err(at(format!("{what} needs at least {min} vertices, found {}", values.len())));
                }
                for word in &values {
                    check_vertex_reference(word, [positions, texcoords, normals]).map_err(at)?;
                }
                if key == "f" {
                    face_lines.push(i + 1);
                }
            }
            _ => {}
        }
    }
    Ok(face_lines)
}

/// Checks one vertex of a face, `v`, `v/vt`, `v//vn` or `v/vt/vn`, against the
/// numbers of positions, texture coordinates and normals defined so far.
fn check_vertex_reference(word: &str, defined: [usize; 3]) -> Result<(), String> {
    let parts: Vec<&str> = word.split('/').collect();
    if parts.len() > 3 || parts[0].is_empty() {
        return Err(format!("{} is not a vertex reference (v, v/vt, v//vn or v/vt/vn)", quoted(word)));
    }
    let names = [("vertex", "vertices"), ("texture coordinate", "texture coordinates"), ("normal", "normals")];
    for ((part, count), (name, names)) in parts.iter().zip(defined).zip(names) {
        if part.is_empty() {
            continue;
        }
        let index: i64 = part
            .parse()
            .map_err(|_| format!("{} is not a vertex reference: {} is not a whole number", quoted(word), quoted(part)))?;
        if index == 0 {
            return Err(format!("{} refers to {name} 0, but OBJ counts from 1", quoted(word)));
        }
        let count = count as i64;
        if index.unsigned_abs() > count.unsigned_abs() {
            let counted = match count {
                0 => format!("no {names} are"),
                1 => format!("only 1 {name} is"),
                n => format!("only {n} {names} are"),
            };
            return Err(format!("{} refers to {name} {index}, but {counted} defined before it", quoted(word)));
        }
    }
    Ok(())
}

/// Checks the MTL statements Glint reads and returns the text `tobj` should
/// parse: colours (`Ka`, `Kd`, `Ks`, `Ke`, `Tf`) take r g b or one grey value
/// (which `tobj` cannot read, so it is written out as three), `Ns`, `Ni`, `d`
/// and `Tr` one number, and every number must be finite.
pub(super) fn check_mtl(text: &str) -> Result<std::borrow::Cow<'_, str>, LineError> {
    let mut rewritten: Option<String> = None;
    for (i, line) in text.lines().enumerate() {
        let at = |message: String| (i + 1, message);
        let mut words = line.split_whitespace();
        let Some(key) = words.next() else { continue };
        let values: Vec<&str> = words.collect();
        match key {
            "Ka" | "Kd" | "Ks" | "Ke" | "Tf" => {
                if !matches!(values.len(), 1 | 3) {
                    return Err(at(format!("`{key}` takes r g b or one grey value; found {} value(s)", values.len())));
                }
                values.iter().try_for_each(|w| finite_value(w, key).map(drop)).map_err(at)?;
                if values.len() == 1 && key != "Tf" {
                    let out = rewritten.get_or_insert_with(|| {
                        text.lines().take(i).fold(String::with_capacity(text.len() + 16), |mut s, l| {
                            s.push_str(l);
                            s.push('\n');
                            s
                        })
                    });
                    out.push_str(&format!("{key} {0} {0} {0}\n", values[0]));
                    continue;
                }
            }
            "Ns" | "Ni" | "d" | "Tr" => {
                if values.len() != 1 {
                    return Err(at(format!("`{key}` takes one number; found {} value(s)", values.len())));
                }
                finite_value(values[0], key).map_err(at)?;
            }
            _ => {}
        }
        if let Some(out) = rewritten.as_mut() {
            out.push_str(line);
            out.push('\n');
        }
    }
    Ok(rewritten.map_or(std::borrow::Cow::Borrowed(text), std::borrow::Cow::Owned))
}

/// The 1-based line at which `fails` first fails on a prefix of `text` (whole
/// lines), found by bisection: `tobj` reports what went wrong but not where.
pub(super) fn first_failing_line(text: &str, fails: impl Fn(&str) -> bool) -> Option<usize> {
    let ends: Vec<usize> = text.match_indices('\n').map(|(i, _)| i + 1).chain(std::iter::once(text.len())).collect();
    let prefix = |lines: usize| &text[..ends[lines - 1]];
    let (mut lo, mut hi) = (1, ends.len());
    if !fails(prefix(hi)) {
        return None;
    }
    while lo < hi {
        let mid = (lo + hi) / 2;
        if fails(prefix(mid)) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    Some(lo)
}
