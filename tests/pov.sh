#!/bin/sh
# pov.sh: the POV-Ray references (ref/, made by `make ref`) against today's exporter. Every case
# tests/pov/NAME.mcrt has ref/NAME.pov and ref/NAME.exr, and ref/NAME.pov is byte for byte what
# `mcrt pov` writes now, so a reference never silently drifts from its scene; scenes POV-Ray cannot
# reproduce are refused (exit 2, one line naming the feature, no file written).
# Run from the repository root after the build; $O is the build folder. Prints "ok ..." or
# "FAIL ...: why" per check, then "N passed, N failed"; exits 1 if any failed.
. tests/harness.sh.inc

# ---- every case has a reference, and the reference is today's export ----
n=0
for scene in tests/pov/*.mcrt; do
    name=$(basename "$scene" .mcrt)
    n=$((n + 1))
    if [ ! -f "ref/$name.pov" ] || [ ! -f "ref/$name.exr" ]; then
        fail "$name" "ref/$name.pov or ref/$name.exr is missing (run make ref)"
    elif ! "$MCRT" pov "$scene" -o "$tmp/$name.pov" 2>"$tmp/err"; then
        fail "$name" "mcrt pov failed: $(cat "$tmp/err")"
    elif cmp -s "$tmp/$name.pov" "ref/$name.pov"; then
        ok "ref/$name.pov is what mcrt pov exports from $scene"
    else
        fail "$name" "ref/$name.pov differs from today's export (run make ref):
$(diff "ref/$name.pov" "$tmp/$name.pov" | head -n 10)"
    fi
done
if [ "$n" -ge 12 ]; then ok "$n reference cases"; else fail "cases" "only $n in tests/pov"; fi
for pov in ref/*.pov; do
    [ -f "tests/pov/$(basename "$pov" .pov).mcrt" ] || fail "$pov" "no tests/pov case exports it"
done
if [ -s ref/POVRAY_VERSION ]; then ok "ref/POVRAY_VERSION: $(cat ref/POVRAY_VERSION)"
else fail "ref/POVRAY_VERSION" "missing or empty"; fi

# ---- refusals ----
# refuse NAME REGEX SCENE-TEXT: mcrt pov exits 2 with one line on stderr matching REGEX, and
# writes no file.
refuse() {
    printf '%s\n' "$3" >"$tmp/r.mcrt"
    rm -f "$tmp/r.pov"
    "$MCRT" pov "$tmp/r.mcrt" -o "$tmp/r.pov" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -ne 2 ]; then fail "refuses $1" "exit $rc, expected 2"
    elif [ "$(wc -l <"$tmp/err")" -ne 1 ] || ! grep -Eq -- "$2" "$tmp/err"; then
        fail "refuses $1" "message '$(cat "$tmp/err")' does not match /$2/"
    elif [ -e "$tmp/r.pov" ] || ls "$tmp" | grep -q 'r.pov.tmp'; then
        fail "refuses $1" "a file was written"
    else ok "refuses $1: $(cat "$tmp/err")"; fi
}
lit='point_light { position 0 3 3 }'
refuse "metal" "material 'm'.*glossy metal" \
    "material m { metal 0.9 roughness 0.3 } sphere { material m } $lit"
refuse "smooth metal" "glossy metal" "material m { metal 0.9 } sphere { material m } $lit"
refuse "plastic" "glossy plastic" "material m { plastic 0.5 } sphere { material m } $lit"
refuse "rough glass" "rough glass" \
    "material m { glass roughness 0.2 } sphere { material m } $lit"
refuse "tinted glass" "tinted glass" \
    "material m { glass tint 0.9 0.5 0.5 } sphere { material m } $lit"
refuse "glass on a quad" "glass on a quad" "material m { glass } quad { material m } $lit"
refuse "an environment" "environment" "environment { radiance 1 } sphere { }"
refuse "the default sky" "environment" "sphere { }"
refuse "an emitting disk" "emitting disk" "disk { emit 1 } sphere { center 0 0 -3 }"
refuse "an emitting triangle" "emitting triangle" "triangle { emit 1 } sphere { center 0 0 -3 }"
refuse "a two-sided emitter" "two_sided" "quad { emit 1 two_sided } sphere { center 0 0 -3 }"
refuse "spin" "spin" \
    "mesh { file \"$(pwd)/scenes/cube.obj\" spin 0 1 0 90 } $lit"
refuse "smooth normals" "smooth-shaded" "mesh { file \"$(pwd)/scenes/icosphere.obj\" } $lit"
refuse "a mirror with an area light" "light -> specular -> diffuse" \
    "material m { mirror 1 } quad { material m } sphere { center 0 0 -3 } quad { corner -1 3 -1 edge1 2 0 0 edge2 0 0 2 emit 1 }"
refuse "glass with an area light, direct lighting" "mirror or glass with area lights" \
    "integrator { method direct } material m { glass } sphere { material m } sphere { center 0 3 0 radius 0.2 emit 1 }"
refuse "max_depth 0" "max_depth 0" "integrator { max_depth 0 } sphere { } $lit"
refuse "a textured sphere" "r.mcrt:1:48: .*texture of material 'm'.*quad" \
    "texture c { checker 0 1 } material m { diffuse texture c } sphere { material m } $lit"
refuse "a textured mirror" "texture of material 'm'.*diffuse" \
    "texture c { checker 0 1 } material m { mirror texture c } quad { material m } $lit"
printf 'film { width 2 height 2 spp 1 } quad { corner -9 -9 0 edge1 18 0 0 edge2 0 18 0 } %s\n' \
    "$lit" >"$tmp/pfm.mcrt"
"$MCRT" --quiet -o "$tmp/t.pfm" "$tmp/pfm.mcrt" # a PFM of values in [0, 1]: a dimly lit wall
refuse "a PFM texture" "PNG and EXR" \
    "texture c { image \"$tmp/t.pfm\" } material m { diffuse texture c } quad { material m } $lit"
"$MCRT" pov "$tmp/missing.mcrt" -o "$tmp/m.pov" 2>"$tmp/err"
rc=$?
if [ "$rc" -eq 2 ] && [ ! -e "$tmp/m.pov" ]; then ok "a missing scene exits 2"
else fail "a missing scene" "exit $rc"; fi

# ---- images against the references ----
# render_diff NAME SPP FLOOR BIAS SCENE [CROP]: render SCENE at SPP samples per pixel with its
# variance layer, then `mcrt diff --variance` against ref/NAME.exr: the per-pixel z-test
# (z = |mcrt - ref| / sqrt(var + FLOOR^2), Sidak-corrected alpha 0.01 over all pixels, at least
# 99.75% of pixels agreeing) and |mean(mcrt - ref)| <= BIAS, over the window CROP (x0,y0,x1,y1)
# if given. Sets $diff_rc (0 pass, 1 fail, 2 bad input); the output is in $tmp/diff.out. The
# random sampler: a per-pixel z-test needs a variance of many degrees of freedom, which only
# independent samples give (n - 1); a stratified or Sobol render's variance layer is unbiased too
# but has one per pixel (its two halves, src/render/film.h), and z would be Student's t with one.
render_diff() {
    "$MCRT" "$5" --spp "$2" --sampler random --aov variance -o "$tmp/$1.exr" --quiet 2>"$tmp/err" ||
        { diff_rc=2; return; }
    "$MCRT" diff "$tmp/$1.exr" "ref/$1.exr" --variance "$tmp/$1.exr" --floor "$3" \
        --max-bias "$4" ${6:+--crop "$6"} >"$tmp/diff.out" 2>&1
    diff_rc=$?
}
# diff_case NAME SPP FLOOR BIAS [CROP]: case NAME matches its reference.
diff_case() {
    render_diff "$1" "$2" "$3" "$4" "tests/pov/$1.mcrt" "$5"
    if [ "$diff_rc" -eq 0 ]; then ok "$1 matches POV-Ray: $(grep z-test "$tmp/diff.out")"
    else fail "$1 against ref/$1.exr" "$(cat "$tmp/err" "$tmp/diff.out")"; fi
}
# must_fail NAME SPP FLOOR BIAS SCENE-TEXT WHAT: a deliberately wrong variant of case NAME fails
# the same diff, so that the diff has the power to see the error WHAT.
must_fail() {
    printf '%s\n' "$5" >"$tmp/broken.mcrt"
    render_diff "$1" "$2" "$3" "$4" "$tmp/broken.mcrt"
    if [ "$diff_rc" -eq 1 ]; then ok "$1 with $6 fails the diff"
    else fail "$1 with $6" "diff exit $diff_rc, expected 1: $(cat "$tmp/err" "$tmp/diff.out")"; fi
}

# The reference's own errors (povray-mapping.md, measured there): EXR half floats round to 2^-11
# = 4.9e-4 relative; the 16x16 quad-light grid is off by <= 0.09% and its jitter leaves ~0.1% rms
# in penumbrae (measured at R4; the references are R5, with 3x more subsamples, so this is an
# upper bound); a sphere light is low by 0.75 (R/d)^2; K = 64 clock frames miss the time integral
# by <= 1/K of the moving contrast (0.4/K on average); radiosity (see the GI cases). FLOOR is the
# largest of these per pixel, in the case's radiance units (its brightest lit surface, Lmax); hard
# edges (R5: 0.0036 of the edge contrast) touch few pixels and are left to the 0.25% of pixels
# allowed to disagree. BIAS is 3 sigma of mcrt's image mean (from the variance layer, under 0.06%
# for every case here) plus the reference's known mean error, rounded up, so that a 1% error in a
# light or an albedo (a mean shift of 1%) fails.
# Point light, hard shadows. Lmax 0.32: half floats 1.6e-4. Mean 0.076: BIAS 0.2% (1.5e-4).
diff_case point-shadows 64 0.0002 0.00015
# Pinhole framing, many edges. Lmax 0.26: 1.3e-4, 1.5e-4 for the edges at R5 (rms 0.0015 of a
# contrast of 0.1). Mean 0.048: BIAS 0.2%.
diff_case framing 64 0.00015 0.0001
# Quad light, soft shadows. Lmax 0.38: half floats, grid 0.09% and jitter 0.1%, in quadrature
# 0.14%: 5.5e-4. BIAS: mcrt's mean is 0.24% above POV-Ray's (measured: 0.040151, its three
# samplers agreeing within 1e-5 over 14 renders), plus 3 sigma of a random-sampler 64-spp mean
# (1.86e-5 over 6 seeds): 1.52e-4, rounded up to 0.4% of the mean 0.040.
diff_case quad-light 64 0.00055 0.00016
# Sphere light R = 0.1 at >= 1.75 from lit surfaces: POV-Ray's disc is low by <= 0.75 (R/d)^2 =
# 0.24% at the ball's top (Lmax 0.21): 5e-4, with jitter 2e-4 and half floats: 6e-4. The visible
# light (radiance 80, rows 1-6) has a huge variance at its rim, so the test window starts at row 16.
# BIAS: mean bias <= 0.25% x 0.1 + 3 sigma: 3e-4.
diff_case sphere-light 64 0.0006 0.0003 0,16,128,96
# Thin lens (all three spheres out of focus). Lmax 0.32: 1.6e-4; the lens-radius fit of the note
# (0.25 +- 0.003 of the aperture, i.e. +-1.2% of the blur radius) moves a blurred edge by < 0.1 px:
# 3e-4 in quadrature. BIAS 0.3% of 0.071: POV-Ray's lens is a fixed pattern of 100 points, and
# the image mean came out 0.2% above mcrt's (3 sigma of mcrt's mean: 0.06%).
diff_case dof 256 0.0003 0.00021
# Mirror (reflectance exact at every angle). Lmax 0.46: 2.3e-4. BIAS 0.2% of 0.097.
diff_case mirror 64 0.00025 0.0002
# Glass sphere (Fresnel to 4.5e-4 relative, refraction first-order to 2e-4). Lmax 1.5 (the
# backdrop under the light): 7.4e-4. BIAS 0.2% of 0.098.
diff_case glass 128 0.00075 0.0002
# Motion blur, 64 clock frames: <= 1/64 of the moving contrast (0.19) at the moving edges, 0.4/64
# on average: 1.2e-3. BIAS 0.2% of 0.06 (the frame error averages out over the image).
diff_case motion 128 0.0012 0.00012
# Checker at grazing angles: nearly every pixel holds tile edges, so the R5 edge error (rms 0.0015
# of a contrast of 0.37) applies everywhere: 6e-4 (half floats: 2.1e-4). BIAS 0.3% of 0.11.
diff_case checker 64 0.0006 0.0003
# Two coloured point lights, a quad light and a sphere light (R 0.08 at >= 15 radii: low by
# <= 0.33%). Lmax ~0.3: half floats 1.5e-4, quad grid and jitter 0.14% (4.2e-4), the sphere
# light's 0.33% of its third of the light (3.3e-4): 5.5e-4 in quadrature. The visible sphere
# light (rows 13-17) is left out of the window, as in sphere-light. BIAS 0.3% of the mean 0.13.
diff_case multi-light 128 0.00055 0.0004 0,24,128,96
# GI in a closed box and a Cornell-like box: POV-Ray's radiosity at the finest measured settings
# (mapping note, section 3: 0.00% mean in a closed sphere; the note's default settings made these
# two cases 1.2% and 1.75% too bright). The reference's own error, measured against two 256-spp
# mcrt renders (seeds 11, 12) as the excess of the residual variance over mcrt's own: gi-box mean
# +5.6e-4 (0.21% of its mean 0.265), rms 5.0e-4 about it; cornell mean +1.44e-3 (0.88% of 0.163),
# rms 2.2e-3 about it, most of it a few corner pixels where POV-Ray's irradiance cache is up to 30%
# dark (left to the 0.25% allowance). FLOOR is the reference's rms error including its mean:
# gi-box 7.5e-4, cornell 2.6e-3; BIAS its mean error plus 3 sigma of mcrt's mean (1.6e-4, 1e-4):
# gi-box 7.5e-4 (0.28%), cornell 1.6e-3 (1%).
diff_case gi-box 256 0.00075 0.00075
diff_case cornell 256 0.0026 0.0016
# Textures (POV-Ray's image_map with interpolate 2, and checker, carried onto the quad by a
# matrix: src/export/pov.c). An image magnified to ~8 pixels a texel under a point light: Lmax
# 0.31, half floats 1.6e-4, hard edges (the quads' outlines, R5) to the 0.25%; FLOOR 3e-4.
# BIAS 0.3% of the mean 0.059 (measured -1.1e-5 to -1.6e-5 over 3 seeds). The checker: Lmax
# 0.32, half floats 1.6e-4 and the R5 error at its many seams (rms 0.0015 of a contrast of 0.25:
# 3.7e-4), 4e-4 in quadrature. At 64 spp a seam pixel whose sliver of the other square no
# random sample hit has a zero variance and fails alone (0.5% of pixels did); 256 spp makes
# that rare (0 to 4 pixels over 3 seeds). BIAS 0.3% of the mean 0.071 (measured <= 1.2e-5).
diff_case texture-image 64 0.0003 0.00018
diff_case texture-checker 256 0.0004 0.00021

# The diffs see the errors they are for: 1/pi dropped (every light pi times too bright), the lens
# radius halved, and a light 2% too bright.
must_fail point-shadows 64 0.0002 0.00015 "$(sed 's/intensity 20 }/intensity 62.831853 }/' tests/pov/point-shadows.mcrt)" "1/pi dropped"
must_fail point-shadows 64 0.0002 0.00015 "$(sed 's/intensity 20 }/intensity 20.4 }/' tests/pov/point-shadows.mcrt)" "light 2% too bright"
must_fail dof 256 0.0003 0.00021 "$(sed 's/lens_radius 0.12/lens_radius 0.06/' tests/pov/dof.mcrt)" "lens radius halved"
# ... and a texture upside down, shifted by half a texel (texel centres at x/w instead of
# (x + 1/2)/w) or its checker squares swapped.
must_fail texture-image 64 0.0003 0.00018 "$(sed -e 's/scale 2 1 /scale 2 -1 /' -e "s|\"texture-image.png\"|\"$(pwd)/tests/pov/texture-image.png\"|" tests/pov/texture-image.mcrt)" "the image upside down"
must_fail texture-image 64 0.0003 0.00018 "$(sed -e 's/offset 0.25 0 /offset 0.3125 0 /' -e "s|\"texture-image.png\"|\"$(pwd)/tests/pov/texture-image.png\"|" tests/pov/texture-image.mcrt)" "the image half a texel off"
must_fail texture-checker 256 0.0004 0.00021 "$(sed 's/offset 0.5 0 /offset 1.5 0 /' tests/pov/texture-checker.mcrt)" "the squares swapped"

finish
