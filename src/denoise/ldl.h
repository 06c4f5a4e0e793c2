/* ldl.h: the symmetric linear systems of the denoiser's least-squares fits, solved by an LDLᵀ
 * factorisation that drops the columns adding nothing to the ones before.
 *
 * Both fits (nfor.c's first-order regression, light_edge.c's plane along a light's edge) solve
 * normal equations XᵀWX β = XᵀWy whose design matrix can be rank deficient: a feature constant
 * over the window or a copy of another, a window whose pixels lie in one row. A pivot below
 * 1e-7 of its diagonal marks such a column; it is dropped, its coefficient 0 -- the basic
 * least-squares solution a pivoted QR gives, at a fraction of the cost. With the factor,
 * [(XᵀWX)⁺]₀₀, the variance of the fit's constant term, is the solution's first entry for the
 * right-hand side e₀. */
#ifndef MCRT_DENOISE_LDL_H
#define MCRT_DENOISE_LDL_H

/* Factor the symmetric n×n matrix M (row-major; only its lower triangle is read) as L D Lᵀ in
 * place: L, unit lower triangular, into M's strict lower triangle, D into D[n], a dropped
 * column's pivot and its column of L 0. Returns the rank, the pivots kept. */
int mc_ldl_factor(double *M, int n, double *D);

/* Solve L D Lᵀ x = b in place for the nrhs right-hand sides of b (n × nrhs, row-major), the
 * dropped columns' entries of x 0. */
void mc_ldl_solve(const double *L, const double *D, int n, double *b, int nrhs);

#endif
