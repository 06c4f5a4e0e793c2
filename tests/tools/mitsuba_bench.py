#!/usr/bin/env python3
"""mitsuba_bench.py (make bench): the efficiency 1/(relMSE x CPU s) of mcrt against Mitsuba 3 on
the same scenes at the same samples per pixel, one thread each.

  mitsuba_bench.py MCRT [--scene S.mcrt [--scene ...]] [--size 256] [--spp 64] [--runs 3]
                   [--ref-spp 1024] [--cache DIR]

Each scene (default scenes/cornell.mcrt) has its film set to SIZE x SIZE and is exported with
`mcrt mitsuba`. The reference is an mcrt render at REF_SPP (all cores), kept in DIR between runs
(named by a hash of the scene's text);
both renderers' relMSE is `mcrt diff`'s against it, less the reference's own estimated relMSE
(mcrt --stats; the expected squared error of a difference is the sum of the two images'
variances, plus the bias squared). mcrt runs with --threads 1; Mitsuba (variant scalar_rgb, and
llvm_ad_rgb as well when DRJIT_LIBLLVM_PATH names an LLVM newer than 15) with
drjit.set_thread_count(1), in this process, its scene loaded (and, for llvm, its kernels compiled
by a first render) before the clock starts. CPU seconds are user + system time (the child's for
mcrt, this process's for Mitsuba), the median of RUNS runs with seeds 0, 1, ...; mcrt's are the
render's alone like Mitsuba's: the CPU time of a one-pixel, one-sample render of the same scene
(loading, BVH and light tree), the median of RUNS, is taken off. relMSE is the mean over the
runs. Runs are interleaved, so that the load of a shared machine falls on both alike. A table of
every scene's ratios ends the output, beside issue 19's targets (2x on the Cornell box, 1.5x on
the others). Without Mitsuba it says how to install it and exits 0.
"""
import argparse
import hashlib
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


# Issue 19's targets for mcrt's efficiency over Mitsuba's, by scene name; 1.5x for any other.
TARGETS = {"cornell": 2.0}


def child_cpu(cmd):
    """The CPU seconds (user + system) of running cmd."""
    t0 = os.times()
    subprocess.run(cmd, check=True)
    t1 = os.times()
    return (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system)


def bench(a, dr, mi, variants, scene, tmp):
    """One scene's table; returns {variant: (ratio, relMSE ratio, CPU ratio)} and mcrt's row."""
    name = os.path.splitext(os.path.basename(scene))[0]
    # The scene at SIZE x SIZE, in a copy of its folder so that its meshes resolve.
    folder = os.path.join(tmp, name)
    shutil.copytree(os.path.dirname(os.path.abspath(scene)), folder)
    with open(scene) as f:
        text = f.read()
    text = re.sub(r"(?m)^film\s*\{[^}]*\}", "", text)
    sized = os.path.join(folder, name + ".bench.mcrt")
    with open(sized, "w") as f:
        f.write("film { width %d height %d spp %d }\n%s" % (a.size, a.size, a.spp, text))
    xml = os.path.join(folder, name + ".xml")
    subprocess.run([a.mcrt, "mitsuba", sized, "-o", xml], check=True)
    # Named by the scene's text too, so that a changed scene gets a new reference.
    tag = hashlib.sha1(text.encode()).hexdigest()[:10]
    ref = os.path.join(a.cache, "%s-%d-ref%d-%s.exr" % (name, a.size, a.ref_spp, tag))
    ref_stats = ref + ".json"
    if not (os.path.exists(ref) and os.path.exists(ref_stats)):
        print("mitsuba_bench: making the reference of %s (%d spp, once; kept in %s)" % (name, a.ref_spp, ref))
        sys.stdout.flush()
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
    setup = []
    for run in range(a.runs):
        out = os.path.join(tmp, "mcrt.exr")
        setup.append(child_cpu([a.mcrt, "--quiet", "--threads", "1", "--spp", "1", "--crop", "0,0,1,1",
                                "-o", out, sized]))
        cpu["mcrt"].append(child_cpu([a.mcrt, "--quiet", "--threads", "1", "--seed", str(run), "-o", out,
                                      sized]))
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
    del scenes
    shutil.rmtree(folder)
    print("efficiency 1/(relMSE x CPU s) on %s, %dx%d, %d spp, one thread each, %d runs "
          "(relMSE against an mcrt %d spp reference, its own %.3g taken off; mcrt's set-up, "
          "%.2f CPU s, taken off its time):"
          % (name, a.size, a.size, a.spp, a.runs, a.ref_spp, ref_err, median(setup)))
    e, c, eff = {}, {}, {}
    for k in ["mcrt"] + variants:
        e[k] = sum(err[k]) / len(err[k]) - ref_err
        c[k] = median(cpu[k]) - (median(setup) if k == "mcrt" else 0.0)
        eff[k] = 1.0 / (e[k] * c[k])
        print("  %-22s relMSE %.4g  CPU %.2f s  efficiency %.4g"
              % (k if k == "mcrt" else "Mitsuba " + k, e[k], c[k], eff[k]))
    ratios = {}
    for v in variants:
        ratios[v] = (eff["mcrt"] / eff[v], e[v] / e["mcrt"], c[v] / c["mcrt"])
        print("  mcrt / Mitsuba %-12s %.2fx (relMSE %.2fx lower, CPU time %.2fx)" % ((v,) + ratios[v]))
    sys.stdout.flush()
    return name, ratios


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mcrt")
    ap.add_argument("--scene", action="append")
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
    os.makedirs(a.cache, exist_ok=True)
    tmp = tempfile.mkdtemp()
    rows = []
    try:
        for scene in a.scene or ["scenes/cornell.mcrt"]:
            rows.append(bench(a, dr, mi, variants, scene, tmp))
    finally:
        shutil.rmtree(tmp)
    print("mcrt's efficiency / Mitsuba's (issue 19's target; met or not):")
    print("  %-14s %s" % ("scene", "".join("%-24s" % v for v in variants)))
    for name, ratios in rows:
        target = TARGETS.get(name, 1.5)
        print("  %-14s %s" % (name, "".join("%-24s" % ("%.2fx (%.1fx %s)" % (ratios[v][0], target,
                                                       "met" if ratios[v][0] >= target else "not met"))
                                            for v in variants)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
