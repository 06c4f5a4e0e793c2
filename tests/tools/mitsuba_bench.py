#!/usr/bin/env python3
"""mitsuba_bench.py (make bench): the efficiency 1/(relMSE x CPU s) of mcrt against Mitsuba 3 on
the same scene at the same samples per pixel, one thread each.

  mitsuba_bench.py MCRT [--scene scenes/cornell.mcrt] [--size 256] [--spp 64] [--runs 3]
                   [--ref-spp 1024] [--cache DIR]

The scene's film is set to SIZE x SIZE and it is exported with `mcrt mitsuba`. The reference is an
mcrt render at REF_SPP (all cores), kept in DIR between runs; both renderers' relMSE is `mcrt diff`'s
against it, less the reference's own estimated relMSE (mcrt --stats; the expected squared error of
a difference is the sum of the two images' variances, plus the bias squared). mcrt runs with
--threads 1; Mitsuba (variant scalar_rgb, and llvm_ad_rgb as well when DRJIT_LIBLLVM_PATH names an
LLVM newer than 15) with drjit.set_thread_count(1), in this process, its scene loaded (and, for
llvm, its kernels compiled by a first render) before the clock starts. CPU seconds are user +
system time (the child's for mcrt, this process's for Mitsuba), the median of RUNS runs with seeds
0, 1, ...; relMSE is the mean over those runs. Runs are interleaved, so that the load of a shared
machine falls on both alike. Without Mitsuba it says how to install it and exits 0.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile


def relmse(mcrt, test, ref):
    out = subprocess.run([mcrt, "diff", test, ref], capture_output=True, text=True, check=True).stdout
    return float(re.search(r"relMSE ([0-9.e+-]+)", out).group(1))


def median(xs):
    s = sorted(xs)
    return s[len(s) // 2] if len(s) % 2 else 0.5 * (s[len(s) // 2 - 1] + s[len(s) // 2])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mcrt")
    ap.add_argument("--scene", default="scenes/cornell.mcrt")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--cache", default="build/bench")
    a = ap.parse_args()
    try:
        import drjit as dr
        import mitsuba as mi
    except ImportError:
        print("mitsuba_bench: Mitsuba 3 is not installed, so no efficiency ratio against it: "
              "pip install mitsuba (the scalar_rgb variant needs nothing else; llvm_ad_rgb needs "
              "DRJIT_LIBLLVM_PATH=/path/to/libLLVM.so of LLVM 16 or newer, such as the Rust "
              "toolchain's)")
        return 0
    variants = ["scalar_rgb"] + (["llvm_ad_rgb"] if os.environ.get("DRJIT_LIBLLVM_PATH") else [])
    name = os.path.splitext(os.path.basename(a.scene))[0]
    os.makedirs(a.cache, exist_ok=True)
    tmp = tempfile.mkdtemp()
    # The scene at SIZE x SIZE, in a copy of its folder so that its meshes resolve.
    shutil.copytree(os.path.dirname(os.path.abspath(a.scene)), os.path.join(tmp, "scene"))
    with open(a.scene) as f:
        text = f.read()
    text = re.sub(r"(?m)^film\s*\{[^}]*\}", "", text)
    sized = os.path.join(tmp, "scene", name + ".bench.mcrt")
    with open(sized, "w") as f:
        f.write("film { width %d height %d spp %d }\n%s" % (a.size, a.size, a.spp, text))
    try:
        xml = os.path.join(tmp, name + ".xml")
        subprocess.run([a.mcrt, "mitsuba", sized, "-o", xml], check=True)
        ref = os.path.join(a.cache, "%s-%d-ref%d.exr" % (name, a.size, a.ref_spp))
        ref_stats = ref + ".json"
        if not (os.path.exists(ref) and os.path.exists(ref_stats)):
            print("mitsuba_bench: making the reference (%d spp, once; kept in %s)" % (a.ref_spp, ref))
            subprocess.run([a.mcrt, "--quiet", "--spp", str(a.ref_spp), "--seed", "999",
                            "--stats", ref_stats, "-o", ref, sized], check=True)
        with open(ref_stats) as f:
            ref_err = float(json.load(f)["est_relmse"])
        scenes = {}
        threads = dr.thread_count()  # restored outside the timed renders: with 1, writing an
        for v in variants:           # EXR (OpenEXR's own threads) does not return
            mi.set_variant(v)
            scenes[v] = mi.load_file(xml)
            mi.render(scenes[v], spp=1)  # llvm: compile the kernels outside the clock
        cpu = {k: [] for k in ["mcrt"] + variants}
        err = {k: [] for k in ["mcrt"] + variants}
        for run in range(a.runs):
            out = os.path.join(tmp, "mcrt.exr")
            t0 = os.times()
            subprocess.run([a.mcrt, "--quiet", "--threads", "1", "--seed", str(run), "-o", out, sized],
                           check=True)
            t1 = os.times()
            cpu["mcrt"].append((t1.children_user - t0.children_user) + (t1.children_system - t0.children_system))
            err["mcrt"].append(relmse(a.mcrt, out, ref))
            for v in variants:
                mi.set_variant(v)
                dr.set_thread_count(1)
                t0 = os.times()
                img = mi.render(scenes[v], seed=run, spp=a.spp)
                dr.eval(img)
                t1 = os.times()
                dr.set_thread_count(threads)
                cpu[v].append((t1.user - t0.user) + (t1.system - t0.system))
                out = os.path.join(tmp, v + ".exr")
                mi.Bitmap(img).write(out)
                err[v].append(relmse(a.mcrt, out, ref))
    finally:
        shutil.rmtree(tmp)
    print("efficiency 1/(relMSE x CPU s) on %s, %dx%d, %d spp, one thread each, %d runs "
          "(relMSE against an mcrt %d spp reference, its own %.3g taken off):"
          % (name, a.size, a.size, a.spp, a.runs, a.ref_spp, ref_err))
    eff = {}
    for k in ["mcrt"] + variants:
        e = sum(err[k]) / len(err[k]) - ref_err
        c = median(cpu[k])
        eff[k] = 1.0 / (e * c)
        print("  %-22s relMSE %.4g  CPU %.2f s  efficiency %.4g" % (k if k == "mcrt" else "Mitsuba " + k, e, c, eff[k]))
    for v in variants:
        print("  mcrt / Mitsuba %-12s %.2fx (relMSE %.2fx lower, CPU time %.2fx)"
              % (v, eff["mcrt"] / eff[v], (sum(err[v]) / len(err[v]) - ref_err) / (sum(err["mcrt"]) / len(err["mcrt"]) - ref_err),
                 median(cpu[v]) / median(cpu["mcrt"])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
