/* SPDX-License-Identifier: MIT */
/* SuiteSparseQR (SuiteSparse's rank-revealing sparse QR) for rollcon_sparse_qr: the numerical
 * rank of one sparse matrix and, column by column in the order SPQR eliminated them, |R(k,k)|;
 * the least-norm solution and the dependent rows of a matrix given by its rows; the greedy
 * choice of columns in an order held, with strong rank-revealing swaps, and a last column's
 * combination of the others (the order held: SPQR_ORDERING_FIXED, R left squeezed).
 * In C so that CHOLMOD's structs (cholmod_common, cholmod_sparse) stay out of Fortran. The
 * matrix comes in compressed columns, 0-based, int indices; CHOLMOD's "long" interface, the
 * one SuiteSparseQR_C takes, is given a copy in its own index type.
 *
 * SPQR orders the columns to reduce fill (SPQR_ORDERING_DEFAULT) and treats a column whose
 * norm, after the Householder reflections of the columns before it, is at most tol as
 * dependent (Heath's rule): that column gets no pivot, so the rank is the number of columns
 * with one (Davis, "Algorithm 915, SuiteSparseQR", ACM TOMS 38(1), 2011, §2.3). */
#include <math.h>
#include <stdlib.h>
#include <suitesparse/SuiteSparseQR_C.h>

/* The rank of the m x n matrix (ap[n + 1], ai[ap[n]], ax[ap[n]]) with tolerance tol; order[k]
 * (0-based) the column SPQR put k-th and diagonal[k] |R(k,k)| for k below the rank (those
 * past it set to 0). Returns the rank, or -1 when SPQR failed (status: CHOLMOD's status). */
int rollcon_spqr_rank(int m, int n, const int *ap, const int *ai, const double *ax,
                      double tol, int *order, double *diagonal, int *status)
{
    cholmod_common common;
    cholmod_sparse *a, *r = NULL;
    SuiteSparse_long *e = NULL, *rp, *ri, rank;
    double *rx;
    int j, k, nnz = ap[n];

    cholmod_l_start(&common);
    a = cholmod_l_allocate_sparse((size_t)m, (size_t)n, (size_t)(nnz > 0 ? nnz : 1), 1, 1, 0,
                                  CHOLMOD_REAL, &common);
    if (a == NULL) {
        *status = common.status;
        cholmod_l_finish(&common);
        return -1;
    }
    rp = a->p;
    ri = a->i;
    rx = a->x;
    for (j = 0; j <= n; j++) rp[j] = ap[j];
    for (k = 0; k < nnz; k++) {
        ri[k] = ai[k];
        rx[k] = ax[k];
    }
    rank = SuiteSparseQR_C(SPQR_ORDERING_DEFAULT, tol, 0, 0, a, NULL, NULL, NULL, NULL, &r, &e,
                           NULL, NULL, NULL, &common);
    *status = common.status;
    if (rank < 0 || r == NULL) {
        cholmod_l_free_sparse(&a, &common);
        if (r != NULL) cholmod_l_free_sparse(&r, &common);
        free(e);
        cholmod_l_finish(&common);
        return -1;
    }
    /* R is rank x n (econ 0: e = rank), upper trapezoidal in the permuted columns: column k's
     * last entry is on the diagonal for k below the rank */
    rp = r->p;
    ri = r->i;
    rx = r->x;
    for (k = 0; k < n; k++) {
        order[k] = e == NULL ? k : (int)e[k];
        diagonal[k] = 0.0;
        if (k < rank && rp[k + 1] > rp[k] && ri[rp[k + 1] - 1] == k) {
            diagonal[k] = fabs(rx[rp[k + 1] - 1]);
        }
    }
    cholmod_l_free_sparse(&a, &common);
    cholmod_l_free_sparse(&r, &common);
    cholmod_l_free(n, sizeof(SuiteSparse_long), e, &common);
    cholmod_l_finish(&common);
    return (int)rank;
}

