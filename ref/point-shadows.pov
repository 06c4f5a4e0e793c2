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
  location <0, 3, 6>
  direction <0, -0.5283611, -1.268067>
  right <1.333333, 0, 0>
  up <0, 0.923077, -0.3846154>
}
// material 'ball'
#declare T2 = texture { pigment { rgb <0.2, 0.5, 0.8> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'floor'
#declare T1 = texture { pigment { rgb <0.5, 0.5, 0.5> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'card'
#declare T3 = texture { pigment { rgb <0.8, 0.7, 0.3> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <1.5, 4, 2> color rgb <3183099, 3183099, 3183099> fade_distance 0.001 fade_power 2 }
sphere { <-0.8, 0.6, 0>, 0.6 texture { T2 } }
polygon { 5, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6>, <-6, 0, 6> texture { T1 } }
polygon { 5, <0.6, 0, -0.5>, <1.6, 0, -0.2>, <1.6, 1.2, -0.2>, <0.6, 1.2, -0.5>, <0.6, 0, -0.5> texture { T3 } }
