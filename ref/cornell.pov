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
  location <0, 0, 0.95>
  direction <0, 0, -0.8321397>
  right <1, 0, 0>
  up <0, 1, 0>
}
// material 'white'
#declare T1 = texture { pigment { rgb <0.7, 0.7, 0.7> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'red'
#declare T2 = texture { pigment { rgb <0.65, 0.07, 0.05> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'green'
#declare T3 = texture { pigment { rgb <0.14, 0.45, 0.09> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'ball'
#declare T4 = texture { pigment { rgb <0.6, 0.6, 0.3> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
polygon { 5, <-1, 1, -1>, <1, 1, -1>, <1, 1, 1>, <-1, 1, 1>, <-1, 1, -1> texture { T1 } }
polygon { 5, <-1, -1, 1>, <1, -1, 1>, <1, -1, -1>, <-1, -1, -1>, <-1, -1, 1> texture { T1 } }
polygon { 5, <-1, -1, 1>, <1, -1, 1>, <1, 1, 1>, <-1, 1, 1>, <-1, -1, 1> texture { T1 } }
polygon { 5, <-1, -1, -1>, <1, -1, -1>, <1, 1, -1>, <-1, 1, -1>, <-1, -1, -1> texture { T1 } }
polygon { 5, <-1, -1, 1>, <-1, -1, -1>, <-1, 1, -1>, <-1, 1, 1>, <-1, -1, 1> texture { T2 } }
polygon { 5, <1, -1, -1>, <1, -1, 1>, <1, 1, 1>, <1, 1, -1>, <1, -1, -1> texture { T3 } }
polygon { 5, <0.65, -1, 0>, <0.65, -1, -0.6>, <0.65, -0.3, -0.6>, <0.65, -0.3, 0>, <0.65, -1, 0> texture { T4 } }
polygon { 5, <0.65, -1, -0.6>, <0.04999995, -1, -0.6>, <0.04999995, -0.3, -0.6>, <0.65, -0.3, -0.6>, <0.65, -1, -0.6> texture { T4 } }
polygon { 5, <0.05, -1, 0>, <0.65, -1, 0>, <0.65, -0.3, 0>, <0.05, -0.3, 0>, <0.05, -1, 0> texture { T4 } }
polygon { 5, <0.05, -1, -0.6>, <0.05, -1, 0>, <0.05, -0.3, 0>, <0.05, -0.3, -0.6>, <0.05, -1, -0.6> texture { T4 } }
polygon { 5, <0.05, -0.3, 0>, <0.65, -0.3, 0>, <0.65, -0.3, -0.6>, <0.05, -0.3, -0.6>, <0.05, -0.3, 0> texture { T4 } }
light_source { <0, 0.999, 0> color rgb <477464.8, 477464.8, 477464.8>
  fade_distance 0.001 fade_power 2
  spotlight point_at <0, -0.0009999871, 0> radius 90 falloff 90 tightness 1
  area_light <0.46875, 0, 0>, <0, 0, 0.46875>, 16, 16 jitter area_illumination on
  looks_like { polygon { 5, <-0.25, 0, -0.25>, <0.25, 0, -0.25>, <0.25, 0, 0.25>, <-0.25, 0, 0.25>, <-0.25, 0, -0.25> pigment { rgb 1 } finish { ambient 0 diffuse 0 specular 0 phong 0 emission rgb <12, 12, 12> } no_radiosity } } }
