/* SPDX-License-Identifier: MIT */
/* KLU (SuiteSparse) for rollcon_sparse_lu: one sparse matrix of fixed pattern, analysed once,
 * factored at every new set of values, solved with any number of right-hand sides. In C so
 * that KLU's structs (klu_common, whose layout is KLU's own) stay out of Fortran: Fortran
 * holds an opaque pointer. The matrix is in compressed columns, 0-based (KLU's form).
 *
 * A new factorisation reuses the pivot order of the last full one (klu_refactor: no
 * allocation, no search) unless its reciprocal condition estimate (klu_rcond) falls below
 * eps^(2/3), when it factors afresh with pivoting (klu_factor): the rule of SUNDIALS' KLU
 * linear solver. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <suitesparse/klu.h>

typedef struct {
    klu_common common;
    klu_symbolic *symbolic;
    klu_numeric *numeric;
    int n;
} rollcon_klu;

/* Analyse the pattern (n x n, ap[n + 1], ai[ap[n]]): a handle, or NULL (status set). */
void *rollcon_klu_analyse(int n, int *ap, int *ai, int *status)
{
    rollcon_klu *self = calloc(1, sizeof *self);
    if (self == NULL) {
        *status = KLU_OUT_OF_MEMORY;
        return NULL;
    }
    klu_defaults(&self->common);
    self->n = n;
    self->symbolic = klu_analyze(n, ap, ai, &self->common);
    if (self->symbolic == NULL) {
        *status = self->common.status;
        free(self);
        return NULL;
    }
    *status = KLU_OK;
    return self;
}

/* Factor the values ax of the analysed pattern: 0 on success, else KLU's status (negative)
 * or 1 for a singular matrix. */
int rollcon_klu_factor(void *handle, int *ap, int *ai, double *ax)
{
    rollcon_klu *self = handle;
    if (self->numeric != NULL) {
        if (klu_refactor(ap, ai, ax, self->symbolic, self->numeric, &self->common)
            && klu_rcond(self->symbolic, self->numeric, &self->common)
            && self->common.rcond >= pow(DBL_EPSILON, 2.0 / 3.0)) {
            return 0;
        }
        klu_free_numeric(&self->numeric, &self->common);
    }
    self->numeric = klu_factor(ap, ai, ax, self->symbolic, &self->common);
    if (self->numeric == NULL) {
        return self->common.status == KLU_SINGULAR ? 1 : self->common.status;
    }
    if (self->common.status == KLU_SINGULAR) return 1;
    return 0;
}

/* Solve in place for nrhs right-hand sides b (leading dimension ldb): 0 or KLU's status. */
int rollcon_klu_solve(void *handle, int ldb, int nrhs, double *b)
{
    rollcon_klu *self = handle;
    if (klu_solve(self->symbolic, self->numeric, ldb, nrhs, b, &self->common)) return 0;
    return self->common.status == KLU_OK ? -1 : self->common.status;
}

/* Free a handle and its factors (NULL: nothing). */
void rollcon_klu_free(void *handle)
{
    rollcon_klu *self = handle;
    if (self == NULL) return;
    if (self->numeric != NULL) klu_free_numeric(&self->numeric, &self->common);
    if (self->symbolic != NULL) klu_free_symbolic(&self->symbolic, &self->common);
    free(self);
}
