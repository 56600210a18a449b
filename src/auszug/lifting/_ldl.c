/* Sparse LDL^T without pivoting in a given ordering, for the lifting's KKT matrices (auszug.lifting._ldl).

   The up-looking algorithm: the elimination tree and the column counts of L once per sparsity pattern
   (ldl_symbolic), then per matrix the rows of L one after the other, each a sparse triangular solve whose
   pattern is the reach of the row's entries in the tree (ldl_numeric). Matrices are given by the upper
   triangle (diagonal included) of the permuted matrix in CSC form, columns' row indices in any order.
   Built by `make install` (cc -O2 -shared -fPIC); loaded with ctypes. Plain C, no Python API. */

#include <stdint.h>

/* parent[n] (-1 at the roots) and counts[n] (non-zeros of L's columns below the diagonal); flag[n] is
   scratch. */
void ldl_symbolic(int64_t n, const int64_t *Ap, const int64_t *Ai, int64_t *parent, int64_t *counts,
                  int64_t *flag)
{
    for (int64_t k = 0; k < n; k++) {
        parent[k] = -1;
        counts[k] = 0;
    }
    for (int64_t k = 0; k < n; k++) {
        flag[k] = k;
        for (int64_t p = Ap[k]; p < Ap[k + 1]; p++) {
            int64_t i = Ai[p];
            while (i < k && flag[i] != k) {     /* up the tree to the first node already seen for row k */
                if (parent[i] == -1)
                    parent[i] = k;
                counts[i]++;
                flag[i] = k;
                i = parent[i];
            }
        }
    }
}

/* Fills Li, Lx (the unit lower triangle in CSC, column j from Lp[j]) and D. Scratch: y[n] (zero on
   entry, zero on return), flag[n], pattern[n], filled[n]. Returns 0, or k + 1 at a zero pivot in row k. */
int64_t ldl_numeric(int64_t n, const int64_t *Ap, const int64_t *Ai, const double *Ax,
                    const int64_t *parent, const int64_t *Lp, int32_t *Li, double *Lx, double *D,
                    double *y, int64_t *flag, int64_t *pattern, int64_t *filled)
{
    for (int64_t k = 0; k < n; k++)
        filled[k] = 0;
    for (int64_t k = 0; k < n; k++) {
        int64_t top = n;
        flag[k] = k;
        for (int64_t p = Ap[k]; p < Ap[k + 1]; p++) {
            int64_t i = Ai[p];
            if (i > k)
                continue;
            y[i] += Ax[p];
            int64_t len = 0;
            while (flag[i] != k) {              /* the path from i up to a marked node */
                pattern[len++] = i;
                flag[i] = k;
                i = parent[i];
            }
            while (len > 0)                     /* reversed onto the stack: pattern[top:] is topological */
                pattern[--top] = pattern[--len];
        }
        double d = y[k];
        y[k] = 0.0;
        for (int64_t t = top; t < n; t++) {
            int64_t i = pattern[t];
            double yi = y[i];
            y[i] = 0.0;
            int64_t end = Lp[i] + filled[i];
            for (int64_t p = Lp[i]; p < end; p++)
                y[Li[p]] -= Lx[p] * yi;
            double lki = yi / D[i];
            d -= lki * yi;
            Li[end] = (int32_t)k;
            Lx[end] = lki;
            filled[i]++;
        }
        if (d == 0.0)
            return k + 1;                       /* y is zero again: every entry used was reset */
        D[k] = d;
    }
    return 0;
}

/* x <- (L D L^T)^-1 x, in place. */
void ldl_solve(int64_t n, const int64_t *Lp, const int32_t *Li, const double *Lx, const double *D, double *x)
{
    for (int64_t j = 0; j < n; j++) {
        double xj = x[j];
        if (xj != 0.0)
            for (int64_t p = Lp[j]; p < Lp[j + 1]; p++)
                x[Li[p]] -= Lx[p] * xj;
    }
    for (int64_t j = 0; j < n; j++)
        x[j] /= D[j];
    for (int64_t j = n - 1; j >= 0; j--) {
        double s = x[j];
        for (int64_t p = Lp[j]; p < Lp[j + 1]; p++)
            s -= Lx[p] * x[Li[p]];
        x[j] = s;
    }
}
