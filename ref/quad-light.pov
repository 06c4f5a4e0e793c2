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
  location <0, 2.5, 6>
  direction <0, -0.4147203, -1.309643>
  right <1.333333, 0, 0>
  up <0, 0.9533421, -0.3018917>
}
// material 'floor'
#declare T1 = texture { pigment { rgb <0.6, 0.6, 0.6> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'card'
#declare T2 = texture { pigment { rgb <0.7, 0.4, 0.2> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'box'
#declare T3 = texture { pigment { rgb <0.3, 0.5, 0.7> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
polygon { 5, <-6, 0, 6>, <6, 0, 6>, <6, 0, -6>, <-6, 0, -6>, <-6, 0, 6> texture { T1 } }
polygon { 5, <-1.3, 0.9, -0.2>, <-0.1999999, 1.1, -0.2>, <-0.1999999, 1, -1.2>, <-1.3, 0.8, -1.2>, <-1.3, 0.9, -0.2> texture { T2 } }
polygon { 5, <1.2, 0, 0.6>, <1.2, 0, -0.2>, <1.2, 0.8, -0.2>, <1.2, 0.8, 0.6>, <1.2, 0, 0.6> texture { T3 } }
polygon { 5, <1.2, 0, -0.2>, <0.4, 0, -0.2>, <0.4, 0.8, -0.2>, <1.2, 0.8, -0.2>, <1.2, 0, -0.2> texture { T3 } }
polygon { 5, <0.4, 0, 0.6>, <1.2, 0, 0.6>, <1.2, 0.8, 0.6>, <0.4, 0.8, 0.6>, <0.4, 0, 0.6> texture { T3 } }
polygon { 5, <0.4, 0, -0.2>, <0.4, 0, 0.6>, <0.4, 0.8, 0.6>, <0.4, 0.8, -0.2>, <0.4, 0, -0.2> texture { T3 } }
polygon { 5, <0.4, 0.8, 0.6>, <1.2, 0.8, 0.6>, <1.2, 0.8, -0.2>, <0.4, 0.8, -0.2>, <0.4, 0.8, 0.6> texture { T3 } }
light_source { <0, 3, 0> color rgb <1375099, 1375099, 1375099>
  fade_distance 0.001 fade_power 2
  spotlight point_at <0, 2, 0> radius 90 falloff 90 tightness 1
  area_light <1.125, 0, 0>, <0, 0, 1.125>, 16, 16 jitter area_illumination on
  looks_like { polygon { 5, <-0.6, 0, -0.6>, <0.6, 0, -0.6>, <0.6, 0, 0.6>, <-0.6, 0, 0.6>, <-0.6, 0, -0.6> pigment { rgb 1 } finish { ambient 0 diffuse 0 specular 0 phong 0 emission rgb <6, 6, 6> } no_radiosity } } }
