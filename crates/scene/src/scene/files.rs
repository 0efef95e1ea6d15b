//! Surfaces and separations from files named in `[geometry]`, read
//! relative to the scene file, in the scene's units:
//!
//! - `height_map = { file, spacing = [dx, dy], origin = [x0, y0],
//!   interpolation = "linear" }`: a height map on a regular grid, `.npy`
//!   (a 2-D array of float64 or float32, either byte order, C or Fortran
//!   order, its header read as numpy reads it, `Z[j, i]` at
//!   `(x0 + i dx, y0 + j dy)`) or CSV (one grid row along x per line, rows
//!   in increasing y), interpolated to the candidate points bilinearly or
//!   by the natural bicubic spline (`elcon_analysis::HeightMap`,
//!   `elcon_analysis::Interpolation`) and added to the surfaces' heights;
//!   `origin` defaults to the map centred on the first point of contact;
//! - `profile = { file, axis = "y", interpolation = "linear" }`: an axial
//!   profile, CSV rows `position, drop` (a roller's crown along y, a
//!   beam's along x), interpolated linearly or by the natural cubic spline
//!   (`elcon_analysis::AxialProfile`);
//! - `separation_file = "eps.csv"`: CSV rows `x, y, separation` (or
//!   `x, separation` on a line), each candidate point taking the row at its
//!   position (within `MATCH_TOLERANCE` of the grid's spacing).
//!
//! CSV: UTF-8 (a byte-order mark ignored), values separated by commas or
//! blanks; blank lines and lines starting with `#` (comments, a header)
//! skipped; any other line that is not numbers refused, naming its number
//! and quoting its first [`QUOTED_CHARS`] characters. The tables' own checks (a NaN, a hole, a wrong shape, a table
//! that does not cover the points) are elcon-analysis's, their messages
//! naming the file and the row.

use std::path::PathBuf;
use std::sync::Arc;

use elcon_analysis::{AxialProfile, Departure, Geometry, HeightMap, Interpolation, ProfileAxis};
use elcon_influence::PointSet;
use toml::Spanned;

use super::npy;
use crate::ctx::{Ctx, Num};
use crate::error::SceneError;
use crate::inputs::{DataInput, outside_confinement};
use crate::schema::{GeometryToml, HeightMapToml, ProfileToml};

/// How far from a candidate point, in the grid's spacings, a row of a
/// separation file still matches it (the rounding of coordinates written
/// to a file and read back).
const MATCH_TOLERANCE: f64 = 1e-6;

/// The most bytes a data file (height map, profile, separations) may hold:
/// a height map of 5792 x 5792 doubles. Read once, no further: a device
/// or a runaway file is refused instead of filling the memory.
pub const MAX_DATA_BYTES: u64 = 256 << 20;

/// A data file named in `[geometry]`, as its refusals name it: its key
/// (`geometry.height_map.file`), where and how the scene names it, and its
/// path, relative to the scene file's directory.
struct DataFile<'c, 'a> {
    ctx: &'c Ctx<'a>,
    field: &'static str,
    name: &'c Spanned<String>,
    path: PathBuf,
}

impl<'c, 'a> DataFile<'c, 'a> {
    /// The file `name` under `field`.
    fn new(ctx: &'c Ctx<'a>, field: &'static str, name: &'c Spanned<String>) -> Self {
        let path = ctx.dir().join(name.get_ref());
        Self {
            ctx,
            field,
            name,
            path,
        }
    }

    /// The file refused for `reason`, as it is (the tables of
    /// elcon-analysis name the file themselves).
    fn invalid(&self, reason: impl Into<String>) -> SceneError {
        let name = format!("{:?}", self.name.get_ref());
        self.ctx.invalid(self.name.span(), self.field, name, reason)
    }

    /// The file refused for `reason`, after its path.
    fn refuse(&self, reason: impl std::fmt::Display) -> SceneError {
        self.invalid(format!("{}: {reason}", self.path.display()))
    }

