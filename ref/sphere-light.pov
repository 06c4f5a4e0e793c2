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
#declare T2 = texture { pigment { rgb <0.8, 0.3, 0.3> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'floor'
#declare T1 = texture { pigment { rgb <0.5, 0.5, 0.5> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
sphere { <0, 0.5, 0>, 0.5 texture { T2 } }
light_source { <0.5, 2.6, 0.5> color rgb <400000, 400000, 400000>
  fade_distance 0.001 fade_power 2
  area_light <0.1875, 0, 0>, <0, 0.1875, 0>, 16, 16 circular orient jitter area_illumination on
  looks_like { sphere { 0, 0.1 pigment { rgb 1 } finish { ambient 0 diffuse 0 specular 0 phong 0 emission rgb <80, 80, 80> } no_radiosity } } }
polygon { 5, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6>, <-6, 0, 6> texture { T1 } }
