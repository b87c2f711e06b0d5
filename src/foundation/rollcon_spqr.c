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

/* The x (n) of least norm among those that minimise |A x - b| for the m x n matrix A given by
 * its rows (rp, rj, rx as transpose_of_rows), through SuiteSparseQR's QR of A^T with rank
 * tolerance tol: A^T E = Q R, so A = E R^T Q^T, and x = Q y with R^T y = E^T b (SPQR's
 * SPQR_RTX_EQUALS_ETB solve, then Q applied by SPQR_QX) lies in the row space of A, the
 * solution of least norm (the scheme of SPQR's own SuiteSparseQR_min2norm). A column of A^T
 * (a row of A) whose norm after the reflections of those before it is at most tol is dead
 * (Heath's rule): its equation is left out of the triangular solve, so with dependent rows
 * the rows kept are met and the dead ones only as far as they follow from them (exactly when
 * the rows are consistent). Returns 0, or -1 when SPQR failed (status: CHOLMOD's status). */
int rollcon_spqr_min_norm(int m, int n, const int *rp, const int *rj, const double *rx,
                          double tol, const double *b, double *x, int *status)
{
    cholmod_common common;
    cholmod_sparse *at;
    cholmod_dense *rhs = NULL, *y = NULL, *z = NULL;
    SuiteSparseQR_C_factorization *qr = NULL;
    double *v;
    int i, result = -1;

    cholmod_l_start(&common);
    at = transpose_of_rows(m, n, rp, rj, rx, &common);
    if (at != NULL) qr = SuiteSparseQR_C_factorize(SPQR_ORDERING_DEFAULT, tol, at, &common);
    if (qr != NULL) rhs = cholmod_l_allocate_dense((size_t)m, 1, (size_t)m, CHOLMOD_REAL,
                                                   &common);
    if (rhs != NULL) {
        v = rhs->x;
        for (i = 0; i < m; i++) v[i] = b[i];
        y = SuiteSparseQR_C_solve(SPQR_RTX_EQUALS_ETB, qr, rhs, &common);
    }
    if (y != NULL) z = SuiteSparseQR_C_qmult(SPQR_QX, qr, y, &common);
    if (z != NULL && z->nrow == (size_t)n) {
        v = z->x;
        for (i = 0; i < n; i++) x[i] = v[i];
        result = 0;
    }
    *status = common.status;
    if (z != NULL) cholmod_l_free_dense(&z, &common);
    if (y != NULL) cholmod_l_free_dense(&y, &common);
    if (rhs != NULL) cholmod_l_free_dense(&rhs, &common);
    if (qr != NULL) SuiteSparseQR_C_free(&qr, &common);
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
    SuiteSparse_long *e = NULL, *cp, *ci, rank = -1;
    double *cx, *w = NULL, length;
    int i, j, k, p, good = 1;

    cholmod_l_start(&common);
    for (i = 0; i < m; i++) involved[i] = 0;
    at = transpose_of_rows(m, n, rp, rj, rx, &common);
    if (at != NULL) {
        rank = SuiteSparseQR_C(SPQR_ORDERING_DEFAULT, tol, 0, 0, at, NULL, NULL, NULL, NULL, &r,
                               &e, NULL, NULL, NULL, &common);
    }
    *status = common.status;
    if (rank < 0 || r == NULL) good = 0;
    if (good) {
        cp = r->p;
        ci = r->i;
        cx = r->x;
        /* R11's columns end on their diagonal, which is not zero */
        for (k = 0; k < rank && good; k++) {
            if (!(cp[k + 1] > cp[k] && ci[cp[k + 1] - 1] == k && cx[cp[k + 1] - 1] != 0.0)) {
                good = 0;
            }
        }
        if (good && rank < m) {
            w = malloc(sizeof(double) * (size_t)(rank > 0 ? rank : 1));
            if (w == NULL) good = 0;
        }
    }
    for (k = (int)rank; good && k < m; k++) {
        for (j = 0; j < rank; j++) w[j] = 0.0;
        for (p = (int)cp[k]; p < cp[k + 1]; p++) w[ci[p]] = -cx[p];
        for (j = (int)rank - 1; j >= 0; j--) {
            w[j] /= cx[cp[j + 1] - 1];
            for (p = (int)cp[j]; p < cp[j + 1] - 1; p++) w[ci[p]] -= cx[p] * w[j];
        }
        length = 1.0;
        for (j = 0; j < rank; j++) length += w[j] * w[j];
        length = sqrt(length);
        for (j = 0; j < rank; j++) {
            if (fabs(w[j]) / length > involvement) involved[e == NULL ? j : (int)e[j]] = 1;
        }
        if (1.0 / length > involvement) involved[e == NULL ? k : (int)e[k]] = 1;
    }
    free(w);
    if (r != NULL) cholmod_l_free_sparse(&r, &common);
    if (e != NULL) cholmod_l_free(m, sizeof(SuiteSparse_long), e, &common);
    if (at != NULL) cholmod_l_free_sparse(&at, &common);
    cholmod_l_finish(&common);
    return good ? (int)rank : -1;
}
