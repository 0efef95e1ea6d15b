//! How a contact problem holds its influence matrix `S = A(1) + A(2)`:
//! [`Storage`], resolved from [`Storage::Auto`] by
//! [`ProblemBuilder`](crate::ProblemBuilder) (the rule is in
//! `crate::contact::builder`), and what each storage offers by default.

use elcon_lcp::Method;

use crate::AnalysisError;

/// Above this many unknowns [`Storage::Auto`] holds S matrix-free where
/// the lattice operator applies (docs/performance.md, "Dense or
/// matrix-free": where the conjugate gradient on the lattice operator
/// overtakes block pivoting on the dense S).
pub const AUTO_DENSE_LIMIT: usize = 2000;

/// How a contact problem holds S.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Storage {
    /// Decided from the problem (the default; see the module documentation).
    #[default]
    Auto,
    /// Every entry of S.
    Dense,
    /// One unknown per orbit of a mirror-symmetric problem, the folded
    /// matrix assembled in place of S (never the full S); S dense when the
    /// problem is not symmetric. The solution is the same and is returned
    /// at every point.
    Folded,
    /// S by its products: a zero-padded FFT convolution of the lattice
    /// kernel (`elcon_influence::LatticeKernel`), O(N) memory, for grids
    /// too large to store S (10^4 to 10^6 points). Solved by the conjugate
    /// gradient; the points must be a lattice and no body a beam.
    Lattice,
}

impl Storage {
    /// Every storage, in the order messages list them.
    pub const ALL: [Storage; 4] = [
        Storage::Auto,
        Storage::Dense,
        Storage::Folded,
        Storage::Lattice,
    ];

    /// Its name: "auto", "dense", "folded", "lattice" (a scene's
    /// `solver.storage`); [`FromStr`](std::str::FromStr) reads it back.
    pub const fn name(self) -> &'static str {
        match self {
            Storage::Auto => "auto",
            Storage::Dense => "dense",
            Storage::Folded => "folded",
            Storage::Lattice => "lattice",
        }
    }

    /// The storage of an S given as a matrix (`ContactProblem::from_parts`):
    /// it is held as given, dense. `Auto` and `Dense` take it; the other
    /// storages make their own S from the bodies' models.
    ///
    /// # Errors
    /// [`AnalysisError::Incompatible`] naming `storage`.
    pub fn of_given_matrix(self) -> Result<Storage, AnalysisError> {
        match self {
            Storage::Auto | Storage::Dense => Ok(Storage::Dense),
            other => Err(AnalysisError::Incompatible {
                field: "storage",
                reason: format!(
                    "\"{other}\" cannot hold an S given as a matrix, which is held dense: give \
                     \"auto\" or \"dense\", or the bodies' models for the other storages"
                ),
            }),
        }
    }

    /// How S is held, in result.json's words: "dense" (every entry, or the
    /// folded matrix's) or "matrix-free".
    pub fn held_as(self) -> &'static str {
        match self {
            Storage::Lattice => "matrix-free",
            _ => "dense",
        }
    }

    /// The method a problem of this storage is solved by when the caller
    /// has no preference: the conjugate gradient matrix-free (the pivoting
    /// methods need S's entries), block principal pivoting otherwise.
    pub fn default_method(self) -> Method {
        match self {
            Storage::Lattice => Method::ConjugateGradient,
            _ => Method::BlockPivoting,
        }
    }

    /// Whether a problem of this storage holds S's entries (what the
    /// pivoting methods and the paper's design program read).
    pub fn holds_entries(self) -> bool {
        self != Storage::Lattice
    }
}

elcon_num::named!(Storage, "storage");
#[cfg(feature = "serde")]
elcon_num::named_serde!(Storage);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_storage_parses_its_name_and_an_unknown_one_lists_them() {
        assert_eq!(elcon_num::unparsed(&Storage::ALL), None);
        let e = "sparse".parse::<Storage>().unwrap_err();
        assert_eq!(e.allowed, Storage::NAMES);
        assert_eq!(
            e.to_string(),
            "unknown storage `sparse`, expected one of `auto`, `dense`, `folded`, `lattice`"
        );
    }

    #[cfg(feature = "serde")]
    #[test]
    fn a_storage_deserializes_from_its_name() {
        let read = elcon_num::from_name::<Storage>;
        assert_eq!(read("lattice").unwrap(), Storage::Lattice);
        let e = read("matrix-free").unwrap_err().to_string();
        assert!(e.starts_with("unknown variant `matrix-free`"), "{e}");
    }
}

#[cfg(test)]
mod given {
    use super::*;

    #[test]
    fn a_given_matrix_is_held_dense() {
        assert_eq!(Storage::Auto.of_given_matrix().unwrap(), Storage::Dense);
        assert_eq!(Storage::Dense.of_given_matrix().unwrap(), Storage::Dense);
        for other in [Storage::Folded, Storage::Lattice] {
            let e = other.of_given_matrix().unwrap_err().to_string();
            assert!(
                e.starts_with(&format!("`storage`: \"{other}\" cannot hold")),
                "{e}"
            );
        }
    }
}