/* The m x n matrix A given by its rows, (rp[m + 1], rj[rp[m]], rx[rp[m]]) 0-based, as the n x m
 * CHOLMOD matrix A^T in compressed columns (row i of A is column i of A^T); NULL when CHOLMOD
 * cannot allocate it. */
static cholmod_sparse *transpose_of_rows(int m, int n, const int *rp, const int *rj,
                                         const double *rx, cholmod_common *common)
{
    cholmod_sparse *at;
    SuiteSparse_long *p, *i;
    double *x;
    int j, k, nnz = rp[m];

    at = cholmod_l_allocate_sparse((size_t)n, (size_t)m, (size_t)(nnz > 0 ? nnz : 1), 1, 1, 0,
                                   CHOLMOD_REAL, common);
    if (at == NULL) return NULL;
    p = at->p;
    i = at->i;
    x = at->x;
    for (j = 0; j <= m; j++) p[j] = rp[j];
    for (k = 0; k < nnz; k++) {
        i[k] = rj[k];
        x[k] = rx[k];
    }
    return at;
}

/* x (n) = Q R^-T E^T b from SuiteSparseQR's QR of the n x k matrix at = A^T (A^T E = Q R, rank
 * tolerance tol): SPQR's SPQR_RTX_EQUALS_ETB solve, then Q applied by SPQR_QX (the scheme of
 * SPQR's own SuiteSparseQR_min2norm). For A of full row rank, the x of least norm with
 * A x = b (it lies in the row space of A). Returns 0, or -1 when SPQR failed. */
static int min2norm(cholmod_sparse *at, double tol, const double *b, double *x,
                    cholmod_common *common)
{
    cholmod_dense *rhs = NULL, *y = NULL, *z = NULL;
    SuiteSparseQR_C_factorization *qr;
    double *v;
    size_t i, k = at->ncol, n = at->nrow;
    int result = -1;

    qr = SuiteSparseQR_C_factorize(SPQR_ORDERING_DEFAULT, tol, at, common);
    if (qr != NULL) rhs = cholmod_l_allocate_dense(k, 1, k, CHOLMOD_REAL, common);
    if (rhs != NULL) {
        v = rhs->x;
        for (i = 0; i < k; i++) v[i] = b[i];
        y = SuiteSparseQR_C_solve(SPQR_RTX_EQUALS_ETB, qr, rhs, common);
    }
    if (y != NULL) z = SuiteSparseQR_C_qmult(SPQR_QX, qr, y, common);
    if (z != NULL && z->nrow == n) {
        v = z->x;
        for (i = 0; i < n; i++) x[i] = v[i];
        result = 0;
    }
    if (z != NULL) cholmod_l_free_dense(&z, common);
    if (y != NULL) cholmod_l_free_dense(&y, common);
    if (rhs != NULL) cholmod_l_free_dense(&rhs, common);
    if (qr != NULL) SuiteSparseQR_C_free(&qr, common);
    return result;
}

/* Whether R (rank x m, from SuiteSparseQR_C with econ 0) is upper trapezoidal, R = [R11 R12]:
 * each of R11's columns ends on its diagonal, which is not zero. */
static int trapezoidal(const cholmod_sparse *r, SuiteSparse_long rank)
{
    const SuiteSparse_long *cp = r->p, *ci = r->i;
    const double *cx = r->x;
    SuiteSparse_long k;

    for (k = 0; k < rank; k++) {
        if (!(cp[k + 1] > cp[k] && ci[cp[k + 1] - 1] == k && cx[cp[k + 1] - 1] != 0.0)) return 0;
    }
    return 1;
}

/* c (rank) = R11^-1 R(:, k) for a dead column k of an upper trapezoidal R (back substitution
 * over R11's columns): column k of A^T E is Q R(:, k) = (A^T E)(:, live) c, so A's dead row k
 * is the combination c of its live rows. */
