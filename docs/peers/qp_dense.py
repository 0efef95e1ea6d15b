"""Dense QP/LCP peers on the Conry & Seireg discrete problem (Example 1, Hertz spheres):
   min 0.5 F'SF + eps'F  s.t. sum F = P, F >= 0   (alpha = multiplier of the equality),
S = Love square-patch influence matrix (patch side h, combined modulus E*), grid points with
r <= 1.3a, eps_k = r_k^2/(2R). Solved in scaled units F/P, lengths/delta_Hertz.
Usage: python qp_dense.py --m 6,9,12 --solvers quadprog,clarabel-qdldl,clarabel-faer,osqp,activeset"""
import argparse, json, time
import numpy as np, scipy.linalg as sla, scipy.sparse as sp
from threadpoolctl import threadpool_limits
from hertz import A, DELTA, P, R, love_square

# All solvers single-threaded: numpy and scipy each bundle their own OpenBLAS, and on 2 cores
# their spinning thread pools can slow mixed numpy/scipy code by up to ~50x.
threadpool_limits(1)

ap = argparse.ArgumentParser()
ap.add_argument("--m", default="6,9,12,18,24,30,36", help="grid points per 1.3a radius")
ap.add_argument("--solvers", default="activeset,quadprog,clarabel-qdldl,clarabel-faer,osqp")
ap.add_argument("--tlimit", type=float, default=120.0, help="skip a solver at larger N once one solve exceeds this")
args = ap.parse_args()


def timed(fn, reps=3, single_if_over=20.0):
    """median wall time of up to `reps` runs (1 run if the first exceeds single_if_over s)"""
    time.sleep(0.3)   # let other thread pools (OpenBLAS, rayon) go idle: 2-core machine
    t = time.perf_counter(); out = fn(); ts = [time.perf_counter() - t]
    while len(ts) < reps and ts[0] < single_if_over:
        t = time.perf_counter(); out = fn(); ts.append(time.perf_counter() - t)
    return float(np.median(ts)), len(ts), out


def build(m):
    h = 1.3 * A / m
    i, j = np.mgrid[-m:m + 1, -m:m + 1]
    keep = i**2 + j**2 <= m * m
    i, j = i[keep], j[keep]
    x, y = i * h, j * h
    eps = (x**2 + y**2) / (2 * R)
    build_direct = lambda: love_square(x[:, None] - x[None, :], y[:, None] - y[None, :], h)
    def build_table():   # Toeplitz trick: Love on (4m+1)^2 offsets, then gather
        o = np.arange(-2 * m, 2 * m + 1) * h
        T = love_square(o[:, None], o[None, :], h)
        return T[(i[:, None] - i[None, :]) + 2 * m, (j[:, None] - j[None, :]) + 2 * m]
    return h, x, y, eps, build_direct, build_table


def sol_quadprog(S, e):
    import quadprog
    N = len(e)
    C = np.hstack([np.ones((N, 1)), np.eye(N)])
    b = np.concatenate([[1.0], np.zeros(N)])
    x, _, _, _, lag, _ = quadprog.solve_qp(S, -e, C, b, meq=1)
    return x, lag[0], "ok"


def sol_clarabel(S, e, method):
    import clarabel
    N = len(e)
    Pm = sp.csc_matrix(np.triu(S))
    Am = sp.vstack([sp.csr_matrix(np.ones((1, N))), -sp.identity(N)]).tocsc()
    b = np.concatenate([[1.0], np.zeros(N)])
    st = clarabel.DefaultSettings()
    st.verbose = False
    st.direct_solve_method = method
    st.tol_gap_abs = st.tol_gap_rel = st.tol_feas = 1e-9
    st.max_threads = 1
    s = clarabel.DefaultSolver(Pm, e, Am, b, [clarabel.ZeroConeT(1), clarabel.NonnegativeConeT(N)], st)
    r = s.solve()
    return np.array(r.x), -r.z[0], f"{r.status} it={r.iterations}"


def sol_osqp(S, e):
    import osqp
    N = len(e)
    Pm = sp.csc_matrix(np.triu(S))
    Am = sp.vstack([sp.csr_matrix(np.ones((1, N))), sp.identity(N)]).tocsc()
    l = np.concatenate([[1.0], np.zeros(N)]); u = np.concatenate([[1.0], np.full(N, np.inf)])
    prob = osqp.OSQP()
    prob.setup(Pm, e, Am, l, u, eps_abs=1e-9, eps_rel=1e-9, polishing=True, verbose=False,
               max_iter=100000, time_limit=args.tlimit)
    r = prob.solve(raise_error=False)
    return r.x, -r.y[0], f"{r.info.status} it={r.info.iter} polish={r.info.status_polish}"


