// POV-Ray 3.7 reference of an mcrt scene, written by `mcrt pov` (see mcrt(1)).
// povray +W96 +H96 +FE +A0.0 +AM2 +R5 -J
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
  location <0, 0, 0.9>
  direction <0, -0.07885629, -0.7097065>
  right <1, 0, 0>
  up <0, 0.9938837, -0.1104315>
}
// material 'grey'
#declare T1 = texture { pigment { rgb <0.5, 0.5, 0.5> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <0.3, 0.5, 0.2> color rgb <318309.9, 318309.9, 318309.9> fade_distance 0.001 fade_power 2 }
polygon { 5, <1, -1, -1>, <1, -1, 1>, <1, 1, 1>, <1, 1, -1>, <1, -1, -1> texture { T1 } }
polygon { 5, <-1, 1, -1>, <1, 1, -1>, <1, 1, 1>, <-1, 1, 1>, <-1, 1, -1> texture { T1 } }
polygon { 5, <-1, -1, 1>, <-1, -1, -1>, <-1, 1, -1>, <-1, 1, 1>, <-1, -1, 1> texture { T1 } }
polygon { 5, <-1, -1, 1>, <1, -1, 1>, <1, -1, -1>, <-1, -1, -1>, <-1, -1, 1> texture { T1 } }
polygon { 5, <-1, -1, 1>, <1, -1, 1>, <1, 1, 1>, <-1, 1, 1>, <-1, -1, 1> texture { T1 } }
polygon { 5, <-1, -1, -1>, <1, -1, -1>, <1, 1, -1>, <-1, 1, -1>, <-1, -1, -1> texture { T1 } }
