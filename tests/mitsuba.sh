#!/bin/sh
# mitsuba.sh: `mcrt mitsuba` without Mitsuba. Each kind of shape, material, light, camera, filter,
# sampler and integrator setting is exported from a one-line scene and its XML (or OBJ) must hold
# the fragment that the mapping of mcrt(1) derives from the scene's numbers; every file must be
# well-formed XML (python3's parser, skipped without it); and each construct Mitsuba cannot
# reproduce is refused with "file:line:col:" at its place, exit status 2, and no file written.
# (make crosscheck renders the exports with Mitsuba itself.)
. tests/harness.sh.inc

lit='point_light { position 0 3 3 }'
have_python=0
command -v python3 >/dev/null 2>&1 && have_python=1

# wellformed FILE: python3's XML parser reads FILE and finds a <scene version="3.0.0"> root.
wellformed() {
    python3 -c 'import sys, xml.etree.ElementTree as E
r = E.parse(sys.argv[1]).getroot()
sys.exit(0 if r.tag == "scene" and r.get("version") == "3.0.0" else 1)' "$1" 2>"$tmp/perr"
}

# export NAME SCENE-TEXT: write SCENE-TEXT to $tmp/NAME.mcrt and export it to $tmp/NAME.xml.
export_scene() {
    printf '%s\n' "$2" >"$tmp/$1.mcrt"
    rm -f "$tmp/$1.xml" "$tmp/$1"-mesh*.obj
    if ! "$MCRT" mitsuba "$tmp/$1.mcrt" -o "$tmp/$1.xml" 2>"$tmp/err"; then
        fail "$1" "export failed: $(cat "$tmp/err")"
        return 1
    fi
    if [ "$have_python" -eq 1 ] && ! wellformed "$tmp/$1.xml"; then
        fail "$1" "not a well-formed Mitsuba scene: $(cat "$tmp/perr")"
        return 1
    fi
}

# has NAME FILE WHY FRAGMENT...: FILE (under $tmp) holds every FRAGMENT, as fixed strings.
has() {
    name=$1 file=$2 why=$3
    shift 3
    for frag in "$@"; do
        if ! grep -qF -- "$frag" "$tmp/$file"; then
            fail "$name" "$why: no '$frag' in $file:
$(head -c 1500 "$tmp/$file")"
            return
        fi
    done
    ok "$name: $why"
}

# expect NAME SCENE-TEXT WHY FRAGMENT...: the export of SCENE-TEXT holds every FRAGMENT.
expect() {
    name=$1 text=$2 why=$3
    shift 3
    export_scene "$name" "$text" && has "$name" "$name.xml" "$why" "$@"
}

# ---- shapes ----
expect sphere "sphere { center 1 2 3 radius 0.5 } $lit" "centre and radius as given" \
    '<shape type="sphere"><point name="center" x="1" y="2" z="3"/><float name="radius" value="0.5"/><ref id="m0"/></shape>'
# Rectangle [-1,1]^2 scaled by half the edges about the centre corner + (e1 + e2)/2 = (1, 2, 0);
# the normal column is e1 x e2 normalised (0 0 1).
expect quad "quad { corner 0 0 0 edge1 2 0 0 edge2 0 4 0 } $lit" "to_world = [e1/2 e2/2 n centre]" \
    '<shape type="rectangle"><transform name="to_world"><matrix value="1 0 0 1 0 2 0 2 0 0 1 0 0 0 0 1"/></transform><ref id="m0"/></shape>'
expect flipped-quad "quad { corner 0 0 0 edge1 2 0 0 edge2 0 4 0 flip } $lit" "flip_normals" \
    '<boolean name="flip_normals" value="true"/>'
# Unit disk scaled by the radius 2 about the centre; the frame about n = +z is x, y.
expect disk "disk { center 1 2 3 normal 0 0 1 radius 2 } $lit" "to_world = [r t, r b, n, centre]" \
    '<shape type="disk"><transform name="to_world"><matrix value="2 0 0 1 0 2 0 2 0 0 1 3 0 0 0 1"/></transform>'
expect triangle "triangle { v0 0 0 0 v1 1 0 0 v2 0 1 0 } $lit" "an OBJ mesh with face normals" \
    '<shape type="obj"><string name="filename" value="triangle-mesh0.obj"/><boolean name="face_normals" value="true"/><ref id="m0"/></shape>' &&
    has triangle-obj triangle-mesh0.obj "the vertices in order" "v 0 0 0
