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
