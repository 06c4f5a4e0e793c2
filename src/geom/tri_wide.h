/* tri_wide.h: the SIMD watertight test of 4 or 8 triangles or quads, written once for both vector
 * widths. Private to src/geom/bvh.c, which includes it once per width with these defined (this
 * file undefines them at its end, ready for the next width; hence no include guard):
 *   TRI_TEST     the function's name
 *   TRI_TARGET   its target attribute (empty, or AVX2's under run-time dispatch)
 *   TRI_LANES    the member of struct tri_ray with the ray's broadcasts at this width: o[3] (the
 *                origin in the permuted axis order kx, ky, kz) and the shear sx, sy, sz
 *   VF, VI       the float and the 32-bit integer vector of the width
 *   VOP(op)      the intrinsic of op (add, sub, mul, div, max, and, or, xor, andnot, set1,
 *                setzero, movemask, storeu) at this width
 *   V_LOAD(k, vertex, axis)  lanes of that coordinate: block k's, or blocks k and k + 1's
 *   V_PRIM(k)    the lanes' prim words (tri4.h)
 *   V_EQ, V_GT, V_LT, V_UNORD  the ordered comparisons == > <, and "either is NaN"
 *   V_CAST_FI(x), V_SIGN_FILL(x)  an integer vector as floats; every lane's sign bit spread
 *                over the lane
 * Lane l of the result is lane l & 3 of block k + (l >> 2). */

/* The watertight test of Woop, Benthin and Wald (prim.c's intersect_triangle) on all lanes at once:
 * the same float operations in the same order, so every lane it decides gets bitwise the scalar
 * answer. It leaves undecided the lanes where the scalar test would do more than this: an edge
 * function exactly 0 (recomputed in double there) and a NaN determinant (the NaN lanes of
 * tri4.h, which are not triangles or are degenerate ones, and non-finite input). A lane that
 * survives every rejection and would reach the scalar degenerate() check is a triangle that
 * tri4.c found not degenerate, so the check would pass. */
