//! The validation context: a file and its text, so that every message can
//! name the file, the line and column, and the field; and the TOML parser
//! with located errors.

use std::cell::RefCell;
use std::ops::Range;
use std::path::Path;

use toml::Spanned;

use crate::error::{Location, SceneError};
use crate::inputs::DataInput;

/// The largest scene or batch file read, in bytes: a scene is a page of
/// TOML (point sets and surfaces from files are read on their own), so a
/// file above this is not a scene, and is refused before it is held in
/// memory.
pub const MAX_INPUT_BYTES: u64 = 16 << 20;

/// A scene or batch file's text, read once (so `/dev/stdin` and a pipe
/// work as a file does) and at most [`MAX_INPUT_BYTES`] of it.
///
/// # Errors
/// [`SceneError::Io`] when it cannot be read, is not UTF-8, or is larger.
pub fn read_text(path: &Path) -> Result<String, SceneError> {
    use std::io::Read as _;
    let file = std::fs::File::open(path).map_err(|e| SceneError::io(path, e))?;
    let mut bytes = Vec::new();
    file.take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| SceneError::io(path, e))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(SceneError::io(
            path,
            format!(
                "larger than {} MiB, the largest scene or batch file elcon reads: \
                 is it the scene? (point sets go in their own files)",
                MAX_INPUT_BYTES >> 20
            ),
        ));
    }
    String::from_utf8(bytes).map_err(|e| SceneError::io(path, format!("not UTF-8 text: {e}")))
}

/// Validation context: the file and its text, for locations, and the data
/// files read while validating it.
pub(crate) struct Ctx<'a> {
    pub file: &'a Path,
    pub text: &'a str,
    /// The data files read so far, in the order they were read.
    pub inputs: RefCell<Vec<DataInput>>,
}

impl<'a> Ctx<'a> {
    /// The context of `file`'s `text`, no data file read yet.
    pub(crate) fn new(file: &'a Path, text: &'a str) -> Self {
        Self {
            file,
            text,
            inputs: RefCell::new(Vec::new()),
        }
    }

