/* SPDX-License-Identifier: MIT */
/* SuiteSparseQR (SuiteSparse's rank-revealing sparse QR) for rollcon_sparse_qr: the numerical
 * rank of one sparse matrix and, column by column in the order SPQR eliminated them, |R(k,k)|.
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
