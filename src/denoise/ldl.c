/* ldl.c: LDLᵀ factorisation and solve with dropped columns (see ldl.h). */
#include "denoise/ldl.h"

#include "core/simd.h"

int mc_ldl_factor(double *M, int n, double *D)
{
    int i, j, k, rank = 0;
    for (j = 0; j < n; j++) {
        double djj = M[j * n + j], diag = M[j * n + j];
        for (k = 0; k < j; k++)
            djj -= M[j * n + k] * M[j * n + k] * D[k];
        D[j] = djj > 1e-7 * diag && diag > 1e-30 ? djj : 0.0;
        rank += D[j] != 0.0;
        for (i = j + 1; i < n; i++) {
            double s = M[i * n + j];
            if (D[j] == 0.0) {
                M[i * n + j] = 0.0;
                continue;
            }
            for (k = 0; k < j; k++)
                s -= M[i * n + k] * M[j * n + k] * D[k];
            M[i * n + j] = s / D[j];
        }
    }
    return rank;
}

/* mc_ldl_solve with the right-hand sides innermost, contiguous, so that they go together in
 * vector registers; each one's own sums are taken in the same order as one at a time. */
static MC_ALWAYS_INLINE void solve_n(const double *L, const double *D, int n, double *b, int nrhs)
{
    int i, k, c;
    for (i = 0; i < n; i++)
        for (k = 0; k < i; k++)
            for (c = 0; c < nrhs; c++)
                b[i * nrhs + c] -= L[i * n + k] * b[k * nrhs + c];
    for (i = 0; i < n; i++)
        for (c = 0; c < nrhs; c++)
            b[i * nrhs + c] = D[i] != 0.0 ? b[i * nrhs + c] / D[i] : 0.0;
    for (i = n - 1; i >= 0; i--)
        for (k = i + 1; k < n; k++)
            for (c = 0; c < nrhs; c++)
                b[i * nrhs + c] -= L[k * n + i] * b[k * nrhs + c];
}

void mc_ldl_solve(const double *L, const double *D, int n, double *b, int nrhs)
{
    if (nrhs == 4) /* the denoiser's regression: colour and probe */
        solve_n(L, D, n, b, 4);
    else
        solve_n(L, D, n, b, nrhs);
}