static void dead_combination(const cholmod_sparse *r, SuiteSparse_long rank, SuiteSparse_long k,
                             double *c)
{
    const SuiteSparse_long *cp = r->p, *ci = r->i;
    const double *cx = r->x;
    SuiteSparse_long j, p;

    for (j = 0; j < rank; j++) c[j] = 0.0;
    for (p = cp[k]; p < cp[k + 1]; p++) c[ci[p]] = cx[p];
    for (j = rank - 1; j >= 0; j--) {
        c[j] /= cx[cp[j + 1] - 1];
        for (p = cp[j]; p < cp[j + 1] - 1; p++) c[ci[p]] -= cx[p] * c[j];
    }
}

/* The x (n) of least norm among those that minimise |A x - b| for the m x n matrix A given by
 * its rows (rp, rj, rx as transpose_of_rows), through SuiteSparseQR's QR of A^T with rank
 * tolerance tol: A^T E = Q [R11 R12], a row of A whose norm after the reflections of those
 * before it is at most tol dead (Heath's rule), R11 over the live rows A_L. Every row live
 * (full row rank): x = min2norm. Else A (rows in E's order) = [I; K] A_L, K's row for dead row
 * k the combination R11^-1 R12(:, k) (dead_combination), so min |A x - b| is min |[I; K] v -
 * E^T b| over v = A_L x (A_L of full row rank reaches every v): v by SPQR's least squares on
 * the sparse [I; K] (full column rank), then x = min2norm of A_L x = v, the least norm among
 * the minimisers, as the SVD's minimum-norm solution. Returns 0, or -1 when SPQR failed or R
 * is not trapezoidal (status: CHOLMOD's status). */
