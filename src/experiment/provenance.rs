//! Where an output came from: the build (crate version, git commit, a mark
//! for a tree with uncommitted changes), when it was made, and the command
//! that made it.
//!
//! Every file the CLI and the page write carries it: a `provenance` object
//! in JSON, `#` lines atop a CSV, a caption under a chart. It is kept out
//! of the bytes that must compare equal (shards merged and a single run;
//! the page and the CLI): [`ResultSet::to_json`] and [`ResultSet::csv`]
//! hold none, the files are those bytes with the provenance added
//! ([`ResultSet::stamped_json`], [`ResultSet::stamped_csv`]), and [`strip`]
//! takes it out again.

use super::read::{merge, read, MergeError};
use super::result::{ResultError, ResultSet};
use serde_json::Value;

/// The crate version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
/// The git commit this build was made from (40 hex digits), or `unknown`
/// (built outside a git checkout: build.rs).
pub const COMMIT: &str = env!("TORUS_SEARCH_COMMIT");
const DIRTY: &str = env!("TORUS_SEARCH_DIRTY");

/// The program's name in captions and comments.
const PROGRAM: &str = "torus-search";

/// Whether this build's tree had uncommitted changes (`None`: unknown).
pub fn dirty() -> Option<bool> {
    match DIRTY {
        "true" => Some(true),
        "false" => Some(false),
        _ => None,
    }
}

/// The provenance fields, in the order every output writes them.
pub const FIELDS: &[&str] = &["version", "commit", "dirty", "date", "command", "sources"];

/// Where an output came from.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Provenance {
    /// The crate version of the build that made it.
    pub version: String,
    /// The git commit of that build: 40 hex digits, or `unknown`.
    pub commit: String,
    /// Whether that build's tree had uncommitted changes (`None`: unknown).
    pub dirty: Option<bool>,
    /// When it was made: UTC, ISO 8601 to the second (`2025-01-31T12:00:00Z`).
    pub date: String,
    /// What made it: the command line (shell-quoted), or the page's URL.
    pub command: String,
    /// A merge's inputs: each file's own provenance, in the order given.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sources: Vec<Provenance>,
}

