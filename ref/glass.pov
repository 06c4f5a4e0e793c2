// POV-Ray 3.7 reference of an mcrt scene, written by `mcrt pov` (see mcrt(1)).
// povray +W128 +H96 +FE +A0.0 +AM2 +R5 -J
#version 3.7;
global_settings {
  assumed_gamma 1.0
  max_trace_level 64
  adc_bailout 0
  radiosity {
    count 800 nearest_count 20 error_bound 0.1 recursion_limit 20
    pretrace_start 0.08 pretrace_end 0.005 low_error_factor 0.5 gray_threshold 0
    brightness 1 minimum_reuse 0.015 adc_bailout 0.0001 always_sample off normal off media off
  }
}
camera {
  perspective
  location <0.03, 0.3, 5>
  direction <0, -0.08227637, -1.371273>
  right <1.333333, 0, 0>
  up <0, 0.9982049, -0.05989229>
}
// material 'clear'
#declare T3 = texture { pigment { rgbf 1 } finish { ambient 0 diffuse 0 specular 0 phong 0 reflection { 0, 1 fresnel on } conserve_energy } }
#declare I3 = interior { ior 1.5 }
// material 'a'
#declare T1 = texture { pigment { rgb <0.9, 0.85, 0.3> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'b'
#declare T2 = texture { pigment { rgb <0.15, 0.25, 0.6> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <0, 2.5, -2.5> color rgb <1909859, 1909859, 1909859> fade_distance 0.001 fade_power 2 }
sphere { <0, 0, 0>, 0.6 texture { T3 } interior { I3 } }
polygon { 5, <0, -3, -4>, <2, -3, -4>, <2, -1, -4>, <0, -1, -4>, <0, -3, -4> texture { T1 } }
polygon { 5, <0, 1, -4>, <2, 1, -4>, <2, 3, -4>, <0, 3, -4>, <0, 1, -4> texture { T1 } }
polygon { 5, <2, -1, -4>, <4, -1, -4>, <4, 1, -4>, <2, 1, -4>, <2, -1, -4> texture { T1 } }
polygon { 5, <-2, -1, -4>, <0, -1, -4>, <0, 1, -4>, <-2, 1, -4>, <-2, -1, -4> texture { T1 } }
polygon { 5, <-4, -3, -4>, <-2, -3, -4>, <-2, -1, -4>, <-4, -1, -4>, <-4, -3, -4> texture { T1 } }
polygon { 5, <-4, 1, -4>, <-2, 1, -4>, <-2, 3, -4>, <-4, 3, -4>, <-4, 1, -4> texture { T1 } }
polygon { 5, <0, -1, -4>, <2, -1, -4>, <2, 1, -4>, <0, 1, -4>, <0, -1, -4> texture { T2 } }
polygon { 5, <2, -3, -4>, <4, -3, -4>, <4, -1, -4>, <2, -1, -4>, <2, -3, -4> texture { T2 } }
polygon { 5, <2, 1, -4>, <4, 1, -4>, <4, 3, -4>, <2, 3, -4>, <2, 1, -4> texture { T2 } }
polygon { 5, <-2, -3, -4>, <0, -3, -4>, <0, -1, -4>, <-2, -1, -4>, <-2, -3, -4> texture { T2 } }
polygon { 5, <-2, 1, -4>, <0, 1, -4>, <0, 3, -4>, <-2, 3, -4>, <-2, 1, -4> texture { T2 } }
polygon { 5, <-4, -1, -4>, <-2, -1, -4>, <-2, 1, -4>, <-4, 1, -4>, <-4, -1, -4> texture { T2 } }