int rollcon_spqr_min_norm(int m, int n, const int *rp, const int *rj, const double *rx,
                          double tol, const double *b, double *x, int *status)
{
    cholmod_common common;
    cholmod_sparse *at, *r = NULL, *live = NULL, *stacked = NULL;
    cholmod_triplet *t = NULL;
    cholmod_dense *rhs = NULL, *v = NULL;
    SuiteSparse_long *e = NULL, rank = -1, k, j, p, q, nnz, *ti, *tj, *lp, *li, *ap, *ai;
    double *c = NULL, *tx, *lx, *ax, *rv;
    int result = -1;

    cholmod_l_start(&common);
    at = transpose_of_rows(m, n, rp, rj, rx, &common);
    if (at != NULL) {
        rank = SuiteSparseQR_C(SPQR_ORDERING_DEFAULT, tol, 0, 0, at, NULL, NULL, NULL, NULL, &r,
                               &e, NULL, NULL, NULL, &common);
    }
    if (rank == 0 && r != NULL) {
        /* every row dead (zero to the tolerance): x = 0, as the SVD with no singular value */
        for (j = 0; j < n; j++) x[j] = 0.0;
        result = 0;
    } else if (rank == m && r != NULL) {
        result = min2norm(at, tol, b, x, &common);
    } else if (rank >= 0 && r != NULL && trapezoidal(r, rank)) {
        c = malloc(sizeof(double) * (size_t)(rank > 0 ? rank : 1));
        /* [I; K] as triplets: its nonzeros counted, then written */
        nnz = rank;
        for (k = rank; c != NULL && k < m; k++) {
            dead_combination(r, rank, k, c);
            for (j = 0; j < rank; j++) nnz += c[j] != 0.0;
        }
        if (c != NULL) t = cholmod_l_allocate_triplet((size_t)m, (size_t)(rank > 0 ? rank : 1),
                                                      (size_t)(nnz > 0 ? nnz : 1), 0,
                                                      CHOLMOD_REAL, &common);
        if (t != NULL) {
            ti = t->i;
            tj = t->j;
            tx = t->x;
            q = 0;
            for (j = 0; j < rank; j++, q++) {
                ti[q] = j;
                tj[q] = j;
                tx[q] = 1.0;
            }
            for (k = rank; k < m; k++) {
                dead_combination(r, rank, k, c);
                for (j = 0; j < rank; j++) {
                    if (c[j] == 0.0) continue;
                    ti[q] = k;
                    tj[q] = j;
                    tx[q] = c[j];
                    q++;
                }
            }
            t->nnz = (size_t)q;
            stacked = cholmod_l_triplet_to_sparse(t, (size_t)q, &common);
        }
        if (stacked != NULL) {
            rhs = cholmod_l_allocate_dense((size_t)m, 1, (size_t)m, CHOLMOD_REAL, &common);
        }
        if (rhs != NULL) {
            rv = rhs->x;
            for (k = 0; k < m; k++) rv[k] = b[e == NULL ? k : e[k]];
            v = SuiteSparseQR_C_backslash(SPQR_ORDERING_DEFAULT, SPQR_NO_TOL, stacked, rhs,
                                          &common);
        }
        if (v != NULL) {
            /* A_L^T: the live columns of A^T, in E's order */
            ap = at->p;
            ai = at->i;
            ax = at->x;
            nnz = 0;
            for (j = 0; j < rank; j++) {
                k = e == NULL ? j : e[j];
                nnz += ap[k + 1] - ap[k];
            }
            live = cholmod_l_allocate_sparse((size_t)n, (size_t)rank,
                                             (size_t)(nnz > 0 ? nnz : 1), 1, 1, 0,
                                             CHOLMOD_REAL, &common);
        }
        if (live != NULL) {
            lp = live->p;
            li = live->i;
            lx = live->x;
            lp[0] = 0;
            for (j = 0; j < rank; j++) {
                k = e == NULL ? j : e[j];
                q = lp[j];
                for (p = ap[k]; p < ap[k + 1]; p++, q++) {
                    li[q] = ai[p];
                    lx[q] = ax[p];
                }
                lp[j + 1] = q;
            }
            result = min2norm(live, tol, v->x, x, &common);
        }
    }
    *status = common.status;
    free(c);
    if (live != NULL) cholmod_l_free_sparse(&live, &common);
    if (v != NULL) cholmod_l_free_dense(&v, &common);
    if (rhs != NULL) cholmod_l_free_dense(&rhs, &common);
    if (stacked != NULL) cholmod_l_free_sparse(&stacked, &common);
    if (t != NULL) cholmod_l_free_triplet(&t, &common);
    if (r != NULL) cholmod_l_free_sparse(&r, &common);
    if (e != NULL) cholmod_l_free(m, sizeof(SuiteSparse_long), e, &common);
    if (at != NULL) cholmod_l_free_sparse(&at, &common);
    cholmod_l_finish(&common);
    return result;
}

/* The rank of the m x n matrix A given by its rows (rp, rj, rx as transpose_of_rows) by
 * SuiteSparseQR's QR of A^T with rank tolerance tol (Heath's rule, as rollcon_spqr_rank), and
 * which rows take part in a dependency: involved[i] = 1 when row i has an entry above
 * involvement in a unit left null vector of A. SPQR leaves R upper trapezoidal, A^T E = Q
 * [R11 R12], R11 rank x rank upper triangular over the live columns; each dead column k gives
 * the null vector w of R with w_k = 1 and R11 w_live = -R12(:, k) (back substitution), and
 * A^T (E w) = Q R w = 0, so E w, scaled to unit length, is a left null vector of A; they span
 * the left null space. Returns the rank, or -1 when SPQR failed or R is not so (status). */