v 1 0 0
v 0 1 0
f 1 2 3"
expect flipped-triangle "triangle { v0 0 0 0 v1 1 0 0 v2 0 1 0 flip } $lit" "wound the other way" \
    'triangle-mesh0.obj' && has flipped-triangle-obj flipped-triangle-mesh0.obj "p0 p2 p1" "v 0 0 0
v 0 1 0
v 1 0 0"
expect smooth-mesh "mesh { file \"$(pwd)/scenes/icosphere.obj\" } $lit" "interpolated normals" \
    'value="smooth-mesh-mesh0.obj"/><ref id="m0"/>' && has smooth-mesh-obj smooth-mesh-mesh0.obj \
    "each corner's normal" 'vn ' 'f 1//1 2//2 3//3'
if grep -q face_normals "$tmp/smooth-mesh.xml"; then fail "smooth mesh" "written with face normals"; fi
expect two-meshes "material a { diffuse 0.5 } material b { diffuse 0.25 }
triangle { v0 0 0 0 v1 1 0 0 v2 0 1 0 material a } triangle { v0 0 0 1 v1 1 0 1 v2 0 1 1 material b }
triangle { v0 0 0 2 v1 1 0 2 v2 0 1 2 material a emit 2 } $lit" "one mesh per material and emission" \
    'mesh0.obj"/><boolean name="face_normals" value="true"/><ref id="m1"/></shape>' \
    'mesh1.obj"/><boolean name="face_normals" value="true"/><ref id="m1"/><emitter type="area"><rgb name="radiance" value="2, 2, 2"/></emitter></shape>' \
    'mesh2.obj"/><boolean name="face_normals" value="true"/><ref id="m2"/></shape>'

# ---- materials ----
m() { printf 'material m { %s } sphere { material m } %s' "$1" "$lit"; }
expect diffuse "$(m 'diffuse 0.5 0.25 0.125')" "Lambertian, two-sided" \
    '<bsdf type="twosided" id="m1"><bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.25, 0.125"/></bsdf></bsdf>'
expect mirror "$(m 'mirror 0.9 0.8 0.7')" "a perfect conductor scaled by the colour" \
    '<bsdf type="twosided" id="m1"><bsdf type="conductor"><string name="material" value="none"/><rgb name="specular_reflectance" value="0.9, 0.8, 0.7"/></bsdf></bsdf>'
expect glass "$(m 'glass ior 1.33 tint 0.9 0.8 0.7')" "dielectric, tint on transmission" \
    '<bsdf type="dielectric" id="m1"><float name="int_ior" value="1.33"/><float name="ext_ior" value="1"/><rgb name="specular_transmittance" value="0.9, 0.8, 0.7"/></bsdf>'
expect rough-glass "$(m 'glass roughness 0.5')" "GGX alpha = roughness^2" \
    '<bsdf type="roughdielectric" id="m1"><string name="distribution" value="ggx"/><float name="alpha" value="0.25"/><float name="int_ior" value="1.5"/>'
expect metal "$(m 'metal eta 0.2 0.9 1.1 k 3.9 2.4 2.2')" "smooth conductor, eta and k" \
    '<bsdf type="twosided" id="m1"><bsdf type="conductor"><rgb name="eta" value="0.2, 0.9, 1.1"/><rgb name="k" value="3.9, 2.4, 2.2"/></bsdf></bsdf>'
# reflectance 0.75: eta 1, k = 2 sqrt(R)/sqrt(1 - R) = 2 sqrt(3) = 3.464102 (mcrt.5, metal).
expect rough-metal "$(m 'metal 0.75 alpha 0.1')" "GGX conductor, k from the reflectance" \
    '<bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.1"/><rgb name="eta" value="1, 1, 1"/><rgb name="k" value="3.464102, 3.464102, 3.464102"/>'
expect plastic "$(m 'plastic 0.5 0.25 0.125 ior 1.6')" "plastic, linear" \
    '<bsdf type="twosided" id="m1"><bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.5, 0.25, 0.125"/><float name="int_ior" value="1.6"/><float name="ext_ior" value="1"/><boolean name="nonlinear" value="true"/></bsdf></bsdf>'
expect white-plastic "$(m 'plastic 1 roughness 0.3')" "roughplastic, the base capped at 0.999" \
    '<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.09"/><rgb name="diffuse_reflectance" value="0.999, 0.999, 0.999"/>'

