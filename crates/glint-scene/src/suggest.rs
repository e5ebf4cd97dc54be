//! "Did you mean …?": the nearest of a few known names to a misspelt one.

/// The optimal string alignment distance between `a` and `b`: the number of
/// single-character insertions, deletions, substitutions and transpositions of
/// neighbours that turn one into the other (`radus` → `radius` is 1, and so
/// is `raduis` → `radius`). Case is ignored.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.to_lowercase().chars().collect();
    let b: Vec<char> = b.to_lowercase().chars().collect();
    // Three rows of the dynamic programme: i − 2, i − 1 and i.
    let mut before: Vec<usize> = vec![0; b.len() + 1];
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    let mut current = vec![0; b.len() + 1];
    for i in 1..=a.len() {
        current[0] = i;
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut d = (previous[j] + 1).min(current[j - 1] + 1).min(previous[j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                d = d.min(before[j - 2] + 1);
            }
            current[j] = d;
        }
        std::mem::swap(&mut before, &mut previous);
        std::mem::swap(&mut previous, &mut current);
    }
    previous[b.len()]
}

/// The candidate closest to `word`, if it is close enough to be what was
/// meant: at most 2 edits, or a third of the word's length for long words.
/// Ties go to the earlier candidate.
pub fn nearest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let limit = (word.chars().count() / 3).max(2);
    candidates
        .into_iter()
        .map(|c| (edit_distance(word, c), c))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(edit_distance("radus", "radius"), 1);
        assert_eq!(edit_distance("raduis", "radius"), 1, "a transposition is one edit");
        assert_eq!(edit_distance("colour", "color"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("abc", ""), 3);
        assert_eq!(edit_distance("Center", "center"), 0);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }

    #[test]
    fn nearest_picks_the_closest_close_candidate() {
        let keys = ["type", "material", "center", "radius"];
        assert_eq!(nearest("radus", keys), Some("radius"));
        assert_eq!(nearest("centre", keys), Some("center"));
        assert_eq!(nearest("colour", keys), None);
        assert_eq!(nearest("objects", ["image", "camera", "object", "light"]), Some("object"));
    }
}
