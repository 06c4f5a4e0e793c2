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
  location <3, 1.6, 4>
  direction <-0.6792261, -0.2328775, -0.970323>
  right <1.092309, 0, -0.7646164>
  up <-0.1106335, 0.981214, -0.1580479>
}
// material 'a'
#declare T1 = texture { pigment { rgb <0.8, 0.2, 0.2> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'b'
#declare T2 = texture { pigment { rgb <0.2, 0.6, 0.8> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'c'
#declare T3 = texture { pigment { rgb <0.9, 0.9, 0.5> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'glassy'
#declare T4 = texture { pigment { rgb 0 } finish { ambient 0 diffuse 0 specular 0 phong 0 reflection { rgb <0.9, 0.9, 0.9> } } }
light_source { <0.5, 3, 2> color rgb <2387324, 2387324, 2387324> fade_distance 0.001 fade_power 2 }
polygon { 5, <-3, 0, 3>, <-1, 0, 3>, <-1, 0, 1>, <-3, 0, 1>, <-3, 0, 3> texture { T1 } }
polygon { 5, <1, 0, -1>, <3, 0, -1>, <3, 0, -2>, <1, 0, -2>, <1, 0, -1> texture { T1 } }
polygon { 5, <-1, 0, 1>, <1, 0, 1>, <1, 0, -1>, <-1, 0, -1>, <-1, 0, 1> texture { T1 } }
polygon { 5, <-3, 0, -1>, <-1, 0, -1>, <-1, 0, -2>, <-3, 0, -2>, <-3, 0, -1> texture { T2 } }
polygon { 5, <1, 0, 1>, <3, 0, 1>, <3, 0, -1>, <1, 0, -1>, <1, 0, 1> texture { T2 } }
polygon { 5, <-1, 0, 3>, <1, 0, 3>, <1, 0, 1>, <-1, 0, 1>, <-1, 0, 3> texture { T2 } }
polygon { 5, <-3, 0, 1>, <-1, 0, 1>, <-1, 0, -1>, <-3, 0, -1>, <-3, 0, 1> texture { T3 } }
polygon { 5, <1, 0, 3>, <3, 0, 3>, <3, 0, 1>, <1, 0, 1>, <1, 0, 3> texture { T3 } }
polygon { 5, <-1, 0, -1>, <1, 0, -1>, <1, 0, -2>, <-1, 0, -2>, <-1, 0, -1> texture { T3 } }
polygon { 5, <-3, 0, -2>, <3, 0, -2>, <3, 2.5, -2>, <-3, 2.5, -2>, <-3, 0, -2> texture { T4 } }