int rollcon_spqr_dependent(int m, int n, const int *rp, const int *rj, const double *rx,
                           double tol, double involvement, int *involved, int *status)
{
    cholmod_common common;
    cholmod_sparse *at, *r = NULL;
    SuiteSparse_long *e = NULL, rank = -1, j, k;
    double *c = NULL, length;
    int i, good = 1;

    cholmod_l_start(&common);
    for (i = 0; i < m; i++) involved[i] = 0;
    at = transpose_of_rows(m, n, rp, rj, rx, &common);
    if (at != NULL) {
        rank = SuiteSparseQR_C(SPQR_ORDERING_DEFAULT, tol, 0, 0, at, NULL, NULL, NULL, NULL, &r,
                               &e, NULL, NULL, NULL, &common);
    }
    *status = common.status;
    if (rank < 0 || r == NULL || !trapezoidal(r, rank)) good = 0;
    if (good && rank < m) {
        c = malloc(sizeof(double) * (size_t)(rank > 0 ? rank : 1));
        if (c == NULL) good = 0;
    }
    /* dead row k: w = (-c, 1) over (live rows, k), scaled to unit length */
    for (k = rank; good && k < m; k++) {
        dead_combination(r, rank, k, c);
        length = 1.0;
        for (j = 0; j < rank; j++) length += c[j] * c[j];
        length = sqrt(length);
        for (j = 0; j < rank; j++) {
            if (fabs(c[j]) / length > involvement) involved[e == NULL ? j : e[j]] = 1;
        }
        if (1.0 / length > involvement) involved[e == NULL ? k : e[k]] = 1;
    }
    free(c);
    if (r != NULL) cholmod_l_free_sparse(&r, &common);
    if (e != NULL) cholmod_l_free(m, sizeof(SuiteSparse_long), e, &common);
    if (at != NULL) cholmod_l_free_sparse(&at, &common);
    cholmod_l_finish(&common);
    return good ? (int)rank : -1;
}

/* The m x n matrix (ap, ai, ax: compressed columns, 0-based) as a CHOLMOD matrix with its
 * columns in the order perm (perm[k]: the column put k-th); NULL when CHOLMOD cannot allocate
 * it. */
static cholmod_sparse *permuted_columns(int m, int n, const int *ap, const int *ai,
                                        const double *ax, const SuiteSparse_long *perm,
                                        cholmod_common *common)
{
    cholmod_sparse *a;
    SuiteSparse_long *p, *i, q = 0, s;
    double *x;
    int k, j, nnz = ap[n];

    a = cholmod_l_allocate_sparse((size_t)m, (size_t)n, (size_t)(nnz > 0 ? nnz : 1), 1, 1, 0,
                                  CHOLMOD_REAL, common);
    if (a == NULL) return NULL;
    p = a->p;
    i = a->i;
    x = a->x;
    p[0] = 0;
    for (k = 0; k < n; k++) {
        j = (int)perm[k];
        for (s = ap[j]; s < ap[j + 1]; s++, q++) {
            i[q] = ai[s];
            x[q] = ax[s];
        }
        p[k + 1] = q;
    }
    return a;
}

/* SuiteSparseQR of the columns of (ap, ai, ax) in the order perm held (SPQR_ORDERING_FIXED),
 * rank tolerance tol (< 0: none). With a fixed order SPQR leaves R "squeezed": the dead
 * columns in place, without a pivot row; a column is live when its last entry is on the next
 * pivot row. live[j] (for column j of the matrix given): whether it is; pivot[i]: the column
 * of R (0-based, in the order held) whose diagonal is on row i; *r, *e: SPQR's R and E (to be
 * freed). Returns the rank, or -1 when SPQR failed. */
static SuiteSparse_long factor_held(int m, int n, const int *ap, const int *ai, const double *ax,
                                    const SuiteSparse_long *perm, double tol, int *live,
                                    SuiteSparse_long *pivot, cholmod_sparse **r,
                                    SuiteSparse_long **e, cholmod_common *common)
{
    cholmod_sparse *a;
    SuiteSparse_long rank, k, pivots = 0, *rp, *ri;

    *r = NULL;
    *e = NULL;
    a = permuted_columns(m, n, ap, ai, ax, perm, common);
    if (a == NULL) return -1;
    rank = SuiteSparseQR_C(SPQR_ORDERING_FIXED, tol < 0.0 ? SPQR_NO_TOL : tol, 0, 0, a, NULL,
                           NULL, NULL, NULL, r, e, NULL, NULL, NULL, common);
    cholmod_l_free_sparse(&a, common);
    if (rank < 0 || *r == NULL) return -1;
    rp = (*r)->p;
    ri = (*r)->i;
    for (k = 0; k < n; k++) {
        SuiteSparse_long j = perm[*e == NULL ? k : (*e)[k]];
        live[j] = rp[k + 1] > rp[k] && ri[rp[k + 1] - 1] == pivots && pivots < rank;
        if (live[j]) pivot[pivots++] = k;
    }
    return pivots == rank ? rank : -1;
}