    /// The directory files named in the scene are read relative to: the
    /// scene file's, or a batch run's base scene's (its label, `<base>
    /// [run k: ...]`, is not a path).
    pub(crate) fn dir(&self) -> &'a Path {
        let file: &'a Path = self.file;
        let text = file.to_str().unwrap_or("");
        match text.find(" [run ") {
            Some(i) => Path::new(&text[..i]).parent().unwrap_or(Path::new("")),
            None => file.parent().unwrap_or(Path::new("")),
        }
    }

    pub(crate) fn at(&self, span: Range<usize>) -> Location {
        Location::of(self.text, span.start)
    }

    /// An `Invalid` error at `span`.
    pub(crate) fn invalid(
        &self,
        span: Range<usize>,
        field: impl Into<String>,
        value: impl Printed,
        reason: impl Into<String>,
    ) -> SceneError {
        SceneError::Invalid {
            file: self.file.to_path_buf(),
            at: self.at(span),
            field: field.into(),
            value: value.printed(),
            reason: reason.into(),
        }
    }

    /// `value` (of `field`, at `span`) when `holds`; else refused, saying
    /// `why`.
    pub(crate) fn ensure<T: Printed>(
        &self,
        value: T,
        holds: bool,
        span: Range<usize>,
        field: &str,
        why: impl Into<String>,
    ) -> Result<T, SceneError> {
        if holds {
            Ok(value)
        } else {
            Err(self.invalid(span, field, &value, why))
        }
    }

    /// A value that must be finite and > 0.
    pub(crate) fn positive(&self, v: &Spanned<f64>, field: &str) -> Result<f64, SceneError> {
        let x = *v.get_ref();
        if !x.is_finite() {
            return Err(self.invalid(v.span(), field, Num(x), "must be a finite number"));
        }
        if x <= 0.0 {
            return Err(self.invalid(v.span(), field, Num(x), "must be > 0"));
        }
        if x < f64::MIN_POSITIVE {
            return Err(self.invalid(
                v.span(),
                field,
                Num(x),
                "must be at least 2.2e-308 (a normal floating-point number): what is computed \
                 from a value this small overflows",
            ));
        }
        Ok(x)
    }

    /// A value that must be finite.
    pub(crate) fn finite(&self, v: &Spanned<f64>, field: &str) -> Result<f64, SceneError> {
        let x = *v.get_ref();
        if !x.is_finite() {
            return Err(self.invalid(v.span(), field, Num(x), "must be a finite number"));
        }
        Ok(x)
    }

    /// A count that must be >= `min`.
    pub(crate) fn count(
        &self,
        v: &Spanned<i64>,
        field: &str,
        min: i64,
    ) -> Result<usize, SceneError> {
        let x = *v.get_ref();
        if x < min {
            let why = if field.starts_with("points.") && min == 1 {
                format!("must be at least {min} (an empty point set)")
            } else {
                format!("must be at least {min}")
            };
            return Err(self.invalid(v.span(), field, x, why));
        }
        usize::try_from(x).map_err(|_| self.invalid(v.span(), field, x, "too large"))
    }

    pub(crate) fn required<'s, T>(
        &self,
        v: &'s Option<Spanned<T>>,
        section: Range<usize>,
        field: &str,
        why: &str,
    ) -> Result<&'s Spanned<T>, SceneError> {
        v.as_ref()
            .ok_or_else(|| self.invalid(section, field, "(missing)", format!("is required {why}")))
    }

    /// Every key given in `section` must be one that `owner` (a model, a
    /// grid) takes: `given` is each key present, with its span and its
    /// value as the message shows it ("" for none); the first that `owner`
    /// does not take is refused, naming what it does take.
    pub(crate) fn allowed_keys<'k>(
        &self,
        section: &str,
        owner: &str,
        allowed: &[&str],
        given: impl IntoIterator<Item = (&'k str, Range<usize>, String)>,
    ) -> Result<(), SceneError> {
        for (key, span, value) in given {
            if !allowed.contains(&key) {
                let takes = if allowed.is_empty() {
                    "it takes none".to_string()
                } else {
                    format!("it takes: {}", allowed.join(", "))
                };
                return Err(self.invalid(
                    span,
                    format!("{section}.{key}"),
                    value,
                    format!("is not a parameter of {owner} ({takes})"),
                ));
            }
        }
        Ok(())
    }

    pub(crate) fn forbid<T: Shown>(
        &self,
        v: &Option<Spanned<T>>,
        field: &str,
        why: &str,
    ) -> Result<(), SceneError> {
        match v {
            Some(s) => Err(self.invalid(s.span(), field, s.get_ref().shown(), why.to_string())),
            None => Ok(()),
        }
    }
}

/// A value as a message about a key that does not belong shows it: a number
/// as written in Rust (`3.0`), a name quoted as in the file (`"lundberg"`),
/// a list or a table as nothing (the message names its key).
pub(crate) trait Shown {
    /// The value, printed.
    fn shown(&self) -> String;
}

impl Shown for elcon_design::LogEnd {
    fn shown(&self) -> String {
        format!("\"{}\"", self.name())
    }
}

impl Shown for f64 {
    fn shown(&self) -> String {
        format!("{self:?}")
    }
}

impl Shown for i64 {
    fn shown(&self) -> String {
        self.to_string()
    }
}

impl Shown for String {
    fn shown(&self) -> String {
        format!("{self:?}")
    }
}

impl<T> Shown for Vec<T> {
    fn shown(&self) -> String {
        String::new()
    }
}