    /// The file refused for its size.
    fn too_large(&self) -> SceneError {
        self.refuse(format!(
            "is larger than {} MiB, the largest data file elcon reads",
            MAX_DATA_BYTES >> 20
        ))
    }

    /// Its path, as the tables it becomes name it.
    fn label(&self) -> String {
        self.path.display().to_string()
    }

    /// Its bytes, at most [`MAX_DATA_BYTES`], from a regular file only.
    fn bytes(&self) -> Result<Vec<u8>, SceneError> {
        use std::io::Read;
        let unreadable = |e: std::io::Error| self.refuse(format!("cannot be read: {e}"));
        if let Some(why) = outside_confinement(&self.path) {
            return Err(self.refuse(why));
        }
        // A pipe would block the read until its writer came (deaf to an
        // interrupt), a device would stream: only regular files are read.
        let meta = std::fs::metadata(&self.path).map_err(unreadable)?;
        if !meta.is_file() {
            return Err(self.refuse(
                "is not a regular file (a pipe, a device or a directory): give a file on disk",
            ));
        }
        if meta.len() > MAX_DATA_BYTES {
            return Err(self.too_large());
        }
        let file = std::fs::File::open(&self.path).map_err(unreadable)?;
        let mut bytes = Vec::new();
        file.take(MAX_DATA_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(unreadable)?;
        if bytes.len() as u64 > MAX_DATA_BYTES {
            return Err(self.too_large());
        }
        (self.ctx.inputs.borrow_mut()).push(DataInput::of(self.field, &self.path, &bytes));
        Ok(bytes)
    }

    /// Its numbers as CSV, a row per line (see the module documentation),
    /// each with its line number (from 1). A byte-order mark is no part of
    /// the text; a line that is not numbers is refused, quoted by at most
    /// [`QUOTED_CHARS`] characters.
    fn csv_rows(&self) -> Result<Vec<(usize, Vec<f64>)>, SceneError> {
        let bytes = self.bytes()?;
        if bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]) {
            return Err(self.refuse("is UTF-16 text; save it as UTF-8 (or ASCII)"));
        }
        let text = String::from_utf8(bytes)
            .map_err(|_| self.refuse("cannot be read: it is not text (UTF-8)"))?;
        let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
        let mut rows = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let values: Result<Vec<f64>, _> = line
                .split(|c: char| c == ',' || c.is_whitespace())
                .filter(|f| !f.is_empty())
                .map(str::parse::<f64>)
                .collect();
            match values {
                Ok(v) => rows.push((i + 1, v)),
                Err(_) => {
                    let header = if rows.is_empty() {
                        " (a header line starts with #)"
                    } else {
                        ""
                    };
                    return Err(self.refuse(format!(
                        "line {} is not numbers: {}{header}",
                        i + 1,
                        quoted(line)
                    )));
                }
            }
        }
        if rows.is_empty() {
            return Err(self.refuse("has no rows of numbers"));
        }
        Ok(rows)
    }

    /// Its 2-D `.npy` array of float64 or float32, either byte order, C
    /// or Fortran order: its values row by row (C order) and its shape
    /// `(rows, columns)`.
    fn npy(&self) -> Result<(Vec<f64>, usize, usize), SceneError> {
        let bytes = self.bytes()?;
        if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
            return Err(self.refuse("is not a .npy file (no \\x93NUMPY magic)"));
        }
        let (header_len, start) = match bytes[6] {
            1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
            2 | 3 if bytes.len() >= 12 => (
                u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
                12,
            ),
            v => return Err(self.refuse(format!("has .npy format version {v}, not 1, 2 or 3"))),
        };
        let header = bytes
            .get(start..start + header_len)
            .and_then(|h| std::str::from_utf8(h).ok())
            .ok_or_else(|| self.refuse("has a truncated .npy header"))?;
        let header = npy::parse_header(header)
            .map_err(|e| self.refuse(format!("has a .npy header numpy would not write: {e}")))?;
        let (width, big) = match header.descr.as_str() {
            "<f8" => (8, false),
            ">f8" => (8, true),
            "<f4" => (4, false),
            ">f4" => (4, true),
            other => {
                let shown: String = other.chars().take(12).collect();
                return Err(self.refuse(format!(
                    "holds values of type {shown:?}, not float64 or float32 ('<f8', '<f4')"
                )));
            }
        };
        let [ny, nx] = header.shape[..] else {
            return Err(self.refuse(format!(
                "holds a {}-D array, not a 2-D one",
                header.shape.len()
            )));
        };
        let data = &bytes[start + header_len..];
        let n = nx
            .checked_mul(ny)
            .ok_or_else(|| self.refuse("has a shape too large"))?;
        if data.len() as u128 != n as u128 * width as u128 {
            return Err(self.refuse(format!(
                "holds {} bytes after its header where its shape ({ny}, {nx}) of {width}-byte \
                 values needs {}",
                data.len(),
                n as u128 * width as u128
            )));
        }
        let value = |c: &[u8]| match (width, big) {
            (8, false) => f64::from_le_bytes(c.try_into().unwrap_or([0; 8])),
            (8, true) => f64::from_be_bytes(c.try_into().unwrap_or([0; 8])),
            (_, false) => f32::from_le_bytes(c.try_into().unwrap_or([0; 4])) as f64,
            (_, true) => f32::from_be_bytes(c.try_into().unwrap_or([0; 4])) as f64,
        };
        let stored: Vec<f64> = data.chunks_exact(width).map(value).collect();
        let values = if header.fortran_order {
            // Column by column: Z[j, i] is the (i ny + j)-th value.
            (0..n).map(|k| stored[(k % nx) * ny + k / nx]).collect()
        } else {
            stored
        };
        Ok((values, ny, nx))
    }
}