/* c (the pivots before R's column k) = R11^-1 R(:, k) for a column k of a squeezed R
 * (factor_held): the combination of the live columns before it that is its projection on
 * their span (back substitution on R's triangle). */
static void squeezed_combination(const cholmod_sparse *r, const SuiteSparse_long *pivot,
                                 SuiteSparse_long pivots, SuiteSparse_long k, double *c)
{
    const SuiteSparse_long *rp = r->p, *ri = r->i;
    const double *rx = r->x;
    SuiteSparse_long j, p, q;

    for (j = 0; j < pivots; j++) c[j] = 0.0;
    for (p = rp[k]; p < rp[k + 1]; p++) {
        if (ri[p] < pivots) c[ri[p]] = rx[p];
    }
    for (j = pivots - 1; j >= 0; j--) {
        q = pivot[j];
        c[j] /= rx[rp[q + 1] - 1];
        for (p = rp[q]; p < rp[q + 1] - 1; p++) c[ri[p]] -= rx[p] * c[j];
    }
}

/* The columns of the m x n matrix (ap, ai, ax) chosen greedily in an order that holds every
 * column j with group[j] = 0 before the others, within each group in COLAMD's fill-reducing
 * order of the whole matrix (fill nonzero: CHOLMOD's colamd on A^T, which orders the columns
 * of A for A^T A) or as given (fill zero): SuiteSparseQR with that order held and rank
 * tolerance tol (factor_held; Heath's rule, tol < 0: every column live). A column is dead when
 * its norm after the reflections of the live columns before it is at most tol: the live ones
 * are those a greedy choice in that order keeps. Then, with bound > 1, swaps (Gu and
 * Eisenstat's strong rank-revealing QR, SIAM J. Sci. Comput. 17(4), 1996, on the combinations
 * R11^-1 R12): a dead column k is the combination c of the live ones; where |c_j| > bound for
 * a live column j of group 1, k is kept instead of j, which multiplies the live columns'
 * volume (|det R11|) by |c_j|: in a round, the largest such |c_j| of each dead column whose
 * combination touches no column of a swap made before it in the round (the swaps of a round
 * then do not change each other's combinations); then the live columns of group 1 before the
 * dead ones, refactored, until no swap is left (at most 50 rounds). Afterwards no live column
 * of group 1 takes part in a dead one's combination with a coefficient above bound. order[k]
 * (0-based): the live columns in the order of elimination, then the dead ones in it;
 * diagonal[k] |R(k,k)| of live column order[k] (its distance from the span of the live columns
 * before it), 0 for the dead. Returns the rank, or -1 when CHOLMOD or SPQR failed (status:
 * CHOLMOD's status). */
