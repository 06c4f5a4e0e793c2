// POV-Ray 3.7 reference of an mcrt scene, written by `mcrt pov` (see mcrt(1)).
// povray +W128 +H96 +FE +A0.0 +AM2 +R5 -J
#version 3.7;
global_settings {
  assumed_gamma 1.0
  max_trace_level 1
  adc_bailout 0
}
camera {
  perspective
  location <0.1, 2, 5>
  direction <-0.02550529, -0.5101058, -1.275265>
  right <1.333067, 0, -0.02666133>
  up <-0.007425048, 0.9285023, -0.3712524>
}
// material 'floor'
#declare T1 = texture { pigment { checker rgb <0.18, 0.2, 0.18>, rgb <0.8099999, 0.8, 0.27> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <1.5, 4, 2> color rgb <3183099, 3183099, 3183099> fade_distance 0.001 fade_power 2 }
polygon { 5, <-1.451, 0, 3.987>, <3.987, 0, 1.451>, <1.451, 0, -3.987>, <-3.987, 0, -1.451>, <-1.451, 0, 3.987> texture { T1 translate <-0.5, 0, -0.5> scale <0.0833333333, 0.0833333333, 1> matrix <5.438, 0, -2.536, -2.536, 0, -5.438, 0, 1, 0, -1.451, 0, 3.987> } }
