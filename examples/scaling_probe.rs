//! How each method's solve compares with one faer Cholesky of the same
//! influence matrix S, the floor any exact dense method pays, measured in
//! the same process.
//!
//! The problem: Hertz spheres on Love patches, about `--n` candidate points
//! (elcon-fixtures' `benchmark`), solved in full. For each method it prints the best of
//! `--repeat` solves (default 3; `--method NAME` for one method), pivots (index exchanges for block
//! pivoting), block iterations, time per pivot and the certificate; then the
//! Cholesky of S, best of the same number, with faer's default parallelism
//! (all cores) and sequential. Its last line is
//! `n=<N> fastest=<method> solve_s=<s> cholesky_s=<s> ratio=<solve/cholesky>`,
//! against the faster of the two Cholesky timings.
//!
//! Run: `cargo run --release --example scaling_probe -- --n 2000`

use std::time::Instant;

use elcon::analysis::{Method, Options};
use elcon_fixtures::benchmark;
use faer::Side;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{
    LltRegularization, cholesky_in_place, cholesky_in_place_scratch,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut n, mut repeat) = (2000usize, 3usize);
    let mut methods: Vec<Method> = Method::ALL.to_vec();
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--n" => n = value.parse()?,
            "--repeat" => repeat = value.parse::<usize>()?.max(1),
            "--method" => {
                methods = vec![
                    value
                        .parse::<Method>()
                        .map_err(|_| format!("unknown method {value}"))?,
                ]
            }
            other => return Err(format!("unknown option {other} (--n, --repeat, --method)").into()),
        }
    }
    let t = Instant::now();
    let problem = benchmark::problem(n);
    let assembly = t.elapsed().as_secs_f64();
    let size = problem.points().len();
    println!(
        "Hertz spheres on Love patches, N = {size} points (asked {n}), full problem; assembly of S {assembly:.4} s"
    );
    let mut fastest: Option<(Method, f64)> = None;
    for &method in &methods {
        let mut best = f64::INFINITY;
        let mut last = None;
        for _ in 0..repeat {
            let sol = problem.solve(method, &Options::default())?;
            best = best.min(sol.solve_seconds);
            last = Some(sol);
        }
        let sol = last.expect("at least one solve");
        let st = &sol.statistics;
        println!(
            "{:<20} solve {:>9.4} s  pivots {:>6}  iterations {:>3}  {:>8.2} us/pivot  contact {:>6}  certificate {:.1e}",
            method.name(),
            best,
            st.pivots(),
            st.iterations(),
            1e6 * best / st.pivots().max(1) as f64,
            sol.contact.len(),
            sol.certificate.worst()
        );
        if fastest.is_none_or(|(_, t)| best < t) {
            fastest = Some((method, best));
        }
    }
    let s = problem
        .entries("the scaling probe")
        .expect("dense")
        .to_owned();
    let mut par = f64::INFINITY;
    let mut seq = f64::INFINITY;
    for _ in 0..repeat {
        let t = Instant::now();
        let llt = s.llt(Side::Lower).map_err(|e| format!("{e:?}"))?;
        par = par.min(t.elapsed().as_secs_f64());
        drop(llt);
        let mut a = s.clone();
        let mut mem = MemBuffer::new(cholesky_in_place_scratch::<f64>(
            size,
            faer::Par::Seq,
            Default::default(),
        ));
        let t = Instant::now();
        cholesky_in_place(
            a.as_mut(),
            LltRegularization {
                dynamic_regularization_delta: 0.0,
                dynamic_regularization_epsilon: 0.0,
            },
            faer::Par::Seq,
            MemStack::new(&mut mem),
            Default::default(),
        )
        .map_err(|e| format!("{e:?}"))?;
        seq = seq.min(t.elapsed().as_secs_f64());
    }
    println!("faer Cholesky of S   all cores {par:.4} s, sequential {seq:.4} s");
    let cholesky = par.min(seq);
    let (method, solve) = fastest.expect("a method ran");
    println!(
        "n={size} fastest={} solve_s={solve:.4} cholesky_s={cholesky:.4} ratio={:.2}",
        method.name(),
        solve / cholesky
    );
    Ok(())
}