# ---- lights ----
expect point "point_light { position 1 2 3 intensity 4 5 6 } sphere { }" "intensity in W/sr" \
    '<emitter type="point"><point name="position" x="1" y="2" z="3"/><rgb name="intensity" value="4, 5, 6"/></emitter>'
expect area "quad { corner 0 0 0 edge1 2 0 0 edge2 0 4 0 emit 1 2 3 } sphere { center 0 0 -3 }" \
    "an area emitter on the shape" '<ref id="m0"/><emitter type="area"><rgb name="radiance" value="1, 2, 3"/></emitter></shape>'
expect emitting-sphere "sphere { emit 5 flip } $lit" "an inward-emitting sphere" \
    '<boolean name="flip_normals" value="true"/><ref id="m0"/><emitter type="area"><rgb name="radiance" value="5, 5, 5"/></emitter></shape>'
expect sky "environment { radiance 0.5 0.6 0.7 } sphere { }" "a constant sky" \
    '<emitter type="constant"><rgb name="radiance" value="0.5, 0.6, 0.7"/></emitter>'
expect default-sky "sphere { }" "the default white sky" \
    '<emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>'
# The map's own frame turned half a turn about y (Mitsuba's u = 0 looks along -z, mcrt's along +z).
expect envmap "environment { map \"$(pwd)/scenes/sky.exr\" scale 2 } sphere { }" "an envmap, turned" \
    "<emitter type=\"envmap\"><string name=\"filename\" value=\"$(pwd)/scenes/sky.exr\"/><float name=\"scale\" value=\"2\"/><transform name=\"to_world\"><matrix value=\"-1 0 0 0 0 1 0 0 0 0 -1 0 0 0 0 1\"/></transform></emitter>"
# rotate 0 1 0 90 takes the map's x to -z and z to x: columns -(-z) = z, y, -x (a zero may be
# float rounding, |x| < 1e-6).
expect envmap-rotated "environment { map \"$(pwd)/scenes/sky.exr\" rotate 0 1 0 90 } sphere { }" \
    "orient after the half turn" 'name="to_world"><matrix value="'
z='(0|-?[0-9.]+e-0[7-9])'
one='(1|0.99999[0-9]*)'
if grep -Eq "matrix value=\"$z $z -1 0 $z $one $z 0 1 $z $z 0 0 0 0 1\"" "$tmp/envmap-rotated.xml"; then
    ok "envmap-rotated: the matrix is [z y -x]"
