//! A designed profile sampled for the workshop: the positions at which
//! profile.csv gives its drop, from one end of the design grid's cells
//! along the axis to the other, evenly spaced.
//!
//! The stations of a design grid are its cells' centres along the axis;
//! the cells reach half a gap beyond the end stations (a roller's ends,
//! the end of a beam), and so do the samples:
//!
//! ```text
//!     s_0 = t_0 - (t_1 - t_0) / 2,     s_end = t_n + (t_n - t_(n-1)) / 2,
//!     s_i = s_0 + i h  (i < m),        s_m = s_end,      m = ceil((s_end - s_0) / h)
//! ```
//!
//! with `t` the stations and h the spacing: given, or by default
//! `(s_end - s_0) / (SAMPLES_PER_STATION n)`, ten samples to a station
//! (the stations' own spacing over ten on a uniform grid). Read linearly
//! between samples, a profile whose curvature is `y''` is off by at most
//! `h^2 |y''| / 8`: a hundredth of what the stations alone, read
//! linearly, are off by.

use crate::DesignError;

/// How many samples a design station has in a profile sampled at the
/// default spacing.
pub const SAMPLES_PER_STATION: usize = 10;

/// The most samples a profile is sampled at (a million rows of
/// profile.csv, about 40 MB).
pub const MAX_PROFILE_SAMPLES: usize = 1_000_000;

/// Where a profile is sampled (see the [module documentation](self)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sampling {
    /// The first sample: the lower edge of the first station's cell
    /// (length).
    pub start: f64,
    /// The last sample: the upper edge of the last station's cell
    /// (length).
    pub end: f64,
    /// The spacing h of the samples (length); the last interval, up to
    /// `end`, may be shorter.
    pub spacing: f64,
    /// The intervals between samples: one sample more.
    pub intervals: usize,
}

impl Sampling {
    /// The samples over the cells of `stations` (a design grid's, sorted,
    /// as [`axial_stations`](crate::axial_stations) gives them) at
    /// `spacing`, or by default [`SAMPLES_PER_STATION`] to a station.
    ///
    /// # Errors
    /// [`DesignError::InvalidInput`] naming `profile_spacing` for a spacing
    /// that is not finite and > 0, or so fine that the samples would exceed
    /// [`MAX_PROFILE_SAMPLES`]; [`DesignError::Incompatible`] for no
    /// station.
    pub fn new(stations: &[f64], spacing: Option<f64>) -> Result<Self, DesignError> {
        let (Some(&first), Some(&last)) = (stations.first(), stations.last()) else {
            return Err(DesignError::Incompatible {
                field: "cases",
                reason: "a profile is sampled over the design grid's stations, and it has none"
                    .into(),
            });
        };
        let n = stations.len();
        let (start, end) = if n < 2 {
            (first, last)
        } else {
            (
                first - 0.5 * (stations[1] - first),
                last + 0.5 * (last - stations[n - 2]),
            )
        };
        let extent = end - start;
        let spacing = match spacing {
            Some(h) => h,
            None if extent > 0.0 => extent / (SAMPLES_PER_STATION * n) as f64,
            None => 1.0,
        };
        elcon_num::check([(
            spacing.is_finite() && spacing > 0.0,
            "profile_spacing",
            spacing,
            "must be finite and > 0",
        )])?;
        let ratio = extent / spacing;
        // A spacing that divides the extent, to rounding, has no short
        // last interval.
        let whole = ratio.round();
        let intervals = if (ratio - whole).abs() <= 1e-9 * whole.max(1.0) {
            whole
        } else {
            ratio.ceil()
        };
        elcon_num::check([(
            intervals < MAX_PROFILE_SAMPLES as f64,
            "profile_spacing",
            spacing,
            "too fine: more than 1,000,000 samples over the design grid's extent along the axis",
        )])?;
        Ok(Self {
            start,
            end,
            spacing,
            intervals: intervals as usize,
        })
    }

    /// The positions of the samples, `start` to `end` (length), each
    /// rounded to a decimal of 1e-12 of the extent, so that a round
    /// spacing from a round start gives round positions (`-4.9875`, not
    /// `-4.987500000000001`).
    pub fn positions(&self) -> Vec<f64> {
        if self.intervals == 0 {
            return vec![self.start];
        }
        let extent = self.end - self.start;
        let decimals = (12.0 - extent.log10().floor()).clamp(0.0, 340.0) as usize;
        let rounded = |s: f64| {
            format!("{s:.decimals$}")
                .parse::<f64>()
                .ok()
                .filter(|r| r.is_finite())
                .unwrap_or(s)
        };
        (0..self.intervals)
            .map(|i| rounded(self.start + i as f64 * self.spacing))
            .chain(std::iter::once(self.end))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_span_the_cells_ten_to_a_station_by_default() {
        // 4 cells of 2.5 on [-5, 5]: stations at their centres.
        let stations = [-3.75, -1.25, 1.25, 3.75];
        let s = Sampling::new(&stations, None).unwrap();
        assert_eq!((s.start, s.end, s.intervals), (-5.0, 5.0, 40));
        let p = s.positions();
        assert_eq!(p.len(), 41);
        assert_eq!((p[0], p[40]), (-5.0, 5.0));
        assert_eq!(p[1], -4.75);
        // Round positions from a round spacing, not its rounding errors.
        let fine = Sampling::new(&stations, Some(0.0125)).unwrap().positions();
        assert_eq!(fine.len(), 801);
        for (i, s) in fine.iter().enumerate() {
            assert!(s.to_string().len() <= 7, "{i}: {s}");
        }
        // A spacing that does not divide the extent ends with a short step.
        let s = Sampling::new(&stations, Some(3.0)).unwrap();
        assert_eq!(s.positions(), vec![-5.0, -2.0, 1.0, 4.0, 5.0]);
        // One that does, to rounding, has none.
        let s = Sampling::new(&stations, Some(0.1)).unwrap();
        assert_eq!(s.intervals, 100);
        assert_eq!(s.positions().last(), Some(&5.0));
    }

    #[test]
    fn a_spacing_that_is_no_spacing_is_refused_by_name() {
        let stations = [-1.0, 1.0];
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-9] {
            let e = Sampling::new(&stations, Some(bad)).unwrap_err();
            assert!(e.to_string().starts_with("`profile_spacing` = "), "{e}");
        }
        assert!(Sampling::new(&[], None).is_err());
        // A single station is sampled once.
        let s = Sampling::new(&[2.0], None).unwrap();
        assert_eq!(s.positions(), vec![2.0]);
    }
}
