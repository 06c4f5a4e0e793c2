#!/usr/bin/env python3
"""mitsuba_render.py: render a scene written by `mcrt mitsuba` with Mitsuba 3 (variant scalar_rgb).

  mitsuba_render.py SCENE.xml OUT.exr [--spp N] [--renders K] [--threads T] [--seed S]
                    [--variance VAR.exr [--add-variance MCRT.exr [--blocks N PREFIX]]]
                    [--time TIME.txt] [--independent]

K renders with seeds S, S+1, ... are averaged into OUT.exr; with --variance, the variance of that
mean per pixel and channel (the renders' sample variance / K, K >= 2) goes to VAR.exr, the
reference's own noise for `mcrt diff`. --add-variance adds the variance layer of an mcrt render of
the same scene (`mcrt --aov variance`) into VAR.exr, the variance of the two images' difference,
and prints 4 standard errors of the mean of that difference over the pixels and channels (the
square root of the summed variances over their count): `mcrt diff --max-bias`'s bound. --blocks
also writes the means over blocks of N x N pixels of the mcrt image, of OUT and of the variance
(the block's summed variance / N^4: pixels are independent) to PREFIX-mcrt.exr, PREFIX-mitsuba.exr
and PREFIX-var.exr, for a z-test whose means average N^2 times the samples. --time writes the CPU seconds of the renders (the
process's user + system time spent in mi.render, scene loading excluded). --threads 1 renders on
one thread (drjit.set_thread_count; Mitsuba's scalar variants then trace one ray at a time).
--independent renders with Mitsuba's independent sampler whatever the scene names: its stratified
sampler is biased at the few samples per render the variance estimate splits a render into.
"""
import argparse
import os
import re
import sys
import time


def blocks(mi, t, n, scale):
    """The sums over n x n blocks of tensor t (height, width, 3), times scale."""
    h, w = t.shape[0] // n, t.shape[1] // n
    a, width, out = t.array, t.shape[1], [0.0] * (w * h * 3)
    for y in range(h * n):
        for x in range(w * n):
            i, j = (y * width + x) * 3, ((y // n) * w + x // n) * 3
            for c in range(3):
                out[j + c] += a[i + c]
    return mi.TensorXf([v * scale for v in out], shape=(h, w, 3))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--spp", type=int, default=0)
    ap.add_argument("--renders", type=int, default=1)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--variance")
    ap.add_argument("--add-variance")
    ap.add_argument("--blocks", nargs=2, metavar=("N", "PREFIX"))
    ap.add_argument("--time")
    ap.add_argument("--independent", action="store_true")
    a = ap.parse_args()
    try:
        import drjit as dr
        import mitsuba as mi
    except ImportError:
        sys.stderr.write("mitsuba_render.py: Mitsuba 3 is not installed (pip install mitsuba)\n")
        return 3
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Error)  # stdout carries the bias bound
    if a.threads > 0:
        dr.set_thread_count(a.threads)
    if a.independent:
        # Mitsuba's stratified sampler at a few samples per render is biased: cornell 256^2,
        # 16 renders of 4 spp, green +1.1% (0.12990 against 0.12854 independent, se 1e-4;
        # mcrt 0.12847), though it agrees at 64 spp. A copy of the scene beside it (its meshes
        # resolve the same) with the independent sampler, whose renders' spread is also exactly
        # the variance the --variance estimate assumes.
        with open(a.scene) as f:
            text = re.sub(r'<sampler type="[a-z]+">', '<sampler type="independent">', f.read())
        path = a.scene + ".independent.xml"
        with open(path, "w") as f:
            f.write(text)
        scene = mi.load_file(path)
        os.remove(path)
    else:
        scene = mi.load_file(a.scene)
    total = None
    total2 = None
    cpu = 0.0
    for k in range(a.renders):
        t0 = os.times()
        img = mi.render(scene, seed=a.seed + k, spp=a.spp)
        t1 = os.times()
        cpu += (t1.user - t0.user) + (t1.system - t0.system)
        x = mi.TensorXf(img)
        total = x if total is None else total + x
        total2 = x * x if total2 is None else total2 + x * x
    n = a.renders
    mean = total / n  # float32 sums: K renders of values near 1 lose nothing that matters
    mi.Bitmap(mean).write(a.out)
    if a.variance:
        if n < 2:
            sys.stderr.write("mitsuba_render.py: --variance needs --renders 2 or more\n")
            return 2
        var = dr.maximum((total2 - n * mean * mean) / (n - 1) / n, 0.0)
        if a.add_variance:
            layers = dict(mi.Bitmap(a.add_variance).split())
            if "variance" not in layers:
                sys.stderr.write("mitsuba_render.py: %s has no variance layer\n" % a.add_variance)
                return 2
            var = var + mi.TensorXf(layers["variance"])
            print("%.4g" % (4.0 * dr.sqrt(dr.sum(var.array)) / len(var.array)))
            if a.blocks:
                n, prefix = int(a.blocks[0]), a.blocks[1]
                mc = mi.TensorXf(layers["<root>"])
                mi.Bitmap(blocks(mi, mc, n, 1.0 / n ** 2)).write(prefix + "-mcrt.exr")
                mi.Bitmap(blocks(mi, mean, n, 1.0 / n ** 2)).write(prefix + "-mitsuba.exr")
                mi.Bitmap(blocks(mi, var, n, 1.0 / n ** 4)).write(prefix + "-var.exr")
        mi.Bitmap(var).write(a.variance)
    if a.time:
        with open(a.time, "w") as f:
            f.write("%.3f\n" % cpu)
    return 0


if __name__ == "__main__":
    sys.exit(main())
