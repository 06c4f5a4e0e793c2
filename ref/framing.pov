// POV-Ray 3.7 reference of an mcrt scene, written by `mcrt pov` (see mcrt(1)).
// povray +W160 +H120 +FE +A0.0 +AM2 +R5 -J
#version 3.7;
global_settings {
  assumed_gamma 1.0
  max_trace_level 1
  adc_bailout 0
}
camera {
  perspective
  location <2.5, 1.8, 5>
  direction <-0.75269, -0.376345, -1.344089>
  right <1.172112, -0.2344223, -0.5907442>
  up <0.04387109, 0.9553882, -0.2920765>
}
// material 'red'
#declare T2 = texture { pigment { rgb <0.8, 0.15, 0.1> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'green'
#declare T3 = texture { pigment { rgb <0.1, 0.7, 0.2> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'white'
#declare T4 = texture { pigment { rgb <0.9, 0.9, 0.9> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
// material 'floor'
#declare T1 = texture { pigment { rgb <0.45, 0.45, 0.45> } finish { ambient 0 diffuse 1 brilliance 1 specular 0 phong 0 } }
light_source { <-2, 5, 4> color rgb <4774648, 4774648, 4774648> fade_distance 0.001 fade_power 2 }
triangle { <-1.8, 0, -1>, <-0.4, 0, -1.4>, <-1.2, 1.6, -1.2> texture { T2 } }
sphere { <1, 0.35, 0.6>, 0.35 texture { T3 } }
sphere { <-0.6, 0.15, 0.9>, 0.15 texture { T4 } }
polygon { 5, <-5, 0, 5>, <5, 0, 5>, <5, 0, -5>, <-5, 0, -5>, <-5, 0, 5> texture { T1 } }
polygon { 5, <0.6, 0, -0.6>, <0.68, 0, -0.6>, <0.98, 1.5, -0.6>, <0.9, 1.5, -0.6>, <0.6, 0, -0.6> texture { T4 } }
polygon { 5, <0.2, 0, -1>, <0.35, 0, -1>, <0.35, 1.8, -1>, <0.2, 1.8, -1>, <0.2, 0, -1> texture { T4 } }