/// The most characters of a data file's line that a refusal quotes: enough
/// to find the line, too few to pass a file's contents on.
const QUOTED_CHARS: usize = 40;

/// `line` quoted, its first [`QUOTED_CHARS`] characters and `...` when it
/// is longer.
fn quoted(line: &str) -> String {
    match line.char_indices().nth(QUOTED_CHARS) {
        Some((end, _)) => format!("{:?}...", &line[..end]),
        None => format!("{line:?}"),
    }
}

/// Two finite numbers under `key` (`spacing`, `origin`).
fn pair(ctx: &Ctx<'_>, v: &Spanned<Vec<f64>>, field: &str) -> Result<(f64, f64), SceneError> {
    match v.get_ref()[..] {
        [a, b] if a.is_finite() && b.is_finite() => Ok((a, b)),
        _ => Err(ctx.invalid(
            v.span(),
            field,
            format!("{:?}", v.get_ref()),
            "must be two finite numbers [along x, along y]",
        )),
    }
}

/// A table's `interpolation`, linear when left out.
fn interpolation(given: &Option<Spanned<Interpolation>>) -> Interpolation {
    given
        .as_ref()
        .map_or(Interpolation::Linear, |i| *i.get_ref())
}

/// `geometry.height_map`: the map read and checked.
pub(super) fn height_map(
    ctx: &Ctx<'_>,
    t: &Spanned<HeightMapToml>,
) -> Result<Departure, SceneError> {
    let t = t.get_ref();
    let file = DataFile::new(ctx, "geometry.height_map.file", &t.file);
    let (values, ny, nx) = if t.file.get_ref().ends_with(".npy") {
        file.npy()?
    } else {
        let rows = file.csv_rows()?;
        let nx = rows[0].1.len();
        if let Some((line, r)) = rows.iter().find(|(_, r)| r.len() != nx) {
            return Err(file.refuse(format!(
                "line {line} has {} values, the first row {nx}: a height map's rows are all \
                 as long",
                r.len()
            )));
        }
        let ny = rows.len();
        (rows.into_iter().flat_map(|(_, r)| r).collect(), ny, nx)
    };
    let spacing = pair(ctx, &t.spacing, "geometry.height_map.spacing")?;
    if !(spacing.0 > 0.0 && spacing.1 > 0.0) {
        return Err(ctx.invalid(
            t.spacing.span(),
            "geometry.height_map.spacing",
            format!("{:?}", t.spacing.get_ref()),
            "both spacings [along x, along y] must be > 0 (the distance between the map's \
             columns and between its rows)",
        ));
    }
    let origin = match &t.origin {
        Some(o) => pair(ctx, o, "geometry.height_map.origin")?,
        None => (
            -0.5 * nx.saturating_sub(1) as f64 * spacing.0,
            -0.5 * ny.saturating_sub(1) as f64 * spacing.1,
        ),
    };
    let map = HeightMap::new(file.label(), values, nx, ny, spacing, origin)
        .and_then(|m| m.with_interpolation(interpolation(&t.interpolation)))
        .map_err(|e| file.invalid(e.to_string()))?;
    Ok(Departure::HeightMap(Arc::new(map)))
}

