//! The stability table of docs/stability.md: every case of the stability
//! suite (elcon-fixtures' `stability_cases`) at the report's sizes (41
//! points across the Hertz cases, N up to 4096), by every method: N, a
//! 1-norm condition estimate of S (Hager-Higham), pivots, refactorizations,
//! the route (each attempt's tableau, with its method where the strategy
//! moved to another, and why: fallback, retry), the certificate's worst
//! relative residual, the error against the closed form, and pass or the
//! error returned. "pass" means the certificate holds at 1e-12 and the
//! case's expectation (a truncation warning, a single point) is met.
//!
//! Run: `cargo run --release --example stability_report` (about 30 s on the
//! 2-core test machine, after the build)

use elcon::analysis::{Method, Options, Warning};
use elcon::lcp::{Reason, Statistics};
use elcon_fixtures::stability_cases::{Expect, catalogue, error};

fn main() {
    let cases = catalogue(41, &[256, 1024, 2048, 4096]);
    println!(
        "| family | case | N | cond_1(S) est. | method | pivots | refact. | route | certificate | error | result |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    let (mut passed, mut total) = (0, 0);
    for case in &cases {
        let n = case.problem.points().len();
        let cond = elcon::lcp::condition_estimate(
            case.problem
                .entries("the condition estimate")
                .expect("dense"),
        );
        for method in Method::ALL {
            total += 1;
            let row = |pivots: String,
                       refact: String,
                       route: String,
                       cert: String,
                       err: String,
                       result: String| {
                println!(
                    "| {} | {} | {n} | {cond:.2e} | {method} | {pivots} | {refact} | {route} | {cert} | {err} | {result} |",
                    case.family, case.name
                );
            };
            match case.problem.solve(method, &Options::default()) {
                Ok(sol) => {
                    let st = &sol.statistics;
                    let expectation = match case.expect {
                        Expect::Solved => true,
                        Expect::EdgeWarning => sol
                            .warnings
                            .iter()
                            .any(|w| matches!(w, Warning::ContactAtEdge { .. })),
                        Expect::OnePoint => sol.contact.len() == 1,
                    };
                    let ok =
                        sol.certificate.holds() && sol.certificate.worst() <= 1e-12 && expectation;
                    passed += usize::from(ok);
                    let note = match case.expect {
                        Expect::Solved => "",
                        Expect::EdgeWarning => " (warns: truncated)",
                        Expect::OnePoint => " (one point)",
                    };
                    row(
                        st.pivots().to_string(),
                        st.refactorizations().to_string(),
                        route(st),
                        format!("{:.1e}", sol.certificate.worst()),
                        error(case.reference, sol.approach, sol.load)
                            .map_or("-".into(), |e| format!("{e:+.2e}")),
                        if ok {
                            format!("pass{note}")
                        } else {
                            "FAIL".into()
                        },
                    );
                }
                Err(e) => row(
                    "-".into(),
                    "-".into(),
                    "-".into(),
                    "-".into(),
                    "-".into(),
                    format!("error: {e}"),
                ),
            }
        }
    }
    println!();
    println!("{passed} of {total} solves pass");
}

/// The attempts of a solve in order: the tableau (or "block"), prefixed by
/// the method where it is not the one asked for, suffixed by a reason other
/// than the route's own order.
fn route(st: &Statistics) -> String {
    st.attempts
        .iter()
        .map(|a| {
            let tableau = a.tableau.map_or("block", |t| t.name());
            let step = if a.method == st.method {
                tableau.to_string()
            } else {
                format!("{} {tableau}", a.method)
            };
            match a.reason {
                Reason::First | Reason::Fallback => step,
                reason => format!("{step} ({reason})"),
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}