int rollcon_spqr_grouped_rank(int m, int n, const int *ap, const int *ai, const double *ax,
                              double tol, const int *group, int fill, double bound, int *order,
                              double *diagonal, int *status)
{
    cholmod_common common;
    cholmod_sparse *at = NULL, *r = NULL, *given = NULL;
    SuiteSparse_long *perm = NULL, *colamd = NULL, *e = NULL, *pivot = NULL, *rp, rank = -1,
                     k, j, q, g, pivots, best, round;
    int *live = NULL, *tier = NULL, *touched = NULL, result = -1, swaps, clean;
    double *rx, *c = NULL;

    cholmod_l_start(&common);
    perm = malloc(sizeof(SuiteSparse_long) * (size_t)(n > 0 ? n : 1));
    colamd = malloc(sizeof(SuiteSparse_long) * (size_t)(n > 0 ? n : 1));
    pivot = malloc(sizeof(SuiteSparse_long) * (size_t)(n > 0 ? n : 1));
    live = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    tier = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    touched = malloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    c = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    if (perm == NULL || colamd == NULL || pivot == NULL || live == NULL || tier == NULL ||
        touched == NULL || c == NULL)
        goto done;
    for (k = 0; k < n; k++) colamd[k] = k;
    if (fill && n > 1) {
        given = permuted_columns(m, n, ap, ai, ax, colamd, &common);
        if (given != NULL) at = cholmod_l_transpose(given, 0, &common);
        if (at == NULL || !cholmod_l_colamd(at, NULL, 0, 1, colamd, &common)) goto done;
    }
    /* tier 0: group 0; tier 1: the others (after a round of swaps, 1: live, 2: dead) */
    for (j = 0; j < n; j++) tier[j] = group[j] != 0;
    for (round = 0;; round++) {
        q = 0;
        for (g = 0; g < 3; g++) {
            for (k = 0; k < n; k++) {
                if (tier[colamd[k]] == g) perm[q++] = colamd[k];
            }
        }
        if (r != NULL) cholmod_l_free_sparse(&r, &common);
        if (e != NULL) cholmod_l_free(n, sizeof(SuiteSparse_long), e, &common);
        rank = factor_held(m, n, ap, ai, ax, perm, tol, live, pivot, &r, &e, &common);
        if (rank < 0) goto done;
        if (!(bound > 1.0) || round >= 50) break;
        /* a round of swaps */
        swaps = 0;
        pivots = 0;
        for (j = 0; j < n; j++) touched[j] = 0;
        for (k = 0; k < n; k++) {
            SuiteSparse_long dead = perm[e == NULL ? k : e[k]];
            if (pivots < rank && pivot[pivots] == k) {
                pivots++;
                continue;
            }
            if (group[dead] == 0 || touched[dead]) continue;
            squeezed_combination(r, pivot, pivots, k, c);
            best = -1;
            clean = 1;
            for (j = 0; j < pivots; j++) {
                SuiteSparse_long column;
                if (c[j] == 0.0) continue;
                column = perm[e == NULL ? pivot[j] : e[pivot[j]]];
                if (touched[column]) clean = 0;
                if (group[column] != 0 && (best < 0 || fabs(c[j]) > fabs(c[best]))) best = j;
            }
            if (!clean || best < 0 || !(fabs(c[best]) > bound)) continue;
            for (j = 0; j < pivots; j++) {
                if (c[j] != 0.0) touched[perm[e == NULL ? pivot[j] : e[pivot[j]]]] = 1;
            }
            touched[dead] = 1;
            live[dead] = 1;
            live[perm[e == NULL ? pivot[best] : e[pivot[best]]]] = 0;
            swaps++;
        }
        if (swaps == 0) break;
        for (j = 0; j < n; j++) {
            if (group[j] != 0) tier[j] = live[j] ? 1 : 2;
        }
    }
    /* the live columns in the order of elimination, then the dead ones in it */
    rp = r->p;
    rx = r->x;
    pivots = 0;
    for (k = 0; k < rank; k++) {
        q = pivot[k];
        order[k] = (int)perm[e == NULL ? q : e[q]];
        diagonal[k] = fabs(rx[rp[q + 1] - 1]);
    }
    q = rank;
    for (k = 0; k < n; k++) {
        if (pivots < rank && pivot[pivots] == k) {
            pivots++;
            continue;
        }
        order[q] = (int)perm[e == NULL ? k : e[k]];
        diagonal[q] = 0.0;
        q++;
    }
    result = q == n ? (int)rank : -1;
done:
    *status = common.status;
    if (r != NULL) cholmod_l_free_sparse(&r, &common);
    if (e != NULL) cholmod_l_free(n, sizeof(SuiteSparse_long), e, &common);
    if (at != NULL) cholmod_l_free_sparse(&at, &common);
    if (given != NULL) cholmod_l_free_sparse(&given, &common);
    free(perm);
    free(colamd);
    free(pivot);
    free(live);
    free(tier);
    free(touched);
    free(c);
    cholmod_l_finish(&common);
    return result;
}