/// `geometry.profile`: the profile read and checked.
pub(super) fn profile(ctx: &Ctx<'_>, t: &Spanned<ProfileToml>) -> Result<Departure, SceneError> {
    let t = t.get_ref();
    let axis = match t.axis.as_ref().map(|a| (a, a.get_ref().as_str())) {
        None | Some((_, "y")) => ProfileAxis::Y,
        Some((_, "x")) => ProfileAxis::X,
        Some((a, other)) => {
            return Err(ctx.invalid(
                a.span(),
                "geometry.profile.axis",
                format!("{other:?}"),
                "must be \"x\" or \"y\" (the axis the profile runs along)",
            ));
        }
    };
    let file = DataFile::new(ctx, "geometry.profile.file", &t.file);
    let rows = file.csv_rows()?;
    if let Some((line, r)) = rows.iter().find(|(_, r)| r.len() != 2) {
        return Err(file.refuse(format!(
            "line {line} has {} values: a profile's rows are (position, drop)",
            r.len()
        )));
    }
    let (positions, drops) = rows.iter().map(|(_, r)| (r[0], r[1])).unzip();
    let p = AxialProfile::new(file.label(), axis, positions, drops)
        .and_then(|p| p.with_interpolation(interpolation(&t.interpolation)))
        .map_err(|e| file.invalid(e.to_string()))?;
    Ok(Departure::Profile(Arc::new(p)))
}

/// A table of `(position, drop)` rows read from the CSV file `name` under
/// `field` (a bearing's roller crown): two numbers a row.
pub(crate) fn drop_rows(
    ctx: &Ctx<'_>,
    field: &'static str,
    name: &Spanned<String>,
) -> Result<Vec<(f64, f64)>, SceneError> {
    let file = DataFile::new(ctx, field, name);
    let rows = file.csv_rows()?;
    if let Some((line, r)) = rows.iter().find(|(_, r)| r.len() != 2) {
        return Err(file.refuse(format!(
            "line {line} has {} values: a crown's rows are (position, drop)",
            r.len()
        )));
    }
    Ok(rows.iter().map(|(_, r)| (r[0], r[1])).collect())
}

/// The geometry on the laid-out `points`: a `separation_file`'s rows
/// matched to them, or tables checked to cover them (said at validation,
/// not at the run); any other geometry as it is.
pub(super) fn on_points(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: Geometry,
    points: &PointSet,
) -> Result<Geometry, SceneError> {
    let Some(g) = raw else {
        return Ok(geometry);
    };
    if let Some(file) = &g.get_ref().separation_file {
        return Ok(Geometry::Separation(separations(ctx, file, points)?));
    }
    if let Geometry::Tabulated { .. } = &geometry {
        separations_on(ctx, raw, &geometry, points)?;
    }
    Ok(geometry)
}

/// The separations of `geometry` at `points`
/// (`elcon_analysis::separations`); a failure (a table that does not cover
/// them) refused at the data file they are read from ([`data_file`]), or
/// at `[geometry]`.
pub(super) fn separations_on(
    ctx: &Ctx<'_>,
    raw: Option<&Spanned<GeometryToml>>,
    geometry: &Geometry,
    points: &PointSet,
) -> Result<Vec<f64>, SceneError> {
    elcon_analysis::separations(points, geometry).map_err(|e| match raw {
        Some(g) => {
            let (field, span, value) = data_file(g);
            ctx.invalid(span, field, value, e.to_string())
        }
        None => ctx.invalid(0..0, "geometry", "", e.to_string()),
    })
}

