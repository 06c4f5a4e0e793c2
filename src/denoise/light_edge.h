/* light_edge.h: the emission of a pixel that a light's edge crosses, fitted along the edge.
 *
 * The denoiser takes the light seen directly out of the colour and adds it back unfiltered
 * (nfor.h). Where a light's edge crosses a pixel, that emission is the light's radiance times
 * the share of the pixel's rays that hit it: k of n rays, whose error is the pixel's error there
 * (57% of the denoised Cornell box's at 16 spp sat in its 63 such pixels). The pixels along one
 * straight edge measure the same thing: with a box pixel filter, the share of a pixel that a
 * straight edge covers is an affine function of the pixel's position for as long as the edge
 * crosses the same two sides of the pixels (constant along a horizontal or vertical edge, a ramp
 * along a slanted one). So each such pixel's emission is fitted, channel by channel, as
 * a + b·dx + c·dy by least squares over the edge pixels of a window around it that lie on the
 * same edge (down or across the film, lit on the same side, as their neighbours say), all
 * weighing the same (light_edge.c says why), and the fit's a replaces the pixel's value when it
 * agrees with every pixel of the window within their noise: a reduced chi-square below
 * EDGE_CHI2. Windows
 * of radius 6, 4 and 2 are tried in turn, the first accepted kept: a long edge averages many
 * pixels. A corner, where no plane fits, and the dark pixels beside an edge, are given the share
 * of the pixel inside the light's edges taken as straight lines through the edge pixels' shares
 * (light_edge.c), weighed against the pixel's own emission, where the pixel and its neighbours
 * agree with those lines.
 *
 * The variances are the samples' s²/n (render/aov.h), which stratified and Sobol samples make an
 * overestimate: a light's edge crosses a pixel's strata, whose hits vary less than independent
 * rays' (the Cornell box: 2 times at 16 spp, 5 at 64; cornell-spheres' Sobol samples 8 to 20).
 * Their scale is measured over all the edge pixels of the image, as the halves' (A − B)²/4
 * (unbiased for any sampler, film.h) summed over the samples' s²/n summed, and the chi-square's
 * threshold and the variances returned are scaled by it.
 *
 * A pixel of a light's edge is one whose rays did not all see the same emission (its emission
 * variance is not 0) and that has a neighbour without emission: a light's rim, not the inside of
 * a textured light or of a sky seen behind the scene, whose variance is the texture's. So is an
 * unseen pixel: one that no ray of either half saw lit, with no emission and no variance, in a
 * run of at most two such pixels between two edge pixels of its row or column and at a depth
 * between theirs, which a convex light crosses (light_edge.c): a pixel of the edge whose few
 * chances to hit the light all missed. It joins the fits with its 0, and with the mean variance
 * of those two edge pixels, which no sample of its own measured. */
#ifndef MCRT_LIGHT_EDGE_H
#define MCRT_LIGHT_EDGE_H

/* em: the emission of each half, var: the variance of their mean, W·H·3 floats each (nfor.h);
 * depth: each half's depth feature, W·H floats, or NULL (then no pixel is taken as unseen, below).
 * Writes the emission to add back, (em[0] + em[1])/2 or its fit, into out and that value's
 * variance into out_var (W·H·3 floats each): var, scaled on the edge pixels (an unseen pixel's
 * taken from its neighbours), or where it is fitted the fit's variance, [(XᵀX)⁻¹]₀₀ times the
 * window's mean variance, scaled, or at a corner the variance of the blend of the lines' share
 * and the pixel's own.
 * Returns 0, or -1 when out of memory. */
int mc_light_edge_fit(const float *const em[2], const float *var, const float *const depth[2],
                      int width, int height, float *out, float *out_var);

#endif