/* How the last column b of the m x n matrix (ap, ai, ax) lies in the span of the others A:
 * SuiteSparseQR with the columns in the order given (SPQR_ORDERING_FIXED) and rank tolerance
 * tol, [A b] = Q R with R squeezed (rollcon_spqr_grouped_rank); x (n - 1) = R11^-1 R(live, b)
 * over A's live columns (back substitution on R's triangle), 0 on its dead ones: A x is the
 * projection of b on the span of A, so x is a least-squares solution of A x = b (the only one
 * when A's columns are all live). Returns the rank of A, or -1 when SPQR failed (status). */
int rollcon_spqr_combination(int m, int n, const int *ap, const int *ai, const double *ax,
                             double tol, double *x, int *status)
{
    cholmod_common common;
    cholmod_sparse *a = NULL, *r = NULL;
    SuiteSparse_long *perm = NULL, *e = NULL, *rp, *ri, *pivot = NULL, rank = -1, k, j, p,
                     pivots, last;
    double *rx, *c = NULL;
    int result = -1;

    cholmod_l_start(&common);
    perm = malloc(sizeof(SuiteSparse_long) * (size_t)(n > 0 ? n : 1));
    pivot = malloc(sizeof(SuiteSparse_long) * (size_t)(n > 0 ? n : 1));
    c = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    if (perm == NULL || pivot == NULL || c == NULL || n < 1) goto done;
    for (k = 0; k < n; k++) perm[k] = k;
    for (k = 0; k + 1 < n; k++) x[k] = 0.0;
    a = permuted_columns(m, n, ap, ai, ax, perm, &common);
    if (a == NULL) goto done;
    rank = SuiteSparseQR_C(SPQR_ORDERING_FIXED, tol, 0, 0, a, NULL, NULL, NULL, NULL, &r, &e,
                           NULL, NULL, NULL, &common);
    if (rank < 0 || r == NULL) goto done;
    rp = r->p;
    ri = r->i;
    rx = r->x;
    /* pivot[i]: the column of R whose diagonal is on row i (the i-th live one); last: b's */
    pivots = 0;
    last = -1;
    for (k = 0; k < n; k++) {
        if ((e == NULL ? k : e[k]) == n - 1) {
            last = k;
            break;
        }
        if (rp[k + 1] > rp[k] && ri[rp[k + 1] - 1] == pivots && pivots < rank) {
            pivot[pivots++] = k;
        }
    }
    if (last < 0) goto done;
    /* R(:, b) on the pivot rows of the live columns before it, then R11^-1 of it */
    for (j = 0; j < pivots; j++) c[j] = 0.0;
    for (p = rp[last]; p < rp[last + 1]; p++) {
        if (ri[p] < pivots) c[ri[p]] = rx[p];
    }
    for (j = pivots - 1; j >= 0; j--) {
        k = pivot[j];
        c[j] /= rx[rp[k + 1] - 1];
        for (p = rp[k]; p < rp[k + 1] - 1; p++) c[ri[p]] -= rx[p] * c[j];
    }
    for (j = 0; j < pivots; j++) x[e == NULL ? pivot[j] : e[pivot[j]]] = c[j];
    result = (int)pivots;
done:
    *status = common.status;
    if (r != NULL) cholmod_l_free_sparse(&r, &common);
    if (e != NULL) cholmod_l_free(n, sizeof(SuiteSparse_long), e, &common);
    if (a != NULL) cholmod_l_free_sparse(&a, &common);
    free(perm);
    free(pivot);
    free(c);
    cholmod_l_finish(&common);
    return result;
}