else fail "envmap-rotated" "matrix: $(grep -o 'matrix value="[^"]*"' "$tmp/envmap-rotated.xml")"; fi

# ---- camera, film, integrator ----
expect camera "camera { eye 1 2 3 look 0 1 0 up 0 1 0 fov 30 } film { width 64 height 32 spp 9 sampler stratified } $lit sphere { }" \
    "pinhole, film and a square stratified count" \
    '<sensor type="perspective">' '<float name="fov" value="30"/>' \
    '<lookat origin="1, 2, 3" target="0, 1, 0" up="0, 1, 0"/>' \
    '<sampler type="stratified"><integer name="sample_count" value="9"/></sampler>' \
    '<integer name="width" value="64"/><integer name="height" value="32"/>' '<rfilter type="box"/>'
# focus 0: |look - eye| = 5.
expect lens "camera { lens_radius 0.1 } film { spp 8 sampler random filter tent } sphere { } $lit" \
    "thin lens focused at |look - eye|, independent, tent" \
    '<sensor type="thinlens">' '<float name="aperture_radius" value="0.1"/><float name="focus_distance" value="5"/>' \
    '<sampler type="independent"><integer name="sample_count" value="8"/>' \
    '<rfilter type="tent"><float name="radius" value="1"/></rfilter>'
expect sobol "film { spp 16 sampler sobol filter gaussian } sphere { } $lit" "ldsampler, gaussian" \
    '<sampler type="ldsampler">' '<rfilter type="gaussian"><float name="stddev" value="0.5"/></rfilter>'
expect sobol-8 "film { spp 8 sampler sobol } sphere { } $lit" "sobol, 8 not a power of 4" '<sampler type="multijitter">'
expect default-sampler "film { spp 64 } sphere { } $lit" "the default sampler is sobol" '<sampler type="ldsampler">'
expect multijitter "film { spp 8 sampler stratified } sphere { } $lit" "stratified, 8 not a square" '<sampler type="multijitter">'
expect depth "integrator { max_depth 3 rr_depth 2 } sphere { } $lit" "max_depth counts the camera ray" \
    '<integrator type="path"><integer name="max_depth" value="4"/><integer name="rr_depth" value="2"/></integrator>'
expect direct "integrator { method direct } sphere { } $lit" "direct is two rays" \
    '<integer name="max_depth" value="2"/>'
expect unlimited "sphere { } $lit" "unlimited depth" '<integer name="max_depth" value="-1"/>'

# ---- every scene that can be exported is well-formed ----
if [ "$have_python" -eq 1 ]; then
    for s in scenes/*.mcrt; do
        n=$(basename "$s" .mcrt)
        if "$MCRT" mitsuba "$s" -o "$tmp/scene-$n.xml" 2>"$tmp/err"; then
            if wellformed "$tmp/scene-$n.xml"; then ok "$s exports well-formed"
            else fail "$s" "not well-formed: $(cat "$tmp/perr")"; fi
        elif [ "$?" -ne 2 ]; then fail "$s" "exit status not 2: $(cat "$tmp/err")"
        else ok "$s refused: $(cat "$tmp/err")"; fi
    done
else
    skip "well-formed XML" "no python3"
fi

# ---- refusals ----
# refuse NAME WHERE REGEX SCENE-TEXT: mcrt mitsuba exits 2 with one line on stderr that starts
# with "r.mcrt:WHERE: " and matches REGEX, writes no file and leaves an existing output as it was.
refuse() {
    printf '%s\n' "$4" >"$tmp/r.mcrt"
    rm -f "$tmp"/r-mesh*.obj
    echo "old output" >"$tmp/r.xml"
    "$MCRT" mitsuba "$tmp/r.mcrt" -o "$tmp/r.xml" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -ne 2 ]; then fail "refuses $1" "exit $rc, expected 2"
    elif [ "$(wc -l <"$tmp/err")" -ne 1 ] || ! grep -q "^$tmp/r.mcrt:$2: " "$tmp/err" \
        || ! grep -Eq -- "$3" "$tmp/err"; then
        fail "refuses $1" "message '$(cat "$tmp/err")' is not at r.mcrt:$2 or does not match /$3/"
    elif [ "$(cat "$tmp/r.xml")" != "old output" ] || ls "$tmp" | grep -q 'r-mesh\|r.xml.tmp'; then
        fail "refuses $1" "a file was written"
    else ok "refuses $1: $(cat "$tmp/err")"; fi
}
refuse "a moving shape" 1:21 "moving shape.*motion blur" "sphere { } sphere { move 1 0 0 } $lit"
mesh="mesh { file \"$(pwd)/scenes/cube.obj\" "
refuse "spin" "2:$((${#mesh} + 1))" "moving shape" "sphere { }
${mesh}spin 0 1 0 90 } $lit"
refuse "a moving camera" 1:10 "moving camera" "camera { move 0 1 0 } sphere { } $lit"
refuse "a two-sided emitter" 1:15 "two_sided emitter.*front side" \
    "quad { emit 1 two_sided } sphere { center 0 0 -3 }"
refuse "the bsdf strategy with point lights" 2:1 "bsdf strategy" "sphere { }
integrator { strategy bsdf } $lit"
refuse "the bsdf method with point lights" 1:1 "bsdf strategy" "integrator { method bsdf } sphere { } $lit"
refuse "a tinted map" 1:12 "tinted environment map" \
    "sphere { } environment { map \"$(pwd)/scenes/sky.exr\" radiance 1 0.5 1 }"
refuse "a texture" 1:48 "textured material" \
    "texture t { checker 0 1 } material m { diffuse texture t } sphere { material m } $lit"
"$MCRT" mitsuba "$tmp/missing.mcrt" -o "$tmp/m.xml" 2>"$tmp/err"
rc=$?
if [ "$rc" -eq 2 ] && [ ! -e "$tmp/m.xml" ]; then ok "a missing scene exits 2"
else fail "a missing scene" "exit $rc"; fi
printf 'sphere { radius -1 }\n' >"$tmp/bad.mcrt"
"$MCRT" mitsuba "$tmp/bad.mcrt" -o "$tmp/bad.xml" 2>"$tmp/err"
rc=$?
if [ "$rc" -eq 2 ] && grep -q "bad.mcrt:1:17: " "$tmp/err" && [ ! -e "$tmp/bad.xml" ]; then
    ok "a malformed scene exits 2 at its place: $(cat "$tmp/err")"
else fail "a malformed scene" "exit $rc: $(cat "$tmp/err")"; fi

finish
