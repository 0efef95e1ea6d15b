//! result.json's account of the solve: how S was held ([`Holding`]), the
//! engine's statistics (the totals derived from its log of attempts, then
//! each attempt) and the certificate (the residuals from the original data,
//! the worst of them and whether it holds).

use elcon_analysis::{ContactCertificate, Storage};
use elcon_lcp::Statistics;
use serde::{Deserialize, Serialize};

/// How S was held, as result.json's `influence` says it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Holding {
    /// Every entry (dense or folded).
    Dense,
    /// By its products on a lattice (an FFT convolution).
    MatrixFree,
}

impl Holding {
    /// Every holding, in the order messages list them.
    pub const ALL: [Holding; 2] = [Holding::Dense, Holding::MatrixFree];

    /// Its name: "dense" or "matrix-free".
    pub const fn name(self) -> &'static str {
        match self {
            Holding::Dense => "dense",
            Holding::MatrixFree => "matrix-free",
        }
    }

    /// How `storage` holds S.
    pub fn of(storage: Storage) -> Self {
        match storage {
            Storage::Lattice => Holding::MatrixFree,
            _ => Holding::Dense,
        }
    }
}

elcon_num::named!(Holding, "holding");
elcon_num::named_serde!(Holding);

/// One attempt of the engine's log, as words and counts: its method,
/// tableau (none for the methods without one), why it was made, its pivots,
/// iterations and seconds, and how it ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AttemptJson {
    /// The method's name.
    pub method: String,
    /// The tableau's name, for a pivoting method on one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tableau: Option<String>,
    /// Why it was made: "first", "fallback", "relaxed-bounds", "retry".
    pub reason: String,
    /// Pivots.
    pub pivots: usize,
    /// Iterations.
    pub iterations: usize,
    /// Seconds.
    pub seconds: f64,
    /// How it ended: "returned", "rejected (certificate ...)",
    /// "breakdown: ...".
    pub outcome: String,
}

/// The engine's statistics: the totals over the attempts, and the log.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StatisticsJson {
    /// Pivots, every attempt's.
    pub pivots: usize,
    /// Pivots of step length zero.
    pub degenerate_pivots: usize,
    /// Refactorizations of a tableau from the data.
    pub refactorizations: usize,
    /// Steps of iterative refinement.
    pub refinement_steps: usize,
    /// Iterations (block pivoting's exchanges, the conjugate gradient's).
    pub iterations: usize,
    /// Dense factorizations.
    pub factorizations: usize,
    /// Whether the answer came from a symmetric tableau.
    pub symmetric_tableau: bool,
    /// Each attempt, in order.
    pub attempts: Vec<AttemptJson>,
}

impl StatisticsJson {
    /// The statistics of a solve.
    pub fn of(s: &Statistics) -> Self {
        Self {
            pivots: s.pivots(),
            degenerate_pivots: s.degenerate_pivots(),
            refactorizations: s.refactorizations(),
            refinement_steps: s.refinement_steps(),
            iterations: s.iterations(),
            factorizations: s.factorizations(),
            symmetric_tableau: s.symmetric_tableau(),
            attempts: s
                .attempts
                .iter()
                .map(|a| AttemptJson {
                    method: a.method.name().to_string(),
                    tableau: a.tableau.map(|t| t.name().to_string()),
                    reason: a.reason.to_string(),
                    pivots: a.work.pivots,
                    iterations: a.work.iterations,
                    seconds: a.seconds,
                    outcome: a.outcome.to_string(),
                })
                .collect(),
        }
    }
}

/// The certificate: residuals recomputed from the original data, the worst
/// of them against the tolerance, and whether it holds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CertificateJson {
    /// `|e^T F - P| / P` (or its counterpart under displacement control).
    pub equilibrium: f64,
    /// The most negative force, relative.
    pub min_force: f64,
    /// The most negative gap, relative.
    pub min_gap: f64,
    /// The largest `F_k Y_k`, relative.
    pub complementarity: f64,
    /// The worst of the four.
    pub worst: f64,
    /// The tolerance it is held to.
    pub tolerance: f64,
    /// Whether the worst is within the tolerance.
    pub holds: bool,
}

impl CertificateJson {
    /// The certificate of a solution.
    pub fn of(c: &ContactCertificate) -> Self {
        Self {
            equilibrium: c.equilibrium,
            min_force: c.min_force,
            min_gap: c.min_gap,
            complementarity: c.complementarity,
            worst: c.worst(),
            tolerance: c.tolerance,
            holds: c.holds(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_holding_reads_back_its_name() {
        for h in Holding::ALL {
            let json = serde_json::to_string(&h).unwrap();
            assert_eq!(serde_json::from_str::<Holding>(&json).unwrap(), h);
        }
        assert_eq!(Holding::of(Storage::Lattice).name(), "matrix-free");
        assert_eq!(Holding::of(Storage::Folded).name(), "dense");
        assert!(serde_json::from_str::<Holding>("\"sparse\"").is_err());
    }
}
