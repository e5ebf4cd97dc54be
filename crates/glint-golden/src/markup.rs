//! Escaping text for XML and HTML, which share these rules, and for
//! Markdown.

/// `text` safe inside an element or a quoted attribute. Control characters
/// that XML 1.0 forbids become U+FFFD, so that any message stays well-formed.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if u32::from(c) < 0x20 => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
    out
}

/// `text` as Markdown shows it, character for character: the characters that
/// would start emphasis, code, links, images, headings or tables are
/// backslash-escaped, which every Markdown accepts; `&`, `<` and `>` become
/// entities, which it passes through to HTML.
pub fn escape_markdown(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '\\' | '`' | '*' | '_' | '[' | ']' | '#' | '!' | '|' | '~' => {
                out.push('\\');
                out.push(c);
            }
            c if u32::from(c) < 0x20 && c != '\n' => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_shows_the_text_as_it_is() {
        assert_eq!(
            escape_markdown("flip 0.2 > 0.01, ann_b/*x*.png [1] #2 `c` ![i](u) a|b ~~s~~ \\ & <b>\u{7}"),
            "flip 0.2 &gt; 0.01, ann\\_b/\\*x\\*.png \\[1\\] \\#2 \\`c\\` \\!\\[i\\](u) a\\|b \\~\\~s\\~\\~ \\\\ &amp; &lt;b&gt;\u{fffd}"
        );
    }

    #[test]
    fn markup_and_controls_are_escaped() {
        assert_eq!(escape("a<b & \"c\" 'd'>\u{1b}[0m\n"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;\u{fffd}[0m\n");
    }
}
