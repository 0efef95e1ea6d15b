//! Tests of `chunk` (the parent module).

use super::*;
use crate::methods::conjugate_gradient::passes::arches;

/// Five vectors of `len` entries, `z` about half positive, with a
/// tail past the last full group.
fn vectors(len: usize) -> Vec<Vec<f64>> {
    let h =
        |i: usize, k: usize| (i as f64 * 0.618_033_988_749_895 + k as f64 * 0.37).fract() - 0.45;
    (0..5)
        .map(|k| (0..len).map(|i| h(i, k)).collect())
        .collect()
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn measures_bits(m: &WLanes) -> Vec<u64> {
    [
        m.min_w,
        m.comp,
        m.w_scale,
        m.z_scale,
        m.g,
        m.chopped,
        m.nonfinite,
    ]
    .iter()
    .flat_map(|l| bits(l))
    .chain(bits(&[m.row.sum.value(), m.row.terms.value()]))
    .collect()
}

#[test]
fn the_measures_in_registers_are_the_measures_entry_by_entry() {
    let len = 8 * LANES + 5;
    let v = vectors(len);
    let slices = [&v[0][..], &v[1], &v[2], &v[3], &v[4]];
    let b: Vec<f64> = v[2].iter().map(|x| 1.0 + x).collect();
    for row in [None, Some(&b[..])] {
        let mut reference = WLanes::default();
        for i in 0..len {
            reference.add(i % LANES, slices.map(|v| v[i]));
            if let Some(b) = row {
                reference.row.add(i % LANES, b[i], v[0][i]);
            }
        }
        let expected = measures_bits(&reference);
        assert_eq!(
            measures_bits(&measure_chunk(slices, 1.0, row, None)),
            expected
        );
        for arch in arches() {
            let m = arch.dispatch(MeasureChunk {
                v: slices,
                scale: 1.0,
                row,
                residual: None,
            });
            assert_eq!(measures_bits(&m), expected, "{arch:?}");
        }
        // The residual, written in the same sweep, vector and scalar.
        let residual: Vec<f64> = (0..len)
            .map(|i| residual_at(slices.map(|v| v[i])))
            .collect();
        let mut vector = vec![9.0; len];
        let m = measure_chunk(slices, 1.0, row, Some(&mut vector));
        assert_eq!(
            (measures_bits(&m), bits(&vector)),
            (expected.clone(), bits(&residual))
        );
        for arch in arches() {
            let mut written = vec![9.0; len];
            arch.dispatch(MeasureChunk {
                v: slices,
                scale: 1.0,
                row,
                residual: Some(&mut written),
            });
            assert_eq!(bits(&written), bits(&residual), "{arch:?}");
        }
        // A pending scale multiplies `z` and `u` in registers.
        let (z, u): (Vec<f64>, Vec<f64>) = (0..len).map(|i| (v[0][i] / 1.5, v[1][i] / 1.5)).unzip();
        let pending = measure_chunk([&z, &u, &v[2], &v[3], &v[4]], 1.5, row, None);
        let stored: Vec<Vec<f64>> = [&z, &u]
            .iter()
            .map(|x| x.iter().map(|x| 1.5 * x).collect())
            .collect();
        let at_one = measure_chunk(
            [&stored[0], &stored[1], &v[2], &v[3], &v[4]],
            1.0,
            row,
            None,
        );
        assert_eq!(measures_bits(&pending), measures_bits(&at_one));
    }
    // A non-finite `w` in a full group or in the tail is seen.
    for at in [3, len - 1] {
        let mut u = v[1].clone();
        u[at] = f64::INFINITY;
        let m = measure_chunk([&v[0], &u, &v[2], &v[3], &v[4]], 1.0, None, None);
        assert!(m.nonfinite.iter().any(|x| x.is_nan()), "{at}");
    }
    let m = measure_chunk(slices, 1.0, None, None);
    assert!(m.nonfinite.iter().all(|&x| x == 0.0));
}

#[test]
fn directions_in_registers_are_directions_entry_by_entry() {
    let len = 8 * LANES + 5;
    let v = vectors(len);
    let (z, a, b, c, t0) = (&v[0], &v[1], &v[2], &v[3], &v[4]);
    let rules = [
        Rule::Conjugate {
            u: a,
            c: 1.25,
            q: b,
            s: c,
            beta: 0.7,
        },
        Rule::Chopped {
            u: a,
            c: 0.8,
            q: b,
            s: c,
        },
        Rule::Preconditioned {
            p: a,
            s: c,
            r: b,
            beta: 0.3,
        },
    ];
    for rule in rules {
        let (mut t, mut sum) = (t0.clone(), Lanes::default());
        for i in 0..len {
            let (next, term) = rule.at(i, z[i], t[i]);
            t[i] = next;
            sum.add(i % LANES, term);
        }
        let mut vector = t0.clone();
        let lanes = direction_chunk(rule, z, &mut vector);
        assert_eq!((bits(&vector), bits(&lanes.0)), (bits(&t), bits(&sum.0)));
        for arch in arches() {
            let mut written = t0.clone();
            let lanes = arch.dispatch(DirectionChunk {
                rule,
                z,
                t: &mut written,
            });
            let got = (bits(&written), bits(&lanes.0));
            assert_eq!(got, (bits(&t), bits(&sum.0)), "{arch:?}");
        }
    }
}

#[test]
fn steps_in_registers_are_steps_entry_by_entry() {
    let len = 8 * LANES + 5;
    let v = vectors(len);
    let (z0, u0) = (&v[0], &v[1]);
    // A shift that makes about half the points off `J` interfere.
    let shift = vec![0.3; len];
    for (tau, enter, c) in [(5.0, true, 1.0), (5.0, false, 1.25), (0.0, true, 0.8)] {
        let step = Step {
            c,
            t: &v[2],
            r: &v[3],
            q: &v[4],
            s: &shift,
            tau,
            enter,
        };
        let b: Vec<f64> = v[3].iter().map(|x| 1.0 + x).collect();
        let (mut z, mut u, mut counts) = (z0.clone(), u0.clone(), (0, 0));
        let (mut row, mut row_terms, mut bu) = (
            Compensated::default(),
            Lanes::default(),
            Compensated::default(),
        );
        for i in 0..len {
            let (next, ui, clip, entered) = step.at(i, z[i], u[i]);
            (z[i], u[i]) = (next, ui);
            counts.0 += usize::from(clip);
            counts.1 += usize::from(entered);
            row.add(i % LANES, b[i] * next);
            row_terms.add(i % LANES, (b[i] * next).abs());
            bu.add(i % LANES, (if next > 0.0 { b[i] } else { 0.0 }) * ui);
        }
        assert!(counts.0 > 0 || tau == 0.0);
        assert_eq!(counts.1 > 0, enter);
        let sums = bits(&[row.value(), row_terms.value(), bu.value()]);
        let stepped = |s: &Stepped| {
            let got = bits(&[s.row.sum.value(), s.row.terms.value(), s.bu.value()]);
            ((s.clipped, s.entered), got)
        };
        for row in [None, Some(&b[..])] {
            let (mut zv, mut uv) = (z0.clone(), u0.clone());
            let got = update_chunk(step, (&mut zv, &mut uv), row, true);
            assert_eq!((bits(&zv), bits(&uv)), (bits(&z), bits(&u)));
            assert_eq!(stepped(&got).0, counts);
            if row.is_some() {
                assert_eq!(stepped(&got).1, sums);
            }
            // Without the recurrence: the same step and counts (and
            // row sums), `u` as it was.
            let (mut zv, mut uv) = (z0.clone(), u0.clone());
            let got = update_chunk(step, (&mut zv, &mut uv), row, false);
            assert_eq!((bits(&zv), bits(&uv)), (bits(&z), bits(u0)));
            assert_eq!(stepped(&got).0, counts);
            if row.is_some() {
                assert_eq!(stepped(&got).1[..2], sums[..2]);
            }
            for (arch, recur) in arches().into_iter().flat_map(|i| [(i, true), (i, false)]) {
                let (mut zs, mut us) = (z0.clone(), u0.clone());
                let got = arch.dispatch(UpdateChunk {
                    step,
                    z: &mut zs,
                    u: &mut us,
                    row,
                    recur,
                });
                let u_after = if recur { &u } else { u0 };
                let what = format!("{arch:?}, recur {recur}");
                assert_eq!((bits(&zs), bits(&us)), (bits(&z), bits(u_after)), "{what}");
                assert_eq!(stepped(&got).0, counts, "{what}");
                match (row.is_some(), recur) {
                    (true, true) => assert_eq!(stepped(&got).1, sums, "{what}"),
                    (true, false) => assert_eq!(stepped(&got).1[..2], sums[..2], "{what}"),
                    (false, _) => {}
                }
            }
        }
    }
}