/// Defines an enum of the names a string key takes: deserialized from the
/// name (an unknown one is serde's "unknown variant `x`, expected one of
/// ..." error, located and given its key by [`parse`]), with `name()`,
/// `Display` as the name, and [`Shown`] as the quoted name.
macro_rules! keywords {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident {
            $($(#[$vmeta:meta])* $variant:ident = $text:literal,)+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
        $vis enum $name {
            $($(#[$vmeta])* #[serde(rename = $text)] $variant,)+
        }

        impl $name {
            /// The name a scene gives it.
            $vis fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)+
                }
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl $crate::ctx::Shown for $name {
            fn shown(&self) -> String {
                format!("\"{}\"", self.name())
            }
        }
    };
}
pub(crate) use keywords;

/// A number as a message shows it: elcon-analysis's shortest round-trip
/// form (`-30000000`, `0.5`, `1e300`).
pub(crate) use elcon_analysis::Num;

/// A value as an `Invalid` message prints it: a number as [`Num`] shows
/// it (never a run of hundreds of digits), a count as it is, a text (a
/// quoted name, "(missing)") as it is.
pub(crate) trait Printed {
    /// The value, printed.
    fn printed(&self) -> String;
}

impl Printed for f64 {
    fn printed(&self) -> String {
        Num(*self).to_string()
    }
}

impl Printed for Num {
    fn printed(&self) -> String {
        self.to_string()
    }
}

/// Counts and texts print as they are.
macro_rules! printed_as_displayed {
    ($($t:ty),+) => {
        $(impl Printed for $t {
            fn printed(&self) -> String {
                self.to_string()
            }
        })+
    };
}
printed_as_displayed!(i64, u64, usize, u32, str, String);

/// A TOML value as the file holds it, a number as [`Num`] shows it.
impl Printed for toml::Value {
    fn printed(&self) -> String {
        match self {
            toml::Value::Float(x) => Num(*x).to_string(),
            other => other.to_string(),
        }
    }
}

impl<T: Printed + ?Sized> Printed for &T {
    fn printed(&self) -> String {
        (**self).printed()
    }
}

pub(crate) use elcon_num::rounded;

/// `v >= 0` to four significant digits, never above it: a bound a message
/// hands back ("at most ...") that passes when given back. Rounding to
/// the nearest moves a value by at most half a unit of its fourth digit,
/// 5e-4 of it, so rounding `v (1 - 5e-4)` stays below `v`.
pub(crate) fn at_most(v: f64) -> Num {
    rounded(v * (1.0 - 5e-4))
}

/// Parses TOML text into `T`, turning a parser error into a located
/// [`SceneError::Syntax`].
pub(crate) fn parse<T: serde::de::DeserializeOwned>(
    file: &Path,
    text: &str,
) -> Result<T, SceneError> {
    toml::from_str(text).map_err(|e| {
        let offset = e.span().map_or(0, |s| s.start);
        let message = e.message().trim();
        // The parser names the types, not the key (a value of the wrong
        // type, an unknown variant, a duplicate key, an integer beyond
        // range, nesting too deep): the key is read from the text at the
        // place it points to, when that line assigns one.
        let message = message
            .replace("expected f64", "expected a number")
            .replace("expected i64", "expected a whole number");
        let message = match message.as_str() {
            "duplicate key" => "duplicate key: each key may be given once in its table".to_string(),
            m if m.contains("recursion") => format!(
                "{m}: arrays or tables nested too deep (a scene's tables and arrays nest a few \
                 levels at most)"
            ),
            m if m.contains(" as i128") => match m.split('`').nth(1) {
                Some(digits) => format!(
                    "the integer {digits} is out of range: a whole number here must be \
                     within +-9.2e18"
                ),
                None => "an integer out of range: a whole number here must be within \
                         +-9.2e18"
                    .to_string(),
            },
            _ => message,
        };
        // An array of tables `[[name]]` where a table belongs fails inside
        // it, in the terms of a sequence (or of an enum read from one).
        let structural = [
            "wanted exactly",
            "sequence",
            "unknown variant",
            "invalid length",
        ]
        .iter()
        .any(|m| message.contains(m));
        let message = match (key_at(text, offset), header_at(text, offset)) {
            (_, Some(header)) if header.array && structural => header.explain(&message),
            (Some(key), _) => format!("`{key}`: {message}"),
            (None, Some(header)) if header.here => header.explain(&message),
            (None, _) => message,
        };
        SceneError::Syntax {
            file: file.to_path_buf(),
            at: Location::of(text, offset),
            message,
        }
    })
}

/// A table header of a TOML text: `[name]`, or `[[name]]` for an element
/// of an array of tables.
#[derive(Debug, PartialEq)]
pub(crate) struct Header {
    /// The dotted name between the brackets.
    name: String,
    /// Whether it is written `[[name]]`.
    array: bool,
    /// Whether it is on the line asked about (else above it).
    here: bool,
}

impl Header {
    /// The parser's message about the header, said in TOML terms: which
    /// key, what it must be, and how it is written.
    fn explain(&self, message: &str) -> String {
        let name = &self.name;
        if message.starts_with("duplicate key") {
            return format!(
                "`{name}`: the table `[{name}]` is given twice: give each table once and put \
                 all its keys under that one header"
            );
        }
        if self.array {
            return format!(
                "`{name}` must be a table `[{name}]`, not an array of tables `[[{name}]]`"
            );
        }
        match message.strip_prefix("invalid type: map, expected ") {
            Some("a sequence") => {
                format!("`{name}` must be an array of tables `[[{name}]]`, not a table `[{name}]`")
            }
            Some(wanted) => {
                let last = name.rsplit('.').next().unwrap_or(name);
                format!(
                    "`{name}` must be {wanted} (`{last} = ...` under its table), not a table \
                     `[{name}]`"
                )
            }
            None => format!("`{name}`: {message}"),
        }
    }
}

/// The byte range `(start, end)` of the line holding byte `offset` of
/// `text` (clamped to its end), its newline excluded; `None` inside a
/// character.
fn line_around(text: &str, offset: usize) -> Option<(usize, usize)> {
    let offset = offset.min(text.len());
    if !text.is_char_boundary(offset) {
        return None;
    }
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
    Some((start, end))
}

/// The table header of byte `offset` of a TOML text: the one on its line,
/// else the last one above it (`[name]` or `[[name]]`, comments aside).
pub(crate) fn header_at(text: &str, offset: usize) -> Option<Header> {
    let (start, end) = line_around(text, offset)?;
    let (back, line) = text[..end]
        .lines()
        .rev()
        .map(|l| l.split('#').next().unwrap_or_default().trim())
        .enumerate()
        .find(|(_, l)| l.starts_with('['))?;
    let here = back == 0 && start < end;
    let (inner, array) = match line.strip_prefix("[[") {
        Some(rest) => (rest.strip_suffix("]]")?, true),
        None => (line.strip_prefix('[')?.strip_suffix(']')?, false),
    };
    let name: Vec<&str> = inner
        .split('.')
        .map(|p| p.trim().trim_matches('"'))
        .collect();
    Some(Header {
        name: name.join("."),
        array,
        here,
    })
}

/// The dotted key of the value at byte `offset` of a TOML text: the
/// section of the last `[header]` above it, the key of its line, and, in an
/// inline table or an array of them, the key before the value (`None` when
/// the line has no `key =`).
pub(crate) fn key_at(text: &str, offset: usize) -> Option<String> {
    let offset = offset.min(text.len());
    let (start, end) = line_around(text, offset)?;
    let line = &text[start..end];
    let section = text[..start]
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('['))
        .map(|l| l.trim_matches(|c| c == '[' || c == ']').trim().to_string());
    let (outer, _) = line.split_once('=')?;
    let outer = outer.trim().trim_matches('"');
    let before = &line[..offset - start];
    let inner = before
        .rfind('{')
        .map(|brace| &before[brace + 1..])
        .and_then(|inside| {
            let assignment = inside.rsplit(',').next()?;
            let (key, _) = assignment.split_once('=')?;
            Some(key.trim().trim_matches('"').to_string())
        });
    let mut key: Vec<String> = section.into_iter().collect();
    key.push(outer.to_string());
    key.extend(inner);
    Some(key.join("."))
}