/// The data file a geometry's separations are read from, as a refusal
/// names it: its key (`geometry.height_map.file`, `geometry.profile.file`,
/// `geometry.separation_file`), where it is written and its name; the
/// `geometry` table when it reads none.
fn data_file(g: &Spanned<GeometryToml>) -> (&'static str, std::ops::Range<usize>, String) {
    let t = g.get_ref();
    let named = |f: &Spanned<String>| (f.span(), format!("{:?}", f.get_ref()));
    let (field, (span, value)) = if let Some(m) = &t.height_map {
        ("geometry.height_map.file", named(&m.get_ref().file))
    } else if let Some(p) = &t.profile {
        ("geometry.profile.file", named(&p.get_ref().file))
    } else if let Some(f) = &t.separation_file {
        ("geometry.separation_file", named(f))
    } else {
        ("geometry", (g.span(), String::new()))
    };
    (field, span, value)
}

/// `geometry.separation_file`: a separation for each candidate point, the
/// file's row at its position.
fn separations(
    ctx: &Ctx<'_>,
    file: &Spanned<String>,
    points: &PointSet,
) -> Result<Vec<f64>, SceneError> {
    let file = DataFile::new(ctx, "geometry.separation_file", file);
    let rows = file.csv_rows()?;
    let line = points.dimension() == elcon_influence::Dimension::Line;
    let width = if line { 2 } else { 3 };
    let mut table = Vec::with_capacity(rows.len());
    for (n, r) in &rows {
        if r.len() != width || r.iter().any(|v| !v.is_finite()) {
            let what = if r.len() != width {
                format!("has {} values", r.len())
            } else {
                "has a value that is not finite".to_string()
            };
            return Err(file.refuse(format!(
                "line {n} {what}: a row of a separation file is {width} finite numbers ({})",
                if line {
                    "x, separation"
                } else {
                    "x, y, separation"
                }
            )));
        }
        let (x, y) = if line { (r[0], 0.0) } else { (r[0], r[1]) };
        table.push((x, y, r[width - 1]));
    }
    // Rows keyed by their position in half spacings (cell centres fall on
    // odd multiples, lattice points on even ones: both round stably).
    let cell = points.cell();
    let key = |x: f64, y: f64| {
        (
            (2.0 * x / cell.dx).round() as i64,
            (2.0 * y / cell.dy).round() as i64,
        )
    };
    // Each key's first row, and the first later row that gives it another
    // separation (refused when a candidate point falls there).
    let mut index = std::collections::HashMap::with_capacity(table.len());
    for (i, &(x, y, e)) in table.iter().enumerate() {
        let entry = index.entry(key(x, y)).or_insert((i, None));
        if entry.1.is_none() && table[entry.0].2 != e {
            entry.1 = Some(i);
        }
    }
    let (tx, ty) = (MATCH_TOLERANCE * cell.dx, MATCH_TOLERANCE * cell.dy);
    (0..points.len())
        .map(|k| {
            let (x, y) = (points.x(k), points.y(k));
            let found = index.get(&key(x, if line { 0.0 } else { y }));
            if let Some(&(first, Some(other))) = found {
                return Err(file.refuse(format!(
                    "lines {} and {} both give candidate point {k} ({}, {}), with separations \
                     {} and {}; give one row for each point",
                    rows[first].0,
                    rows[other].0,
                    Num(x),
                    Num(y),
                    Num(table[first].2),
                    Num(table[other].2)
                )));
            }
            found
                .map(|&(i, _)| table[i])
                .filter(|(a, b, _)| (a - x).abs() <= tx && (line || (b - y).abs() <= ty))
                .map(|r| r.2)
                .ok_or_else(|| {
                    file.refuse(format!(
                        "has no row at candidate point {k} ({}, {}); give a row at every \
                         candidate point",
                        Num(x),
                        Num(y)
                    ))
                })
        })
        .collect()
}