static MC_ALWAYS_INLINE TRI_TARGET void TRI_TEST(const struct tri4 *k, const struct tri_ray *ray,
                                                 float tmax, unsigned live,
                                                 struct tri_result *out)
{
    const VF zero = VOP(setzero)();
    const int kx = ray->q.kx, ky = ray->q.ky, kz = ray->q.kz;
    const VF *o = ray->TRI_LANES.o, sx = ray->TRI_LANES.sx, sy = ray->TRI_LANES.sy,
             sz = ray->TRI_LANES.sz;
    VF az = VOP(sub)(V_LOAD(k, 0, kz), o[2]);
    VF bz = VOP(sub)(V_LOAD(k, 1, kz), o[2]);
    VF cz = VOP(sub)(V_LOAD(k, 2, kz), o[2]);
    VF ax = VOP(add)(VOP(sub)(V_LOAD(k, 0, kx), o[0]), VOP(mul)(sx, az));
    VF ay = VOP(add)(VOP(sub)(V_LOAD(k, 0, ky), o[1]), VOP(mul)(sy, az));
    VF bx = VOP(add)(VOP(sub)(V_LOAD(k, 1, kx), o[0]), VOP(mul)(sx, bz));
    VF by = VOP(add)(VOP(sub)(V_LOAD(k, 1, ky), o[1]), VOP(mul)(sy, bz));
    VF cx = VOP(add)(VOP(sub)(V_LOAD(k, 2, kx), o[0]), VOP(mul)(sx, cz));
    VF cy = VOP(add)(VOP(sub)(V_LOAD(k, 2, ky), o[1]), VOP(mul)(sy, cz));
    VF e0 = VOP(sub)(VOP(mul)(bx, cy), VOP(mul)(by, cx));
    VF e1 = VOP(sub)(VOP(mul)(cx, ay), VOP(mul)(cy, ax));
    VF e2 = VOP(sub)(VOP(mul)(ax, by), VOP(mul)(ay, bx));
    VF det = VOP(add)(VOP(add)(e0, e1), e2);
    VF zs[3] = {VOP(mul)(sz, az), VOP(mul)(sz, bz), VOP(mul)(sz, cz)};
    VF ts = VOP(add)(VOP(add)(VOP(mul)(e0, zs[0]), VOP(mul)(e1, zs[1])), VOP(mul)(e2, zs[2]));
    VF undecided = VOP(or)(VOP(or)(V_EQ(e0, zero), V_EQ(e1, zero)),
                           VOP(or)(V_EQ(e2, zero), V_UNORD(det, det)));
    const VF sign = VOP(set1)(-0.0f);
    const VI prim = V_PRIM(k);
    /* Outside the triangle: edge functions of both signs. The lanes decided here have no edge
     * function zero or NaN, so that is a sign bit of e0 ^ e1 or e0 ^ e2 (three operations where
     * comparing each with zero took eleven), and their det, a sum of three nonzero terms of one
     * sign, is not 0. A test with quads (prim[lane] with MC_TRI4_QUAD; a triangle-only one skips
     * this) rejects its quad lanes instead where det is 0, or e1 or e2 is of the other sign than
     * det or larger than |det|: s or t outside [0, 1] (mc_watertight_intersect). Only sign bits
     * of `shape` are read, as of the rest of `reject`. */
    VF shape = VOP(or)(VOP(xor)(e0, e1), VOP(xor)(e0, e2)), reject;
    unsigned und, cand;
    if ((unsigned)VOP(movemask)(V_CAST_FI(prim)) & live) {
        VF quad = V_SIGN_FILL(prim), adet = VOP(andnot)(sign, det);
        VF outside = VOP(or)(VOP(or)(VOP(xor)(e1, det), VOP(xor)(e2, det)),
                             VOP(or)(V_GT(VOP(andnot)(sign, e1), adet),
                                     V_GT(VOP(andnot)(sign, e2), adet)));
        outside = VOP(or)(outside, V_EQ(det, zero));
        shape = VOP(or)(VOP(and)(quad, outside), VOP(andnot)(quad, shape));
    }
    /* Rejected: outside the shape; ts = 0 or of the other sign than det (the sign bit of
     * det ^ ts). */
    reject = VOP(or)(VOP(or)(shape, VOP(xor)(det, ts)), V_EQ(ts, zero));
    und = (unsigned)VOP(movemask)(undecided) & live;
    cand = live & ~und & ~(unsigned)VOP(movemask)(reject);
    out->undecided = und;
    out->hit = 0;
    if (cand) {
        /* t must exceed mc_tri_t_error's bound (prim.h), computed in the same operations. */
        const VF g2 = VOP(set1)(MC_GAMMA(2)), g3 = VOP(set1)(MC_GAMMA(3)),
                 g5 = VOP(set1)(MC_GAMMA(5));
        VF t = VOP(div)(ts, det);
        VF mx = VOP(max)(VOP(max)(VOP(andnot)(sign, ax), VOP(andnot)(sign, bx)),
                         VOP(andnot)(sign, cx));
        VF my = VOP(max)(VOP(max)(VOP(andnot)(sign, ay), VOP(andnot)(sign, by)),
                         VOP(andnot)(sign, cy));
        VF mz = VOP(max)(VOP(max)(VOP(andnot)(sign, zs[0]), VOP(andnot)(sign, zs[1])),
                         VOP(andnot)(sign, zs[2]));
        VF me = VOP(max)(VOP(max)(VOP(andnot)(sign, e0), VOP(andnot)(sign, e1)),
                         VOP(andnot)(sign, e2));
        VF dz = VOP(mul)(g3, mz);
        VF dx = VOP(mul)(g5, VOP(add)(mx, mz));
        VF dy = VOP(mul)(g5, VOP(add)(my, mz));
        VF de = VOP(mul)(VOP(set1)(2.0f),
                         VOP(add)(VOP(add)(VOP(mul)(VOP(mul)(g2, mx), my), VOP(mul)(dy, mx)),
                                  VOP(mul)(dx, my)));
        VF dt = VOP(div)(VOP(mul)(VOP(set1)(3.0f),
                                  VOP(add)(VOP(add)(VOP(mul)(VOP(mul)(g3, me), mz),
                                                    VOP(mul)(de, mz)),
                                           VOP(mul)(dz, me))),
                         VOP(andnot)(sign, det));
        cand &= (unsigned)VOP(movemask)(VOP(and)(V_GT(t, dt), V_LT(t, VOP(set1)(tmax))));
        out->hit = cand;
        VOP(storeu)(out->t, t);
        VOP(storeu)(out->e1, e1);
        VOP(storeu)(out->e2, e2);
        VOP(storeu)(out->det, det);
    }
}

#undef TRI_TEST
#undef TRI_TARGET
#undef TRI_LANES
#undef VF
#undef VI
#undef VOP
#undef V_LOAD
#undef V_PRIM
#undef V_EQ
#undef V_GT
#undef V_LT
#undef V_UNORD
#undef V_CAST_FI
#undef V_SIGN_FILL
