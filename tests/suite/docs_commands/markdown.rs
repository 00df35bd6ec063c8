//! Markdown, as far as the checker reads it: fenced code blocks, prose,
//! inline code spans, headings' anchors and relative links.

use std::collections::BTreeSet;

/// A fenced code block: its first line's number (1-based) and its lines.
pub struct Block<'a> {
    pub first: usize,
    pub lines: Vec<&'a str>,
}

pub fn fence(line: &str) -> bool {
    let t = line.trim_start();
    t.starts_with("```") || t.starts_with("~~~")
}

/// The fenced code blocks of a Markdown text.
pub fn blocks(text: &str) -> Vec<Block<'_>> {
    let mut out = Vec::new();
    let mut open: Option<Block> = None;
    for (i, line) in text.lines().enumerate() {
        if fence(line) {
            match open.take() {
                Some(b) => out.push(b),
                None => {
                    open = Some(Block {
                        first: i + 2,
                        lines: Vec::new(),
                    })
                }
            }
        } else if let Some(b) = open.as_mut() {
            b.lines.push(line);
        }
    }
    out
}

/// The text outside fenced code blocks, line by line (1-based numbers).
pub fn prose(text: &str) -> Vec<(usize, &str)> {
    let mut inside = false;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if fence(line) {
            inside = !inside;
        } else if !inside {
            out.push((i + 1, line));
        }
    }
    out
}

/// The inline code spans of a doc's prose, each with the line it starts
/// on; a span may wrap onto the next lines, but not past a blank line.
pub fn inline_spans(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut open: Option<(usize, String)> = None;
    for (n, line) in prose(text) {
        if line.trim().is_empty() {
            open = None;
            continue;
        }
        if let Some((_, span)) = open.as_mut() {
            span.push(' ');
        }
        for (k, piece) in line.split('`').enumerate() {
            if k > 0 {
                match open.take() {
                    Some(done) => out.push(done),
                    None => open = Some((n, String::new())),
                }
            }
            if let Some((_, span)) = open.as_mut() {
                span.push_str(piece);
            }
        }
    }
    out
}

/// GitHub's anchor for a heading: lower case, punctuation dropped, spaces
/// as hyphens.
pub fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a Markdown text's headings.
pub fn anchors(text: &str) -> BTreeSet<String> {
    prose(text)
        .into_iter()
        .filter_map(|(_, l)| l.strip_prefix('#'))
        .map(|h| slug(h.trim_start_matches('#')))
        .collect()
}

/// The relative link targets of a doc's prose (`](target)`), with lines.
pub fn links(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (n, line) in prose(text) {
        for piece in line.split("](").skip(1) {
            let Some(target) = piece.split(')').next() else {
                continue;
            };
            if !target.contains("://") && !target.starts_with("mailto:") {
                out.push((n, target.to_string()));
            }
        }
    }
    out
}
