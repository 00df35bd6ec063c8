//! The commands of a doc's code blocks, split into words as a shell would.

use super::markdown::{blocks, Block};
use super::Finding;
use std::collections::HashMap;

/// The program prefixes that start a command.
pub const PREFIXES: [&str; 2] = ["torus-search ", "cargo run --release -- "];

/// Shell variables a doc may use without assigning them in its code block
/// (a scheduler or GNU parallel sets them), with the value the test uses.
pub const STAND_INS: &[(&str, &str)] = &[
    ("SLURM_ARRAY_TASK_ID", "1"),
    ("SLURM_CPUS_PER_TASK", "2"),
    ("{}", "1"),
];

/// A command shown in a doc: where, and its words after the program.
#[derive(Clone, Debug, PartialEq)]
pub struct DocCommand {
    pub file: String,
    pub line: usize,
    pub args: Vec<String>,
}

/// `NAME=value` assignments at the start of a block's lines.
pub fn assignments(block: &Block) -> HashMap<String, String> {
    let mut vars = HashMap::new();
    for line in &block.lines {
        let t = line.trim_start();
        let Some((name, rest)) = t.split_once('=') else {
            continue;
        };
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            continue;
        }
        if let Ok(words) = shell_words(rest, &HashMap::new()) {
            if let Some(v) = words.first() {
                vars.insert(name.to_string(), v.clone());
            }
        }
    }
    vars
}

/// A variable's value: the block's own, else a stand-in.
pub fn variable(name: &str, vars: &HashMap<String, String>) -> Result<String, String> {
    vars.get(name)
        .cloned()
        .or_else(|| {
            STAND_INS
                .iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        })
        .ok_or_else(|| {
            format!("the shell variable ${name} is neither set in the block nor a stand-in")
        })
}

/// Splits one shell command line into words, as a POSIX shell would for the
/// simple commands the docs show: quotes, backslashes and `$VAR`/`${VAR}`.
/// The command ends at a comment or an operator (`&&`, `|`, `;`, `>`,
/// GNU parallel's `:::`). `{}` is replaced like a variable.
pub fn shell_words(line: &str, vars: &HashMap<String, String>) -> Result<Vec<String>, String> {
    let mut words: Vec<String> = Vec::new();
    let mut cur = String::new();
    let mut in_word = false;
    let mut chars = line.chars().peekable();
    let mut quote: Option<char> = None;
    while let Some(c) = chars.next() {
        match (quote, c) {
            (Some('\''), '\'') | (Some('"'), '"') => quote = None,
            (Some('\''), _) => cur.push(c),
            (_, '$') => {
                let braced = chars.peek() == Some(&'{');
                if braced {
                    chars.next();
                } else if chars.peek() == Some(&'(') {
                    return Err("command substitution $( … ) is not supported".into());
                }
                let mut name = String::new();
                while let Some(&d) = chars.peek() {
                    if d.is_ascii_alphanumeric() || d == '_' {
                        name.push(d);
                        chars.next();
                    } else {
                        break;
                    }
                }
                if braced && chars.next() != Some('}') {
                    return Err(format!("unclosed ${{{name}"));
                }
                cur.push_str(&variable(&name, vars)?);
                in_word = true;
            }
            (Some('"'), '\\') => {
                if let Some(d) = chars.next() {
                    cur.push(d);
                }
            }
            (Some(_), _) => cur.push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                in_word = true;
            }
            (None, '\\') => {
                if let Some(d) = chars.next() {
                    cur.push(d);
                    in_word = true;
                }
            }
            (None, '{') if chars.peek() == Some(&'}') => {
                chars.next();
                cur.push_str(&variable("{}", vars)?);
                in_word = true;
            }
            (None, c) if c.is_whitespace() => {
                if in_word {
                    words.push(std::mem::take(&mut cur));
                    in_word = false;
                    if words.last().is_some_and(|w| w == ":::") {
                        words.pop();
                        return Ok(words);
                    }
                }
            }
            (None, '#') if !in_word => break,
            (None, ';' | '|' | '&' | '>' | '<') => break,
            (None, _) => {
                cur.push(c);
                in_word = true;
            }
        }
    }
    if quote.is_some() {
        return Err("an unclosed quote".into());
    }
    if in_word {
        words.push(cur);
    }
    if words.last().is_some_and(|w| w == ":::") {
        words.pop();
    }
    Ok(words)
}

/// The program-less words of a command that starts a line, or `None`.
pub fn strip_program(words: &[String]) -> Option<Vec<String>> {
    for prefix in PREFIXES {
        let p: Vec<&str> = prefix.split_whitespace().collect();
        if words.len() >= p.len() && words.iter().zip(&p).all(|(w, q)| w == q) {
            return Some(words[p.len()..].to_vec());
        }
    }
    None
}

/// The commands of a doc's fenced blocks, and what could not be read.
pub fn commands(file: &str, text: &str) -> (Vec<DocCommand>, Vec<Finding>) {
    let (mut out, mut bad) = (Vec::new(), Vec::new());
    for block in blocks(text) {
        let vars = assignments(&block);
        let mut i = 0;
        while i < block.lines.len() {
            let start = i;
            let t = block.lines[i].trim_start();
            i += 1;
            if !PREFIXES.iter().any(|p| t.starts_with(p)) {
                continue;
            }
            let mut joined = t.trim_end().to_string();
            while joined.ends_with('\\') && i < block.lines.len() {
                joined.pop();
                joined.push(' ');
                joined.push_str(block.lines[i].trim());
                i += 1;
            }
            let line = block.first + start;
            match shell_words(&joined, &vars).map(|w| strip_program(&w)) {
                Ok(Some(args)) => out.push(DocCommand {
                    file: file.into(),
                    line,
                    args,
                }),
                Ok(None) => {}
                Err(what) => bad.push(Finding {
                    file: file.into(),
                    line,
                    what: format!("cannot read `{joined}`: {what}"),
                }),
            }
        }
    }
    (out, bad)
}