def sol_activeset(S, e):
    """Own 20-line baseline: guess contact set, solve [S_CC -1; 1' 0] by Cholesky, drop F<0, add Y<0."""
    c = e < 1.0
    for it in range(1, 200):
        cf = sla.cho_factor(S[np.ix_(c, c)])
        u, v = sla.cho_solve(cf, -e[c]), sla.cho_solve(cf, np.ones(c.sum()))
        al = (1 - u.sum()) / v.sum()
        F = np.zeros(len(e)); F[c] = u + al * v
        Y = S @ F + e - al
        neg, pen = c & (F < 0), ~c & (Y < -1e-12)
        if not neg.any() and not pen.any():
            return F, al, f"ok it={it}"
        c = (c & ~neg) | pen
    return F, al, "maxit"


SOLVERS = {"quadprog": sol_quadprog, "activeset": sol_activeset, "osqp": sol_osqp,
           "clarabel-qdldl": lambda S, e: sol_clarabel(S, e, "qdldl"),
           "clarabel-faer": lambda S, e: sol_clarabel(S, e, "faer")}


def residuals(S, e, F, al):
    N = len(e)
    Y = S @ F + e - al
    nat = np.max(np.abs(np.minimum(F * N, Y)))          # natural LCP residual, F in units of P/N, Y in delta
    return dict(kkt_res=float(max(nat, abs(F.sum() - 1))), min_F=float(F.min() * N), min_Y=float(Y.min()),
                max_FY=float(np.max(np.abs(F * N * Y))))


skip, allrows = set(), []
for m in [int(v) for v in args.m.split(",")]:
    h, x, y, eps, b_direct, b_table = build(m)
    N = len(eps)
    tb_d, _, S = timed(b_direct)
    tb_t, _, S2 = timed(b_table)
    build_reldiff = float(np.max(np.abs(S - S2) / S))   # direct vs table: rounding in far-field cancellation
    Sh, eh = S * P / DELTA, eps / DELTA                  # scaled problem
    tch, _, _ = timed(lambda: np.linalg.cholesky(Sh), reps=5)
    with threadpool_limits(2):
        tch2, _, _ = timed(lambda: np.linalg.cholesky(Sh), reps=5)
    base = dict(m=m, N=N, h_over_a=h / A, build_reldiff=build_reldiff, t_build_direct=tb_d, t_build_table=tb_t, t_chol_full=tch, t_chol_full_2thr=tch2)
    rows = []
    for name in args.solvers.split(","):
        if name in skip:
            continue
        try:
            t, reps, (F, al, status) = timed(lambda: SOLVERS[name](Sh, eh))
        except Exception as ex:                           # record and go on
            rows.append(dict(base, solver=name, status=f"FAILED {type(ex).__name__}: {ex}"[:120]))
            continue
        if t > args.tlimit:
            skip.add(name)
        rows.append(dict(base, solver=name, t_solve=t, reps=reps, status=status, alpha=al * DELTA,
                         err_alpha_hertz=al - 1, n_contact=int((F > 1e-9 / N).sum()), F=F,
                         **residuals(Sh, eh, F, al)))
    ok = [r for r in rows if "kkt_res" in r]
    ref = min(ok, key=lambda r: r["kkt_res"])
    cset = ref["F"] > 1e-9 / N
    Scc = Sh[np.ix_(cset, cset)]
    tcc, _, _ = timed(lambda: np.linalg.cholesky(Scc), reps=5)
    with threadpool_limits(2):
        tcc2, _, _ = timed(lambda: np.linalg.cholesky(Scc), reps=5)
    for r in rows:
        r.pop("F", None)
        r.update(ref_solver=ref["solver"], t_chol_contact=tcc, t_chol_contact_2thr=tcc2, n_contact_ref=int(cset.sum()))
        if "alpha" in r:
            r["err_alpha_ref"] = r["alpha"] / ref["alpha"] - 1
        print(json.dumps(r), flush=True)
        allrows.append(r)

print("\n| N | solver | t_solve_s | reps | err_alpha_hertz | err_alpha_ref | kkt_res | status |")
print("|---|---|---|---|---|---|---|---|")
for r in allrows:
    if "kkt_res" in r:
        print(f"| {r['N']} | {r['solver']} | {r['t_solve']:.3g} | {r['reps']} | {r['err_alpha_hertz']:+.3e} | "
              f"{r['err_alpha_ref']:+.1e} | {r['kkt_res']:.1e} | {r['status']} |")
    else:
        print(f"| {r['N']} | {r['solver']} | - | - | - | - | - | {r['status']} |")
print("\n| N | n_contact | h/a | build S direct s | build S table s | chol(S) s 1thr / 2thr | chol(S_CC) s 1thr / 2thr |")
print("|---|---|---|---|---|---|---|")
for r in {r["N"]: r for r in allrows}.values():
    print(f"| {r['N']} | {r['n_contact_ref']} | {r['h_over_a']:.4f} | {r['t_build_direct']:.3g} | "
          f"{r['t_build_table']:.3g} | {r['t_chol_full']:.3g} / {r['t_chol_full_2thr']:.3g} | "
          f"{r['t_chol_contact']:.3g} / {r['t_chol_contact_2thr']:.3g} |")