/// `secs` seconds after 1970-01-01T00:00:00Z as `YYYY-MM-DDTHH:MM:SSZ`
/// (proleptic Gregorian calendar; years 0 to 9999).
pub fn utc_date(secs: i64) -> String {
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Days to a civil date (the era-based method: 400-year eras of 146097 days).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// True for a date as [`utc_date`] writes it.
pub fn is_utc_date(s: &str) -> bool {
    let b = s.as_bytes();
    let digits = |r: std::ops::Range<usize>| b[r].iter().all(u8::is_ascii_digit);
    b.len() == 20
        && digits(0..4)
        && b[4] == b'-'
        && digits(5..7)
        && b[7] == b'-'
        && digits(8..10)
        && b[10] == b'T'
        && digits(11..13)
        && b[13] == b':'
        && digits(14..16)
        && b[16] == b':'
        && digits(17..19)
        && b[19] == b'Z'
}

/// A command line as one string a POSIX shell reads back into the same
/// arguments: arguments with other characters than `A-Za-z0-9_./:=,@%+-`
/// are single-quoted.
pub fn shell_line<S: AsRef<str>>(args: &[S]) -> String {
    args.iter()
        .map(|a| {
            let a = a.as_ref();
            let plain = !a.is_empty()
                && a.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_./:=,@%+-".contains(c));
            if plain {
                a.to_string()
            } else {
                format!("'{}'", a.replace('\'', r"'\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

impl Provenance {
    /// This build's provenance for an output made at `date` by `command`.
    pub fn new(date: String, command: String) -> Provenance {
        Provenance {
            version: VERSION.to_string(),
            commit: COMMIT.to_string(),
            dirty: dirty(),
            date,
            command,
            sources: Vec::new(),
        }
    }

    /// This build's provenance for an output made now by `command`. The
    /// date is the clock's, or `SOURCE_DATE_EPOCH`'s when that is set (the
    /// reproducible-builds convention, for outputs that must not change).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn now(command: String) -> Provenance {
        let secs = std::env::var("SOURCE_DATE_EPOCH")
            .ok()
            .and_then(|s| s.trim().parse::<i64>().ok())
            .unwrap_or_else(|| {
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_secs() as i64)
            });
        Provenance::new(utc_date(secs), command)
    }

    /// The build, as captions show it: `torus-search 0.1.0, commit
    /// 0123456789ab (uncommitted changes)`.
    pub fn build(&self) -> String {
        build_label(&self.version, &self.commit, self.dirty)
    }

    /// The `#` lines a CSV starts with: one `# field: value` line per field
    /// (the JSON's names), the spec, then one line per source.
    pub fn csv_comments(&self, spec: &str) -> String {
        let one_line = |s: &str| s.replace(['\n', '\r'], " ");
        let mut out = format!(
            "# {PROGRAM} results; these lines are comments (pandas: comment='#'; R: comment.char='#')\n\
             # version: {}\n# commit: {}\n# dirty: {}\n# date: {}\n# command: {}\n# spec: {}\n",
            self.version,
            self.commit,
            self.dirty.map_or("unknown".to_string(), |d| d.to_string()),
            self.date,
            one_line(&self.command),
            one_line(spec)
        );
        for (i, s) in self.sources.iter().enumerate() {
            out += &format!(
                "# source {}: {}, made {} by {}\n",
                i + 1,
                s.build(),
                s.date,
                one_line(&s.command)
            );
        }
        out
    }

    /// Reads a `provenance` object.
    ///
    /// # Errors
    /// What is missing or malformed, naming the field.
    pub fn from_value(v: &Value) -> Result<Provenance, String> {
        let obj = v
            .as_object()
            .ok_or_else(|| format!("must be an object {{{}}}", FIELDS.join(", ")))?;
        if let Some(k) = obj.keys().find(|k| !FIELDS.contains(&k.as_str())) {
            return Err(format!(
                ".{k} is not a provenance field ({})",
                FIELDS.join(", ")
            ));
        }
        let text = |k: &str| match obj.get(k) {
            Some(Value::String(s)) => Ok(s.clone()),
            _ => Err(format!(".{k} must be a string")),
        };
        let commit = text("commit")?;
        if commit != "unknown"
            && !(commit.len() == 40 && commit.bytes().all(|b| b.is_ascii_hexdigit()))
        {
            return Err(format!(
                ".commit must be 40 hex digits or \"unknown\", got {commit:?}"
            ));
        }
        let date = text("date")?;
        if !is_utc_date(&date) {
            return Err(format!(
                ".date must be UTC as YYYY-MM-DDTHH:MM:SSZ, got {date:?}"
            ));
        }
        let dirty = match obj.get("dirty") {
            Some(Value::Bool(b)) => Some(*b),
            Some(Value::Null) => None,
            _ => return Err(".dirty must be true, false or null".into()),
        };
        let sources = match obj.get("sources") {
            None => Vec::new(),
            Some(Value::Array(a)) => a
                .iter()
                .enumerate()
                .map(|(i, s)| Provenance::from_value(s).map_err(|e| format!(".sources[{i}]{e}")))
                .collect::<Result<_, _>>()?,
            Some(_) => return Err(".sources must be a list".into()),
        };
        Ok(Provenance {
            version: text("version")?,
            commit,
            dirty,
            date,
            command: text("command")?,
            sources,
        })
    }
}

/// A build as captions show it.
fn build_label(version: &str, commit: &str, dirty: Option<bool>) -> String {
    let commit = if commit == "unknown" {
        "commit unknown".to_string()
    } else {
        format!("commit {}", &commit[..12.min(commit.len())])
    };
    let mark = match dirty {
        Some(true) => " (uncommitted changes)",
        _ => "",
    };
    format!("{PROGRAM} {version}, {commit}{mark}")
}

/// This build, as captions and the page's footer show it.
pub fn this_build() -> String {
    build_label(VERSION, COMMIT, dirty())
}

/// The result file's provenance: `None` for a file written before results
/// carried one.
///
/// # Errors
/// A [`ResultError`] for text that is not JSON, or a malformed provenance.
pub fn of_result(text: &str) -> Result<Option<Provenance>, ResultError> {
    let v: Value = serde_json::from_str(text).map_err(|e| ResultError::Json(e.to_string()))?;
    let Some(p) = v.get("provenance") else {
        return Ok(None);
    };
    let p = Provenance::from_value(p).map_err(|problem| ResultError::Field {
        field: "provenance".into(),
        problem: problem.trim_start_matches('.').to_string(),
    })?;
    if v.get("version").and_then(Value::as_str) != Some(p.version.as_str()) {
        return Err(ResultError::Field {
            field: "provenance.version".into(),
            problem: format!(
                "is {:?} but the file's version is {}: the file was edited",
                p.version,
                v.get("version").map_or("absent".into(), Value::to_string)
            ),
        });
    }
    Ok(Some(p))
}

/// Reads and checks a result file, with its provenance.
///
/// # Errors
/// As [`read`] and [`of_result`].
pub fn read_stamped(text: &str) -> Result<(ResultSet, Option<Provenance>), ResultError> {
    let set = read(text)?;
    Ok((set, of_result(text)?))
}

/// One of a result's CSV tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsvTable {
    /// One row per point (`<name>.csv`).
    Points,
    /// One row per trial (`<name>.trials.csv`).
    Trials,
    /// One row per paired comparison (`<name>.paired.csv`).
    Paired,
}

/// A CSV table of a result JSON text, after the `#` lines of the result's
/// provenance (none for a file without one).
///
/// # Errors
/// As [`read_stamped`].
pub fn csv_of_result(text: &str, table: CsvTable) -> Result<String, ResultError> {
    let (set, p) = read_stamped(text)?;
    let body = match table {
        CsvTable::Points => set.csv(),
        CsvTable::Trials => set.trials_csv(),
        CsvTable::Paired => set.paired_csv(),
    };
    Ok(match p {
        Some(p) => p.csv_comments(&set.plan.spec.to_text()) + &body,
        None => body,
    })
}

impl ResultSet {
    /// The result JSON with `provenance` after `version`: [`strip`] gives
    /// back [`ResultSet::to_json`].
    pub fn stamped_json(&self, p: &Provenance) -> String {
        self.json_with(Some(p))
    }

    /// The per-point CSV after the provenance's comment lines.
    pub fn stamped_csv(&self, p: &Provenance) -> String {
        p.csv_comments(&self.plan.spec.to_text()) + &self.csv()
    }

    /// The per-trial CSV after the provenance's comment lines.
    pub fn stamped_trials_csv(&self, p: &Provenance) -> String {
        p.csv_comments(&self.plan.spec.to_text()) + &self.trials_csv()
    }

    /// The paired CSV after the provenance's comment lines.
    pub fn stamped_paired_csv(&self, p: &Provenance) -> String {
        p.csv_comments(&self.plan.spec.to_text()) + &self.paired_csv()
    }
}

/// The colour of a chart's caption, which alone holds its provenance: in
/// an SVG no other text has it, so [`strip`] can take the caption out.
pub const CAPTION_RGB: [u8; 3] = [0x59, 0x59, 0x59];

/// An SVG without its caption's `<text>` elements (those in [`CAPTION_RGB`]).
fn strip_svg(text: &str) -> String {
    let fill = format!(
        "fill=\"#{:02X}{:02X}{:02X}\"",
        CAPTION_RGB[0], CAPTION_RGB[1], CAPTION_RGB[2]
    );
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("<text") {
        out.push_str(&rest[..at]);
        let end = rest[at..]
            .find("</text>")
            .map_or(rest.len(), |e| at + e + "</text>".len());
        let element = &rest[at..end];
        let open = &element[..element.find('>').unwrap_or(element.len())];
        if !open.contains(&fill) {
            out.push_str(element);
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// The text without its provenance: a result JSON without its top-level
/// `provenance` member, a CSV without its leading `#` lines, a chart's SVG
/// without its caption. Other text is returned as it is.
pub fn strip(text: &str) -> String {
    if text.starts_with("<svg") {
        return strip_svg(text);
    }
    if text.starts_with('#') {
        return text
            .lines()
            .skip_while(|l| l.starts_with('#'))
            .map(|l| format!("{l}\n"))
            .collect();
    }
    const KEY: &str = ",\"provenance\":";
    // In JSON text `,"` cannot occur inside a string (its quote would be
    // escaped), so the first match is a member; ours is the top level's.
    let Some(at) = text.find(KEY) else {
        return text.to_string();
    };
    let rest = &text[at + KEY.len()..];
    let (mut depth, mut in_string, mut escaped) = (0i32, false, false);
    for (i, c) in rest.char_indices() {
        match c {
            _ if escaped => escaped = false,
            '\\' if in_string => escaped = true,
            '"' => in_string = !in_string,
            '{' | '[' if !in_string => depth += 1,
            '}' | ']' if !in_string => {
                depth -= 1;
                if depth == 0 {
                    return format!("{}{}", &text[..at], &rest[i + 1..]);
                }
            }
            _ => {}
        }
    }
    text.to_string()
}

/// [`merge`], with each file's provenance (`None` for a file without one).
///
/// # Errors
/// As [`merge`]; a malformed provenance names its file.
pub fn merge_stamped(
    files: &[(&str, &str)],
) -> Result<(ResultSet, Vec<Option<Provenance>>), MergeError> {
    let set = merge(files)?;
    let provs = files
        .iter()
        .map(|&(name, text)| {
            of_result(text).map_err(|e| MergeError {
                file: Some(name.to_string()),
                problem: e.to_string(),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((set, provs))
}

/// A source for a file without provenance: everything unknown.
pub fn unknown() -> Provenance {
    Provenance {
        version: "unknown".into(),
        commit: "unknown".into(),
        dirty: None,
        date: utc_date(0),
        command: "unknown (the file carries no provenance)".into(),
        sources: Vec::new(),
    }
}

/// The warnings a merge of `files` (name, provenance) by this build gives:
/// files made by other commits than the first file's, or than this build,
/// from a tree with uncommitted changes, or without provenance. Their
/// specs and rows agree (the merge checked them), so they are merged.
pub fn merge_warnings(files: &[(&str, Option<&Provenance>)]) -> Vec<String> {
    let mut out = Vec::new();
    let label = |p: &Provenance| {
        let mark = if p.dirty == Some(true) {
            " with uncommitted changes"
        } else {
            ""
        };
        format!("commit {}{mark}", p.commit)
    };
    let first = files.iter().find_map(|(n, p)| p.map(|p| (*n, p)));
    for (name, p) in files {
        match p {
            None => out.push(format!(
                "{name} carries no provenance (it predates it): its build and commit are unknown"
            )),
            Some(p) => {
                if let Some((first_name, f)) = first {
                    if f.commit != p.commit {
                        out.push(format!(
                            "{name} was made by {}, {first_name} by {}; their specs and rows agree, so they are merged",
                            label(p),
                            label(f)
                        ));
                    }
                }
                if p.dirty == Some(true) {
                    out.push(format!(
                        "{name} was made by a build with uncommitted changes ({}): its code may be in no commit",
                        label(p)
                    ));
                }
            }
        }
    }
    if let Some((name, f)) = first {
        if f.commit != COMMIT {
            out.push(format!(
                "{name} was made by {}, and this build is commit {COMMIT}; this build derives the same statistics from its rows",
                label(f)
            ));
        }
    }
    out
}

#[cfg(test)]
#[path = "provenance_tests.rs"]
mod tests;
